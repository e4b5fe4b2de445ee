"""The control screen: step joints with the keyboard, read the pose, see the arm.

Data flows one way: a key changes the joint vector; the screen asks the core
for the frames and the read-out, asks the scene layer for the projected
views, and hands the results to the widgets, which only draw.

Keys change the state at once (every key counts, none is dropped), but the
drawing is coalesced: a change marks the screen dirty and queues one redraw,
at most one a frame (1/60 s), so a burst of auto-repeat is drawn a few times,
not once per key, and never builds a backlog.
"""

from __future__ import annotations

from dataclasses import dataclass
from time import monotonic

import numpy as np
from rich.text import Text
from textual import work
from textual.app import ComposeResult
from textual.containers import Container, Vertical
from textual.events import Resize
from textual.reactive import reactive
from textual.screen import Screen
from textual.widgets import Footer, Static
from textual.worker import get_current_worker

from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.jacobian import controllable_rows, dexterity, jacobian_from_frames
from dhsim_tui.core.jog import (
    CARTESIAN_ROWS,
    DEFAULT_STEP_LEVEL,
    REVOLUTE_STEPS_DEG,
    TOOL,
    WORLD,
    branch_caption,
    branch_goal,
    branch_index,
    cartesian_move,
    cartesian_step_size,
    move_pose,
    row_name,
    set_joint,
    step_size,
)
from dhsim_tui.core.kinematics import read_out
from dhsim_tui.core.model import Robot
from dhsim_tui.core.text import printable
from dhsim_tui.core.validation import fmt
from dhsim_tui.scene import VIEWS, build_wireframe
from dhsim_tui.scene.oblique import Orbit
from dhsim_tui.screens.control_entry import ValueFlows
from dhsim_tui.screens.control_keys import (
    CARTESIAN_ACTIONS,
    CONTROL_BINDINGS,
    HELP_NOTES,
    JOINT_ACTIONS,
    KEYS_LEGEND,
    KEYS_LEGEND_ASCII,
    help_rows,
)
from dhsim_tui.screens.help import HelpScreen
from dhsim_tui.screens.motion import SmoothMotion
from dhsim_tui.terminal import ascii_mode, shown
from dhsim_tui.typeahead import FRAME, draw_later
from dhsim_tui.widgets.cartesian_panel import TITLES as CARTESIAN_TITLES
from dhsim_tui.widgets.cartesian_panel import CartesianPanel
from dhsim_tui.widgets.joint_panel import JointPanel, JointRow
from dhsim_tui.widgets.pose_panel import READOUTS, PosePanel
from dhsim_tui.widgets.views_panel import ViewsPanel, is_wide

#: below this the screen shows a message instead of a layout
MIN_SIZE = (60, 18)
#: Cartesian mode shows the pose panel too from this height on
TALL_FOR_BOTH = 32
#: how many tool poses' IK solutions (b) are kept
BRANCH_CACHE = 8
#: how many points the workspace cloud (W) has
CLOUD_POINTS = 20000
#: what can stop the search for a pose's solutions or the workspace's sampling
#: (said in the status line, never a crash)
SEARCH_ERRORS = (DhsimError, ValueError, ArithmeticError, np.linalg.LinAlgError)


@dataclass(frozen=True)
class BranchCycle:
    """The arm's solutions for one tool pose (``b``), and the one it is in or
    moving to."""

    found: object  # ik_all.Solutions
    index: int
    labels: tuple[str, ...] = ()  # the joints' labels (Th1 ..), to name whole turns

    @property
    def goal(self) -> tuple[float, ...]:
        return branch_goal(self.found.solutions[self.index].q)

    @property
    def caption(self) -> str:
        return branch_caption(self.found, self.index, self.labels)


class ControlScreen(ValueFlows, SmoothMotion, Screen):
    """Joint stepping, home, poses, read-outs and the three views.

    | Key | Action |
    | :- | :- |
    | up / down | Select a joint (Cartesian: an axis) |
    | left / right | Step the joint, or move the tool (shift: ten steps) |
    | [ / ] | Smaller / larger step |
    | enter | Type the joint's exact value (Cartesian: a target) |
    | h / home | Every joint home (the D-H table's values) |
    | p | Next named pose |
    | v | Read-out: OAT, roll-pitch-yaw, 4×4 transform |
    | tab / 1 2 3 4 | Select the top, front, side or 3-D view |
    | z | Maximise the selected view, and back |
    | + / - / 0 | Zoom in, out about the arm; the whole work area |
    | a d / w s | Orbit the 3-D view (azimuth / elevation) |
    | c | Joint <-> Cartesian jogging (X, Y, Z, turns about x, y, z) |
    | f | Cartesian: WORLD <-> TOOL frame |
    | b | The next IK branch for this tool pose (the tool stays) |
    | W | Workspace cloud on / off |
    | P | Save the current joints as a named pose |
    | m | Smooth motion on or off (the footer shows which) |
    | escape | Stop a smooth move |
    | e | Edit the robot in a table |
    | ? | Help |
    | q | Quit |
    """

    BINDINGS = CONTROL_BINDINGS

    q: reactive[tuple[float, ...]] = reactive(tuple, init=False, repaint=False)
    selected: reactive[int] = reactive(0, init=False, repaint=False)
    step_level: reactive[int] = reactive(DEFAULT_STEP_LEVEL, init=False, repaint=False)
    readout: reactive[str] = reactive("oat", init=False, repaint=False)
    view_index: reactive[int] = reactive(1, init=False, repaint=False)
    cartesian: reactive[bool] = reactive(False, init=False, repaint=False)

    def __init__(self, robot: Robot, renderer: str = "plotext", animate: bool = True) -> None:
        super().__init__()
        self.robot = robot
        self.renderer = renderer
        self.animate = animate
        self.cartesian_row = 0
        self._commanded = None  # the Cartesian target while jogging
        self.frame = WORLD  # Cartesian jogging's frame (f)
        self._branches: BranchCycle | None = None  # b: the solutions cycled through
        self._branch_cache: dict[bytes, object] = {}
        self.finding_branches = False  # a worker is looking for them
        self._branch_presses = 0  # b pressed while it looks
        self.cloud_state = "off"  # W: "off", "computing" or "on"
        self._cloud_points = None  # the workspace cloud, once sampled
        self._animation = None
        self._pose_cursor = -1
        self._said: tuple[str, bool] = ("", False)
        self._ready = False
        self._dirty = False  # q changed and the widgets don't show it yet
        self.redraws = 0  # how many times the pose was drawn (tests, benches)
        self._drawn_at = 0.0  # when (time.monotonic)
        self.set_reactive(ControlScreen.q, robot.home)

    # -- layout -------------------------------------------------------------
    def compose(self) -> ComposeResult:
        robot = self.robot
        with Container(id="layout"):
            with Vertical(id="side-panel"):
                panel = JointPanel(id="joints")
                # file content: control characters escaped, never markup
                panel.border_title = Text(
                    shown(printable(f"{robot.name} · {robot.type_string}"), self.app)
                )
                with panel:
                    for i, (joint, value) in enumerate(
                        zip(robot.joints, self.q, strict=True), start=1
                    ):
                        yield JointRow(i, joint, robot.units, value)
                yield CartesianPanel(id="cartesian")
                yield PosePanel(id="pose")
                yield Static("", id="status")
                yield Static(
                    KEYS_LEGEND_ASCII if ascii_mode(self.app) else KEYS_LEGEND,
                    id="keys",
                )
            yield ViewsPanel(self.renderer, id="views")
        yield Static("", id="too-small")
        yield Footer(compact=True)

    def on_mount(self) -> None:
        self._views = self.query_one(ViewsPanel)
        self._joints = self.query_one(JointPanel)
        self._pose_panel = self.query_one(PosePanel)
        self._cartesian_panel = self.query_one(CartesianPanel)
        self._cartesian_panel.border_title = CARTESIAN_TITLES[self.frame]
        self._ready = True
        self._joints.select(self.selected)
        self._update_step_caption()
        self._views.select(self.view_index)
        self._apply_size(self.app.size.width, self.app.size.height)
        self._refresh_pose()

    def on_resize(self, event: Resize) -> None:
        self._apply_size(event.size.width, event.size.height)

    def _apply_size(self, width: int, height: int) -> None:
        too_small = width < MIN_SIZE[0] or height < MIN_SIZE[1]
        self.set_class(too_small, "-too-small")
        self.set_class(is_wide(width, height), "-wide")
        self.set_class(height < TALL_FOR_BOTH, "-short")
        if too_small:
            self.query_one("#too-small", Static).update(
                shown(
                    f"Terminal too small: {width}×{height}.\n"
                    f"dhsim needs at least {MIN_SIZE[0]}×{MIN_SIZE[1]}. q quits.",
                    self.app,
                )
            )

    # -- the one-way flow: q -> core -> scene -> widgets -----------------------
    def _invalidate(self) -> None:
        """q changed: draw it once the keys already queued are handled, and
        no sooner than a frame after the last drawing (keys reach the screen
        one at a time, see typeahead.py, so a burst is drawn a few times a
        frame apart rather than once per key)."""
        if not self._dirty:
            self._dirty = True
            wait = self._drawn_at + FRAME - monotonic()
            if wait > 0:
                self.set_timer(wait, self._redraw)
            else:
                self.call_later(self._redraw)

    def _redraw(self) -> None:
        """Draw the latest q if it isn't drawn yet; while more keys of a burst
        wait, a frame later (they will change it again)."""
        if not self._dirty:
            return
        if draw_later(self.app, self._drawn_at, monotonic()):
            self.set_timer(FRAME, self._redraw)
            return
        self._refresh_pose()

    def _show_now(self) -> None:
        """Show the pose panels now (a changed read-out, row or mode)."""
        if self._dirty:
            self._refresh_pose()
        else:
            self._show_pose()

    def _refresh_pose(self) -> None:
        if not self._ready:  # a key that arrived before the screen was mounted
            return
        self._dirty = False
        self._drawn_at = monotonic()
        self.redraws += 1
        frames = self.robot.kinematics.frames(self.q)
        self.pose = read_out(frames[-1])
        self.dexterity = dexterity(self.robot, jac=jacobian_from_frames(self.robot, frames))
        wire = build_wireframe(self.robot, frames)
        self._views.show(wire)
        self._joints.show(self.q)
        self.warnings = wire.warnings
        self._show_pose()

    def _show_pose(self) -> None:
        branch = shown(printable(self._branches.caption), self.app) if self._branches else ""
        self._pose_panel.show(
            self.pose, self.readout, self.robot.units, self.dexterity, self.warnings, branch
        )
        if self.cartesian:
            self._cartesian_panel.show(
                self.pose.xyz,
                self.pose.rpy,
                self.cartesian_row,
                self.robot.units,
                self.frame,
                [self.pose.matrix[:3, i] for i in range(3)],  # the tool's x, y, z
            )

    def watch_q(self) -> None:
        self._commanded = None  # any other move ends a Cartesian run (_jog sets it again)
        self._leave_branch()
        self._invalidate()

    def _leave_branch(self) -> bool:
        """Forget the branch cycle once the arm is neither in the branch it
        went to nor on its way there: b then starts afresh from where it is."""
        cycle = self._branches
        if cycle is None or cycle.goal in (self.q, self.motion_goal):
            return False
        self._branches = None
        return True

    def _stop_motion(self) -> bool:
        stopped = super()._stop_motion()
        if stopped and self._leave_branch():  # stopped on the way to a branch
            self._show_now()
        return stopped

    def watch_readout(self) -> None:
        if not self._ready:
            return
        self._show_now()

    def watch_cartesian(self) -> None:
        if not self._ready:
            return
        self.set_class(self.cartesian, "-cartesian")
        # one ▶ on screen: the Cartesian row's, or the joint's
        self._joints.select(-1 if self.cartesian else self.selected)
        self._update_step_caption()
        self._show_now()
        self.refresh_bindings()  # the arrows' labels in the footer

    def watch_selected(self) -> None:
        if not self._ready:
            return
        self._joints.select(-1 if self.cartesian else self.selected)
        self._update_step_caption()

    def watch_step_level(self) -> None:
        if not self._ready:
            return
        self._update_step_caption()

    def watch_view_index(self) -> None:
        if not self._ready:
            return
        self._views.select(self.view_index)

    def _update_step_caption(self) -> None:
        if self.cartesian:
            row = self.cartesian_row
            unit = self.robot.units if row < 3 else "deg"
            step = cartesian_step_size(self.robot, row, self.step_level)
            self._cartesian_panel.border_subtitle = Text(f"step {fmt(step)} {unit}  [ ]")
            return
        joint = self.robot.joints[self.selected]
        unit = joint.unit(self.robot.units)
        step = step_size(self.robot, self.selected, self.step_level)
        self._joints.border_subtitle = Text(f"step {fmt(step)} {unit}  [ ]")

    def say(self, message: str, error: bool = False) -> None:
        """Under the panels, wrapped to show all of it: what just happened, or
        why nothing did. It may quote file content: control characters are
        shown escaped, and it is never read as markup."""
        message = shown(printable(message), self.app)
        if (message, error) == self._said:
            return
        self._said = (message, error)
        status = self.query_one("#status", Static)
        status.set_class(error, "-error")
        status.update(Text(message), layout=False)

    # -- actions ----------------------------------------------------------------
    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """Grey out keys that can't do anything for this robot (or yet)."""
        if not self._ready:
            return False
        # False hides a binding and lets the key fall through to the next one:
        # the arrows are the joints' in joint mode, the tool's in Cartesian mode
        if action in JOINT_ACTIONS:
            return not self.cartesian
        if action in CARTESIAN_ACTIONS:
            return self.cartesian
        if action == "toggle_motion":  # the label shows the state motion is in
            return bool(parameters and parameters[0]) == self.animate
        if action == "cartesian":  # the label names the mode c switches to
            return bool(parameters and parameters[0]) == self.cartesian
        if action == "next_pose" and not self.robot.pose_names:
            return None
        if action == "frame":  # Cartesian only; the label names the frame f switches to
            return self.cartesian and bool(parameters) and parameters[0] != self.frame
        return True

    def action_select(self, delta: int) -> None:
        self.selected = (self.selected + delta) % self.robot.dof

    def action_row(self, delta: int) -> None:
        self.cartesian_row = (self.cartesian_row + delta) % len(CARTESIAN_ROWS)
        self._update_step_caption()
        self._show_now()

    def action_jog(self, multiple: int) -> None:
        self._interrupt()
        row = self.cartesian_row
        self._jog(row, multiple * cartesian_step_size(self.robot, row, self.step_level))

    def action_step(self, multiple: int) -> None:
        self._interrupt()
        index = self.selected
        delta = multiple * step_size(self.robot, index, self.step_level)
        self._move_to(index, self.q[index] + delta)

    def _move_to(self, index: int, value: float) -> None:
        joint = self.robot.joints[index]
        label = joint.label(index + 1)
        unit = joint.unit(self.robot.units)
        move = set_joint(self.robot, self.q, index, value)
        if move.limit is not None:
            bound = joint.min if move.limit == "min" else joint.max
            verb = "is at" if not move.moved else "stopped at"
            self.say(f"{label} {verb} its {move.limit} limit, {fmt(bound)} {unit}", error=True)
        else:
            self.say("")
        if move.moved:
            self.q = move.q

    def _jog(self, row: int, delta: float) -> None:
        """Move the tool; the joints follow by inverse kinematics from where they
        are. Steps add up on the commanded pose, not on the reached one, so a
        run of steps stays on its line instead of collecting solver residue."""
        base = (
            self._commanded if self._commanded is not None else self.robot.kinematics.pose(self.q)
        )
        target = move_pose(base, row, delta, self.frame)
        move = cartesian_move(self.robot, self.q, target)
        if not move.moved:
            self.say(f"{row_name(row, self.frame)}: {move.reason or 'no change'}", error=True)
            return
        self.say("")
        self.q = move.q
        self._commanded = target

    def action_cartesian(self, _in_cartesian: int = 0) -> None:
        self.cartesian = not self.cartesian
        self.say(
            f"Cartesian jogging, {self.frame.upper()} frame (f): ↑↓ axis, ←→ move the tool"
            if self.cartesian
            else "joint jogging"
        )

    def action_frame(self, frame: str = "") -> None:
        """``f``: Cartesian jogging along and about the world's axes, or the
        tool's own (``frame``: the one to switch to; either, when not given)."""
        self.frame = frame if frame in (WORLD, TOOL) else (TOOL if self.frame == WORLD else WORLD)
        self._cartesian_panel.border_title = CARTESIAN_TITLES[self.frame]
        self._show_now()
        self.refresh_bindings()
        self.say(
            "TOOL frame: along and about the tool's own x, y, z (z: the approach)"
            if self.frame == TOOL
            else "WORLD frame: along and about the world's X, Y, Z (turns about the tool point)"
        )

    # -- b: the arm's other solutions for the same tool pose -------------------------
    def action_next_branch(self) -> None:
        """The next of the arm's solutions for the tool's pose: the tool stays,
        the arm takes another configuration (smoothly when motion is on). The
        solutions are found once per pose, in a worker; pressed again, ``b``
        goes on to the next; any other move of the arm starts afresh. Pressed
        while they are being found (a few ms to a second), each press counts:
        the arm then goes that many branches on."""
        if self.finding_branches:
            self._branch_presses += 1
            return
        cycle = self._branches
        if cycle is not None and cycle.goal in (self.q, self.motion_goal):
            self._next_branch(cycle.found, cycle.index)
            return
        pose = self.robot.kinematics.pose(self.q)
        key = self._branch_key(pose)
        found = self._branch_cache.get(key)
        if found is not None:
            self._branches_found(self.q, key, found, presses=1)
            return
        self.finding_branches = True
        self._branch_presses = 1
        self.say("finding the arm's solutions for this pose…")
        self._find_branches(self.robot, self.q, pose, key)

    def _branch_key(self, pose: np.ndarray) -> bytes:
        """The tool pose, rounded: the same pose reached again finds its solutions kept."""
        scale = max(float(np.abs(pose[:3, 3]).max()), 1.0)
        rounded = np.round(np.concatenate([pose[:3, :3].ravel(), pose[:3, 3] / scale]), 7)
        return (rounded + 0.0).tobytes()

    @work(thread=True, exclusive=True, group="branches")
    def _find_branches(self, robot: Robot, q: tuple[float, ...], pose, key: bytes) -> None:
        from dhsim_tui.core.ik_all import all_solutions

        # an arm with fewer joints than directions it moves in positions its tool (as a jog)
        position_only = robot.dof < int(controllable_rows(robot).sum())
        worker = get_current_worker()
        try:
            with np.errstate(all="ignore"):
                found = all_solutions(robot, pose, q, position_only=position_only)
        except SEARCH_ERRORS as exc:
            if not worker.is_cancelled:
                self.app.call_from_thread(self._branches_failed, str(exc))
            return
        if not worker.is_cancelled:  # (the screen went away meanwhile)
            self.app.call_from_thread(self._branches_found, q, key, found)

    def _branches_failed(self, reason: str) -> None:
        self.finding_branches = False
        self.say(f"no other solutions found: {reason}", error=True)

    def _branches_found(
        self, q: tuple[float, ...], key: bytes, found, presses: int | None = None
    ) -> None:
        """``presses``: how many times b was pressed for this (all of them
        while the solutions were being found, when not given)."""
        self.finding_branches = False
        presses = self._branch_presses if presses is None else presses
        self._branch_cache[key] = found
        while len(self._branch_cache) > BRANCH_CACHE:
            self._branch_cache.pop(next(iter(self._branch_cache)))
        if q != self.q:  # the arm moved while they were being found: b again
            return
        if not found.solutions:
            note = f": {found.note}" if found.note else ""
            self.say(f"no solution found for this pose{note}", error=True)
            return
        self._next_branch(found, branch_index(self.robot, found.solutions, q), presses)

    @staticmethod
    def _note(found) -> str:
        """A short caveat for the status line (the core's note is longer)."""
        if found.method == "numerical" and not found.family:
            return " (found numerically: one may be missing)"
        return ""

    def _next_branch(self, found, index: int, steps: int = 1) -> None:
        """Move to the solution ``steps`` after ``index`` (-1: the arm is in
        none of them)."""
        count = len(found.solutions)
        if count == 1 and index == 0:
            self._branches = BranchCycle(found, 0, tuple(self.robot.labels))
            self._show_now()
            self.say(self._branches.caption + self._note(found))
            return
        self._stop_motion()  # (a move to the branch before: the cycle goes on)
        cycle = BranchCycle(found, (index + steps) % count, tuple(self.robot.labels))
        self._branches = cycle
        self._go_to(cycle.goal, cycle.caption + self._note(found))
        self._show_now()

    # -- W: the workspace cloud ----------------------------------------------------------
    def action_workspace(self) -> None:
        """Show the points the tool can reach, faint behind the arm in every
        view (sampled once, in a worker); again: hide them, or stop waiting."""
        if self.cloud_state != "off":
            self.cloud_state = "off"
            self.workers.cancel_group(self, "workspace")
            self._views.set_cloud(None)
            self.say("workspace cloud off")
            return
        self.cloud_state = "computing"
        if self._cloud_points is not None:
            self._cloud_ready(self._cloud_points)
            return
        self.say("sampling the workspace… (W again: never mind)")
        self._sample_workspace(self.robot)

    @work(thread=True, exclusive=True, group="workspace")
    def _sample_workspace(self, robot: Robot) -> None:
        from dhsim_tui.core.workspace import position_chunks

        worker = get_current_worker()
        chunks = []
        try:
            with np.errstate(all="ignore"):  # sample_positions, chunk by chunk: W may stop it
                for chunk in position_chunks(robot, CLOUD_POINTS, 0):
                    if worker.is_cancelled:
                        return
                    chunks.append(chunk)
            points = np.concatenate(chunks)
        except SEARCH_ERRORS as exc:
            if not worker.is_cancelled:
                self.app.call_from_thread(self._cloud_failed, str(exc))
            return
        if not worker.is_cancelled:  # W again, or the screen went away
            self.app.call_from_thread(self._cloud_ready, points)

    def _cloud_failed(self, reason: str) -> None:
        if self.cloud_state == "computing":
            self.cloud_state = "off"
            self.say(f"workspace not sampled: {reason}", error=True)

    def _cloud_ready(self, points) -> None:
        """The samples (kept: the joints, base and tool don't change on this
        screen); shown unless W was pressed again meanwhile."""
        self._cloud_points = points
        if self.cloud_state != "computing":
            return
        self.cloud_state = "on"
        self._views.set_cloud(points)
        self.say(f"workspace: {len(points)} positions the tool can reach (W hides them)")

    def action_step_size(self, delta: int) -> None:
        self.step_level = max(0, min(len(REVOLUTE_STEPS_DEG) - 1, self.step_level + delta))

    def action_home(self) -> None:
        self._pose_cursor = -1
        self._go_to(self.robot.home, "home")

    def action_next_pose(self) -> None:
        names = self.robot.pose_names
        if not names:
            self.say(f"{self.robot.name} has no named poses", error=True)
            return
        self.go_to_pose(names[(self._pose_cursor + 1) % len(names)])

    def go_to_pose(self, name: str) -> None:
        """Move to the named pose as ``p`` does (smoothly when motion is on);
        ``p`` then goes on from it."""
        names = self.robot.pose_names
        if name not in names:
            self.say(f"{self.robot.name} has no pose {name!r}", error=True)
            return
        self._pose_cursor = names.index(name)
        self._go_to(self.robot.pose(name), f"pose {name} ({self._pose_cursor + 1}/{len(names)})")

    def action_readout(self) -> None:
        self.readout = READOUTS[(READOUTS.index(self.readout) + 1) % len(READOUTS)]

    def action_next_view(self) -> None:
        self.view_index = (self.view_index + 1) % len(VIEWS)

    def action_view(self, index: int) -> None:
        self.view_index = index

    def action_maximise(self) -> None:
        self._views.toggle_maximise()

    def action_zoom(self, steps: int) -> None:
        if steps == 0:
            self._views.reset_zoom()
        else:
            self._views.zoom_by(steps)

    def action_orbit(self, azimuth: int, elevation: int) -> None:
        """Turn the 3-D view (and show it, if it is hidden)."""
        if not self._views.views[3].display or not self._views.views[3].size.area:
            self.view_index = 3
        self._views.orbit_by(azimuth * Orbit.STEP, elevation * Orbit.STEP)

    def action_edit(self) -> None:
        self.app.action_edit()  # type: ignore[attr-defined]

    def action_help(self) -> None:
        self.app.push_screen(HelpScreen("Keys", help_rows(self.robot), HELP_NOTES))

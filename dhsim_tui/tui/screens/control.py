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

from time import monotonic

from rich.text import Text
from textual.app import ComposeResult
from textual.containers import Container, Vertical
from textual.events import Resize
from textual.reactive import reactive
from textual.screen import Screen
from textual.widgets import Footer, Static

from dhsim_tui.core.analysis.jacobian import dexterity, jacobian_from_frames
from dhsim_tui.core.model.kinematics import read_out
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.validation import fmt
from dhsim_tui.core.motion.jog import (
    DEFAULT_STEP_LEVEL,
    REVOLUTE_STEPS_DEG,
    WORLD,
    cartesian_step_size,
    set_joint,
    snapped,
    step_size,
)
from dhsim_tui.scene import build_wireframe
from dhsim_tui.terminal.charset import shown
from dhsim_tui.terminal.typeahead import FRAME, draw_later
from dhsim_tui.tui.screens.control_branches import (
    BRANCH_CACHE,
    SEARCH_ERRORS,
    BranchCycle,
    BranchCycling,
)
from dhsim_tui.tui.screens.control_cartesian import CartesianJogging
from dhsim_tui.tui.screens.control_cloud import CLOUD_POINTS, WorkspaceCloud
from dhsim_tui.tui.screens.control_entry import ValueFlows
from dhsim_tui.tui.screens.control_keys import (
    CARTESIAN_ACTIONS,
    CONTROL_BINDINGS,
    HELP_NOTES,
    JOINT_ACTIONS,
    KeyHints,
    help_rows,
)
from dhsim_tui.tui.screens.control_views import ViewControls
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.screens.motion import SmoothMotion
from dhsim_tui.tui.widgets.cartesian_panel import TITLES as CARTESIAN_TITLES
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel
from dhsim_tui.tui.widgets.joint_panel import JointPanel, JointRow
from dhsim_tui.tui.widgets.pose_panel import ALL_READOUTS, READOUTS, PosePanel
from dhsim_tui.tui.widgets.views_panel import ViewsPanel, is_wide

__all__ = [
    "BRANCH_CACHE",
    "CLOUD_POINTS",
    "MIN_SIZE",
    "SEARCH_ERRORS",
    "TALL_FOR_BOTH",
    "BranchCycle",
    "ControlScreen",
]

#: below this the screen shows a message instead of a layout
MIN_SIZE = (60, 18)
#: Cartesian mode shows the pose panel too from this height on
TALL_FOR_BOTH = 32
#: from this height on the pose panel shows every read-out at once (OAT,
#: roll-pitch-yaw and the 4×4 transform): a tall side panel has the room
TALL_FOR_ALL_READOUTS = 44


class ControlScreen(
    CartesianJogging,
    BranchCycling,
    WorkspaceCloud,
    ViewControls,
    ValueFlows,
    SmoothMotion,
    Screen,
):
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
                yield KeyHints(id="keys")
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
        self._apply_size(self.app.size.width, self.app.size.height)
        self._refresh_pose()
        if self._said[0]:  # a message given before the screen was up
            message, error = self._said
            self._said = ("", False)
            self.say(message, error)

    def on_resize(self, event: Resize) -> None:
        self._apply_size(event.size.width, event.size.height)

    def _apply_size(self, width: int, height: int) -> None:
        too_small = width < MIN_SIZE[0] or height < MIN_SIZE[1]
        self.set_class(too_small, "-too-small")
        self.set_class(is_wide(width, height), "-wide")
        self.set_class(height < TALL_FOR_BOTH, "-short")
        if self._ready and hasattr(self, "pose"):
            self._show_now()  # every read-out at once, or one
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
        tall = self.app.size.height >= TALL_FOR_ALL_READOUTS and not self.cartesian
        readout = ALL_READOUTS if tall else self.readout
        self._pose_panel.show(
            self.pose, readout, self.robot.units, self.dexterity, self.warnings, branch
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

    def on_views_panel_maximised(self, message: ViewsPanel.Maximised) -> None:
        """The selected view over the whole screen: the side panel makes way."""
        self.set_class(message.maximised, "-max")

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
        if not self._ready:  # said before the screen is up (after a reload): shown at mount
            return
        found = self.query("#status").results(Static)
        status = next(found, None)
        if status is None:  # a late worker's word after the screen was taken down
            return
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

    # -- the mouse on the joints: the rows ask, the screen decides -------------
    def on_joint_row_picked(self, message: JointRow.Picked) -> None:
        """A click selects the joint (back in joint jogging); on its bar, or
        dragged along it, the joint goes to the value under the pointer,
        rounded to the current step and kept within its limits."""
        index = message.row.index
        if self.cartesian:
            self.cartesian = False
        self.selected = index
        if message.value is not None:
            self._interrupt()
            self._move_to(index, snapped(self.robot, index, message.value, self.step_level))

    def on_joint_row_wheeled(self, message: JointRow.Wheeled) -> None:
        """The wheel over a joint steps it (and selects it)."""
        if self.cartesian:
            self.cartesian = False
        self.selected = message.row.index
        self.action_step(message.steps)

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

    def action_edit(self) -> None:
        self.app.action_edit()  # type: ignore[attr-defined]

    def action_help(self) -> None:
        self.app.push_screen(HelpScreen("Keys", help_rows(self.robot), HELP_NOTES))

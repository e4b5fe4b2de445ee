"""The control screen: step joints with the keyboard, read the pose, see the arm.

Data flows one way: the panels post what a key or the mouse asks for; the
screen, which holds the robot and the joint values ``q``, answers by asking
the core, and hands the frames, read-outs and projected views back to the
widgets, which only draw.

Joint or Cartesian jogging is which panel has the focus (``c`` moves it).
Keys change the state at once (every key counts, none is dropped), but the
drawing is coalesced: a change marks the screen dirty and queues one redraw,
at most one a frame (1/60 s), so a burst of auto-repeat is drawn a few times,
not once per key, and never builds a backlog.

(About 700 lines, on purpose: this is where every panel's messages are
answered, and where b's search, W's sampling and smooth moves start and end.
Each is a few lines of glue over the core (:mod:`.control_jobs` runs the
searches, :mod:`.control_program` the programs); split by feature again, a
key's path would be spread over several classes that reach into one
another, the mixins this replaced.)
"""

from __future__ import annotations

from functools import partial
from time import monotonic

from rich.text import Text
from textual import work
from textual.app import ComposeResult
from textual.containers import Container, Vertical
from textual.events import DescendantFocus, Resize
from textual.reactive import reactive
from textual.screen import Screen
from textual.widgets import Static

from dhsim_tui.core.analysis.jacobian import dexterity, jacobian_from_frames
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics import read_out
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.validation import fmt
from dhsim_tui.core.motion.branches import (
    BranchCache,
    BranchCycle,
    branch_key,
)
from dhsim_tui.core.motion.jog import (
    DEFAULT_STEP_LEVEL,
    REVOLUTE_STEPS_DEG,
    TOOL,
    cartesian_move,
    cartesian_step_size,
    move_pose,
    row_name,
    set_joint,
    snapped,
    step_size,
)
from dhsim_tui.core.motion.smooth import SmoothMove
from dhsim_tui.scene import build_wireframe
from dhsim_tui.terminal.charset import shown
from dhsim_tui.terminal.typeahead import FRAME, draw_later
from dhsim_tui.tui.flows.values import (
    PATH_WIDTH,
    ask_cartesian_step,
    ask_joint_value,
    ask_pose_name,
    shorten_path_in,
)
from dhsim_tui.tui.keys import help_rows
from dhsim_tui.tui.screens.control_commands import control_commands
from dhsim_tui.tui.screens.control_jobs import (
    BranchesFailed,
    BranchesFound,
    CloudFailed,
    CloudSampled,
    find_branches,
    sample_workspace,
)
from dhsim_tui.tui.screens.control_keys import (
    CONTROL_BINDINGS,
    HELP_NOTES,
    KeyHints,
    bindings_in_effect,
)
from dhsim_tui.tui.screens.control_program import ProgramPlayer
from dhsim_tui.tui.screens.dialogs import short_path
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel
from dhsim_tui.tui.widgets.footer import KeysFooter
from dhsim_tui.tui.widgets.joint_panel import JointPanel, JointRow
from dhsim_tui.tui.widgets.pose_panel import ALL_READOUTS, READOUTS, PosePanel
from dhsim_tui.tui.widgets.program_panel import ProgramPanel
from dhsim_tui.tui.widgets.stepping import StepSizeRequested
from dhsim_tui.tui.widgets.views_panel import ViewsPanel, is_wide

#: below this the screen shows a message instead of a layout
MIN_SIZE = (60, 18)
#: Cartesian mode shows the pose panel too from this height on
TALL_FOR_BOTH = 32
#: from this height on the pose panel shows every read-out at once (OAT,
#: roll-pitch-yaw and the 4×4 transform): a tall side panel has the room
TALL_FOR_ALL_READOUTS = 44


#: while a program plays, the joints' and the pose's numbers are shown every
#: this many frames (15 a second): nobody reads them faster, and each frame
#: then costs the terminal less, so a key pressed during playback is answered
#: sooner (bench/latency.py --during-playback)
PANELS_EVERY = 2


class ControlScreen(Screen):
    """Joint stepping, home, poses, read-outs and the four views.

    The keys are the focused panel's (arrows, ``[ ]``, enter; ``f`` in
    Cartesian jogging), the views panel's (handed on) and this screen's
    (``CONTROL_BINDINGS``); ``?`` lists the ones in effect.
    """

    BINDINGS = CONTROL_BINDINGS
    AUTO_FOCUS = "#joints"

    q: reactive[tuple[float, ...]] = reactive(tuple, init=False, repaint=False)
    step_level: reactive[int] = reactive(DEFAULT_STEP_LEVEL, init=False, repaint=False)
    readout: reactive[str] = reactive("oat", init=False, repaint=False)

    def __init__(self, robot: Robot, renderer: str = "plotext", animate: bool = True) -> None:
        super().__init__()
        self.robot = robot
        self.renderer = renderer
        self.animate = animate
        self._commanded = None  # the Cartesian target while jogging
        self._branches: BranchCycle | None = None  # b: the solutions cycled through
        self._branch_cache = BranchCache()
        self.finding_branches = False  # a worker is looking for them
        self._branch_presses = 0  # b pressed while it looks
        self.cloud_state = "off"  # W: "off", "computing" or "on"
        self._cloud_points = None  # the workspace cloud, once sampled
        self._move: SmoothMove | None = None  # the smooth move under way
        self._ticker = None
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
                yield ProgramPanel(id="program")
                yield PosePanel(id="pose")
                yield Static("", id="status")
                yield KeyHints(id="keys")
            yield ViewsPanel(self.renderer, id="views")
        yield Static("", id="too-small")
        yield KeysFooter(compact=True)  # Textual's, minus its leak (widgets/footer.py)

    def on_mount(self) -> None:
        self._views = self.query_one(ViewsPanel)
        self._joints = self.query_one(JointPanel)
        self._pose_panel = self.query_one(PosePanel)
        self._cartesian_panel = self.query_one(CartesianPanel)
        self._program_panel = self.query_one(ProgramPanel)
        self._programs = ProgramPlayer(self, self._program_panel)
        self._ready = True
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

    @property
    def cartesian(self) -> bool:
        """Cartesian jogging: the Cartesian panel has the focus."""
        return self._ready and self.focused is self._cartesian_panel

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
        wire = build_wireframe(self.robot, frames, self._programs.trail)
        self._views.show(wire)
        self.warnings = wire.warnings
        if self._programs.playing and self.redraws % PANELS_EVERY:
            return  # playing: the numbers every other frame, the views every frame
        self._joints.show(self.q)
        self._show_pose()

    def _show_pose(self) -> None:
        branch = shown(printable(self._branches.caption), self.app) if self._branches else ""
        tall = self.app.size.height >= TALL_FOR_ALL_READOUTS and not self.cartesian
        readout = ALL_READOUTS if tall else self.readout
        self._pose_panel.show(
            self.pose, readout, self.robot.units, self.dexterity, self.warnings, branch
        )
        if self.cartesian:
            tool_axes = [self.pose.matrix[:3, i] for i in range(3)]
            self._cartesian_panel.show(self.pose.xyz, self.pose.rpy, self.robot.units, tool_axes)

    def watch_q(self) -> None:
        self._commanded = None  # any other move ends a Cartesian run (_jog sets it again)
        self._leave_branch()
        self._invalidate()

    def watch_readout(self) -> None:
        if self._ready:
            self._show_now()

    def watch_step_level(self) -> None:
        if self._ready:
            self._update_step_caption()

    def _update_step_caption(self) -> None:
        if self.cartesian:
            row = self._cartesian_panel.row
            unit = self.robot.units if row < 3 else "deg"
            step = cartesian_step_size(self.robot, row, self.step_level)
            self._cartesian_panel.border_subtitle = Text(f"step {fmt(step)} {unit}  [ ]")
            return
        index = self._joints.selected
        unit = self.robot.joints[index].unit(self.robot.units)
        step = step_size(self.robot, index, self.step_level)
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
        status = next(self.query("#status").results(Static), None)
        if status is None:  # a late worker's word after the screen was taken down
            return
        status.set_class(error, "-error")
        status.update(Text(message), layout=False)

    # -- which panel jogs: the focus ----------------------------------------------
    def on_descendant_focus(self, event: DescendantFocus) -> None:
        """The panel with the focus jogs (c, or a click on it): the layout,
        the step caption, the pose shown and the keys follow."""
        if event.widget not in (self._joints, self._cartesian_panel, self._program_panel):
            return
        self.set_class(self.cartesian, "-cartesian")
        self.set_class(self.focused is self._program_panel, "-program")
        self._update_step_caption()
        self._show_now()
        self.refresh_bindings()  # c's label in the footer
        self.query_one(KeyHints).refresh_hints()

    def action_switch(self, to: str) -> None:
        """c: Cartesian jogging, or back to the joints (``to``); g: the
        program panel, or back to the joints."""
        if to == "program":
            if self.focused is self._program_panel:
                self._joints.focus()
                self.say("joint jogging")
                return
            self.add_class("-program")  # shown first: a hidden panel takes no focus
            self._program_panel.focus()
            self.say(
                "program: R records a step at the end, I inserts, D waits, enter edits, "
                "space plays; ? lists all"
            )
            return
        if to == "cartesian":
            self.add_class("-cartesian")  # shown first: a hidden panel takes no focus
            self._cartesian_panel.focus()
            frame = self._cartesian_panel.frame.upper()
            self.say(f"Cartesian jogging, {frame} frame (f): ↑↓ axis, ←→ move the tool")
        else:
            self._joints.focus()
            self.say("joint jogging")

    # -- keys -------------------------------------------------------------------
    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """Hide or grey out keys that can't do anything for this robot (or yet)."""
        if not self._ready:
            return False
        if action == "toggle_motion":  # the label shows the state motion is in
            return bool(parameters and parameters[0]) == self.animate
        if action == "switch" and parameters[0] == "program":
            return True
        if action == "switch":  # c's label names the mode it switches to
            return (parameters[0] == "cartesian") != self.cartesian
        if action == "next_pose" and not self.robot.pose_names:
            return None
        return True

    def action_forward(self, target: str, action: str, parameters: tuple = ()) -> None:
        """A key of a widget that takes no focus (the views panel's)."""
        getattr(self.query_one(f"#{target}"), f"action_{action}")(*parameters)

    def action_step_size(self, delta: int) -> None:
        self.step_level = max(0, min(len(REVOLUTE_STEPS_DEG) - 1, self.step_level + delta))

    def on_step_size_requested(self, message: StepSizeRequested) -> None:
        self.action_step_size(message.delta)

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
        names = printable(", ".join(self.robot.pose_names))
        more = {"robot.pose": f": {names}" if names else " (this robot has none)"}
        bindings = bindings_in_effect(self)
        keys = {b.key for b in bindings}  # and Cartesian jogging's own (f), from joint jogging
        bindings += [b for b in self._cartesian_panel.BINDINGS if b.key not in keys]
        rows = help_rows(bindings, more)
        self.app.push_screen(HelpScreen("Keys", rows, HELP_NOTES))

    def palette_commands(self) -> list:
        """The command palette's commands for this screen as it is now."""
        return list(control_commands(self.app, self))

    # -- joints: what the joints panel asks ------------------------------------------
    def on_joint_panel_selected(self, message: JointPanel.Selected) -> None:
        self._update_step_caption()

    def on_joint_panel_step_requested(self, message: JointPanel.StepRequested) -> None:
        self._interrupt()
        index = message.index
        delta = message.steps * step_size(self.robot, index, self.step_level)
        self._move_to(index, self.q[index] + delta)

    def on_joint_panel_value_requested(self, message: JointPanel.ValueRequested) -> None:
        """A click or drag on a bar: the value under the pointer, rounded to
        the current step and kept within the joint's limits."""
        self._interrupt()
        index = message.index
        self._move_to(index, snapped(self.robot, index, message.value, self.step_level))

    def on_joint_panel_value_asked(self, message: JointPanel.ValueAsked) -> None:
        self._interrupt()  # now, not when the dialog's worker gets to run
        self._ask_joint(message.index)

    @work(exclusive=True, group="modal")
    async def _ask_joint(self, index: int) -> None:
        value = await ask_joint_value(self.app, self.robot, index, self.q[index])
        if value is not None:
            self._move_to(index, value)

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

    # -- Cartesian: what the Cartesian panel asks -------------------------------------
    def on_cartesian_panel_row_selected(self, message: CartesianPanel.RowSelected) -> None:
        self._update_step_caption()

    def on_cartesian_panel_jog_requested(self, message: CartesianPanel.JogRequested) -> None:
        self._interrupt()
        step = cartesian_step_size(self.robot, message.row, self.step_level)
        self._jog(message.row, message.steps * step, message.frame)

    def on_cartesian_panel_target_asked(self, message: CartesianPanel.TargetAsked) -> None:
        self._interrupt()
        self._ask_target(message.row, message.frame)

    @work(exclusive=True, group="modal")
    async def _ask_target(self, row: int, frame: str) -> None:
        self._redraw()  # self.pose must be the pose of the current q
        step = await ask_cartesian_step(self.app, self.robot, row, frame, self.pose)
        if step is not None:
            self._jog(row, step, frame)

    def on_cartesian_panel_frame_changed(self, message: CartesianPanel.FrameChanged) -> None:
        self._show_now()
        self.say(
            "TOOL frame: along and about the tool's own x, y, z (z: the approach)"
            if message.frame == TOOL
            else "WORLD frame: along and about the world's X, Y, Z (turns about the tool point)"
        )

    def _jog(self, row: int, delta: float, frame: str) -> None:
        """Move the tool; the joints follow by inverse kinematics from where they
        are. Steps add up on the commanded pose, not on the reached one, so a
        run of steps stays on its line instead of collecting solver residue."""
        base = (
            self._commanded if self._commanded is not None else self.robot.kinematics.pose(self.q)
        )
        target = move_pose(base, row, delta, frame)
        move = cartesian_move(self.robot, self.q, target)
        if not move.moved:
            self.say(f"{row_name(row, frame)}: {move.reason or 'no change'}", error=True)
            return
        self.say("")
        self.q = move.q
        self._commanded = target

    # -- P: save the joints as a pose ----------------------------------------------
    @work(exclusive=True, group="modal")
    async def action_save_pose(self) -> None:
        """Keep the current joints as a named pose, in the robot and its file."""
        answer = await ask_pose_name(self.app, self.robot, self.q)
        if answer is None:
            return
        self.robot, name = answer
        app = self.app
        try:
            saved_to = app.keep_robot(self.robot)  # type: ignore[attr-defined]
        except DhsimError as exc:
            reason = shorten_path_in(str(exc), app.robot_path)  # type: ignore[attr-defined]
            self.say(f"not saved: {reason} (pose {name} is kept in memory)", error=True)
        else:
            where = (
                f"saved in {short_path(saved_to, PATH_WIDTH)}"
                if saved_to
                else "kept until you quit (e, ctrl+s saves)"
            )
            self.say(f"pose {name} {where}")
        self.refresh_bindings()

    # -- smooth motion (m): a quintic move over about a second --------------------------
    def _go_to(self, goal: tuple[float, ...], message: str) -> None:
        """Straight to ``goal``, or a smooth move when motion is on; a key that
        moves the arm interrupts it where it is."""
        self._stop_motion()
        self.say(message)
        if not self.animate or goal == self.q:
            self.q = goal
            return
        self._move = SmoothMove(self.q, goal, monotonic())
        self._ticker = self.set_interval(1 / 30, self._tick)

    def _tick(self) -> None:
        if self._move is None:
            return
        q, done = self._move.at(monotonic())
        self.q = q
        if done:
            self._stop_motion()

    @property
    def moving(self) -> bool:
        return self._move is not None

    @property
    def motion_goal(self) -> tuple[float, ...] | None:
        """Where the move under way ends (None when none is under way)."""
        return self._move.goal if self._move is not None else None

    def _stop_motion(self) -> bool:
        if self._move is None:
            return False
        if self._ticker is not None:
            self._ticker.stop()
        self._move = self._ticker = None
        if self._leave_branch():  # stopped on the way to a branch
            self._show_now()
        return True

    def _interrupt(self) -> None:
        """A key that moves the arm: stop a move where it is, and say so (the
        key's own action may say something else right after)."""
        if self._ready and self._programs.pause():
            self.say("paused")
        if self._stop_motion():
            self.say("stopped")

    def action_stop(self) -> None:
        """escape: stop sampling a program, or a smooth move (nothing else)."""
        if self._ready and self._programs.cancel_sampling():
            return
        self._interrupt()

    def action_toggle_motion(self, _shown_as_on: int = 0) -> None:
        """``m``: the parameter only tells the footer's two labels apart."""
        self.animate = not self.animate
        self.app.animate = self.animate  # a new control screen (after the editor) keeps it
        self.refresh_bindings()
        self.query_one(KeyHints).refresh_hints()
        self.say(
            "smooth motion on: h, p and b move over a second; escape stops"
            if self.animate
            else "smooth motion off: h, p and b jump"
        )

    # -- b: the arm's other solutions for the same tool pose ------------------------------
    def _leave_branch(self) -> bool:
        """Forget the branch cycle once the arm is neither in the branch it
        went to nor on its way there: b then starts afresh from where it is."""
        cycle = self._branches
        if cycle is None or cycle.holds(self.q, self.motion_goal):
            return False
        self._branches = None
        return True

    def action_next_branch(self) -> None:
        """The next of the arm's solutions for the tool's pose: the tool stays,
        the arm takes another configuration (smoothly when motion is on). The
        solutions are found once per pose, in a worker; pressed again, ``b``
        goes on to the next; any other move of the arm starts afresh. Pressed
        while they are being found, each press counts."""
        if self.finding_branches:
            self._branch_presses += 1
            return
        cycle = self._branches
        if cycle is not None and cycle.holds(self.q, self.motion_goal):
            self._next_branch(cycle, 1)
            return
        pose = self.robot.kinematics.pose(self.q)
        key = branch_key(pose)
        found = self._branch_cache.get(key)
        if found is not None:
            self._next_branch(BranchCycle.of(self.robot, found, self.q), 1)
            return
        self.finding_branches = True
        self._branch_presses = 1
        self.say("finding the arm's solutions for this pose…")
        job = partial(find_branches, self.post_message, self.robot, self.q, pose, key)
        self.run_worker(job, thread=True, exclusive=True, group="branches")

    def on_branches_failed(self, message: BranchesFailed) -> None:
        self.finding_branches = False
        self.say(f"no other solutions found: {message.reason}", error=True)

    def on_branches_found(self, message: BranchesFound) -> None:
        """Every press of b while they were being found counts."""
        self.finding_branches = False
        self._branch_cache.put(message.key, message.found)
        if message.q != self.q:  # the arm moved while they were being found: b again
            return
        found = message.found
        if not found.solutions:
            note = f": {found.note}" if found.note else ""
            self.say(f"no solution found for this pose{note}", error=True)
            return
        self._next_branch(BranchCycle.of(self.robot, found, self.q), self._branch_presses)

    def _next_branch(self, cycle: BranchCycle, steps: int) -> None:
        """``steps`` solutions on from ``cycle``'s (the only one: stays)."""
        following = cycle.after(steps)
        if following is None:
            self._branches = cycle
            self._show_now()
            self.say(cycle.caption + cycle.note)
            return
        self._stop_motion()  # (a move to the branch before: the cycle goes on)
        self._branches = following
        self._go_to(following.goal, following.caption + following.note)
        self._show_now()

    # -- W: the workspace cloud --------------------------------------------------------
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
            self.on_cloud_sampled(CloudSampled(self._cloud_points))
            return
        self.say("sampling the workspace… (W again: never mind)")
        job = partial(sample_workspace, self.post_message, self.robot)
        self.run_worker(job, thread=True, exclusive=True, group="workspace")

    def on_cloud_failed(self, message: CloudFailed) -> None:
        if self.cloud_state == "computing":
            self.cloud_state = "off"
            self.say(f"workspace not sampled: {message.reason}", error=True)

    def on_cloud_sampled(self, message: CloudSampled) -> None:
        """The samples (kept: the joints, base and tool don't change on this
        screen); shown unless W was pressed again meanwhile."""
        self._cloud_points = message.points
        if self.cloud_state != "computing":
            return
        self.cloud_state = "on"
        self._views.set_cloud(message.points)
        self.say(f"workspace: {len(message.points)} positions the tool can reach (W hides them)")

    # -- programs: the program panel, R and space (control_program) ---------------
    def stop_moving(self) -> None:
        """A program starts playing: a smooth move stops where it is."""
        self._stop_motion()

    def refresh_views(self) -> None:
        """The program's path came or went: the views draw it (or not) now."""
        if self._ready:
            self._refresh_pose()

    def action_record(self) -> None:
        self._programs.record()
        self.add_class("-program")

    def action_record_move(self) -> None:
        self._programs.toggle_record_move()

    def action_play(self) -> None:
        self._programs.toggle()

    def on_program_panel_changed(self, message: ProgramPanel.Changed) -> None:
        self._programs.change(message.change, message.index)

    def on_program_panel_seek(self, message: ProgramPanel.Seek) -> None:
        self._programs.seek(message.steps)

    def on_program_panel_next_problem(self, message: ProgramPanel.NextProblem) -> None:
        self._programs.next_problem()

    def on_program_panel_plot_asked(self, message: ProgramPanel.PlotAsked) -> None:
        self._programs.plot()

    def on_program_panel_speed_asked(self, message: ProgramPanel.SpeedAsked) -> None:
        self._programs.change_speed(message.delta)

    # -- the views panel ------------------------------------------------------------
    def on_views_panel_maximised(self, message: ViewsPanel.Maximised) -> None:
        """The selected view over the whole screen: the side panel makes way."""
        self.set_class(message.maximised, "-max")

"""The control screen's keys: bindings, the help table and the legend text."""

from __future__ import annotations

from rich.text import Text
from textual import events
from textual.binding import Binding
from textual.widgets import Static

from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.validation import fmt
from dhsim_tui.core.motion.jog import REVOLUTE_STEPS_DEG
from dhsim_tui.terminal.charset import ascii_mode

#: the side panel's key hints: (keys, what they do); a pair is (Unicode,
#: 7-bit ASCII) where the ASCII form differs
Hint = tuple[str | tuple[str, str], str | tuple[str, str]]
KEY_HINTS: tuple[Hint, ...] = (
    (("↑ ↓", "up down"), "joint"),
    (("← →", "left right"), ("step (shift ×10)", "step")),
    ("[ ]", "step size"),
    (("⏎", "enter"), "exact value"),
    ("h", "home"),
    ("p", "next pose"),
    ("v", "read-out"),
    ("c", "Cartesian"),
    ("P", "save pose"),
    ("m", "smooth motion"),
    ("tab 1-4", "view"),
    ("z", "maximise view"),
    ("+ - 0", "zoom"),
    ("F", "fit the arm"),
    ("a d w s", "orbit 3-D"),
    ("x", "frames drawn"),
    ("b", "IK branch"),
    ("f", "world/tool frame"),
    ("W", "workspace"),
    ("i", "save picture"),
    ("e", "edit table"),
    ("?", "help"),
    ("q", "quit"),
    ("mouse", "click, wheel"),
)
#: the width of the left column of hints when two share a line
HINT_COLUMN = 21


def _hint(keys: str, words: str) -> str:
    return f"{keys:<{max(5, len(keys) + 1)}}{words}"


def keys_legend(ascii: bool, rows: int) -> Text:
    """The key hints under a bold title: one a line when ``rows`` hold them
    all, else two a line."""
    pick = 1 if ascii else 0
    hints = [
        _hint(
            keys[pick] if isinstance(keys, tuple) else keys,
            words[pick] if isinstance(words, tuple) else words,
        )
        for keys, words in KEY_HINTS
    ]
    text = Text()
    text.append("Keys", style="bold")
    if rows - 1 >= len(hints):
        for keys, words in KEY_HINTS:
            keys = keys[pick] if isinstance(keys, tuple) else keys
            words = words[pick] if isinstance(words, tuple) else words
            text.append(f"\n{keys:<10}{words}")
        return text
    for left, right in zip(hints[::2], [*hints[1::2], ""], strict=False):
        text.append(f"\n{left:<{HINT_COLUMN}}{right}".rstrip())
    return text


class KeyHints(Static):
    """The key hints, laid out for the rows the side panel leaves them."""

    def on_resize(self, event: events.Resize) -> None:
        self.update(keys_legend(ascii_mode(self.app), event.size.height))


#: joint jogging's arrow actions, and Cartesian jogging's (check_action shows one set)
JOINT_ACTIONS = frozenset({"select", "step"})
CARTESIAN_ACTIONS = frozenset({"row", "jog"})


def _arrows(mode: str, select: str, step: str, what: str, moves: str) -> list[Binding]:
    """The arrow keys of one jogging mode: ``select`` a row, ``step`` it."""
    return [
        Binding("up", f"{select}(-1)", what, key_display="↑↓", id=f"{mode}.prev",
                tooltip=f"Select the previous {what.lower()}"),
        Binding("down", f"{select}(1)", what, show=False, id=f"{mode}.next",
                tooltip=f"Select the next {what.lower()}"),
        Binding("left", f"{step}(-1)", moves, key_display="←→", id=f"{mode}.step_down",
                tooltip=f"{moves}: one step down"),
        Binding("right", f"{step}(1)", moves, show=False, id=f"{mode}.step_up",
                tooltip=f"{moves}: one step up"),
        Binding("shift+left", f"{step}(-10)", "×10", show=False, id=f"{mode}.big_step_down",
                tooltip="Ten steps down"),
        Binding("shift+right", f"{step}(10)", "×10", show=False, id=f"{mode}.big_step_up",
                tooltip="Ten steps up"),
    ]  # fmt: skip


#: the views' keys, on the simulator and (1-4, z, zoom, orbit) in the editor's preview
VIEW_BINDINGS = [
    Binding("tab", "next_view", "View", show=False, id="view.next", tooltip="Select the next view"),
    Binding("1", "view(0)", "Top", show=False, id="view.top", tooltip="Top view"),
    Binding("2", "view(1)", "Front", show=False, id="view.front", tooltip="Front view"),
    Binding("3", "view(2)", "Side", show=False, id="view.side", tooltip="Side view"),
    Binding("4", "view(3)", "3-D", show=False, id="view.iso", tooltip="3-D view (a d w s: orbit)"),
    Binding("z", "maximise", "Maximise", show=False, id="view.maximise",
            tooltip="The selected view over the whole screen; again: back"),
    Binding("plus,equals_sign", "zoom(1)", "Zoom in", show=False, id="view.zoom_in",
            tooltip="Zoom in about the arm"),
    Binding("minus", "zoom(-1)", "Zoom out", show=False, id="view.zoom_out",
            tooltip="Zoom out"),
    Binding("0", "zoom(0)", "Whole area", show=False, id="view.zoom_reset",
            tooltip="Back to the whole work area (reach + 30, floor at -base height)"),
    Binding("F", "fit", "Fit", show=False, id="view.fit",
            tooltip="Fit every view to the arm as it stands; again: the whole work area"),
    Binding("x", "frames", "Frames", show=False, id="view.frames",
            tooltip="Frame axes drawn: every frame, base and tool only, none"),
    Binding("a", "orbit(-1, 0)", "Orbit", show=False, id="view.orbit_left",
            tooltip="Turn the 3-D view: azimuth down"),
    Binding("d", "orbit(1, 0)", "Orbit", show=False, id="view.orbit_right",
            tooltip="Turn the 3-D view: azimuth up"),
    Binding("w", "orbit(0, 1)", "Orbit", show=False, id="view.orbit_up",
            tooltip="Turn the 3-D view: look from higher"),
    Binding("s", "orbit(0, -1)", "Orbit", show=False, id="view.orbit_down",
            tooltip="Turn the 3-D view: look from lower"),
]  # fmt: skip

CONTROL_BINDINGS = [
    *_arrows("joint", "select", "step", "Joint", "Step"),
    *_arrows("cartesian", "row", "jog", "Axis", "Move tool"),
    Binding(
        "left_square_bracket",
        "step_size(-1)",
        "Step size",
        key_display="[]",
        show=False,
        id="step.smaller",
        tooltip="Smaller step",
    ),
    Binding(
        "right_square_bracket",
        "step_size(1)",
        "Step size",
        show=False,
        id="step.larger",
        tooltip="Larger step",
    ),
    Binding(
        "enter",
        "enter_value",
        "Set",
        key_display="⏎",
        show=False,
        id="joint.enter",
        tooltip="Type the exact value of the selected row",
    ),
    Binding(
        "h,home",
        "home",
        "Home",
        id="robot.home",
        tooltip="Send every joint home (the D-H table's values)",
    ),
    Binding("p", "next_pose", "Pose", id="robot.pose", tooltip="Go to the next named pose"),
    Binding(  # not in the footer (no room at 80 columns): the pose panel's caption names it
        "v",
        "readout",
        "Readout",
        show=False,
        id="pose.readout",
        tooltip="OAT, roll-pitch-yaw or the full transform",
    ),
    *VIEW_BINDINGS,
    # c's label names the mode it switches to
    Binding(
        "c",
        "cartesian(0)",
        "Cartesian",
        id="mode.cartesian",
        tooltip="Switch to Cartesian jogging: the arrows move the tool",
    ),
    Binding(
        "c",
        "cartesian(1)",
        "Joints",
        id="mode.joints",
        tooltip="Switch back to joint jogging: the arrows step joints",
    ),
    Binding(
        "P",
        "save_pose",
        "Save pose",
        show=False,
        id="robot.save_pose",
        tooltip="Save the current joints as a named pose",
    ),
    # one key, two labels: the footer shows the state smooth motion is in
    Binding(
        "m",
        "toggle_motion(1)",
        "Motion on",
        id="motion.on",
        tooltip="Smooth moves to home and poses are on: m turns them off",
    ),
    Binding(
        "m",
        "toggle_motion(0)",
        "Motion off",
        id="motion.off",
        tooltip="Smooth moves to home and poses are off: m turns them on",
    ),
    Binding("escape", "stop", "Stop", show=False, id="motion.stop", tooltip="Stop a smooth move"),
    Binding("e", "edit", "Edit", id="robot.edit", tooltip="Edit the robot's D-H table"),
    Binding("question_mark", "help", "Help", key_display="?", id="app.help", tooltip="Every key"),
    Binding("q", "app.quit", "Quit", id="app.quit", tooltip="Quit dhsim"),
    # not in the footer (no room at 80 columns): help, the palette and the legend name them
    Binding(
        "b",
        "next_branch",
        "Branch",
        show=False,
        id="ik.next_branch",
        tooltip="The arm's next solution (IK branch) for this tool pose: the tool stays",
    ),
    # f's label names the frame it switches to; Cartesian mode only
    Binding(
        "f",
        "frame('tool')",
        "Tool frame",
        show=False,
        id="cartesian.tool_frame",
        tooltip="Jog in the TOOL frame: along and about the tool's own x, y, z",
    ),
    Binding(
        "f",
        "frame('world')",
        "World frame",
        show=False,
        id="cartesian.world_frame",
        tooltip="Jog in the WORLD frame: along and about the world's X, Y, Z",
    ),
    Binding(
        "i",
        "app.save_picture",
        "Picture",
        show=False,
        id="app.save_picture",
        tooltip="Save the screen as an SVG picture in the working folder (for a report)",
    ),
    Binding(
        "W",
        "workspace",
        "Workspace",
        show=False,
        id="view.workspace",
        tooltip="Show or hide the workspace: a faint cloud of points the tool can reach",
    ),
]


def help_rows(robot: Robot) -> list[tuple[str, str]]:
    """(keys, what they do), as the help screen lists them."""
    return [
        ("↑ ↓", "select a joint (Cartesian: an axis)"),
        ("← →", "step the selected joint (Cartesian: move the tool)"),
        ("shift+← →", "ten steps at once"),
        (
            "[ ]",
            "smaller / larger step: "
            + ", ".join(fmt(s) for s in REVOLUTE_STEPS_DEG)
            + " deg; 0.1, 1, 10, 50, 100 mm",
        ),
        ("enter", "type the joint's exact value"),
        ("h, home", "every joint home (the D-H table's values)"),
        (
            "p",
            "next named pose"
            + (
                f": {printable(', '.join(robot.pose_names))}"
                if robot.pose_names
                else " (this robot has none)"
            ),
        ),
        ("v", "read-out: OAT → roll/pitch/yaw → 4×4 transform"),
        ("tab, 1 2 3 4", "select the top, front, side or 3-D view"),
        ("z", "maximise the selected view (again: back)"),
        ("+ - 0", "zoom in / out about the arm; 0: the whole work area"),
        ("F", "fit every view to the arm as it stands (again, or 0: the work area)"),
        ("x", "frame axes drawn: every frame → base and tool only → none"),
        ("i", "save the screen as an SVG picture in the working folder (for a report)"),
        ("a d, w s", "orbit the 3-D view: azimuth, elevation (15° a press)"),
        ("c", "joint ⇄ Cartesian jogging: move the tool along X, Y, Z, turn it about them"),
        ("f", "Cartesian: along/about the world's X, Y, Z ⇄ the tool's own x, y, z (TOOL)"),
        ("b", "the arm's next solution (IK branch) for this tool pose: the tool stays"),
        ("W", "workspace: a faint cloud of points the tool can reach (again: off)"),
        ("P", "save the current joints as a named pose (and in the robot file)"),
        ("m", "smooth moves to home, poses and branches on/off; escape stops"),
        ("e", "edit the robot's D-H table"),
        ("ctrl+p", "command palette: open, import, save, export, convert, poses, views…"),
        ("?", "this help"),
        ("q", "quit"),
    ]


HELP_NOTES = (
    "\nViews: the links are the orange bars, ● a revolute joint, ■ a prismatic "
    "one, ◆ the tool; red, green, blue = each joint frame's x, y, z axes "
    "(without colour, letters at their tips; x shows fewer). Top, front and "
    "side share one scale, the same on both axes, with ticks in the robot's "
    "unit (F fits each view to the arm instead). Frames that share an origin "
    "are drawn with longer axes.\n"
    "Mouse: click a joint to select it; click or drag along its bar to set it "
    "(rounded to the step); the wheel over a joint steps it. Click a view to "
    "select it, double-click to maximise it, the wheel zooms, a drag turns "
    "the 3-D view. Shift+drag selects text to copy, as in any terminal.\n"
    "OAT (Unimation VAL): O = azimuth of the approach vector, A = its "
    "depression below horizontal, T = roll about it.\n"
    "μ (manipulability): how freely the tool can move, from 0 (singular: some "
    "direction is lost) up; yellow below 0.02, red below 0.001."
)

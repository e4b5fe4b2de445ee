"""The control screen's keys: bindings, the help table and the legend text."""

from __future__ import annotations

from textual.binding import Binding

from dhsim_tui.core.jog import REVOLUTE_STEPS_DEG
from dhsim_tui.core.model import Robot
from dhsim_tui.core.text import printable
from dhsim_tui.core.validation import fmt

KEYS_LEGEND = (
    "[b]Keys[/]\n"
    "↑ ↓  joint          ← →  step (shift ×10)\n"
    "[ ]  step size      ⏎    exact value\n"
    "h    home           p    next pose\n"
    "v    read-out       tab 1 2 3  view\n"
    "c    Cartesian      P    save pose\n"
    "m    smooth motion  e    edit table\n"
    "?    help           q    quit"
)

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
    Binding("tab", "next_view", "View", show=False, id="view.next", tooltip="Show the next view"),
    Binding("1", "view(0)", "Top", show=False, id="view.top", tooltip="Top view"),
    Binding("2", "view(1)", "Front", show=False, id="view.front", tooltip="Front view"),
    Binding("3", "view(2)", "Side", show=False, id="view.side", tooltip="Side view"),
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
        ("tab, 1 2 3", "show the top, front or side view"),
        ("c", "joint ⇄ Cartesian jogging: X, Y, Z in the world, turns about the tool"),
        ("P", "save the current joints as a named pose (and in the robot file)"),
        ("m", "smooth moves to home and poses on/off; escape stops"),
        ("e", "edit the robot's D-H table"),
        ("?", "this help"),
        ("q", "quit"),
    ]


HELP_NOTES = (
    "\nViews: red, green, blue = each joint frame's x, y, z axes; ◆ = the tool. "
    "Both axes of a view have the same scale. Frames that share an origin "
    "are drawn with longer axes.\nOAT (Unimation VAL): O = azimuth of the "
    "approach vector, A = its depression below horizontal, T = roll about it."
)

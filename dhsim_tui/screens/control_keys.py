"""The control screen's keys: bindings, the help table and the legend text."""

from __future__ import annotations

from textual.binding import Binding

from dhsim_tui.core.jog import REVOLUTE_STEPS_DEG
from dhsim_tui.core.model import Robot
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

CONTROL_BINDINGS = [
    Binding(
        "up",
        "select(-1)",
        "Joint",
        key_display="↑↓",
        id="joint.prev",
        tooltip="Select the previous joint",
    ),
    Binding(
        "down",
        "select(1)",
        "Joint",
        show=False,
        id="joint.next",
        tooltip="Select the next joint",
    ),
    Binding(
        "left",
        "step(-1)",
        "Step",
        key_display="←→",
        id="joint.step_down",
        tooltip="Step the selected joint down",
    ),
    Binding(
        "right",
        "step(1)",
        "Step",
        show=False,
        id="joint.step_up",
        tooltip="Step the selected joint up",
    ),
    Binding(
        "shift+left",
        "step(-10)",
        "×10",
        show=False,
        id="joint.big_step_down",
        tooltip="Ten steps down",
    ),
    Binding(
        "shift+right",
        "step(10)",
        "×10",
        show=False,
        id="joint.big_step_up",
        tooltip="Ten steps up",
    ),
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
        tooltip="Type the selected joint's exact value",
    ),
    Binding(
        "h,home",
        "home",
        "Home",
        id="robot.home",
        tooltip="Send every joint home (the D-H table's values)",
    ),
    Binding("p", "next_pose", "Pose", id="robot.pose", tooltip="Go to the next named pose"),
    Binding(
        "v",
        "readout",
        "Readout",
        id="pose.readout",
        tooltip="OAT, roll-pitch-yaw or the full transform",
    ),
    Binding("tab", "next_view", "View", show=False, id="view.next", tooltip="Show the next view"),
    Binding("1", "view(0)", "Top", show=False, id="view.top", tooltip="Top view"),
    Binding("2", "view(1)", "Front", show=False, id="view.front", tooltip="Front view"),
    Binding("3", "view(2)", "Side", show=False, id="view.side", tooltip="Side view"),
    Binding(
        "c",
        "cartesian",
        "Cart",
        id="mode.cartesian",
        tooltip="Switch between joint and Cartesian jogging",
    ),
    Binding(
        "P",
        "save_pose",
        "Save pose",
        show=False,
        id="robot.save_pose",
        tooltip="Save the current joints as a named pose",
    ),
    Binding(
        "m",
        "toggle_motion",
        "Motion",
        show=False,
        id="motion.toggle",
        tooltip="Smooth moves to home and poses on or off",
    ),
    Binding("e", "edit", "Edit", id="robot.edit", tooltip="Edit the robot's D-H table"),
    Binding("question_mark", "help", "Help", key_display="?", id="app.help", tooltip="Every key"),
    Binding("q", "app.quit", "Quit", id="app.quit", tooltip="Quit dhsim"),
]


def help_rows(robot: Robot) -> list[tuple[str, str]]:
    """(keys, what they do), as the help screen lists them."""
    return [
        ("↑ ↓", "select a joint"),
        ("← →", "step the selected joint"),
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
                f": {', '.join(robot.pose_names)}" if robot.pose_names else " (this robot has none)"
            ),
        ),
        ("v", "read-out: OAT → roll/pitch/yaw → 4×4 transform"),
        ("tab, 1 2 3", "show the top, front or side view"),
        ("c", "joint ⇄ Cartesian jogging: X, Y, Z in the world, turns about the tool"),
        ("P", "save the current joints as a named pose (and in the robot file)"),
        ("m", "smooth moves to home and poses on/off (any key stops a move)"),
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

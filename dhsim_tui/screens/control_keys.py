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
    "\\[ ]  step size      ⏎    exact value\n"
    "h    home           p    next pose\n"
    "v    read-out       c    Cartesian\n"
    "P    save pose      m    smooth motion\n"
    "tab 1-4  view       z    maximise view\n"
    "+ - 0  zoom         a d w s  orbit 3-D\n"
    "b    IK branch      f    world/tool frame\n"
    "W    workspace      e    edit table\n"
    "?    help           q    quit"
)
#: the same in 7-bit ASCII
KEYS_LEGEND_ASCII = (
    "[b]Keys[/]\n"
    "up down  joint      left right  step\n"
    "\\[ ]  step size      enter  exact value\n"
    "h    home           p    next pose\n"
    "v    read-out       c    Cartesian\n"
    "P    save pose      m    smooth motion\n"
    "tab 1-4  view       z    maximise view\n"
    "+ - 0  zoom         a d w s  orbit 3-D\n"
    "b    IK branch      f    world/tool frame\n"
    "W    workspace      e    edit table\n"
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
    "\nViews: red, green, blue = each joint frame's x, y, z axes (without colour, "
    "letters at their tips); ◆ = the tool. Top, front and side share one scale, "
    "the same on both axes, with ticks in the robot's unit. Frames that share an "
    "origin are drawn with longer axes.\nOAT (Unimation VAL): O = azimuth of the "
    "approach vector, A = its depression below horizontal, T = roll about it."
)

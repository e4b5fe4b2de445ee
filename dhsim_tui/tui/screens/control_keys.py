"""The control screen's own keys, and the key legend and help made from every
key in effect: the focused panel's (joints or Cartesian), the screen's, the
views panel's (handed on by the screen) and the app's."""

from __future__ import annotations

from rich.text import Text
from textual import events
from textual.actions import parse
from textual.binding import Binding
from textual.dom import DOMNode
from textual.widgets import Static

from dhsim_tui.terminal.charset import ascii_mode
from dhsim_tui.tui.keys import Keys, forwarded, legend_rows
from dhsim_tui.tui.widgets.view_keys import BINDINGS as VIEW_BINDINGS

HOME = Keys("home", help="every joint home: the D-H table's values less the offsets")
POSE = Keys("next pose", help="next named pose")
READOUT = Keys("read-out", help="read-out: OAT → roll/pitch/yaw → 4×4 transform")
CARTESIAN = Keys(
    "Cartesian",
    help="Cartesian jogging: the arrows move the tool along X, Y, Z, turn it about them",
)
JOINTS = Keys("joints", help="back to joint jogging: the arrows step joints")
SAVE_POSE = Keys(
    "save pose", help="save the current joints as a named pose (and in the robot file)"
)
MOTION = Keys("smooth motion", help="smooth moves to home, poses and branches on/off")
STOP = Keys(legend=False, help="stop a smooth move where the arm is")
BRANCH = Keys(
    "IK branch", help="the arm's next solution (IK branch) for this tool pose: the tool stays"
)
WORKSPACE = Keys(
    "workspace", help="workspace: a faint cloud of points the tool can reach (again: off)"
)
PICTURE = Keys(
    "save picture", help="save the screen as an SVG picture in the working folder (for a report)"
)
PROGRAM = Keys("program", help="the program panel: its steps (again: back to the joints)")
RECORD = Keys(
    "record step", help="record the current pose as the program's next step (a joint move)"
)
RECORD_MOVE = Keys(
    legend=False, help="what R records: a joint move ⇄ a linear move (the tool in a line)"
)
PLAY = Keys("play/pause", help="play the program in the views, in real time; again: pause")
EDIT = Keys("edit table", help="edit the robot's D-H table")
HELP = Keys("help", help="this help")
QUIT = Keys("quit", help="quit")

CONTROL_BINDINGS = [
    Binding("h,home", "home", "Home", id="robot.home",
            tooltip="Send every joint home: the D-H table's values less the offsets", group=HOME),
    Binding("p", "next_pose", "Pose", id="robot.pose", tooltip="Go to the next named pose",
            group=POSE),
    # not in the footer (no room at 80 columns): the pose panel's caption names it
    Binding("v", "readout", "Readout", show=False, id="pose.readout",
            tooltip="OAT, roll-pitch-yaw or the full transform", group=READOUT),
    # c's label names the mode it switches to
    Binding("c", "switch('cartesian')", "Cartesian", id="mode.cartesian",
            tooltip="Switch to Cartesian jogging: the arrows move the tool", group=CARTESIAN),
    Binding("c", "switch('joints')", "Joints", id="mode.joints",
            tooltip="Switch back to joint jogging: the arrows step joints", group=JOINTS),
    Binding("P", "save_pose", "Save pose", show=False, id="robot.save_pose",
            tooltip="Save the current joints as a named pose", group=SAVE_POSE),
    # one key, two labels: the footer shows the state smooth motion is in
    Binding("m", "toggle_motion(1)", "Motion on", id="motion.on",
            tooltip="Smooth moves to home and poses are on: m turns them off", group=MOTION),
    Binding("m", "toggle_motion(0)", "Motion off", id="motion.off",
            tooltip="Smooth moves to home and poses are off: m turns them on", group=MOTION),
    Binding("escape", "stop", "Stop", show=False, id="motion.stop",
            tooltip="Stop a smooth move, or the sampling of a program", group=STOP),
    *forwarded(VIEW_BINDINGS, "views"),
    # not in the footer (no room at 80 columns): help, the palette and the legend name them
    Binding("b", "next_branch", "Branch", show=False, id="ik.next_branch",
            tooltip="The arm's next solution (IK branch) for this tool pose: the tool stays",
            group=BRANCH),
    Binding("W", "workspace", "Workspace", show=False, id="view.workspace",
            tooltip="Show or hide the workspace: a faint cloud of points the tool can reach",
            group=WORKSPACE),
    Binding("i", "app.save_picture", "Picture", show=False, id="app.save_picture",
            tooltip="Save the screen as an SVG picture in the working folder (for a report)",
            group=PICTURE),
    Binding("g", "switch('program')", "Program", show=False, id="program.show",
            tooltip="The program panel: select, change and play its steps", group=PROGRAM),
    Binding("R", "record", "Record", show=False, id="program.record",
            tooltip="Record the current pose as the program's next step", group=RECORD),
    Binding("L", "record_move", "Record joint/linear", show=False, id="program.record_move",
            tooltip="What R records: a joint move, or a linear move", group=RECORD_MOVE),
    Binding("space", "play", "Play", show=False, id="program.play",
            tooltip="Play the program from the start, or pause and go on", group=PLAY),
    Binding("e", "edit", "Edit", id="robot.edit", tooltip="Edit the robot's D-H table",
            group=EDIT),
    Binding("question_mark", "help", "Help", key_display="?", id="app.help", tooltip="Every key",
            group=HELP),
    Binding("q", "app.quit", "Quit", id="app.quit", tooltip="Quit dhsim", group=QUIT),
]  # fmt: skip


def bindings_in_effect(screen: DOMNode) -> list[Binding]:
    """The keys that do something now, in the order a key is looked up: the
    focused widget's and its containers', the screen's, then the app's. A
    binding its node's ``check_action`` hides (False) is left out."""
    chain: list[DOMNode] = []
    node = getattr(screen, "focused", None)
    while node is not None and node is not screen:
        chain.append(node)
        node = node.parent
    chain += [screen, screen.app]
    found = []
    for node in chain:
        for binding in getattr(node, "BINDINGS", []):
            if not isinstance(binding, Binding):  # a (key, action, description) tuple
                binding = Binding(*binding)
            namespace, name, parameters = parse(binding.action)
            if namespace == "app":
                target: DOMNode = screen.app
            else:
                target = node
            if target.check_action(name, parameters) is not False:
                found.append(binding)
    return found


#: the width of the left column of hints when two share a line
HINT_COLUMN = 21


def _cell(keys: str, words: str, room: int) -> str:
    """One hint of two on a line: a parenthesis that does not fit in ``room``
    columns is left out (``step (shift ×10)``)."""
    cell = f"{keys:<{max(5, len(keys) + 1)}}{words}"
    if len(cell) > room and words.endswith(")") and " (" in words:
        cell = cell[: cell.rindex(" (")]
    return cell


def keys_legend(bindings: list[Binding], ascii: bool, rows: int, width: int = 42) -> Text:
    """The key hints under a bold title: one a line when ``rows`` hold them
    all, else two a line (in ``width`` columns)."""
    hints = legend_rows(bindings, ascii)
    text = Text()
    text.append("Keys", style="bold")
    if rows - 1 >= len(hints):
        for keys, words in hints:
            text.append(f"\n{keys:<10}{words}")
        return text
    left = [_cell(keys, words, HINT_COLUMN - 1) for keys, words in hints[::2]]
    column = max(HINT_COLUMN, *(len(cell) + 1 for cell in left))  # never run together
    right = [_cell(keys, words, width - column) for keys, words in hints[1::2]]
    for one, other in zip(left, [*right, ""], strict=False):
        text.append(f"\n{one:<{column}}{other}".rstrip())
    return text


class KeyHints(Static):
    """The key hints, laid out for the rows the side panel leaves them, for
    the keys in effect (``refresh_hints`` when they change)."""

    def on_resize(self, event: events.Resize) -> None:
        self.refresh_hints()

    def refresh_hints(self) -> None:
        if self.is_attached and self.size.height:
            bindings = bindings_in_effect(self.screen)
            size = self.content_size
            self.update(keys_legend(bindings, ascii_mode(self.app), size.height, size.width))


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
    "direction is lost) up; yellow below 0.02, red below 0.001.\n"
    "Offsets: a joint's value q is theta - offset (d - offset for a prismatic "
    "joint), so home is the table's theta less its offset. From the Robotics "
    "Toolbox: copy d, a, alpha and offset, and set theta = offset (d = offset "
    "for a prismatic joint): its q = 0 is home here too."
)

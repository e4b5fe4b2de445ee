"""The editor's keys: bindings and the help table.

The footer shows them in this order, so that at 80 columns the way back
(escape), help and saving are always visible."""

from __future__ import annotations

from textual.binding import Binding

EDITOR_BINDINGS = [
    Binding(
        "escape",
        "leave",
        "Back",
        key_display="esc",
        id="edit.leave",
        tooltip="Back to the simulator (asks about unsaved changes)",
    ),
    Binding("question_mark", "help", "Help", key_display="?", id="edit.help", tooltip="Every key"),
    Binding(
        "ctrl+s",
        "save",
        "Save",
        key_display="^s",
        id="file.save",
        tooltip="Save the robot (atomically; asks if the file changed on disk)",
    ),
    Binding(
        "S",
        "save_as",
        "Save as",
        key_display="S",
        id="file.save_as",
        tooltip="Save the robot under another name (robots/<name>.toml)",
    ),
    Binding("ctrl+z", "undo", "Undo", key_display="^z", id="edit.undo", tooltip="Undo"),
    Binding(
        "t",
        "toggle_type",
        "R/P",
        id="edit.toggle_type",
        tooltip="Make the joint prismatic or revolute",
    ),
    Binding(
        "a,insert",
        "add",
        "Add",
        id="edit.add",
        tooltip="Add a joint after the cursor (a pose in the fields table)",
    ),
    Binding(
        "d,delete",
        "delete",
        "Delete",
        id="edit.delete",
        tooltip="Delete the joint (or the pose) under the cursor",
    ),
    Binding("ctrl+y", "redo", "Redo", key_display="^y", id="edit.redo", tooltip="Redo"),
    Binding(
        "ctrl+o",
        "open",
        "Open",
        key_display="^o",
        id="file.open",
        tooltip="Open a robot file, or import a .urdf or .csv file",
    ),
    Binding(
        "x",
        "export",
        "Export",
        id="file.export",
        tooltip="Export the robot as URDF, CSV or JSON (asks the format and a file name)",
    ),
    Binding(
        "ctrl+up",
        "move(-1)",
        "Move",
        key_display="^↑↓",
        id="edit.move_up",
        tooltip="Move the joint up",
    ),
    Binding(
        "ctrl+down",
        "move(1)",
        "Move",
        show=False,
        id="edit.move_down",
        tooltip="Move the joint down",
    ),
    Binding("1", "preview(0)", "Top", show=False, id="preview.top", tooltip="Top view"),
    Binding("2", "preview(1)", "Front", show=False, id="preview.front", tooltip="Front view"),
    Binding("3", "preview(2)", "Side", show=False, id="preview.side", tooltip="Side view"),
    Binding("4", "preview(3)", "3-D", show=False, id="preview.iso", tooltip="3-D view"),
    Binding(
        "q",
        "explain_quit",
        "Quit?",
        show=False,
        id="edit.quit_hint",
        tooltip="Says how to leave the editor and how to quit",
    ),
]

EDITOR_HELP_ROWS = [
    ("arrows", "move in the table (a wide table scrolls sideways)"),
    ("enter", "edit the cell or field under the cursor (type: a choice of R or P)"),
    ("t", "revolute <-> prismatic (switched back: its own limits again)"),
    ("a, insert", "add a joint after the cursor; in the fields table, a pose"),
    ("d, delete", "delete the joint or pose (asks first)"),
    ("ctrl+↑ ctrl+↓", "move the joint up or down"),
    ("ctrl+z, ctrl+y", "undo, redo (the status line says what changed)"),
    ("ctrl+o", "open a robot, or import a .urdf or .csv file (saved as a new .toml)"),
    ("ctrl+s", "save (atomic; asks if the file changed on disk since it was opened)"),
    ("S", "save as another file, robots/<name>.toml"),
    ("x", "export as URDF, CSV or JSON (asks the format and a file name)"),
    ("ctrl+p", "command palette: every command by name (convert to the other D-H too)"),
    ("tab", "joints table <-> robot fields and poses"),
    ("1 2 3 4", "preview: top, front, side, 3-D"),
    ("escape", "back to the simulator (asks about unsaved changes)"),
    ("ctrl+q", "quit dhsim (asks about unsaved changes)"),
]

EDITOR_HELP_NOTES = (
    "\nA joint's variable (theta for R, d for P, marked *) is the D-H value at "
    "home. The joint value q (what limits, poses and the simulator use) is "
    "theta - offset, so the home column shows home = theta - offset, which "
    "must lie within min..max (degrees for R, the robot's unit for P). "
    "A new offset shows what home becomes and asks what stays: theta (the "
    "arm's home pose) or the home joint value (theta follows the offset). "
    "From the Robotics Toolbox: copy d, a, alpha and offset (angles in "
    "degrees), and set theta = offset (d = offset for P): its q = 0 is home. "
    "A rejected value shows why and changes nothing."
)

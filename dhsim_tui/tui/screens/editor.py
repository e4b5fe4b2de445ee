"""The table editor: D-H rows and robot fields, live preview, undo, open (and
import), save, export and convert.

Every edit goes through :mod:`dhsim_tui.core.model.editing`, which returns a new
valid robot or raises DhsimError; a rejected value is shown where it was
typed and the robot stays as it was (the edits: :mod:`editor_edits`). Saves
go through :mod:`save_flow`: atomic, and never over a file that changed on
disk without asking (the file commands: :mod:`editor_files`).

A burst of keys is cheap: an edit changes the robot in memory at once, and
the tables (only the cells that changed), title and preview are redrawn
once per frame, however many keys came in it.
"""

from __future__ import annotations

from pathlib import Path
from time import monotonic

from rich.text import Text
from textual import work
from textual.app import ComposeResult
from textual.await_complete import AwaitComplete
from textual.containers import Horizontal, Vertical
from textual.coordinate import Coordinate
from textual.events import Resize
from textual.markup import escape
from textual.screen import Screen
from textual.widgets import DataTable, Static

from dhsim_tui.core.files.robotfile import FileStamp, read_stamp
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError, RobotFileError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.scene import build_wireframe
from dhsim_tui.terminal.charset import ascii_mode, shown
from dhsim_tui.terminal.typeahead import FRAME, draw_later
from dhsim_tui.tui.flows.export import export_flow
from dhsim_tui.tui.flows.save import is_bundled
from dhsim_tui.tui.screens.dialogs import SaveGuard
from dhsim_tui.tui.screens.editor_commands import editor_commands
from dhsim_tui.tui.screens.editor_edits import (
    add_here,
    convert_robot,
    delete_here,
    edit_joint_value,
    edit_robot_field,
    move_joint,
    toggle_type,
    undo_redo,
)
from dhsim_tui.tui.screens.editor_files import open_in_editor, save_edited
from dhsim_tui.tui.screens.editor_keys import EDITOR_BINDINGS, EDITOR_HELP_NOTES, EDITOR_HELP_ROWS
from dhsim_tui.tui.screens.editor_table import (
    JOINT_COLUMNS,
    FittedTable,
    field_rows,
    file_words,
    joint_labels,
    joint_rows,
)
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.widgets.footer import KeysFooter
from dhsim_tui.tui.widgets.views_panel import ViewsPanel, is_wide

__all__ = ["EditorScreen", "is_bundled"]

QUIT_HINT = "q does not quit here: escape goes back to the simulator, ctrl+q quits"


class EditorScreen(Screen[tuple[Robot, Path | None] | None]):
    """Edit a robot in a table (the keys: :mod:`editor_keys`).

    Dismisses with (robot, path) to run, or None to keep what was running.
    """

    BINDINGS = EDITOR_BINDINGS

    _left = False  # dismissed: a second leave does nothing

    def __init__(
        self,
        robot: Robot,
        path: Path | None,
        renderer: str = "plotext",
        saved: Robot | None = None,
        stamp: FileStamp | None = None,
        *,
        new_text: str | None = None,
        imported_from: Path | None = None,
        first_edit: tuple[Robot, str] | None = None,
    ) -> None:
        """``saved`` is the robot as its file holds it (None: not saved
        anywhere); ``stamp`` what the file held when it was read (read at
        mount when not given). A robot with no file: ``new_text`` is where
        the file it is saved to starts (an import's comments),
        ``imported_from`` the file it was imported from. ``first_edit``:
        (robot, message), an edit made as the editor opens (undo reverts it)."""
        super().__init__()
        self.history = editing.History(robot)
        self.new_text = new_text
        self.imported_from = imported_from
        self._first_edit = first_edit
        bundled = is_bundled(path)
        self.path = None if bundled else path
        self.template = path if bundled else None
        self.saved: Robot | None = saved
        self.stamp = stamp
        self.renderer = renderer
        self._ready = False
        self._redraw_pending = False
        self._drawn_at = 0.0  # when the robot was last drawn (time.monotonic)
        #: the joints table's row for the cursor at the next redraw (after add, move)
        self._cursor_row: int | None = None
        #: the fields table's row (its key) for the cursor at the next redraw (a new pose)
        self.field_cursor: str | None = None
        #: the joints' switches of type, to switch back with their own limits
        #: (editor_joint_values.Retype)
        self.retyped: list = []

    # -- state ------------------------------------------------------------------
    @property
    def robot(self) -> Robot:
        return self.history.current

    @property
    def dirty(self) -> bool:
        return self.robot != self.saved

    # -- layout -------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        # the joints across the top; under them the robot's fields and the
        # status beside the preview, which gets half the width and the whole
        # height left (its links drawn, not only its joints)
        with Vertical(id="editor-layout"):
            # "#" stays in view when a wide table scrolls sideways
            yield FittedTable(
                id="joints-table", cursor_type="cell", zebra_stripes=True, fixed_columns=1
            )
            with Horizontal(id="editor-lower"):
                with Vertical(id="editor-side"):
                    yield FittedTable(id="fields-table", cursor_type="row", zebra_stripes=True)
                    yield Static("", id="editor-status")
                yield ViewsPanel(self.renderer, id="preview")
        yield KeysFooter()

    def on_mount(self) -> None:
        self._preview = self.query_one(ViewsPanel)
        self._joints = self.query_one("#joints-table", FittedTable)
        self._fields = self.query_one("#fields-table", FittedTable)
        if self.stamp is None and self.path is not None:
            try:
                self.stamp = read_stamp(self.path)
            except RobotFileError:
                self.stamp = None  # unreadable now: the save will say why
        # framed on the arm, so its links are drawn long enough to see
        self._preview.fit = True
        self._ready = True
        self._apply_size(self.app.size.width, self.app.size.height)
        if self._first_edit is not None:
            robot, message = self._first_edit
            self._first_edit = None
            if self.history.push(robot):
                self.say(message)
        self._redraw()
        # the first cell Enter edits: joint 1's theta (# is only a number)
        self._joints.move_cursor(row=0, column=JOINT_COLUMNS.index("theta"))
        self._joints.focus()

    def on_resize(self, event: Resize) -> None:
        self._apply_size(event.size.width, event.size.height)

    def _apply_size(self, width: int, height: int) -> None:
        self.set_class(is_wide(width, height), "-wide")

    # -- showing the robot ---------------------------------------------------
    def refresh_robot(self, cursor_row: int | None = None) -> None:
        """The robot changed: redraw once the keys already waiting have been
        handled (one redraw per frame); ``cursor_row`` is where the joints
        table's cursor goes then."""
        if cursor_row is not None:
            self._cursor_row = cursor_row
        if not self._redraw_pending:
            self._redraw_pending = True
            self.call_after_refresh(self._redraw)

    def _redraw(self) -> None:
        """Tables, title and preview from the current robot (one-way flow);
        while more keys of a burst wait, a frame later."""
        now = monotonic()
        if draw_later(self.app, self._drawn_at, now):
            self.set_timer(FRAME, self._redraw)
            return
        self._redraw_pending = False
        self._drawn_at = now
        robot = self.robot
        self._joints.show(joint_labels(robot), joint_rows(robot))
        self._joints.border_subtitle = shown(
            "* D-H variable at home · home joint value = * - offset", self.app
        )
        if self._cursor_row is not None:
            self._joints.move_cursor(row=min(self._cursor_row, robot.dof - 1))
            self._cursor_row = None
        mark = (" *" if ascii_mode(self.app) else " ●") if self.dirty else ""
        where = file_words(self.path, self.template, self.imported_from)
        name = printable(robot.name)
        title = f"{name}{mark} · {robot.type_string} · {where}"
        self._joints.border_title = escape(shown(title, self.app))
        self._fields.show(("field", "value"), field_rows(robot))
        if self.field_cursor is not None:
            keys = [key for key, _ in field_rows(robot)]
            if self.field_cursor in keys:
                self._fields.move_cursor(row=keys.index(self.field_cursor))
            self.field_cursor = None
        self._fields.border_title = shown("Robot · poses (a adds, d deletes)", self.app)
        self.app.sub_title = f"{name}{mark}"
        frames = robot.kinematics.frames(robot.home)
        self._preview.show(build_wireframe(robot, frames))
        self._refresh_keys()

    def _refresh_keys(self) -> None:
        """Re-check which keys apply, only when that can have changed (the
        footer rebuilds itself on every refresh_bindings)."""
        state = (self.history.can_undo, self.history.can_redo, self.in_joints())
        if state != getattr(self, "_key_state", None):
            self._key_state = state
            self.refresh_bindings()

    def say(self, message: str, error: bool = False) -> None:
        text = shown(printable(message), self.app)  # user text: escaped, never markup
        status = self.query_one("#editor-status", Static)
        if status.has_class("-error") != error:
            status.set_class(error, "-error")
        elif str(status.content) == text:
            return  # the same words again (a burst of one key): nothing to redraw
        # a new layout only when the line takes another height (min 2, max 6
        # rows): a layout pass per key was most of a burst's cost
        width = status.content_region.width
        old = self._status_height(str(status.content), width)
        status.update(Text(text), layout=not width or old != self._status_height(text, width))

    def _status_height(self, text: str, width: int) -> int:
        """The status line's rows for ``text`` at ``width`` (its CSS: 2 to 6)."""
        rows = len(Text(text).wrap(self.app.console, width)) if width else 0
        return min(max(rows, 2), 6)

    def push_edit(self, robot: Robot, message: str, cursor_row: int | None = None) -> None:
        """``robot`` becomes the edited robot (undo reverts it) and ``message``
        says what changed; nothing happens when it is the same robot."""
        if self.history.push(robot):
            self.refresh_robot(cursor_row)
            self.say(message)

    def attempt(self, edit, message: str, cursor_row: int | None = None) -> bool:
        """Run an edit; on DhsimError show why and change nothing."""
        try:
            robot = edit()
        except DhsimError as exc:
            self.say(str(exc), error=True)
            return False
        self.push_edit(robot, message, cursor_row)
        return True

    # -- where the cursor is -------------------------------------------------
    def in_joints(self) -> bool:
        """The cursor is in the joints table (else in the robot's fields)."""
        return self.focused is self._joints

    def joint_index(self) -> int:
        """The joint under the cursor (where it will be, if a redraw is due)."""
        row = self._joints.cursor_row if self._cursor_row is None else self._cursor_row
        return max(0, min(row, self.robot.dof - 1))

    def field_key(self) -> str:
        """The key of the robot field under the cursor (``pose:<name>`` for a pose)."""
        fields = self._fields
        if fields.row_count == 0:
            return ""
        return str(fields.coordinate_to_cell_key(Coordinate(fields.cursor_row, 0)).row_key.value)

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if not self._ready:  # keys that arrive before the tables exist do nothing
            return False
        if action in ("toggle_type", "move") and not self.in_joints():
            return None
        if action == "undo" and not self.history.can_undo:
            return None
        if action == "redo" and not self.history.can_redo:
            return None
        return True

    def on_descendant_focus(self) -> None:
        self._refresh_keys()

    # -- editing cells --------------------------------------------------------
    def on_data_table_cell_selected(self, event: DataTable.CellSelected) -> None:
        event.stop()
        column = JOINT_COLUMNS[event.coordinate.column]
        index = min(event.coordinate.row, self.robot.dof - 1)
        if column == "#":
            self.say(
                "# is the joint's number, not a value: ctrl+↑ ctrl+↓ move the joint, "
                "a adds one, d deletes it; → goes to its values",
                error=True,
            )
        else:
            self.edit_joint_field(index, column)

    def on_data_table_row_selected(self, event: DataTable.RowSelected) -> None:
        event.stop()
        if event.data_table.id == "fields-table":
            self.edit_field(str(event.row_key.value))

    @work(exclusive=True, group="modal")
    async def edit_joint_field(self, index: int, name: str) -> None:
        await edit_joint_value(self, index, name)

    @work(exclusive=True, group="modal")
    async def edit_field(self, key: str) -> None:
        await edit_robot_field(self, key)

    # -- table actions (editor_edits.py) ----------------------------------------
    def action_toggle_type(self) -> None:
        toggle_type(self)

    @work(exclusive=True, group="modal")
    async def action_add(self) -> None:
        await add_here(self)

    @work(exclusive=True, group="modal")
    async def action_delete(self) -> None:
        await delete_here(self)

    def action_move(self, delta: int) -> None:
        move_joint(self, delta)

    def action_undo(self) -> None:
        undo_redo(self, undo=True)

    def action_redo(self) -> None:
        undo_redo(self, undo=False)

    def palette_commands(self) -> list:
        """The command palette's commands for the editor as it is now."""
        return list(editor_commands(self.app, self))

    def action_preview(self, index: int) -> None:
        self._preview.select(index)

    def action_explain_quit(self) -> None:
        self.say(QUIT_HINT)

    # -- files -------------------------------------------------------------------
    async def save_robot(self, save_as: bool = False) -> bool:
        """Save (asking a name when needed); True once nothing is unsaved
        (:mod:`editor_files`: a reload puts my edits back on the file's robot)."""
        return await save_edited(self, save_as)

    @work(exclusive=True, group="modal")
    async def action_save(self) -> None:
        await self.save_robot()

    @work(exclusive=True, group="modal")
    async def action_save_as(self) -> None:
        await self.save_robot(save_as=True)

    async def guard(self, doing: str) -> bool:
        """True when it is fine to go on: nothing unsaved, saved now, or discarded."""
        if not self.dirty:
            return True
        answer = await self.app.push_screen_wait(SaveGuard(self.robot.name, doing))
        if answer == "save":
            return await self.save_robot()
        return answer == "discard"

    @work(exclusive=True, group="modal")
    async def action_open(self, importing: bool = False) -> None:
        """Open a robot file, or import a .urdf/.csv (``importing``: only those)."""
        await open_in_editor(self, importing)

    @work(exclusive=True, group="modal")
    async def action_export(self) -> None:
        """Export the robot as it is here (unsaved edits too): URDF, CSV or JSON."""
        await export_flow(self.app, self.robot, self.path or self.template, report=self.say)

    def other_convention(self) -> str:
        return "modified" if self.robot.convention == "standard" else "standard"

    def action_convert(self) -> None:
        """The same arm in the other D-H convention: one edit, which undo reverts."""
        convert_robot(self, self.other_convention())

    def dismiss(self, result=None):
        """Leave once, and only from the front: Textual's dismiss pops whatever
        screen is in front, so a second leave, or one that lands while a
        dialog or the help is over the editor (keys typed ahead of a slow
        machine), took away the simulator under it and left a blank screen
        (the long monkey's hangs)."""
        if self._left or self.app.screen is not self:
            return AwaitComplete()
        self._left = True
        return super().dismiss(result)

    @work(exclusive=True, group="modal")
    async def action_leave(self) -> None:
        if not await self.guard("leaving the editor"):
            return
        if self.saved is None:
            self.dismiss(None)
        else:
            self.dismiss((self.saved, self.path or self.template))

    def action_help(self) -> None:
        self.app.push_screen(HelpScreen("Editor keys", EDITOR_HELP_ROWS, EDITOR_HELP_NOTES))

"""The table editor: D-H rows and robot fields, live preview, undo, open (and
import), save, export and convert.

Every edit goes through :mod:`dhsim_tui.core.model.editing`, which returns a new
valid robot or raises DhsimError; a rejected value is shown where it was
typed and the robot stays as it was. Saves go through :mod:`save_flow`:
atomic, and never over a file that changed on disk without asking.

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
from textual.containers import Container, Vertical
from textual.coordinate import Coordinate
from textual.events import Resize
from textual.markup import escape
from textual.screen import Screen
from textual.widgets import DataTable, Footer, Static

from dhsim_tui.core.files.robotfile import FileStamp, read_stamp
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError, RobotFileError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.scene import build_wireframe
from dhsim_tui.terminal.charset import ascii_mode, shown
from dhsim_tui.terminal.typeahead import FRAME, draw_later
from dhsim_tui.tui.flows.export import export_flow
from dhsim_tui.tui.flows.fields import ask_field, ask_joint_field, ask_new_pose_name
from dhsim_tui.tui.flows.recover import offer_recovery
from dhsim_tui.tui.flows.save import is_bundled, reapply_edits, save_flow
from dhsim_tui.tui.screens.dialogs import Confirm, SaveGuard, short_path
from dhsim_tui.tui.screens.editor_changes import describe_change
from dhsim_tui.tui.screens.editor_commands import editor_commands
from dhsim_tui.tui.screens.editor_keys import EDITOR_BINDINGS, EDITOR_HELP_NOTES, EDITOR_HELP_ROWS
from dhsim_tui.tui.screens.editor_table import (
    JOINT_COLUMNS,
    FittedTable,
    field_rows,
    joint_labels,
    joint_rows,
)
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.screens.open_robot import ROBOTS_DIR, ImportNotes, Opened, OpenRobot, header_text
from dhsim_tui.tui.widgets.views_panel import ViewsPanel, is_wide

__all__ = ["EditorScreen", "is_bundled"]

QUIT_HINT = "q does not quit here: escape goes back to the simulator, ctrl+q quits"


class EditorScreen(Screen[tuple[Robot, Path | None] | None]):
    """Edit a robot in a table (the keys: :mod:`editor_keys`).

    Dismisses with (robot, path) to run, or None to keep what was running.
    """

    BINDINGS = EDITOR_BINDINGS

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
        self._field_row: str | None = None

    # -- state ------------------------------------------------------------------
    @property
    def robot(self) -> Robot:
        return self.history.current

    @property
    def dirty(self) -> bool:
        return self.robot != self.saved

    # -- layout -------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        with Container(id="editor-layout"):
            with Vertical(id="editor-tables"):
                # "#" stays in view when a wide table scrolls sideways
                yield FittedTable(
                    id="joints-table", cursor_type="cell", zebra_stripes=True, fixed_columns=1
                )
                yield FittedTable(id="fields-table", cursor_type="row", zebra_stripes=True)
                yield Static("", id="editor-status")
            yield ViewsPanel(self.renderer, id="preview")
        yield Footer()

    def on_mount(self) -> None:
        self._preview = self.query_one(ViewsPanel)
        self._joints = self.query_one("#joints-table", FittedTable)
        self._fields = self.query_one("#fields-table", FittedTable)
        if self.stamp is None and self.path is not None:
            try:
                self.stamp = read_stamp(self.path)
            except RobotFileError:
                self.stamp = None  # unreadable now: the save will say why
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
            "* D-H variable at home · joint value = * - offset", self.app
        )
        if self._cursor_row is not None:
            self._joints.move_cursor(row=min(self._cursor_row, robot.dof - 1))
            self._cursor_row = None
        mark = (" *" if ascii_mode(self.app) else " ●") if self.dirty else ""
        if self.path is not None:
            where = short_path(self.path, 40)
        elif self.template is not None:
            where = f"from bundled {printable(self.template.name)}"
        elif self.imported_from is not None:
            where = f"imported from {printable(self.imported_from.name)}, not saved"
        else:
            where = "not saved yet"
        name = printable(robot.name)
        title = f"{name}{mark} · {robot.type_string} · {where}"
        self._joints.border_title = escape(shown(title, self.app))
        self._fields.show(("field", "value"), field_rows(robot))
        if self._field_row is not None:
            keys = [key for key, _ in field_rows(robot)]
            if self._field_row in keys:
                self._fields.move_cursor(row=keys.index(self._field_row))
            self._field_row = None
        self._fields.border_title = shown("Robot · poses (a adds, d deletes)", self.app)
        self.app.sub_title = f"{name}{mark}"
        frames = robot.kinematics.frames(robot.home)
        self._preview.show(build_wireframe(robot, frames))
        self._refresh_keys()

    def _refresh_keys(self) -> None:
        """Re-check which keys apply, only when that can have changed (the
        footer rebuilds itself on every refresh_bindings)."""
        state = (self.history.can_undo, self.history.can_redo, self._in_joints())
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

    def _apply(self, robot: Robot, message: str, cursor_row: int | None = None) -> None:
        if self.history.push(robot):
            self.refresh_robot(cursor_row)
            self.say(message)

    def _attempt(self, edit, message: str, cursor_row: int | None = None) -> bool:
        """Run an edit; on DhsimError show why and change nothing."""
        try:
            robot = edit()
        except DhsimError as exc:
            self.say(str(exc), error=True)
            return False
        self._apply(robot, message, cursor_row)
        return True

    # -- where the cursor is -------------------------------------------------
    def _in_joints(self) -> bool:
        return self.focused is self._joints

    def _joint_index(self) -> int:
        """The joint under the cursor (where it will be, if a redraw is due)."""
        row = self._joints.cursor_row if self._cursor_row is None else self._cursor_row
        return max(0, min(row, self.robot.dof - 1))

    def _field_key(self) -> str:
        fields = self._fields
        if fields.row_count == 0:
            return ""
        return str(fields.coordinate_to_cell_key(Coordinate(fields.cursor_row, 0)).row_key.value)

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if not self._ready:  # keys that arrive before the tables exist do nothing
            return False
        if action in ("toggle_type", "move") and not self._in_joints():
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
        if column == "type":
            self.action_toggle_type()
        elif column == "#":
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
        answer = await ask_joint_field(self.app, self.robot, index, name)
        if answer is not None:
            self._apply(*answer)

    @work(exclusive=True, group="modal")
    async def edit_field(self, key: str) -> None:
        try:
            new = await ask_field(self.app, self.robot, key)
        except DhsimError as exc:
            self.say(str(exc), error=True)
            return
        if new is not None:
            self._apply(new, describe_change(self.robot, new))

    # -- table actions ----------------------------------------------------------
    def action_toggle_type(self) -> None:
        index = self._joint_index()
        self._attempt(
            lambda: editing.toggle_type(self.robot, index),
            f"joint {index + 1} is now {self._type_after(index)}",
        )

    def _type_after(self, index: int) -> str:
        return "prismatic" if self.robot.joints[index].is_revolute else "revolute"

    @work(exclusive=True, group="modal")
    async def action_add(self) -> None:
        if self._in_joints():
            index = self._joint_index()
            self._attempt(
                lambda: editing.insert_joint(self.robot, index),
                f"joint {index + 2} added",
                cursor_row=index + 1,
            )
            return
        name = await ask_new_pose_name(self.app, self.robot)
        if name is not None and self._attempt(
            lambda: editing.set_pose(self.robot, name, self.robot.home),
            f"pose {name} added (home values; enter on it edits them)",
        ):
            self._field_row = f"pose:{name}"  # the cursor goes to the new pose

    @work(exclusive=True, group="modal")
    async def action_delete(self) -> None:
        if self._in_joints():
            index = self._joint_index()
            if self.robot.dof <= 1:
                self.say("a robot needs at least 1 joint", error=True)
                return
            if await self.app.push_screen_wait(Confirm(f"Delete joint {index + 1}?")):
                self._attempt(
                    lambda: editing.delete_joint(self.robot, index), f"joint {index + 1} deleted"
                )
            return
        key = self._field_key()
        if not key.startswith("pose:"):
            self.say("only joints and poses can be deleted", error=True)
            return
        name = key.removeprefix("pose:")
        if await self.app.push_screen_wait(Confirm(f"Delete pose {name}?")):
            self._attempt(lambda: editing.delete_pose(self.robot, name), f"pose {name} deleted")

    def action_move(self, delta: int) -> None:
        index = self._joint_index()
        self._attempt(
            lambda: editing.move_joint(self.robot, index, delta),
            f"joint {index + 1} moved to {index + 1 + delta}",
            cursor_row=index + delta,
        )

    def action_undo(self) -> None:
        before = self.robot
        if self.history.undo():
            self.refresh_robot()
            self.say(f"undid: {describe_change(before, self.robot)}")
        else:
            self.say("nothing to undo", error=True)

    def action_redo(self) -> None:
        before = self.robot
        if self.history.redo():
            self.refresh_robot()
            self.say(f"redid: {describe_change(before, self.robot)}")
        else:
            self.say("nothing to redo", error=True)

    def palette_commands(self) -> list:
        """The command palette's commands for the editor as it is now."""
        return list(editor_commands(self.app, self))

    def action_preview(self, index: int) -> None:
        self._preview.select(index)

    def action_explain_quit(self) -> None:
        self.say(QUIT_HINT)

    # -- files -------------------------------------------------------------------
    async def save_robot(self, save_as: bool = False) -> bool:
        """Save (asking a name when needed); True once nothing is unsaved."""
        source = self.path or self.template
        base = self.saved
        result = await save_flow(
            self.app,
            self.robot,
            source,
            self.stamp,
            base_text=self.new_text if source is None else None,
            save_as=save_as,
            report=self.say,
        )
        if result is None:
            return False
        self.path, self.template = result.path, None
        self.saved, self.stamp = result.robot, result.stamp
        self.new_text = self.imported_from = None
        if result.kind == "reloaded":  # the file's content, my edits re-applied on top
            mine = self.robot
            again = await reapply_edits(self.app, base, mine, result.robot)
            if again.combined:  # undo takes out my edits, back to the file's
                self.history = editing.History(result.robot)
                self.history.push(again.robot)
            self.say(f"reloaded {short_path(result.path, 40)}: {again.message}", not again.combined)
        self.refresh_robot()
        return not self.dirty

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
        if not await self.guard("opening another robot"):
            return
        opened = await self.app.push_screen_wait(OpenRobot(importing=importing))
        if opened is None:
            return
        if opened.imported:
            self.show_import(opened)
            return
        robot, path, stamp = opened.robot, opened.source, opened.stamp
        found = await offer_recovery(self.app, path, robot)  # changes kept by a crash
        self.history = editing.History(found.robot if found else robot)
        bundled = is_bundled(path)
        self.path = None if bundled else path
        self.template = path if bundled else None
        self.saved, self.stamp = robot, stamp
        self.new_text = self.imported_from = None
        self.refresh_robot()
        self.say(f"opened {short_path(path, 50)}")

    def show_import(self, opened: Opened) -> None:
        """Edit an imported robot: it has no robot file yet, so it is unsaved
        and ctrl+s asks for a name in robots/. The importer's notes are shown."""
        self.history = editing.History(opened.robot)
        self.path = self.template = None
        self.saved, self.stamp = None, None
        self.new_text = header_text(opened.header)
        self.imported_from = opened.source
        self.refresh_robot()
        self.say(f"imported {short_path(opened.source, 40)}; not saved yet: ctrl+s saves it")
        self.app.push_screen(ImportNotes(opened, f"ctrl+s saves it as {ROBOTS_DIR}/<name>.toml"))

    @work(exclusive=True, group="modal")
    async def action_export(self) -> None:
        """Export the robot as it is here (unsaved edits too): URDF, CSV or JSON."""
        await export_flow(self.app, self.robot, self.path or self.template, report=self.say)

    def other_convention(self) -> str:
        return "modified" if self.robot.convention == "standard" else "standard"

    def action_convert(self) -> None:
        """The same arm in the other D-H convention (the core's exact
        conversion: the tool's pose is unchanged at every joint value): one
        edit, which undo reverts."""
        from dhsim_tui.core.interop.convert import convert  # loaded when first used

        convention = self.other_convention()
        before = self.robot.convention
        self._attempt(
            lambda: convert(self.robot, convention),
            f"converted from {before} to {convention} D-H: the same arm (ctrl+z undoes)",
        )

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

"""The table editor: D-H rows and robot fields, live preview, undo, open and save.

Every edit goes through :mod:`dhsim_tui.core.editing`, which returns a new
valid robot or raises DhsimError; a rejected value is shown where it was
typed and the robot stays as it was. Saves are atomic (the core's writer).
"""

from __future__ import annotations

from pathlib import Path

from rich.text import Text
from textual import work
from textual.app import ComposeResult
from textual.containers import Container, Vertical
from textual.coordinate import Coordinate
from textual.events import Resize
from textual.markup import escape
from textual.screen import Screen
from textual.widgets import DataTable, Footer, Static

from dhsim_tui.core import editing
from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.library import bundled_dir
from dhsim_tui.core.model import AXES, CONVENTIONS, UNITS, Robot
from dhsim_tui.core.robotfile import save
from dhsim_tui.core.validation import fmt, perpendicular_axes
from dhsim_tui.scene import build_wireframe
from dhsim_tui.screens.dialogs import Choice, Confirm, SaveGuard
from dhsim_tui.screens.editor_keys import EDITOR_BINDINGS, EDITOR_HELP_NOTES, EDITOR_HELP_ROWS
from dhsim_tui.screens.help import HelpScreen
from dhsim_tui.screens.open_robot import ROBOTS_DIR, OpenRobot
from dhsim_tui.screens.value_entry import ValueEntry
from dhsim_tui.widgets.views_panel import ViewsPanel, is_wide

JOINT_COLUMNS = ("#", "type", "theta", "d", "a", "alpha", "min", "max")
FIELD_ROWS = (
    "name",
    "units",
    "convention",
    "base_height",
    "base_z",
    "base_x",
    "tool_xyz",
    "tool_rpy",
)
FIELD_LABELS = {
    "name": "name",
    "units": "units",
    "convention": "convention",
    "base_height": "base height",
    "base_z": "base z",
    "base_x": "base x",
    "tool_xyz": "tool xyz",
    "tool_rpy": "tool rpy (deg)",
}


def is_bundled(path: Path | None) -> bool:
    return path is not None and path.resolve().parent == bundled_dir().resolve()


def _numbers(values) -> str:
    return ", ".join(fmt(v) for v in values)


class EditorScreen(Screen[tuple[Robot, Path | None] | None]):
    """Edit a robot in a table.

    | Key | Action |
    | :- | :- |
    | arrows | Move in the table |
    | enter | Edit the cell or field under the cursor |
    | t | Revolute <-> prismatic |
    | a / insert | Add a joint after the cursor (in the fields: add a pose) |
    | d / delete | Delete the joint (or the pose) |
    | ctrl+up / ctrl+down | Move the joint up / down |
    | ctrl+z / ctrl+y | Undo / redo |
    | ctrl+o / ctrl+s | Open / save |
    | tab | Joints table <-> robot fields |
    | 1 2 3 | Preview: top, front, side |
    | escape | Back to the simulator |

    Dismisses with (robot, path) to run, or None to keep what was running.
    """

    BINDINGS = EDITOR_BINDINGS

    def __init__(
        self, robot: Robot, path: Path | None, renderer: str = "braille", saved: Robot | None = None
    ) -> None:
        """``saved`` is the robot as its file holds it (None: not saved anywhere)."""
        super().__init__()
        self.history = editing.History(robot)
        self.path = None if is_bundled(path) else path
        self.template = path if is_bundled(path) else None
        self.saved: Robot | None = saved
        self.renderer = renderer
        self._ready = False

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
                joints = DataTable(id="joints-table", cursor_type="cell", zebra_stripes=True)
                joints.add_columns(*JOINT_COLUMNS)
                yield joints
                fields = DataTable(id="fields-table", cursor_type="row", zebra_stripes=True)
                fields.add_columns("field", "value")
                yield fields
                yield Static("", id="editor-status")
            yield ViewsPanel(self.renderer, id="preview")
        yield Footer()

    def on_mount(self) -> None:
        self._preview = self.query_one(ViewsPanel)
        self._ready = True
        self._apply_size(self.app.size.width, self.app.size.height)
        self.refresh_robot()
        self.query_one("#joints-table").focus()

    def on_resize(self, event: Resize) -> None:
        self._apply_size(event.size.width, event.size.height)

    def _apply_size(self, width: int, height: int) -> None:
        self.set_class(is_wide(width, height), "-wide")

    # -- showing the robot ---------------------------------------------------
    def refresh_robot(self) -> None:
        """Tables, title and preview from the current robot (one-way flow)."""
        robot = self.robot
        joints = self.query_one("#joints-table", DataTable)
        cursor = joints.cursor_coordinate
        joints.clear()
        for i, j in enumerate(robot.joints, start=1):
            theta = fmt(j.theta) + ("*" if j.is_revolute else "")
            d = fmt(j.d) + ("" if j.is_revolute else "*")
            joints.add_row(
                str(i),
                "R" if j.is_revolute else "P",
                theta,
                d,
                fmt(j.a),
                fmt(j.alpha),
                fmt(j.min),
                fmt(j.max),
            )
        joints.cursor_coordinate = Coordinate(min(cursor.row, robot.dof - 1), cursor.column)
        mark = " ●" if self.dirty else ""
        if self.path is not None:
            where = str(self.path)
        elif self.template is not None:
            where = f"from bundled {self.template.name}"
        else:
            where = "not saved yet"
        joints.border_title = escape(f"{robot.name}{mark} · {robot.type_string} · {where}")
        joints.border_subtitle = "* joint variable (home)"
        fields = self.query_one("#fields-table", DataTable)
        row = fields.cursor_row
        fields.clear()
        values = {
            "name": robot.name,
            "units": robot.units,
            "convention": robot.convention,
            "base_height": f"{fmt(robot.base_height)} {robot.units}",
            "base_z": robot.base_z,
            "base_x": robot.base_x,
            "tool_xyz": f"{_numbers(robot.tool.xyz)} {robot.units}",
            "tool_rpy": _numbers(robot.tool.rpy),
        }
        for key in FIELD_ROWS:
            fields.add_row(FIELD_LABELS[key], Text(values[key]), key=key)
        for name, pose in robot.poses:
            fields.add_row(Text(f"pose {name}"), _numbers(pose), key=f"pose:{name}")
        fields.move_cursor(row=min(row, fields.row_count - 1))
        fields.border_title = "Robot · poses (a adds, d deletes)"
        self.app.sub_title = f"{robot.name}{mark}"
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
        status = self.query_one("#editor-status", Static)
        status.set_class(error, "-error")
        status.update(Text(message))  # user text: never markup

    def _apply(self, robot: Robot, message: str) -> None:
        if self.history.push(robot):
            self.refresh_robot()
            self.say(message)

    def _attempt(self, edit, message: str) -> bool:
        """Run an edit; on DhsimError show why and change nothing."""
        try:
            robot = edit()
        except DhsimError as exc:
            self.say(str(exc), error=True)
            return False
        self._apply(robot, message)
        return True

    # -- where the cursor is -------------------------------------------------
    def _in_joints(self) -> bool:
        return self.focused is self.query_one("#joints-table")

    def _joint_index(self) -> int:
        return self.query_one("#joints-table", DataTable).cursor_row

    def _field_key(self) -> str:
        fields = self.query_one("#fields-table", DataTable)
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
        index = event.coordinate.row
        if column == "type":
            self.action_toggle_type()
        elif column != "#":
            self.edit_joint_field(index, column)

    def on_data_table_row_selected(self, event: DataTable.RowSelected) -> None:
        event.stop()
        if event.data_table.id == "fields-table":
            self.edit_field(str(event.row_key.value))

    @work(exclusive=True, group="modal")
    async def edit_joint_field(self, index: int, name: str) -> None:
        joint = self.robot.joints[index]
        label = f"joint {index + 1} {name}"
        unit = (
            "deg"
            if name in ("theta", "alpha") or (name in ("min", "max") and joint.is_revolute)
            else self.robot.units
        )

        def check(text: str) -> Robot:
            return editing.set_joint_field(self.robot, index, name, editing.parse_number(text))

        robot = await self.app.push_screen_wait(
            ValueEntry(
                f"{label} ({unit})",
                fmt(getattr(joint, name)),
                f"a number in {unit} · enter sets · escape cancels",
                check,
            )
        )
        if robot is not None:
            self._apply(robot, f"{label} = {fmt(getattr(robot.joints[index], name))} {unit}")

    @work(exclusive=True, group="modal")
    async def edit_field(self, key: str) -> None:
        robot = self.robot
        app = self.app
        if key == "name":
            new = await app.push_screen_wait(
                ValueEntry(
                    "robot name",
                    robot.name,
                    "any text · enter sets · escape cancels",
                    lambda text: editing.set_name(self.robot, text),
                )
            )
        elif key in ("units", "convention", "base_z", "base_x"):
            choices = {
                "units": [
                    (u, u + ("  (lengths are converted)" if u != robot.units else ""))
                    for u in UNITS
                ],
                "convention": [(c, c) for c in CONVENTIONS],
                "base_z": [(a, a) for a in AXES],
                "base_x": [(a, a) for a in perpendicular_axes(robot.base_z)],
            }[key]
            value = await app.push_screen_wait(
                Choice(FIELD_LABELS[key], choices, getattr(robot, key))
            )
            new = None
            if value is not None:
                setter = {
                    "units": editing.set_units,
                    "convention": editing.set_convention,
                    "base_z": editing.set_base_z,
                    "base_x": editing.set_base_x,
                }[key]
                try:
                    new = setter(self.robot, value)
                except DhsimError as exc:
                    self.say(str(exc), error=True)
        elif key == "base_height":
            new = await app.push_screen_wait(
                ValueEntry(
                    f"base height ({robot.units})",
                    fmt(robot.base_height),
                    "frame 0 above the floor, >= 0",
                    lambda text: editing.set_base_height(
                        self.robot, editing.parse_number(text, "base height")
                    ),
                )
            )
        elif key in ("tool_xyz", "tool_rpy"):
            part = key.removeprefix("tool_")
            new = await app.push_screen_wait(
                ValueEntry(
                    FIELD_LABELS[key],
                    _numbers(getattr(robot.tool, part)),
                    "three numbers: x, y, z" if part == "xyz" else "roll, pitch, yaw in degrees",
                    lambda text: editing.set_tool(
                        self.robot, **{part: editing.parse_numbers(text, 3, FIELD_LABELS[key])}
                    ),
                )
            )
        elif key.startswith("pose:"):
            name = key.removeprefix("pose:")
            new = await app.push_screen_wait(
                ValueEntry(
                    f"pose {name}",
                    _numbers(robot.pose(name)),
                    f"{robot.dof} joint values, separated by commas",
                    lambda text: editing.set_pose(
                        self.robot,
                        name,
                        editing.parse_numbers(text, self.robot.dof, f"pose {name}"),
                    ),
                )
            )
        else:
            return
        if new is not None:
            self._apply(new, f"{FIELD_LABELS.get(key, key)} changed")

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
            if self._attempt(
                lambda: editing.insert_joint(self.robot, index), f"joint {index + 2} added"
            ):
                self.query_one("#joints-table", DataTable).move_cursor(row=index + 1)
            return
        name = await self.app.push_screen_wait(
            ValueEntry(
                "new pose",
                f"pose{len(self.robot.poses) + 1}",
                "a name; the pose starts at home",
                self._check_new_pose_name,
            )
        )
        if name is not None:
            self._attempt(
                lambda: editing.set_pose(self.robot, name, self.robot.home),
                f"pose {name} added (home values; enter edits them)",
            )

    def _check_new_pose_name(self, text: str) -> str:
        name = text.strip()
        if not name:
            raise DhsimError("a pose needs a name")
        if name in self.robot.pose_names:
            raise DhsimError(f"there is already a pose named {name!r}")
        return name

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
        if self._attempt(
            lambda: editing.move_joint(self.robot, index, delta),
            f"joint {index + 1} moved to {index + 1 + delta}",
        ):
            table = self.query_one("#joints-table", DataTable)
            table.move_cursor(row=index + delta)

    def action_undo(self) -> None:
        if self.history.undo():
            self.refresh_robot()
            self.say("undone")
        else:
            self.say("nothing to undo", error=True)

    def action_redo(self) -> None:
        if self.history.redo():
            self.refresh_robot()
            self.say("redone")
        else:
            self.say("nothing to redo", error=True)

    def action_preview(self, index: int) -> None:
        self._preview.select(index)

    # -- files -------------------------------------------------------------------
    async def save_robot(self) -> bool:
        """Save to the robot's file, or ask for a name; True once it is on disk."""
        robot = self.robot
        target = self.path
        if target is None:
            name = await self.app.push_screen_wait(
                ValueEntry(
                    "save as",
                    editing.slug(robot.name),
                    f"a file name; saved as {ROBOTS_DIR}/<name>.toml",
                    editing.check_file_name,
                )
            )
            if name is None:
                self.say("not saved")
                return False
            target = ROBOTS_DIR / f"{name}.toml"
            if target.exists() and not await self.app.push_screen_wait(
                Confirm(f"{target} exists. Replace it?", "Replace a file")
            ):
                self.say("not saved")
                return False
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            save(robot, target)
        except (DhsimError, OSError) as exc:
            reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
            self.say(f"not saved: {reason}", error=True)
            return False
        self.path, self.saved = target, robot
        self.refresh_robot()
        self.say(f"saved {target}")
        return True

    @work(exclusive=True, group="modal")
    async def action_save(self) -> None:
        await self.save_robot()

    async def guard(self, doing: str) -> bool:
        """True when it is fine to go on: nothing unsaved, saved now, or discarded."""
        if not self.dirty:
            return True
        answer = await self.app.push_screen_wait(SaveGuard(self.robot.name, doing))
        if answer == "save":
            return await self.save_robot()
        return answer == "discard"

    @work(exclusive=True, group="modal")
    async def action_open(self) -> None:
        if not await self.guard("opening another robot"):
            return
        result = await self.app.push_screen_wait(OpenRobot())
        if result is None:
            return
        robot, path = result
        self.history = editing.History(robot)
        self.path = None if is_bundled(path) else path
        self.template = path if is_bundled(path) else None
        self.saved = robot
        self.refresh_robot()
        self.say(f"opened {path}")

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

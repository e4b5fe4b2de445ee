"""What the editor's tables show: every number whole, every column as wide as
its widest cell, and only the cells that changed rewritten.

Textual's DataTable sizes auto-width columns lazily and never shrinks them,
so after an edit a cell could show "70.1" for 70.125. Here each column gets
an explicit width computed from its cells; a table wider than its box
scrolls sideways instead of cutting a value.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from rich.cells import cell_len
from rich.text import Text
from textual import events
from textual.coordinate import Coordinate
from textual.widgets import DataTable

from dhsim_tui.core.model.editing import ROBOT_FIELDS
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.validation import fmt
from dhsim_tui.tui.screens.dialogs import short_path

Cell = str | Text

FIELD_ROWS = ROBOT_FIELDS  # the fields panel's rows
FIELD_LABELS = {
    "name": "name",
    "units": "units",
    "convention": "convention",
    "base_height": "base height",
    "base_z": "base z",
    "base_x": "base x",
    "base_xyz": "base xyz",
    "base_rpy": "base rpy (deg)",
    "tool_xyz": "tool xyz",
    "tool_rpy": "tool rpy (deg)",
}
#: the joints table's columns (what editing calls them), in order; ``home``
#: is the home joint value, theta - offset (d - offset), shown beside the
#: offset and the limits it must lie within
JOINT_COLUMNS = ("#", "type", "theta", "d", "a", "alpha", "offset", "home", "min", "max")


def number(value: float) -> str:
    """The shortest text that reads back as exactly ``value`` (the core's
    :func:`fmt`): ``70.125``, ``0.089459``, ``-90``; never rounded."""
    return fmt(value)


def numbers(values: Sequence[float]) -> str:
    return ", ".join(number(v) for v in values)


def joint_labels(robot: Robot) -> tuple[str, ...]:
    """Column headers with their units (two lines: name, unit)."""
    unit = robot.units
    return (
        "#",
        "type",
        "theta\n(deg)",
        f"d\n({unit})",
        f"a\n({unit})",
        "alpha\n(deg)",
        f"offset\n({limits_unit(robot)})",
        f"home\n({limits_unit(robot)})",
        f"min\n({limits_unit(robot)})",
        f"max\n({limits_unit(robot)})",
    )


def limits_unit(robot: Robot) -> str:
    """The unit of min and max, which depends on the joint's type:
    ``deg``, the length unit, or ``deg|mm`` for a mixed arm (R rows in deg,
    P rows in mm)."""
    kinds = {j.is_revolute for j in robot.joints}
    if kinds == {True}:
        return "deg"
    if kinds == {False}:
        return robot.units
    return f"deg|{robot.units}"


def joint_rows(robot: Robot) -> list[tuple[str, tuple[Cell, ...]]]:
    rows = []
    for i, j in enumerate(robot.joints, start=1):
        theta = number(j.theta) + ("*" if j.is_revolute else "")
        d = number(j.d) + ("" if j.is_revolute else "*")
        cells = (str(i), "R" if j.is_revolute else "P", theta, d)
        # home is derived (theta - offset): shown without the subtraction's float noise
        cells += (number(j.a), number(j.alpha), number(j.offset), number(round(j.home, 9) + 0.0))
        cells += (number(j.min), number(j.max))
        rows.append((f"joint:{i}", cells))
    return rows


def field_rows(robot: Robot) -> list[tuple[str, tuple[Cell, ...]]]:
    """(key, (label, value)) for the robot's fields, then one row per pose.
    Text from the file (name, pose names) is escaped and never markup."""
    values = {
        "name": printable(robot.name),
        "units": robot.units,
        "convention": robot.convention,
        "base_height": f"{number(robot.base_height)} {robot.units}",
        "base_z": robot.base_z,
        "base_x": robot.base_x,
        "base_xyz": f"{numbers(robot.base_xyz)} {robot.units}",
        "base_rpy": numbers(robot.base_rpy),
        "tool_xyz": f"{numbers(robot.tool.xyz)} {robot.units}",
        "tool_rpy": numbers(robot.tool.rpy),
    }
    rows: list[tuple[str, tuple[Cell, ...]]] = [
        (key, (FIELD_LABELS[key], Text(values[key]))) for key in FIELD_ROWS
    ]
    for name, pose in robot.poses:
        rows.append((f"pose:{name}", (Text(f"pose {printable(name)}"), numbers(pose))))
    return rows


def _width(cell: Cell) -> int:
    text = cell.plain if isinstance(cell, Text) else cell
    return max(cell_len(line) for line in text.split("\n"))


class FittedTable(DataTable):
    """A DataTable whose columns always fit their widest cell (or label).

    The mouse: a click puts the cursor on a cell, a double click edits it
    (as enter does). Textual's table would also edit on a single click of
    the cell the cursor is on, which caught people clicking twice slowly.
    """

    def __init__(self, **kwargs) -> None:
        super().__init__(**kwargs)
        self._labels: tuple[Cell, ...] = ()
        self._widths: list[int] = []
        self._rows: list[tuple[str, tuple[Cell, ...]]] = []

    async def _on_click(self, event: events.Click) -> None:
        meta = event.style.meta
        row, column = meta.get("row", -1), meta.get("column", -1)
        if row < 0 or column < 0 or meta.get("out_of_bounds", False):
            return  # a header or the space beside the cells: Textual's own handling
        event.prevent_default()  # not Textual's: it edits on one click
        event.stop()
        self.cursor_coordinate = Coordinate(row, column)
        if event.chain >= 2:
            self._post_selected_message()

    def show(self, labels: Sequence[Cell], rows: Sequence[tuple[str, Sequence[Cell]]]) -> None:
        """Show ``rows`` of (key, cells); rewrite only what changed."""
        labels = tuple(labels)
        rows = [(key, tuple(cells)) for key, cells in rows]
        widths = [
            max([_width(label)] + [_width(cells[i]) for _, cells in rows])
            for i, label in enumerate(labels)
        ]
        if labels != self._labels or widths != self._widths:
            self._rebuild(labels, widths, rows, columns=True)
        elif [key for key, _ in rows] != [key for key, _ in self._rows]:
            self._rebuild(labels, widths, rows, columns=False)
        else:
            for (key, cells), (_, old) in zip(rows, self._rows, strict=True):
                for i, (cell, before) in enumerate(zip(cells, old, strict=True)):
                    if cell != before:
                        self.update_cell(key, str(i), cell)
        self._rows = rows

    def _rebuild(self, labels, widths, rows, *, columns: bool) -> None:
        cursor = self.cursor_coordinate
        self.clear(columns=columns)
        if columns:
            self.header_height = max(label.count("\n") + 1 for label in map(str, labels))
            for i, (label, width) in enumerate(zip(labels, widths, strict=True)):
                self.add_column(label, width=width, key=str(i))
            self._labels, self._widths = labels, widths
        for key, cells in rows:
            self.add_row(*cells, key=key)
        if rows:
            row = min(cursor.row, len(rows) - 1)
            self.cursor_coordinate = Coordinate(row, min(cursor.column, len(labels) - 1))


def file_words(path: Path | None, template: Path | None, imported_from: Path | None) -> str:
    """The title's words for where the robot is kept: its file (``path``),
    the bundled robot it started from (``template``), the file it was
    imported from, or none yet."""
    if path is not None:
        return short_path(path, 40)
    if template is not None:
        return f"from bundled {printable(template.name)}"
    if imported_from is not None:
        return f"imported from {printable(imported_from.name)}, not saved"
    return "not saved yet"

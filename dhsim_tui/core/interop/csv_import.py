"""A robot from a D-H table in CSV (:func:`from_csv`), as
:mod:`dhsim_tui.core.interop.export` writes it or as a person types a handout's table:

- lines starting with ``#`` are comments; a comment ``# key = value`` with a
  key dhsim writes (name, convention, units, base_height, base_z, base_x,
  base_xyz, base_rpy, tool_xyz, tool_rpy, ``pose "NAME"``) sets that field;
- the first other line is the header: columns ``theta``, ``d``, ``a`` and
  ``alpha`` are required, ``joint``, ``type`` (R/P), ``offset``, ``min`` and
  ``max`` optional, in any order, each optionally followed by its unit in
  parentheses: ``d (mm)``, ``alpha (rad)``, ``min (deg|mm)``;
- each further line is one joint.

Without a ``# convention`` line the table is in ``convention`` (default
standard); with one, the robot is converted to ``convention`` if one is
given and differs.

The text is read line by line and stops at the first thing that decides:
more than :data:`MAX_CSV_BYTES` characters (before reading a line), the
33rd joint row, the first bad cell or comment value, the
:data:`MAX_POSES`-plus-first pose, a pose of more than 32 values. Messages
quote the file's text escaped and cut in the middle past 200 characters.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re
from dataclasses import dataclass
from pathlib import Path

from dhsim_tui.core.files.tomlparse import MAX_POSES as ROBOT_FILE_POSES
from dhsim_tui.core.interop.convert import convert
from dhsim_tui.core.interop.imported import ImportResult, check_choice, quoted
from dhsim_tui.core.model.editing import parse_number
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import (
    CONVENTIONS,
    MAX_JOINTS,
    MIN_JOINTS,
    UNITS,
    Joint,
    Robot,
    Tool,
    default_limits,
)
from dhsim_tui.core.model.text import counted, printable, shortened

#: a CSV longer than this (characters, or bytes of its file) is refused unread:
#: a 32-joint table with a thousand named poses is well under 1 MB
MAX_CSV_BYTES = 2_000_000
#: named poses a CSV may hold
MAX_POSES = ROBOT_FILE_POSES  # what a robot file may hold, so an import can be saved
#: a cell longer than this is no number
MAX_NUMBER_CHARS = 100
_COLUMNS = ("joint", "type", "theta", "d", "a", "alpha", "offset", "min", "max")
_REQUIRED = ("theta", "d", "a", "alpha")
_ALIASES = {"#": "joint", "θ": "theta", "α": "alpha", "q_offset": "offset"}
_HEADER_CELL = re.compile(r"^\s*([^()]*?)\s*(?:\(([^()]*)\))?\s*$")
_TYPES = {"r": "revolute", "revolute": "revolute", "p": "prismatic", "prismatic": "prismatic"}
_ANGLE_UNITS = {
    "deg": 1.0,
    "degrees": 1.0,
    "°": 1.0,
    "rad": 180.0 / math.pi,
    "radians": 180.0 / math.pi,
}


def from_csv(
    text: str,
    *,
    source: str = "<csv>",
    convention: str | None = None,
    units: str | None = None,
    name: str | None = None,
) -> ImportResult:
    """The robot of a D-H table in CSV (see the module's docstring)."""
    if convention is not None:
        check_choice(convention, CONVENTIONS, "--convention", source)
    if units is not None:
        check_choice(units, tuple(UNITS), "--units", source)
    if len(text) > MAX_CSV_BYTES:
        raise DhsimError(
            printable(
                f"{source}: {len(text)} characters is more than dhsim reads from a CSV table "
                f"({MAX_CSV_BYTES} at most)"
            )
        )
    fields: dict[str, object] = {}
    poses: list[tuple[str, tuple[float, ...]]] = []
    columns: dict[str, _Column] | None = None
    file_units: str | None = None
    rows: list[_Row] = []
    for number, line in enumerate(io.StringIO(text, newline=None), start=1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith("#"):
            _comment(stripped[1:].strip(), number, fields, poses, source)
            continue
        try:
            cells = next(csv.reader([line.rstrip("\n")]), [])
        except csv.Error as exc:
            raise DhsimError(printable(f"{source}: line {number}: not a CSV row ({exc})")) from None
        if columns is None:
            columns = _header(cells, number, source)
            file_units = _length_unit(columns, units, number, source)
            continue
        if not any(cell.strip() for cell in cells):
            continue
        if len(rows) == MAX_JOINTS:
            raise DhsimError(
                printable(
                    f"{source}: line {number}: more than {MAX_JOINTS} joint rows; "
                    f"a robot has {MIN_JOINTS} to {MAX_JOINTS} joints"
                )
            )
        rows.append(_csv_row(cells, columns, number, source))
    if columns is None:
        raise DhsimError(printable(f"{source}: no header row (theta, d, a, alpha) and no joints"))
    if not rows:
        raise DhsimError(printable(f"{source}: the header is there but no joint rows follow"))
    declared_units = fields.get("units")
    robot_units = (
        units or (declared_units if isinstance(declared_units, str) else None) or file_units or "mm"
    )
    check_choice(robot_units, tuple(UNITS), "units", source)
    length_scale = UNITS[file_units or robot_units] / UNITS[robot_units]
    joints = [_csv_joint(row, length_scale, robot_units) for row in rows]
    table_convention = fields.pop("convention", None)
    declared = str(table_convention) if table_convention is not None else convention or "standard"
    check_choice(declared, CONVENTIONS, "convention", source)
    try:
        robot = Robot(
            name=str(fields.get("name") or name or Path(source).stem or "imported robot"),
            joints=tuple(joints),
            units=robot_units,
            convention=declared,
            base_height=float(fields.get("base_height", 0.0)) * length_scale,  # type: ignore[arg-type]
            base_z=str(fields.get("base_z", "+z")),
            base_x=str(fields.get("base_x", "+x")),
            base_xyz=tuple(v * length_scale for v in fields.get("base_xyz", (0.0, 0.0, 0.0))),  # type: ignore[union-attr]
            base_rpy=tuple(fields.get("base_rpy", (0.0, 0.0, 0.0))),  # type: ignore[arg-type]
            tool=Tool(
                tuple(v * length_scale for v in fields.get("tool_xyz", (0.0, 0.0, 0.0))),  # type: ignore[union-attr]
                tuple(fields.get("tool_rpy", (0.0, 0.0, 0.0))),  # type: ignore[arg-type]
            ),
            poses=tuple(
                (
                    pose,
                    tuple(
                        v * (1.0 if j.is_revolute else length_scale)
                        for v, j in zip(values, joints, strict=True)
                    )
                    if len(values) == len(joints)
                    else values,  # the robot's check names the count
                )
                for pose, values in poses
            ),
        )
    except DhsimError as exc:  # it may quote a name: cut in the middle past 300 characters
        raise DhsimError(printable(f"{source}: {shortened(str(exc), 300)}")) from None
    notes = [f"{counted(len(joints), 'joint')}, {declared} D-H, lengths in {robot_units}"]
    if convention is not None and declared != convention and table_convention is not None:
        robot = convert(robot, convention)
        notes.append(f"converted from {declared} to {convention} D-H (the same arm)")
    return ImportResult(
        robot, tuple(printable(n) for n in notes), (f"Imported by dhsim from {Path(source).name}.",)
    )


def _comment(text: str, line: int, fields: dict, poses: list, source: str) -> None:
    key, sep, value = text.partition("=")
    if not sep:
        return  # a plain comment
    key, value = key.strip(), value.strip()
    where = f"{source}: line {line}: {shortened(key, 100)}"
    if key.startswith("pose "):
        if len(poses) == MAX_POSES:
            raise DhsimError(printable(f"{source}: line {line}: more than {MAX_POSES} named poses"))
        pose_name = _json_or_text(key[5:].strip())
        poses.append((pose_name, tuple(_numbers(value, None, where))))
    elif key == "name":
        fields["name"] = _json_or_text(value)
    elif key in ("convention", "units", "base_z", "base_x"):
        fields[key] = shortened(_json_or_text(value), 60)  # a longer one is wrong anyway
    elif key == "base_height":
        fields[key] = _numbers(value, 1, where)[0]
    elif key in ("base_xyz", "base_rpy", "tool_xyz", "tool_rpy"):
        fields[key] = tuple(_numbers(value, 3, where))


def _json_or_text(value: str) -> str:
    if value.startswith('"'):
        try:
            loaded = json.loads(value)
        except ValueError:
            return value
        if isinstance(loaded, str):
            return loaded
    return value


def _numbers(text: str, count: int | None, where: str) -> list[float]:
    most = MAX_JOINTS if count is None else count
    if text.count(",") >= most + 1:  # before splitting a line of a million
        raise DhsimError(printable(f"{where}: more than {most} numbers"))
    items = [item.strip() for item in text.strip().strip("[]").split(",") if item.strip()]
    if count is not None and len(items) != count:
        raise DhsimError(
            printable(f"{where}: expected {counted(count, 'number')}, got {len(items)}")
        )
    return [_number(item, where) for item in items]


def _number(item: str, where: str) -> float:
    """A number as the editor reads one (finite, of sane size), named by ``where``."""
    if len(item.strip()) > MAX_NUMBER_CHARS:
        raise DhsimError(
            printable(f"{where}: {quoted(item.strip(), 60)} is too long to be a number")
        )
    try:
        return parse_number(item, where)
    except DhsimError as exc:
        raise DhsimError(printable(str(exc))) from None


@dataclass(frozen=True)
class _Column:
    index: int
    unit: str  # as written in the header, lower case; "" when none


def _header(cells: list[str], line: int, source: str) -> dict[str, _Column]:
    columns: dict[str, _Column] = {}
    for index, cell in enumerate(cells):
        match = _HEADER_CELL.match(cell)
        label = (match.group(1) if match else cell).strip().lower()
        label = _ALIASES.get(label, label)
        unit = ((match.group(2) or "") if match else "").strip().lower()
        if label not in _COLUMNS:
            raise DhsimError(
                printable(
                    f"{source}: line {line}: column {index + 1} {quoted(cell.strip(), 60)} is not "
                    f"one of {', '.join(_COLUMNS)}"
                )
            )
        if label in columns:
            raise DhsimError(printable(f"{source}: line {line}: column {label!r} appears twice"))
        columns[label] = _Column(index, unit)
    missing = [c for c in _REQUIRED if c not in columns]
    if missing:
        raise DhsimError(
            printable(
                f"{source}: line {line}: the header has no {', '.join(missing)} column "
                "(a D-H table needs theta, d, a, alpha)"
            )
        )
    return columns


def _length_unit(
    columns: dict[str, _Column], units: str | None, line: int, source: str
) -> str | None:
    """The length unit the header states for d and a (None: it states none)."""
    found = set()
    for key in ("d", "a"):
        unit = columns[key].unit
        if unit:
            if unit not in UNITS:
                raise DhsimError(
                    printable(
                        f"{source}: line {line}: {key} ({shortened(unit, 60)}): the unit is "
                        f"not one of {', '.join(UNITS)}"
                    )
                )
            found.add(unit)
    if len(found) > 1:
        raise DhsimError(printable(f"{source}: line {line}: d and a are in different units"))
    return found.pop() if found else None


def _angle_scale(column: _Column, line: int, source: str, label: str) -> float:
    unit = column.unit.split("|")[0].strip() if column.unit else "deg"
    if unit not in _ANGLE_UNITS:
        raise DhsimError(
            printable(
                f"{source}: line {line}: {label} ({shortened(column.unit, 60)}): "
                "expected deg or rad"
            )
        )
    return _ANGLE_UNITS[unit]


@dataclass(frozen=True)
class _Row:
    """One joint row read: its kind, and each number given, angles in degrees
    and lengths in the file's unit (None: the cell is absent or empty where
    a default applies)."""

    kind: str
    values: dict[str, float | None]


def _csv_row(cells: list[str], columns: dict[str, _Column], line: int, source: str) -> _Row:
    """A joint row's numbers, each checked as it is read."""

    def cell(key: str) -> str | None:
        column = columns.get(key)
        if column is None:
            return None
        if column.index >= len(cells):
            raise DhsimError(printable(f"{source}: line {line}: no value in column {key!r}"))
        return cells[column.index].strip()

    kind_text = (cell("type") or "R").lower()
    if kind_text not in _TYPES:
        raise DhsimError(
            printable(f"{source}: line {line}: type {quoted(kind_text, 60)} is not R or P")
        )
    kind = _TYPES[kind_text]
    revolute = kind == "revolute"
    values: dict[str, float | None] = {}
    for key in ("theta", "d", "offset", "min", "max", "a", "alpha"):
        text = cell(key)
        if text is None or (text == "" and key in ("offset", "min", "max")):
            values[key] = None
            continue
        number = _number(text, f"{source}: line {line}: {key}")
        is_angle = key in ("theta", "alpha") or (key in ("offset", "min", "max") and revolute)
        if is_angle:
            number *= _angle_scale(columns[key], line, source, key)
        values[key] = number
    return _Row(kind, values)


def _csv_joint(row: _Row, length_scale: float, units: str) -> Joint:
    """The joint of a row read, lengths scaled to the robot's unit, limits
    by default the seed's (widened to hold the home)."""
    revolute = row.kind == "revolute"

    def value(key: str) -> float | None:
        number = row.values[key]
        if number is None:
            return None
        is_angle = key in ("theta", "alpha") or (key in ("offset", "min", "max") and revolute)
        return number if is_angle else number * length_scale

    theta, d = value("theta"), value("d")
    offset = value("offset") or 0.0
    home = (theta if revolute else d) - offset  # type: ignore[operator]
    low, high = default_limits(row.kind, units)
    low_given, high_given = value("min"), value("max")
    return Joint(
        type=row.kind,  # type: ignore[arg-type]
        theta=theta,  # type: ignore[arg-type]
        d=d,  # type: ignore[arg-type]
        a=value("a"),  # type: ignore[arg-type]
        alpha=value("alpha"),  # type: ignore[arg-type]
        min=min(low, home) if low_given is None else low_given,
        max=max(high, home) if high_given is None else high_given,
        offset=offset,
    )

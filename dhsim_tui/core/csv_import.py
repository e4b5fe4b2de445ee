"""A robot from a D-H table in CSV (:func:`from_csv`), as
:mod:`dhsim_tui.core.export` writes it or as a person types a handout's table:

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
"""

from __future__ import annotations

import csv
import io
import json
import math
import re
from dataclasses import dataclass
from pathlib import Path

from dhsim_tui.core.convert import convert
from dhsim_tui.core.editing import parse_number
from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.imported import ImportResult, check_choice
from dhsim_tui.core.model import CONVENTIONS, UNITS, Joint, Robot, Tool, default_limits
from dhsim_tui.core.text import printable

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
    fields: dict[str, object] = {}
    poses: list[tuple[str, tuple[float, ...]]] = []
    table: list[tuple[int, list[str]]] = []
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith("#"):
            _comment(stripped[1:].strip(), number, fields, poses, source)
        else:
            table.append((number, line))
    if not table:
        raise DhsimError(printable(f"{source}: no header row (theta, d, a, alpha) and no joints"))
    rows = [
        (number, cells)
        for number, cells in zip(
            (n for n, _ in table),
            csv.reader(io.StringIO("\n".join(line for _, line in table))),
            strict=False,
        )
    ]
    header_line, header = rows[0]
    columns = _header(header, header_line, source)
    file_units = _length_unit(columns, units, header_line, source)
    declared_units = fields.get("units")
    robot_units = (
        units or (declared_units if isinstance(declared_units, str) else None) or file_units or "mm"
    )
    check_choice(robot_units, tuple(UNITS), "units", source)
    length_scale = UNITS[file_units or robot_units] / UNITS[robot_units]
    joints = []
    for number, cells in rows[1:]:
        if not any(cell.strip() for cell in cells):
            continue
        joints.append(_csv_joint(cells, columns, number, source, length_scale, robot_units))
    if not joints:
        raise DhsimError(printable(f"{source}: the header is there but no joint rows follow"))
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
                        for v, j in zip(values, joints, strict=False)
                    ),
                )
                for pose, values in poses
            ),
        )
    except DhsimError as exc:
        raise DhsimError(printable(f"{source}: {exc}")) from None
    notes = [f"{len(joints)} joints, {declared} D-H, lengths in {robot_units}"]
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
    where = f"{source}: line {line}: {key}"
    if key.startswith("pose "):
        pose_name = _json_or_text(key[5:].strip())
        poses.append((pose_name, tuple(_numbers(value, None, where))))
    elif key == "name":
        fields["name"] = _json_or_text(value)
    elif key in ("convention", "units", "base_z", "base_x"):
        fields[key] = _json_or_text(value)
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
    items = [item.strip() for item in text.strip().strip("[]").split(",") if item.strip()]
    if count is not None and len(items) != count:
        raise DhsimError(printable(f"{where}: expected {count} numbers, got {len(items)}"))
    return [_number(item, where) for item in items]


def _number(item: str, where: str) -> float:
    """A number as the editor reads one (finite, of sane size), named by ``where``."""
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
                    f"{source}: line {line}: column {index + 1} {cell.strip()!r} is not one of "
                    f"{', '.join(_COLUMNS)}"
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
                        f"{source}: line {line}: {key} ({unit}): the unit is not one of "
                        f"{', '.join(UNITS)}"
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
            printable(f"{source}: line {line}: {label} ({column.unit}): expected deg or rad")
        )
    return _ANGLE_UNITS[unit]


def _csv_joint(
    cells: list[str],
    columns: dict[str, _Column],
    line: int,
    source: str,
    length_scale: float,
    units: str,
) -> Joint:
    def cell(key: str) -> str | None:
        column = columns.get(key)
        if column is None:
            return None
        if column.index >= len(cells):
            raise DhsimError(printable(f"{source}: line {line}: no value in column {key!r}"))
        return cells[column.index].strip()

    kind_text = (cell("type") or "R").lower()
    if kind_text not in _TYPES:
        raise DhsimError(printable(f"{source}: line {line}: type {kind_text!r} is not R or P"))
    kind = _TYPES[kind_text]
    revolute = kind == "revolute"

    def value(key: str, default: float | None = None) -> float | None:
        text = cell(key)
        if text is None or (text == "" and default is not None):
            return default
        where = f"{source}: line {line}: {key}"
        number = _number(text, where)
        is_angle = key in ("theta", "alpha") or (key in ("offset", "min", "max") and revolute)
        if is_angle:
            return number * _angle_scale(columns[key], line, source, key)
        return number * length_scale

    theta, d = value("theta"), value("d")
    offset = value("offset", 0.0) or 0.0
    home = (theta if revolute else d) - offset  # type: ignore[operator]
    low, high = default_limits(kind, units)
    low = value("min", min(low, home))
    high = value("max", max(high, home))
    return Joint(
        type=kind,  # type: ignore[arg-type]
        theta=theta,  # type: ignore[arg-type]
        d=d,  # type: ignore[arg-type]
        a=value("a"),  # type: ignore[arg-type]
        alpha=value("alpha"),  # type: ignore[arg-type]
        min=low,  # type: ignore[arg-type]
        max=high,  # type: ignore[arg-type]
        offset=offset,
    )

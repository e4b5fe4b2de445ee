"""The robot file's schema (docs/file-format.md gives it): its keys, the
robot built from a parsed TOML document, every key checked for type and
spelling (:func:`robot_from_dict`), and the document written for a robot
(:func:`robot_to_dict`), with the defaults a file may leave out. The
``[programs]`` table is :mod:`dhsim_tui.core.files.programschema`'s.
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping
from typing import Any

from dhsim_tui.core.files.programschema import programs_from_data, programs_to_data
from dhsim_tui.core.model.editing import HEADER_FIELDS
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Joint, Robot, Tool, default_limits
from dhsim_tui.core.model.text import counted, printable, shortened
from dhsim_tui.core.model.validation import check_choice, check_number

TOP_KEYS = (*HEADER_FIELDS, "tool", "poses", "programs", "joints")
JOINT_KEYS = ("type", "theta", "d", "a", "alpha", "min", "max", "offset", "vmax", "amax")
#: a joint's top speed and acceleration: written only when given (None: the defaults)
JOINT_RATES = ("vmax", "amax")
JOINT_REQUIRED = ("theta", "d", "a", "alpha")
TOOL_KEYS = ("xyz", "rpy")


def _check_keys(table: Mapping[str, Any], allowed: tuple[str, ...], where: str) -> None:
    for key in table:
        if key not in allowed:
            close = difflib.get_close_matches(key, allowed, n=1)
            hint = (
                f" (did you mean {close[0]!r}?)" if close else f" (allowed: {', '.join(allowed)})"
            )
            raise DhsimError(printable(f"{where}{shortened(key)}: unknown key{hint}"))


def _table(value: object, where: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise DhsimError(printable(f"{where}: expected a table"))
    return value


def _string(value: object, where: str) -> str:
    if not isinstance(value, str):
        raise DhsimError(f"{where}: expected a text string in quotes")
    return value


def _triple(value: object, where: str) -> tuple[float, float, float]:
    if not isinstance(value, list) or len(value) != 3:
        raise DhsimError(f"{where}: expected a list of 3 numbers, like [0.0, 0.0, 0.0]")
    x, y, z = (check_number(v, f"{where}[{i}]") for i, v in enumerate(value, start=1))
    return (x, y, z)


def _joint(data: object, number: int, units: str) -> Joint:
    where = f"joints[{number}]"
    table = _table(data, where)
    _check_keys(table, JOINT_KEYS, f"{where}.")
    for key in JOINT_REQUIRED:
        if key not in table:
            raise DhsimError(f"{where}: missing key {key!r}")
    joint_type = check_choice(
        table.get("type", "revolute"), ("revolute", "prismatic"), f"{where}.type"
    )
    values = {key: check_number(table[key], f"{where}.{key}") for key in JOINT_REQUIRED}
    low, high = default_limits(joint_type, units)
    optional = {
        key: check_number(table[key], f"{where}.{key}") if key in table else default
        for key, default in (("min", low), ("max", high), ("offset", 0.0))
    }
    rates = {key: check_number(table[key], f"{where}.{key}") for key in JOINT_RATES if key in table}
    return Joint(type=joint_type, **values, **optional, **rates)  # type: ignore[arg-type]


def robot_from_dict(data: Mapping[str, Any]) -> Robot:
    """Build a robot from parsed TOML, checking every key; raises DhsimError."""
    _check_keys(data, TOP_KEYS, "")
    for key in ("name", "joints"):
        if key not in data:
            raise DhsimError(f"missing key {key!r}")
    units = check_choice(data.get("units", "mm"), ("mm", "cm", "m", "in"), "units")
    joints_data = data["joints"]
    if not isinstance(joints_data, list):
        raise DhsimError("joints: expected an array of tables, written [[joints]]")
    joints = tuple(_joint(j, i, units) for i, j in enumerate(joints_data, start=1))
    tool = Tool()
    if "tool" in data:
        tool_data = _table(data["tool"], "tool")
        _check_keys(tool_data, TOOL_KEYS, "tool.")
        tool = Tool(
            xyz=_triple(tool_data.get("xyz", [0.0, 0.0, 0.0]), "tool.xyz"),
            rpy=_triple(tool_data.get("rpy", [0.0, 0.0, 0.0]), "tool.rpy"),
        )
    poses: list[tuple[str, tuple[float, ...]]] = []
    for name, values in _table(data.get("poses", {}), "poses").items():
        where = printable(f"poses.{shortened(name)}")
        if not isinstance(values, list):
            raise DhsimError(f"{where}: expected a list of {counted(len(joints), 'number')}")
        numbers = tuple(check_number(v, f"{where}[{i}]") for i, v in enumerate(values, start=1))
        poses.append((name, numbers))
    base_height = data.get("base_height", 0.0)
    return Robot(
        name=_string(data["name"], "name"),
        joints=joints,
        units=units,
        convention=_string(data.get("convention", "standard"), "convention"),
        base_height=check_number(base_height, "base_height"),
        base_z=_string(data.get("base_z", "+z"), "base_z"),
        base_x=_string(data.get("base_x", "+x"), "base_x"),
        base_xyz=_triple(data.get("base_xyz", [0.0, 0.0, 0.0]), "base_xyz"),
        base_rpy=_triple(data.get("base_rpy", [0.0, 0.0, 0.0]), "base_rpy"),
        tool=tool,
        poses=tuple(poses),
        programs=programs_from_data(data.get("programs", {})),
    )


def robot_to_dict(robot: Robot, *, full: bool = False) -> dict[str, Any]:
    """The TOML document for a robot; every field written, so it reads back equal.
    ``full`` also writes an identity tool and an empty poses table."""
    data: dict[str, Any] = {
        "name": robot.name,
        "units": robot.units,
        "convention": robot.convention,
        "base_height": robot.base_height,
        "base_z": robot.base_z,
        "base_x": robot.base_x,
    }
    if full or not robot.base_is_shorthand:
        data["base_xyz"] = _floats(robot.base_xyz)
        data["base_rpy"] = _floats(robot.base_rpy)
    if full or not robot.tool.is_identity:
        data["tool"] = {"xyz": _floats(robot.tool.xyz), "rpy": _floats(robot.tool.rpy)}
    if full or robot.poses:
        data["poses"] = {name: _floats(values) for name, values in robot.poses}
    if full or robot.programs:
        data["programs"] = programs_to_data(robot.programs)
    data["joints"] = [
        {"type": j.type} | dict(zip(JOINT_KEYS[1:7], _floats(_values(j)), strict=True))
        for j in robot.joints
    ]
    for row, j in zip(data["joints"], robot.joints, strict=True):
        if full or j.offset:
            row["offset"] = float(j.offset)
        for key in JOINT_RATES:
            if getattr(j, key) is not None:
                row[key] = float(getattr(j, key))
    return data


def _floats(values) -> list[float]:
    return [float(v) for v in values]


def _values(joint: Joint) -> tuple[float, ...]:
    return (joint.theta, joint.d, joint.a, joint.alpha, joint.min, joint.max)


def file_defaults(robot: Robot) -> dict[str, Any]:
    """What a file may leave out, for this robot (limits depend on type and unit)."""
    return {
        "units": "mm",
        "convention": "standard",
        "base_height": 0.0,
        "base_z": "+z",
        "base_x": "+x",
        "base_xyz": [0.0, 0.0, 0.0],
        "base_rpy": [0.0, 0.0, 0.0],
        "tool": {"xyz": [0.0, 0.0, 0.0], "rpy": [0.0, 0.0, 0.0]},
        "poses": {},
        "programs": {},
        "joints": [
            dict(zip(("min", "max"), default_limits(j.type, robot.units), strict=True))
            | {"type": "revolute", "offset": 0.0}
            for j in robot.joints
        ],
    }

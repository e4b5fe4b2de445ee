"""Semantic checks shared by every way a robot or a joint vector is made.

Each check raises :class:`DhsimError` naming the field as it appears in a
robot file (``joints[3].alpha``; joints are numbered from 1, as on screen).
"""

from __future__ import annotations

import math
import numbers
import re
from collections.abc import Iterable
from typing import TYPE_CHECKING

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.program import check_programs
from dhsim_tui.core.model.program_timing import (
    MIN_TOP_ACCELERATION,
    MIN_TOP_SPEED,
    check_programs_timing,
)
from dhsim_tui.core.model.text import control_character, counted, printable, shortened
from dhsim_tui.core.model.units import (
    AXES,
    CONVENTIONS,
    JOINT_TYPES,
    MAX_ABS,
    MAX_JOINTS,
    MIN_JOINTS,
    UNITS,
    min_length,
    mm_to_unit,
)

if TYPE_CHECKING:
    from dhsim_tui.core.model.robot import Joint, Robot


#: a pose name that needs no quotes after ``poses.`` (a TOML bare key)
_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")
#: the longest robot or pose name: any real one is far shorter, and a saved
#: file's lines stay well within what a robot file may hold
MAX_NAME_CHARS = 1000


def fmt(value: float) -> str:
    """A number as people write it, and whole: ``431.8``, ``-90``, ``1e+06``,
    ``160.0000000001``. The short ``:g`` form is used only when it reads back
    as the same number; otherwise the shortest form that does (``repr``).
    Zero is ``0``, whatever its sign."""
    if value == 0:
        return "0"
    short = f"{value:g}"
    if float(short) == value:
        return short
    text = repr(float(value))
    return text.removesuffix(".0")


def pose_where(name: str) -> str:
    """How a pose is named in messages: ``poses.ready``, or quoted (and with
    control characters escaped) when the name is not a bare word:
    ``poses."x\\x1b[2J"``; a long name is shortened in the middle."""
    name = shortened(name)
    if _BARE_KEY.fullmatch(name):
        return f"poses.{name}"
    quoted = printable(name).replace('"', '\\"')
    return f'poses."{quoted}"'


def check_number(value: object, where: str) -> float:
    """A finite number of sane size, as a float (bools are not numbers)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise DhsimError(f"{where}: expected a number, got {_describe(value)}")
    if isinstance(value, numbers.Integral) and abs(int(value)) > MAX_ABS:
        number = math.inf  # float() would overflow on a huge integer
    else:
        number = float(value)
    if math.isnan(number):
        raise DhsimError(f"{where}: NaN is not a number a robot can use")
    if math.isinf(number) or abs(number) > MAX_ABS:
        raise DhsimError(f"{where}: {_describe(value)} is out of range (|value| <= {MAX_ABS:g})")
    return number


def _describe(value: object) -> str:
    if isinstance(value, str):
        return f"the text {shortened(value)!r}"
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if isinstance(value, int) and abs(value) > 1e300:
        return "a huge integer"  # too large for a float, so for fmt()
    if isinstance(value, float | int):
        return fmt(value)
    if isinstance(value, list | tuple):
        return "a list"
    if isinstance(value, dict):
        return "a table"
    return type(value).__name__


def check_choice(value: object, choices: Iterable[str], where: str) -> str:
    options = tuple(choices)
    if not isinstance(value, str) or value not in options:
        listed = ", ".join(repr(c) for c in options)
        raise DhsimError(f"{where}: {_describe(value)} is not one of {listed}")
    return value


def axis_vector(axis: str) -> tuple[int, int, int]:
    """``'-y'`` -> ``(0, -1, 0)``."""
    sign = 1 if axis[0] == "+" else -1
    index = "xyz".index(axis[1])
    vec = [0, 0, 0]
    vec[index] = sign
    return (vec[0], vec[1], vec[2])


def perpendicular_axes(axis: str) -> tuple[str, ...]:
    """The signed axes that may be paired with ``axis`` (for base_x given base_z)."""
    return tuple(a for a in AXES if a[1] != axis[1])


def check_length(value: float, where: str, units: str) -> None:
    """A length is 0 or at least one nanometre (:data:`MIN_LENGTH_MM`): a
    smaller one cannot be computed with (it underflows in products)."""
    bound = min_length(units)
    if value != 0 and abs(value) < bound * (1 - 1e-12):  # tolerance: unit conversions
        raise DhsimError(
            f"{where}: {fmt(value)} {units} is too small to compute with; "
            f"a length is 0 or at least 1 nanometre ({fmt(bound)} {units})"
        )


def check_joint(joint: Joint, number: int, units: str) -> None:
    where = f"joints[{number}]"
    check_choice(joint.type, JOINT_TYPES, f"{where}.type")
    for name in ("theta", "d", "a", "alpha", "min", "max", "offset"):
        check_number(getattr(joint, name), f"{where}.{name}")
    lengths = ("d", "a") if joint.is_revolute else ("d", "a", "min", "max", "offset")
    for name in lengths:
        check_length(getattr(joint, name), f"{where}.{name}", units)
    unit = joint.unit(units)
    if joint.min >= joint.max:
        raise DhsimError(
            f"{where}: min ({fmt(joint.min)}) must be less than max ({fmt(joint.max)})"
        )
    if not joint.min <= joint.home <= joint.max:
        shifted = f" ({joint.variable} - offset)" if joint.offset else ""
        raise DhsimError(
            f"{where}.{joint.variable}: home value {fmt(joint.home)} {unit}{shifted} is "
            f"outside the joint's limits {fmt(joint.min)}..{fmt(joint.max)} {unit}"
        )
    for name, per, least in (("vmax", "/s", MIN_TOP_SPEED), ("amax", "/s²", MIN_TOP_ACCELERATION)):
        value = getattr(joint, name)
        if value is None:
            continue
        if check_number(value, f"{where}.{name}") <= 0:
            raise DhsimError(
                f"{where}.{name}: must be greater than 0 {unit}{per}, not {fmt(value)}"
            )
        floor = least if joint.is_revolute else mm_to_unit(least, units)
        if value < floor:
            raise DhsimError(
                f"{where}.{name}: {fmt(value)} {unit}{per} is slower than any joint; "
                f"give at least {fmt(floor)} {unit}{per}"
            )


def check_triple(values: object, where: str, units: str | None) -> None:
    """Three finite numbers; lengths (``units`` given) 0 or at least 1 nm."""
    if isinstance(values, str | bytes) or not isinstance(values, Iterable):
        raise DhsimError(f"{where}: expected 3 numbers, got {_describe(values)}")
    values = list(values)
    if len(values) != 3:
        raise DhsimError(f"{where}: expected 3 numbers, got {len(values)}")
    for i, v in enumerate(values, start=1):
        check_number(v, f"{where}[{i}]")
        if units is not None:
            check_length(v, f"{where}[{i}]", units)


def check_text(value: str, where: str, what: str) -> None:
    """A name a terminal can show as it is: no control character (C0, DEL, C1,
    bidi overrides, zero-width marks; lone surrogates, which UTF-8 cannot hold)."""
    found = control_character(value)
    if found is not None:
        raise DhsimError(f"{where}: {what} may not hold control characters ({found})")


def check_name_length(value: str, where: str, what: str) -> None:
    """A name of at most :data:`MAX_NAME_CHARS` characters."""
    if len(value) > MAX_NAME_CHARS:
        raise DhsimError(
            f"{where}: {what} has at most {MAX_NAME_CHARS} characters; this one has {len(value)}"
        )


def check_robot(robot: Robot) -> None:
    """Raise :class:`DhsimError` on the first thing that makes ``robot`` invalid."""
    if not isinstance(robot.name, str) or not robot.name.strip():
        raise DhsimError("name: a robot needs a non-empty name")
    check_text(robot.name, "name", "a robot name")
    check_name_length(robot.name, "name", "a robot name")
    check_choice(robot.units, UNITS, "units")
    check_choice(robot.convention, CONVENTIONS, "convention")
    height = check_number(robot.base_height, "base_height")
    if height < 0:
        raise DhsimError(f"base_height: {fmt(height)} is below the floor; it must be >= 0")
    check_length(height, "base_height", robot.units)
    check_choice(robot.base_z, AXES, "base_z")
    check_choice(robot.base_x, AXES, "base_x")
    if robot.base_z[1] == robot.base_x[1]:
        raise DhsimError(
            f"base_x: {robot.base_x!r} is parallel to base_z {robot.base_z!r}; "
            f"choose one of {', '.join(perpendicular_axes(robot.base_z))}"
        )
    for where, values in (
        ("base_xyz", robot.base_xyz),
        ("base_rpy", robot.base_rpy),
        ("tool.xyz", robot.tool.xyz),
        ("tool.rpy", robot.tool.rpy),
    ):
        check_triple(values, where, robot.units if where.endswith("xyz") else None)
    count = len(robot.joints)
    if not MIN_JOINTS <= count <= MAX_JOINTS:
        raise DhsimError(
            f"joints: a robot has {MIN_JOINTS} to {MAX_JOINTS} joints, this one has {count}"
        )
    for number, joint in enumerate(robot.joints, start=1):
        check_joint(joint, number, robot.units)
    seen: set[str] = set()
    for name, values in robot.poses:
        if not isinstance(name, str) or not name.strip():
            raise DhsimError("poses: a pose needs a non-empty name")
        where = pose_where(name)
        check_text(name, where, "a pose name")
        check_name_length(name, where, "a pose name")
        if name in seen:
            raise DhsimError(f"{where}: the name is used twice")
        seen.add(name)
        check_joint_values(robot, values, where)
    check_programs(robot)
    check_programs_timing(robot)


def check_joint_values(robot: Robot, q: object, where: str = "q") -> tuple[float, ...]:
    """A joint vector as floats: one finite number per joint, each within limits."""
    if isinstance(q, str | bytes) or not isinstance(q, Iterable):
        raise DhsimError(
            f"{where}: expected {counted(robot.dof, 'joint value')}, got {_describe(q)}"
        )
    values = list(q)
    if len(values) != robot.dof:
        raise DhsimError(
            f"{where}: expected {counted(robot.dof, 'joint value')} ({', '.join(robot.labels)}), "
            f"got {len(values)}"
        )
    out = []
    for number, (joint, value) in enumerate(zip(robot.joints, values, strict=True), start=1):
        label = joint.label(number)
        v = check_number(value, f"{where}: {label}")
        if not joint.min <= v <= joint.max:
            unit = joint.unit(robot.units)
            raise DhsimError(
                f"{where}: {label} = {fmt(v)} {unit} is outside its limits "
                f"{fmt(joint.min)}..{fmt(joint.max)} {unit}"
            )
        out.append(v)
    return tuple(out)

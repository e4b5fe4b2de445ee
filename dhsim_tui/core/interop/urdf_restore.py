"""A URDF that ``dhsim export`` wrote (:mod:`dhsim_tui.core.interop.urdf_import`):
the robot held in its ``dhsim-robot`` comment
(:mod:`dhsim_tui.core.interop.urdf_export`) read back (:func:`_stored_robot`),
compared with the URDF's joints (:func:`_mismatch`: the same joints, kinds
and limits, and the same forward kinematics), and given back exactly when
it still matches (:func:`restore_stored_robot`), else a remark saying why not.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

from dhsim_tui.core.files.programschema import programs_from_data
from dhsim_tui.core.interop.convert import convert
from dhsim_tui.core.interop.imported import ImportResult, quoted
from dhsim_tui.core.interop.urdf_chain import UrdfChain
from dhsim_tui.core.interop.urdf_check import UrdfReference, checked_note, joint_name_lines
from dhsim_tui.core.interop.urdf_export import (
    STORED_FORMAT,
    STORED_JOINT_FIELDS,
    STORED_OPTIONAL_JOINT_FIELDS,
    STORED_VERSION,
)
from dhsim_tui.core.interop.urdf_xml import DHSIM_COMMENT
from dhsim_tui.core.model.editing import set_units
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import MAX_ABS, MAX_JOINTS, UNITS, Joint, Robot, Tool
from dhsim_tui.core.model.text import counted, printable, shortened


def restore_stored_robot(
    chain: UrdfChain, source: str, convention: str | None, units: str | None, name: str | None
) -> ImportResult | str:
    """The robot stored in the file's dhsim comment, if it still matches the
    chain; else a remark saying why it was not used."""
    fallback = "imported from the URDF's joints alone"
    try:
        stored = _stored_robot(chain.stored or "")
    except DhsimError as exc:
        return (
            f"the robot dhsim stored in the file's {DHSIM_COMMENT} comment cannot be read "
            f"({shortened(str(exc))}); {fallback}"
        )
    why = _mismatch(stored, chain)
    if why is not None:
        return (
            f"the robot dhsim stored in the file ({quoted(stored.name, 60)}) does not match "
            f"its joints from link {quoted(chain.base, 60)} to link {quoted(chain.tip, 60)} "
            f"({why}; edited since dhsim exported it?): {fallback}"
        )
    robot = stored
    notes = [
        f"{counted(robot.dof, 'joint')} restored as dhsim exported them ({robot.convention} D-H, "
        f"lengths in {robot.units}, {len(robot.poses)} named poses)"
    ]
    try:
        if units is not None and units != robot.units:
            robot = set_units(robot, units)
            notes.append(f"lengths converted from {stored.units} to {units}")
        if convention is not None and convention != robot.convention:
            robot = convert(robot, convention)
            notes.append(f"converted from {stored.convention} to {convention} D-H (the same arm)")
        if name:
            robot = replace(robot, name=printable(name).strip() or robot.name)
    except DhsimError as exc:
        raise DhsimError(printable(f"{source}: {exc}")) from None
    reference = UrdfReference.of(chain, robot)
    position, rotation = reference.difference(robot)
    if not reference.matches(position, rotation):  # a conversion lost the match
        raise DhsimError(
            printable(
                f"{source}: the restored robot, converted, is off the URDF by "
                f"{position:.1e} m, {rotation:.1e} rad"
            )
        )
    notes.append(checked_note(position, rotation))
    header = (
        f"Imported by dhsim from {Path(source).name} ({shortened(robot.name)}): the robot "
        f"dhsim exported to it, restored from its {DHSIM_COMMENT} comment.",
        f"Checked against the URDF's joints from link {shortened(chain.base)} to link "
        f"{shortened(chain.tip)}: they still match.",
        *joint_name_lines(chain),
    )
    return ImportResult(
        robot, tuple(printable(n) for n in notes), tuple(printable(h) for h in header)
    )


def _stored_robot(text: str) -> Robot:
    """The robot of a ``dhsim-robot`` comment: dhsim's JSON export of it."""
    start = text.find("{")
    if start < 0:
        raise DhsimError("it holds no JSON object")
    try:
        data, end = json.JSONDecoder().raw_decode(text, start)
    except (ValueError, RecursionError) as exc:
        raise DhsimError(f"not valid JSON: {exc}") from None
    if text[end:].strip():
        raise DhsimError("text follows its JSON object")
    if not isinstance(data, dict):
        raise DhsimError("its JSON is not an object")
    if data.get("format") != STORED_FORMAT or data.get("version") != STORED_VERSION:
        raise DhsimError(f"it is not format {STORED_FORMAT!r} version {STORED_VERSION}")
    if data.get("parameter_order") != list(STORED_JOINT_FIELDS):
        raise DhsimError(f"parameter_order: expected {list(STORED_JOINT_FIELDS)}")
    units, base, tool = (_object(data, key) for key in ("units", "base", "tool"))
    if units.get("angle") != "deg":
        raise DhsimError("units.angle: expected 'deg'")
    joints = data.get("joints")
    if not isinstance(joints, list) or not 1 <= len(joints) <= MAX_JOINTS:
        raise DhsimError(f"joints: expected a list of 1 to {MAX_JOINTS} joints")
    poses = _object(data, "poses")
    rows = []
    for number, joint in enumerate(joints, start=1):
        if not isinstance(joint, dict):
            raise DhsimError(f"joints[{number}]: expected an object")
        missing = [key for key in ("type", *STORED_JOINT_FIELDS) if key not in joint]
        if missing:
            raise DhsimError(f"joints[{number}]: no {', '.join(missing)}")
        values = {key: _number(joint[key]) for key in STORED_JOINT_FIELDS}
        for key in STORED_OPTIONAL_JOINT_FIELDS:
            if key in joint:
                values[key] = _number(joint[key])
        rows.append(Joint(type=joint["type"], **values))
    return Robot(
        name=data.get("name"),  # type: ignore[arg-type]
        joints=tuple(rows),
        units=units.get("length"),  # type: ignore[arg-type]
        convention=data.get("convention"),  # type: ignore[arg-type]
        base_height=_number(base.get("height")),  # type: ignore[arg-type]
        base_z=base.get("z"),  # type: ignore[arg-type]
        base_x=base.get("x"),  # type: ignore[arg-type]
        base_xyz=_numbers(base.get("xyz")),  # type: ignore[arg-type]
        base_rpy=_numbers(base.get("rpy")),  # type: ignore[arg-type]
        tool=Tool(_numbers(tool.get("xyz")), _numbers(tool.get("rpy"))),  # type: ignore[arg-type]
        poses=tuple((key, _numbers(values)) for key, values in poses.items()),  # type: ignore[misc]
        programs=programs_from_data(data.get("programs", {})),
    )


def _object(data: dict, key: str) -> dict:
    value = data.get(key)
    if not isinstance(value, dict):
        raise DhsimError(f"{key}: expected an object")
    return value


def _number(value: object) -> object:
    """A JSON number as a float; anything else as it is, for the robot's own
    checks to name (a huge integer stays one: float() would overflow)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return value
    return float(value) if isinstance(value, float) or abs(value) <= MAX_ABS else value


def _numbers(values: object) -> object:
    if not isinstance(values, list):
        return values
    return tuple(_number(v) for v in values)


def _mismatch(robot: Robot, chain: UrdfChain) -> str | None:
    """What differs between the stored robot and the URDF's chain, or None."""
    moving = chain.moving
    if len(moving) != robot.dof:
        return f"{len(moving)} moving joints, the stored robot has {robot.dof}"
    metres = UNITS[robot.units] / 1000.0
    for number, (joint, theirs) in enumerate(zip(robot.joints, moving, strict=True), start=1):
        if joint.type != theirs.kind:
            return f"joint {number} is {theirs.kind} in the URDF, {joint.type} in the robot"
        scale = math.radians(1.0) if joint.is_revolute else metres
        ours = (joint.min * scale, joint.max * scale)
        if not all(
            math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
            for a, b in zip(ours, (theirs.lower, theirs.upper), strict=True)
        ):
            return f"joint {number}'s limits differ"
    reference = UrdfReference.of(chain, robot)
    position, rotation = reference.difference(robot)
    if not reference.matches(position, rotation):
        return f"the tool is off by {position:.1e} m and {rotation:.1e} rad"
    return None

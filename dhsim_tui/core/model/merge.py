"""Two people's changes to one robot, put together: a three-way merge.

When a robot file changes on disk while it is open with unsaved edits,
"reload" takes the file as it is now (*theirs*) and re-applies *my* edits
on top: every field is compared with what the file held when it was read
(the *base*). A field only I changed takes my value, a field only they
changed takes theirs, a field we both changed to different values is a
:class:`Conflict` that the user settles (``resolve``).

Fields are the robot's parts a user edits one at a time: the name, units,
convention, base and tool fields; each joint's type, theta, d, a, alpha,
offset, min, max, vmax and amax (or the whole table, when the joints were
added, deleted or moved on either side); each named pose; each program,
whole (its steps are one field), by name. A change of units on one
side converts the other two robots to the new unit first, so their lengths
compare; a change of units on both sides to different units is one
conflict over the whole robot. The merged robot is built as a new
:class:`Robot`, so it is checked like any other: a combination that is not
a valid robot (my min above their max) is refused with the reason.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from typing import Literal

from dhsim_tui.core.model.editing import ROBOT_FIELDS, robot_field, set_units
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.program import Program
from dhsim_tui.core.model.robot import Joint, Robot, Tool
from dhsim_tui.core.model.validation import fmt

Side = Literal["mine", "theirs"]
JOINT_FIELDS = tuple(f.name for f in fields(Joint))
#: the key of the whole table (joints added, deleted or moved on a side)
TABLE = "joints"
#: the key of the whole robot (both sides changed its units differently)
WHOLE = "robot"
#: a program's steps, read out in a conflict, are shortened past this
PROGRAM_TEXT_CHARS = 120


@dataclass(frozen=True)
class Conflict:
    """A field both sides changed, to different values: its key, what the
    user reads, and the two values as text."""

    key: str
    label: str
    mine: str
    theirs: str


def _text(value: object) -> str:
    if value is None:
        return "(none)"
    if isinstance(value, float):
        return fmt(value)
    if isinstance(value, tuple):
        return ", ".join(_text(v) for v in value)
    if isinstance(value, Joint):
        return f"{value.type} theta {fmt(value.theta)} d {fmt(value.d)} a {fmt(value.a)}"
    if isinstance(value, Program):
        steps = "; ".join(step.describe() for step in value.steps) or "no steps"
        if len(steps) > PROGRAM_TEXT_CHARS:
            steps = steps[: PROGRAM_TEXT_CHARS - 1] + "…"
        count = len(value.steps)
        return f"{count} step{'' if count == 1 else 's'}: {steps}"
    return str(value)


def _flat(robot: Robot, per_joint: bool) -> dict[str, object]:
    """The robot as {field key: value}."""
    out: dict[str, object] = {name: robot_field(robot, name) for name in ROBOT_FIELDS}
    if per_joint:
        for i, joint in enumerate(robot.joints, start=1):
            for name in JOINT_FIELDS:
                out[f"joint {i} {name}"] = getattr(joint, name)
    else:
        out[TABLE] = robot.joints
    for name, values in robot.poses:
        out[f"pose {name}"] = values
    for program in robot.programs:
        out[f"program {program.name}"] = program
    return out


def _label(key: str) -> str:
    """What a field is called in a question: ``joint 1 max``, ``base xyz``,
    ``pose qr``, ``program demo``."""
    return key.replace("_", " ")


@dataclass(frozen=True)
class Merge:
    """Theirs with my changes on top; ``conflicts`` to settle first."""

    base: Robot
    mine: Robot
    theirs: Robot
    merged: dict[str, object]
    conflicts: tuple[Conflict, ...]
    per_joint: bool
    pose_order: tuple[str, ...] = field(default=())
    program_order: tuple[str, ...] = field(default=())

    def resolve(self, choices: Mapping[str, Side]) -> Robot:
        """The merged robot, each conflict settled by ``choices`` (a key
        missing from it keeps theirs). DhsimError when the combination is
        not a valid robot."""
        if any(c.key == WHOLE for c in self.conflicts):
            return self.mine if choices.get(WHOLE) == "mine" else self.theirs
        values = dict(self.merged)
        mine = _flat(self.mine, self.per_joint)
        theirs = _flat(self.theirs, self.per_joint)
        for conflict in self.conflicts:
            side = mine if choices.get(conflict.key) == "mine" else theirs
            values[conflict.key] = side.get(conflict.key)
        orders = (self.pose_order, self.program_order)
        return _build(values, self.per_joint, orders, len(self.theirs.joints))


def _build(
    values: dict[str, object],
    per_joint: bool,
    orders: tuple[tuple[str, ...], tuple[str, ...]],
    dof: int,
) -> Robot:
    if per_joint:
        joints = tuple(
            Joint(**{name: values[f"joint {i} {name}"] for name in JOINT_FIELDS})
            for i in range(1, dof + 1)
        )
    else:
        joints = values[TABLE]  # type: ignore[assignment]
    pose_order, program_order = orders
    poses = tuple(
        (name, values[f"pose {name}"])
        for name in pose_order
        if values.get(f"pose {name}") is not None
    )
    programs = tuple(
        values[f"program {name}"]
        for name in program_order
        if values.get(f"program {name}") is not None
    )
    try:
        return Robot(
            name=values["name"],  # type: ignore[arg-type]
            joints=joints,  # type: ignore[arg-type]
            units=values["units"],  # type: ignore[arg-type]
            convention=values["convention"],  # type: ignore[arg-type]
            base_height=values["base_height"],  # type: ignore[arg-type]
            base_z=values["base_z"],  # type: ignore[arg-type]
            base_x=values["base_x"],  # type: ignore[arg-type]
            base_xyz=values["base_xyz"],  # type: ignore[arg-type]
            base_rpy=values["base_rpy"],  # type: ignore[arg-type]
            tool=Tool(values["tool_xyz"], values["tool_rpy"]),  # type: ignore[arg-type]
            poses=poses,  # type: ignore[arg-type]
            programs=programs,  # type: ignore[arg-type]
        )
    except DhsimError as exc:
        raise DhsimError(f"your changes and the file's cannot be combined: {exc}") from None


def merge(base: Robot, mine: Robot, theirs: Robot) -> Merge:
    """Theirs with my changes (against ``base``) on top."""
    if mine.units != base.units and theirs.units != base.units and mine.units != theirs.units:
        whole = Conflict(
            WHOLE, "the whole robot (both changed its units)", mine.units, theirs.units
        )
        return Merge(base, mine, theirs, {}, (whole,), False)
    if mine.units != base.units:  # compare everything in the unit I chose
        base, theirs = set_units(base, mine.units), set_units(theirs, mine.units)
    elif theirs.units != base.units:
        base, mine = set_units(base, theirs.units), set_units(mine, theirs.units)
    per_joint = len(base.joints) == len(mine.joints) == len(theirs.joints)
    old, ours, other = _flat(base, per_joint), _flat(mine, per_joint), _flat(theirs, per_joint)
    merged: dict[str, object] = {}
    conflicts: list[Conflict] = []
    keys = list(dict.fromkeys([*other, *ours, *old]))
    for key in keys:
        was, now_mine, now_theirs = old.get(key), ours.get(key), other.get(key)
        if now_mine == was:
            merged[key] = now_theirs
        elif now_theirs == was or now_mine == now_theirs:
            merged[key] = now_mine
        else:
            merged[key] = now_theirs
            conflicts.append(Conflict(key, _label(key), _text(now_mine), _text(now_theirs)))
    order = tuple(dict.fromkeys([name for name, _ in theirs.poses] + [n for n, _ in mine.poses]))
    programs = tuple(dict.fromkeys(theirs.program_names + mine.program_names))
    return Merge(base, mine, theirs, merged, tuple(conflicts), per_joint, order, programs)

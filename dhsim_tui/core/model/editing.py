"""Edits of a robot, each returning a new valid robot or raising DhsimError.

The editor screen is a thin layer over these: a rejected edit leaves the
robot in memory exactly as it was, and every accepted one can be undone.
Joint values follow the joints: an edit that adds, deletes, moves or retypes
a joint, or changes the unit, changes the named poses and the programs' own
joint values (a move's ``to`` list) with it.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.model.robot import (
    MAX_JOINTS,
    MIN_JOINTS,
    UNITS,
    Joint,
    Robot,
    Tool,
    default_limits,
)
from dhsim_tui.core.model.text import counted
from dhsim_tui.core.model.validation import check_number, perpendicular_axes

JOINT_FIELDS = ("theta", "d", "a", "alpha", "min", "max", "offset")
#: the robot's own settings at the top of its file, in file order (the
#: file's schema adds the tool, poses, programs and joints tables)
HEADER_FIELDS = (
    "name",
    "units",
    "convention",
    "base_height",
    "base_z",
    "base_x",
    "base_xyz",
    "base_rpy",
)
#: a robot's fields at the top level, in the order the editor lists them
#: (and a reload's merge asks about them): the header and the tool's
ROBOT_FIELDS = (*HEADER_FIELDS, "tool_xyz", "tool_rpy")


def robot_field(robot: Robot, name: str):
    """The value of one of :data:`ROBOT_FIELDS`."""
    if name in ("tool_xyz", "tool_rpy"):
        return getattr(robot.tool, name[5:])
    return getattr(robot, name)


#: fields whose numbers are lengths (converted when the unit changes)
LENGTH_FIELDS = ("d", "a")
#: a file name for a robot: letters, digits, space, dot, dash, underscore
SAFE_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9 ._-]{0,99}$")


def parse_number(text: str, what: str = "value") -> float:
    """A number typed by a person: finite, of sane size; DhsimError otherwise."""
    stripped = text.strip()
    if not stripped:
        raise DhsimError(f"{what}: type a number")
    try:
        if "_" in stripped or not stripped.isascii():  # float() reads 1_0 and ١ too
            raise ValueError
        value = float(stripped)
    except ValueError:
        raise DhsimError(f"{what}: {stripped!r} is not a number") from None
    return check_number(value, what)


def parse_numbers(text: str, count: int, what: str) -> tuple[float, ...]:
    """``"1, 2, 3"`` -> exactly ``count`` numbers."""
    items = [item for item in re.split(r"[,\s]+", text.strip()) if item]
    if len(items) != count:
        raise DhsimError(
            f"{what}: expected {counted(count, 'number')} separated by commas, got {len(items)}"
        )
    return tuple(parse_number(item, f"{what} item {i}") for i, item in enumerate(items, 1))


def _rebuild(robot: Robot, **changes) -> Robot:
    return replace(robot, **changes)  # Robot.__post_init__ validates


def _joints(robot: Robot, index: int, joint: Joint) -> tuple[Joint, ...]:
    return (*robot.joints[:index], joint, *robot.joints[index + 1 :])


def set_joint_field(robot: Robot, index: int, name: str, value: float) -> Robot:
    """One D-H number of one joint."""
    if name not in JOINT_FIELDS:
        raise DhsimError(f"joint field {name!r} is not one of {', '.join(JOINT_FIELDS)}")
    joint = replace(robot.joints[index], **{name: float(value)})
    return _rebuild(robot, joints=_joints(robot, index, joint))


def toggle_type(robot: Robot, index: int) -> Robot:
    """Revolute <-> prismatic. The variable moves between theta and d; the new
    variable gets the default range, widened if needed to hold its home value."""
    joint = robot.joints[index]
    new_type = "prismatic" if joint.is_revolute else "revolute"
    low, high = default_limits(new_type, robot.units)
    home = joint.d if new_type == "prismatic" else joint.theta
    low, high = min(low, home), max(high, home)
    # the offset, top speed and acceleration were in the old variable's unit:
    # the new variable starts without them
    toggled = replace(joint, type=new_type, min=low, max=high, offset=0.0, vmax=None, amax=None)
    poses = _pose_values(robot, index, lambda _values: toggled.home)

    def retyped(values: tuple[float, ...]) -> tuple[float, ...]:
        return (*values[:index], toggled.home, *values[index + 1 :])

    return _rebuild(
        robot,
        joints=_joints(robot, index, toggled),
        poses=poses,
        programs=_program_values(robot, retyped),
    )


def _pose_values(robot: Robot, index: int, value_of) -> tuple:
    """Poses with joint ``index``'s value replaced by ``value_of(values)``."""
    out = []
    for name, values in robot.poses:
        v = list(values)
        v[index] = value_of(values)
        out.append((name, tuple(v)))
    return tuple(out)


def _program_values(robot: Robot, change, speed=None) -> tuple[Program, ...]:
    """The programs with every move's own joint values (a ``to`` list, not a
    pose name) replaced by ``change(values)``, and, given ``speed``, every
    linear move's speed by ``speed(value)``."""

    def step(item: Step) -> Step:
        if item.is_wait:
            return item
        if item.to is not None and not isinstance(item.to, str):
            item = replace(item, to=tuple(change(tuple(item.to))))
        if speed is not None and item.move == "linear" and item.speed is not None:
            item = replace(item, speed=speed(item.speed))
        return item

    return tuple(
        replace(program, steps=tuple(step(s) for s in program.steps)) for program in robot.programs
    )


def insert_joint(robot: Robot, after: int) -> Robot:
    """A new revolute joint (all zeros, default limits) after joint ``after``."""
    if robot.dof >= MAX_JOINTS:
        raise DhsimError(f"a robot has at most {MAX_JOINTS} joints")
    position = after + 1
    joint = Joint()
    joints = (*robot.joints[:position], joint, *robot.joints[position:])

    def inserted(values: tuple[float, ...]) -> tuple[float, ...]:
        return (*values[:position], joint.home, *values[position:])

    poses = tuple((name, inserted(values)) for name, values in robot.poses)
    programs = _program_values(robot, inserted)
    return _rebuild(robot, joints=joints, poses=poses, programs=programs)


def delete_joint(robot: Robot, index: int) -> Robot:
    if robot.dof <= MIN_JOINTS:
        raise DhsimError(f"a robot needs at least {MIN_JOINTS} joint")
    joints = robot.joints[:index] + robot.joints[index + 1 :]

    def deleted(values: tuple[float, ...]) -> tuple[float, ...]:
        return values[:index] + values[index + 1 :]

    poses = tuple((name, deleted(values)) for name, values in robot.poses)
    return _rebuild(robot, joints=joints, poses=poses, programs=_program_values(robot, deleted))


def move_joint(robot: Robot, index: int, delta: int) -> Robot:
    """Swap a joint with its neighbour (poses follow)."""
    other = index + delta
    if not 0 <= other < robot.dof:
        raise DhsimError("the joint is already at the end of the table")

    def swap(items: tuple) -> tuple:
        items = list(items)
        items[index], items[other] = items[other], items[index]
        return tuple(items)

    poses = tuple((name, swap(values)) for name, values in robot.poses)
    programs = _program_values(robot, swap)
    return _rebuild(robot, joints=swap(robot.joints), poses=poses, programs=programs)


def set_name(robot: Robot, text: str) -> Robot:
    return _rebuild(robot, name=text.strip())


def set_units(robot: Robot, units: str) -> Robot:
    """Change the unit, converting every length so the arm keeps its size."""
    if units not in UNITS:
        raise DhsimError(f"units: {units!r} is not one of {', '.join(UNITS)}")
    ratio = UNITS[robot.units] / UNITS[units]

    def factor_of(value: float) -> float:
        return _clean(value * ratio)

    def joint(j: Joint) -> Joint:
        changes = {"d": factor_of(j.d), "a": factor_of(j.a)}
        if not j.is_revolute:
            changes |= {
                "min": factor_of(j.min),
                "max": factor_of(j.max),
                "offset": factor_of(j.offset),
            }
            for name in ("vmax", "amax"):  # units a second (a second squared)
                if getattr(j, name) is not None:
                    changes[name] = factor_of(getattr(j, name))
        return replace(j, **changes)

    def converted(values: tuple[float, ...]) -> tuple[float, ...]:
        return tuple(
            v if j.is_revolute else factor_of(v) for j, v in zip(robot.joints, values, strict=True)
        )

    poses = tuple((name, converted(values)) for name, values in robot.poses)
    programs = _program_values(robot, converted, factor_of)  # a linear speed: units a second
    tool = replace(robot.tool, xyz=tuple(factor_of(v) for v in robot.tool.xyz))
    return _rebuild(
        robot,
        units=units,
        joints=tuple(joint(j) for j in robot.joints),
        base_height=factor_of(robot.base_height),
        base_xyz=tuple(factor_of(v) for v in robot.base_xyz),
        tool=tool,
        poses=poses,
        programs=programs,
    )


def _clean(value: float) -> float:
    """A converted length without float noise (304.8 mm -> 30.48 cm, not 30.480000000000004)."""
    return float(f"{value:.12g}")


def set_convention(robot: Robot, convention: str) -> Robot:
    return _rebuild(robot, convention=convention)


def set_base_height(robot: Robot, value: float) -> Robot:
    return _rebuild(robot, base_height=float(value))


def set_base_z(robot: Robot, axis: str) -> Robot:
    """Frame 0's z axis; base_x follows to stay perpendicular if it must."""
    base_x = robot.base_x
    if axis[1:] == base_x[1:]:
        base_x = perpendicular_axes(axis)[0]
    return _rebuild(robot, base_z=axis, base_x=base_x)


def set_base_x(robot: Robot, axis: str) -> Robot:
    if axis not in perpendicular_axes(robot.base_z):
        raise DhsimError(
            f"base_x: {axis!r} is parallel to base_z {robot.base_z!r}; "
            f"choose one of {', '.join(perpendicular_axes(robot.base_z))}"
        )
    return _rebuild(robot, base_x=axis)


def set_base(robot: Robot, xyz=None, rpy=None) -> Robot:
    """The general base: frame 0's offset and turn after base_z/base_x."""
    return _rebuild(
        robot,
        base_xyz=tuple(float(v) for v in xyz) if xyz is not None else robot.base_xyz,
        base_rpy=tuple(float(v) for v in rpy) if rpy is not None else robot.base_rpy,
    )


def set_tool(robot: Robot, xyz=None, rpy=None) -> Robot:
    tool = Tool(
        xyz=tuple(xyz) if xyz is not None else robot.tool.xyz,
        rpy=tuple(rpy) if rpy is not None else robot.tool.rpy,
    )
    return _rebuild(robot, tool=tool)


def set_pose(robot: Robot, name: str, values: tuple[float, ...]) -> Robot:
    """Add or replace a named pose (checked against the limits)."""
    name = name.strip()
    if not name:
        raise DhsimError("a pose needs a name")
    poses = dict(robot.poses)
    poses[name] = tuple(values)
    return _rebuild(robot, poses=tuple(poses.items()))


def delete_pose(robot: Robot, name: str) -> Robot:
    """Without the named pose (refused, naming the step, while a program moves to it)."""
    return _rebuild(robot, poses=tuple(p for p in robot.poses if p[0] != name))


def set_program(robot: Robot, program: Program) -> Robot:
    """Add a program, or replace the one of its name where it stands (checked)."""
    name = program.name.strip()
    if not name:
        raise DhsimError("a program needs a name")
    program = replace(program, name=name)
    names = robot.program_names
    if name in names:
        index = names.index(name)
        programs = (*robot.programs[:index], program, *robot.programs[index + 1 :])
    else:
        programs = (*robot.programs, program)
    return _rebuild(robot, programs=programs)


def delete_program(robot: Robot, name: str) -> Robot:
    return _rebuild(robot, programs=tuple(p for p in robot.programs if p.name != name))


def new_robot(name: str = "new robot", joints: int = 1, units: str = "mm") -> Robot:
    """The seed's guided start: ``joints`` revolute rows, everything else default."""
    if not MIN_JOINTS <= joints <= MAX_JOINTS:
        raise DhsimError(f"a robot has {MIN_JOINTS} to {MAX_JOINTS} joints, not {joints}")
    return Robot(name=name, joints=tuple(Joint() for _ in range(joints)), units=units)


def check_file_name(name: str) -> str:
    """A robot file's name (no folder): safe on every platform, no '..', no slash."""
    stripped = name.strip().removesuffix(".toml")
    if not stripped:
        raise DhsimError("file name: type a name")
    if "/" in stripped or "\\" in stripped:
        raise DhsimError(f"file name: {stripped!r} has a slash; give a name, not a path")
    if ".." in stripped or not SAFE_NAME.match(stripped):
        raise DhsimError(
            f"file name: {stripped!r} is not a safe file name "
            "(letters, digits, space, . - _; starting with a letter or digit)"
        )
    return stripped


def slug(name: str) -> str:
    """``"SCARA on a pedestal"`` -> ``"scara_on_a_pedestal"``."""
    text = re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_")
    return text[:60] or "robot"


def unload(robot: Robot) -> Robot:
    """``robot`` without the data computed from it and cached on it (the
    compiled kinematics, the Jacobian samples): only its fields stay, so a
    robot kept for undo costs about a kilobyte, not tens. Nothing it means
    changes: whatever was dropped is computed again on first use."""
    fields = Robot.__dataclass_fields__
    for name in [name for name in vars(robot) if name not in fields]:
        del vars(robot)[name]
    return robot


@dataclass
class History:
    """Undo and redo over immutable robots: each state is a whole robot.

    Robots waiting in the undo and redo stacks are kept :func:`unload`-ed:
    3,000 edits of a 32-joint arm would otherwise keep 3,000 compiled
    kinematics (about 41 KiB each)."""

    current: Robot
    _undo: list[Robot] = field(default_factory=list)
    _redo: list[Robot] = field(default_factory=list)

    def push(self, robot: Robot) -> bool:
        """Make ``robot`` current; False (and nothing recorded) if it is unchanged."""
        if robot == self.current:
            return False
        self._undo.append(unload(self.current))
        self._redo.clear()
        self.current = robot
        return True

    def undo(self) -> bool:
        if not self._undo:
            return False
        self._redo.append(unload(self.current))
        self.current = self._undo.pop()
        return True

    def redo(self) -> bool:
        if not self._redo:
            return False
        self._undo.append(unload(self.current))
        self.current = self._redo.pop()
        return True

    @property
    def can_undo(self) -> bool:
        return bool(self._undo)

    @property
    def can_redo(self) -> bool:
        return bool(self._redo)

"""The robot model: joints, base, tool and named poses as frozen dataclasses.

A :class:`Robot` is immutable and always valid; it is built through
:func:`make_robot` (or the file loader), which checks every field. Editing
means building a new robot, so the one in memory is never half-changed.
Angles are in degrees and lengths in the robot's unit throughout.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Literal

from dhsim_tui.core.errors import DhsimError

if TYPE_CHECKING:
    from dhsim_tui.core.kinematics import Kinematics

JointType = Literal["revolute", "prismatic"]
JOINT_TYPES: tuple[str, ...] = ("revolute", "prismatic")
CONVENTIONS: tuple[str, ...] = ("standard", "modified")
#: millimetres per unit
UNITS: dict[str, float] = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4}
AXES: tuple[str, ...] = ("+x", "-x", "+y", "-y", "+z", "-z")
MIN_JOINTS = 1
MAX_JOINTS = 32
#: decimals shown for a length in each unit (about 0.01 mm); degrees get 2
LENGTH_DECIMALS: dict[str, int] = {"mm": 2, "cm": 3, "m": 5, "in": 4}
#: the largest magnitude any number may have (degrees or robot units)
MAX_ABS = 1e6
REVOLUTE_LIMIT_DEG = 180.0
PRISMATIC_LIMIT_MM = 400.0


def mm_to_unit(value_mm: float, units: str) -> float:
    """Convert a length given in millimetres to the robot's unit."""
    return value_mm / UNITS[units]


def default_limits(joint_type: str, units: str) -> tuple[float, float]:
    """The seed's default range: ±180 deg, or ±400 mm in the robot's unit."""
    if joint_type == "revolute":
        return (-REVOLUTE_LIMIT_DEG, REVOLUTE_LIMIT_DEG)
    span = mm_to_unit(PRISMATIC_LIMIT_MM, units)
    return (-span, span)


@dataclass(frozen=True)
class Joint:
    """One D-H row. The joint variable is theta (revolute) or d (prismatic);
    the value written in the row is the joint's home value."""

    type: JointType = "revolute"
    theta: float = 0.0
    d: float = 0.0
    a: float = 0.0
    alpha: float = 0.0
    min: float = -REVOLUTE_LIMIT_DEG
    max: float = REVOLUTE_LIMIT_DEG

    @property
    def is_revolute(self) -> bool:
        return self.type == "revolute"

    @property
    def home(self) -> float:
        """The joint variable's value in the table."""
        return self.theta if self.is_revolute else self.d

    @property
    def variable(self) -> str:
        """The name of the D-H parameter that moves: ``theta`` or ``d``."""
        return "theta" if self.is_revolute else "d"

    def label(self, number: int) -> str:
        """The seed's label: ``Th3`` for a revolute joint, ``d3`` for a prismatic one."""
        return f"Th{number}" if self.is_revolute else f"d{number}"

    def unit(self, units: str) -> str:
        """The unit of the joint variable."""
        return "deg" if self.is_revolute else units

    def with_home(self, value: float) -> Joint:
        """This joint with its variable's table value replaced."""
        from dataclasses import replace

        return replace(self, **{self.variable: float(value)})


@dataclass(frozen=True)
class Tool:
    """The tool frame relative to the last joint frame: translation, then
    rotation R = Rz(yaw) Ry(pitch) Rx(roll), angles in degrees."""

    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def is_identity(self) -> bool:
        return not any(self.xyz) and not any(self.rpy)

    @property
    def length(self) -> float:
        return math.sqrt(sum(v * v for v in self.xyz))


@dataclass(frozen=True)
class Robot:
    """A serial arm: D-H rows plus everything needed to place it in the world.

    ``poses`` is a tuple of ``(name, values)`` pairs so the robot stays
    hashable and ordered as written in its file.
    """

    name: str
    joints: tuple[Joint, ...]
    units: str = "mm"
    convention: str = "standard"
    base_height: float = 0.0
    base_z: str = "+z"
    base_x: str = "+x"
    tool: Tool = field(default_factory=Tool)
    poses: tuple[tuple[str, tuple[float, ...]], ...] = ()

    def __post_init__(self) -> None:
        from dhsim_tui.core.validation import check_robot

        check_robot(self)

    # -- derived facts ---------------------------------------------------
    @property
    def dof(self) -> int:
        return len(self.joints)

    @property
    def type_string(self) -> str:
        """``RRPRRR``-style summary of the joint types."""
        return "".join("R" if j.is_revolute else "P" for j in self.joints)

    @property
    def home(self) -> tuple[float, ...]:
        return tuple(j.home for j in self.joints)

    @property
    def labels(self) -> tuple[str, ...]:
        return tuple(j.label(i) for i, j in enumerate(self.joints, start=1))

    @property
    def lower(self) -> tuple[float, ...]:
        return tuple(j.min for j in self.joints)

    @property
    def upper(self) -> tuple[float, ...]:
        return tuple(j.max for j in self.joints)

    @property
    def pose_names(self) -> tuple[str, ...]:
        return tuple(name for name, _ in self.poses)

    def pose(self, name: str) -> tuple[float, ...]:
        """The joint values of a named pose; a clear error if there is none."""
        for pose_name, values in self.poses:
            if pose_name == name:
                return values
        known = ", ".join(self.pose_names) or "none"
        raise DhsimError(f"robot {self.name!r} has no pose named {name!r} (poses: {known})")

    def mm(self, value_mm: float) -> float:
        """A length given in millimetres, in this robot's unit."""
        return mm_to_unit(value_mm, self.units)

    @cached_property
    def kinematics(self) -> Kinematics:
        """Forward kinematics compiled for this robot (built once, on first use)."""
        from dhsim_tui.core.kinematics import Kinematics

        return Kinematics(self)

    def check_q(self, q: object) -> tuple[float, ...]:
        """Validate a joint vector: right length, finite numbers, within limits."""
        from dhsim_tui.core.validation import check_joint_values

        return check_joint_values(self, q)

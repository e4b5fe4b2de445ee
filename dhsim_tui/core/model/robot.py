"""The robot model: joints, base, tool and named poses as frozen dataclasses.

A :class:`Robot` is immutable and always valid: building one checks every
field (:func:`dhsim_tui.core.model.validation.check_robot`), so a robot from a file,
from the editor or from code is refused the same way, naming the field. Editing
means building a new robot, so the one in memory is never half-changed.
Angles are in degrees and lengths in the robot's unit throughout.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics import Kinematics
from dhsim_tui.core.model.program import Program
from dhsim_tui.core.model.text import printable, shortened
from dhsim_tui.core.model.units import (
    AXES,
    CONVENTIONS,
    JOINT_TYPES,
    LENGTH_DECIMALS,
    MAX_ABS,
    MAX_JOINTS,
    MIN_JOINTS,
    MIN_LENGTH_MM,
    PRISMATIC_LIMIT_MM,
    REVOLUTE_LIMIT_DEG,
    UNITS,
    JointType,
    default_limits,
    min_length,
    mm_to_unit,
)
from dhsim_tui.core.model.validation import check_joint_values, check_robot

#: the vocabulary lives in :mod:`dhsim_tui.core.model.units`; it is re-exported here,
#: where most callers look for it
__all__ = [
    "AXES",
    "CONVENTIONS",
    "JOINT_TYPES",
    "LENGTH_DECIMALS",
    "MAX_ABS",
    "MAX_JOINTS",
    "MIN_JOINTS",
    "MIN_LENGTH_MM",
    "PRISMATIC_LIMIT_MM",
    "REVOLUTE_LIMIT_DEG",
    "UNITS",
    "Joint",
    "JointType",
    "Robot",
    "Tool",
    "default_limits",
    "min_length",
    "mm_to_unit",
]


@dataclass(frozen=True)
class Joint:
    """One D-H row. The D-H variable is theta (revolute) or d (prismatic); the
    number written in the row is its value at the joint's home.

    ``offset`` relates the joint value ``q`` (what the user sees, types and
    saves, what limits and poses are in, a controller's or URDF's number) to
    the D-H variable, as in the Robotics Toolbox:

        theta = q + offset   (revolute)        d = q + offset   (prismatic)

    so the home joint value is ``theta - offset`` (``d - offset``). With the
    default offset 0 the joint value is the D-H variable itself.
    """

    type: JointType = "revolute"
    theta: float = 0.0
    d: float = 0.0
    a: float = 0.0
    alpha: float = 0.0
    min: float = -REVOLUTE_LIMIT_DEG
    max: float = REVOLUTE_LIMIT_DEG
    offset: float = 0.0
    #: top speed and acceleration (deg/s, deg/s² or robot units); None: the
    #: defaults (core.model.program.top_speed)
    vmax: float | None = None
    amax: float | None = None

    @property
    def is_revolute(self) -> bool:
        return self.type == "revolute"

    @property
    def home(self) -> float:
        """The home joint value: the table's D-H variable less the offset."""
        return (self.theta if self.is_revolute else self.d) - self.offset

    @property
    def table_value(self) -> float:
        """The D-H variable's entry in the table (its value at home)."""
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
        """This joint with its home joint value replaced (the table entry follows)."""
        return replace(self, **{self.variable: float(value) + self.offset})


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
    #: the general base: frame 0 = translate(base_xyz) · axes(base_z, base_x) ·
    #: rpy(base_rpy) in world coordinates (translation in robot units, angles
    #: in degrees, R = Rz(yaw) Ry(pitch) Rx(roll) as for the tool)
    base_xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    base_rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    tool: Tool = field(default_factory=Tool)
    poses: tuple[tuple[str, tuple[float, ...]], ...] = ()
    #: named lists of moves (core.model.program), in file order
    programs: tuple[Program, ...] = ()

    def __post_init__(self) -> None:
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
    def offsets(self) -> tuple[float, ...]:
        return tuple(j.offset for j in self.joints)

    @property
    def has_offsets(self) -> bool:
        return any(self.offsets)

    @property
    def base_is_shorthand(self) -> bool:
        """True when base_height, base_z and base_x alone place frame 0."""
        return not any(self.base_xyz) and not any(self.base_rpy)

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
        known = printable(shortened(", ".join(self.pose_names) or "none"))
        raise DhsimError(
            f"robot {printable(repr(shortened(self.name)))} has no pose named "
            f"{printable(repr(shortened(name)))} (poses: {known})"
        )

    @property
    def program_names(self) -> tuple[str, ...]:
        return tuple(program.name for program in self.programs)

    def program(self, name: str) -> Program:
        """The named program; a clear error if there is none."""
        for program in self.programs:
            if program.name == name:
                return program
        known = printable(shortened(", ".join(self.program_names) or "none"))
        raise DhsimError(
            f"robot {printable(repr(shortened(self.name)))} has no program named "
            f"{printable(repr(shortened(name)))} (programs: {known})"
        )

    def mm(self, value_mm: float) -> float:
        """A length given in millimetres, in this robot's unit."""
        return mm_to_unit(value_mm, self.units)

    @cached_property
    def kinematics(self) -> Kinematics:
        """Forward kinematics compiled for this robot (built once, on first use)."""
        return Kinematics(self)

    def check_q(self, q: object) -> tuple[float, ...]:
        """Validate a joint vector: right length, finite numbers, within limits."""
        return check_joint_values(self, q)

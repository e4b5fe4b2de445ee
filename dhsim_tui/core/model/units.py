"""The fixed vocabulary of a robot: units, axes, conventions, joint types and
the bounds every number must respect.

A leaf module (it imports nothing from the package), so the model, the
validation and the file loader can all share these facts without importing
each other in a circle.
"""

from __future__ import annotations

from typing import Literal

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
#: the smallest nonzero length a robot may have: one nanometre. Lengths span at
#: most MAX_ABS metres = 1e9 mm, so 1e-6 mm keeps every length within 1e15 of
#: the largest, inside a double's 1e-16 precision; squares and products of
#: lengths stay far from underflow (1e-300 once made ``ik`` print "closest nan").
MIN_LENGTH_MM = 1e-6
REVOLUTE_LIMIT_DEG = 180.0
PRISMATIC_LIMIT_MM = 400.0


def mm_to_unit(value_mm: float, units: str) -> float:
    """Convert a length given in millimetres to the robot's unit."""
    return value_mm / UNITS[units]


def min_length(units: str) -> float:
    """:data:`MIN_LENGTH_MM` in the robot's unit."""
    return mm_to_unit(MIN_LENGTH_MM, units)


def default_limits(joint_type: str, units: str) -> tuple[float, float]:
    """The seed's default range: ±180 deg, or ±400 mm in the robot's unit."""
    if joint_type == "revolute":
        return (-REVOLUTE_LIMIT_DEG, REVOLUTE_LIMIT_DEG)
    span = mm_to_unit(PRISMATIC_LIMIT_MM, units)
    return (-span, span)

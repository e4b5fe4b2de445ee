"""Standard ⇄ modified D-H for a whole robot (``dhsim convert``).

The two conventions place the same (a, alpha) pairs one row apart
(kinematics reference section 1, the D-H conventions):
standard row i holds a_i, alpha_i after its joint, modified
row i holds a_{i-1}, alpha_{i-1} before it. So a conversion shifts those
pairs and moves the one left over into the tool or the base:

- standard → modified: row 1 gets a_0 = alpha_0 = 0 and the last row's
  Tx(a_n)·Rx(alpha_n) moves to the front of the tool;
- modified → standard: row 1's Rx(alpha_0)·Tx(a_0) moves to the end of the
  base, and the last row's a_n, alpha_n are taken back out of the tool when
  it begins with Tx(a)·Rx(alpha) followed by a screw along z (what
  standard → modified puts there), else they are 0.

theta, d, offsets, limits, poses, units and the base shorthand are kept, so
joint values mean the same in both, and the end effector's pose is the same
at every joint value (to rounding: numbers computed from matrices keep 12
significant digits, so ~1e-12 of the arm's size). Standard →
modified → standard gives back the same table.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from dhsim_tui.core.interop.dh_chain import tool_link
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.orientation import base_rotation, rotx, rpy_angles, rpy_matrix
from dhsim_tui.core.model.robot import CONVENTIONS, Robot, Tool
from dhsim_tui.core.model.units import min_length

#: numbers computed from matrices keep this many significant digits, so
#: rounding noise (431.80000000000007) does not reach the table
SIGNIFICANT = 12
#: a tool that is Tx(a)·Rx(alpha)·screw must be so to this fraction of the arm's size
PEEL_TOL = 1e-9


def tidy(value: float, size: float = 1.0) -> float:
    """``value`` without rounding noise: 0 below 1e-12 of ``size``, else 12 digits."""
    if abs(value) <= 1e-12 * max(size, 1e-300):
        return 0.0
    return float(f"{value:.{SIGNIFICANT}g}")


def transform(xyz, rpy) -> np.ndarray:
    """4×4 from a translation and roll, pitch, yaw in degrees (R = Rz·Ry·Rx)."""
    m = np.eye(4)
    m[:3, :3] = rpy_matrix(*rpy)
    m[:3, 3] = xyz
    return m


def rpy_of(r: np.ndarray) -> tuple[float, float, float]:
    """Roll, pitch, yaw (degrees, tidied) that rebuild ``r`` to rounding, at
    and near pitch ±90° too (:func:`~dhsim_tui.core.model.orientation.rpy_angles`)."""
    best = tuple(math.degrees(v) for v in rpy_angles(r))
    tidied = tuple(tidy(v, 360.0) for v in best)
    if float(np.abs(rpy_matrix(*tidied) - r).max()) > 1e-10:
        tidied = best
    return tidied  # type: ignore[return-value]


def parts(matrix: np.ndarray, size: float = 1.0, units: str = "mm") -> tuple[tuple, tuple]:
    """(xyz, rpy in degrees) of a rigid transform, tidied; a length below a
    nanometre (which a robot cannot hold) is 0."""
    floor = min_length(units)
    xyz = tuple(0.0 if abs(v := tidy(float(value), size)) < floor else v for value in matrix[:3, 3])
    return xyz, rpy_of(matrix[:3, :3])  # type: ignore[return-value]


def x_link(a: float, alpha: float) -> np.ndarray:
    """Tx(a)·Rx(alpha) (they commute), alpha in degrees."""
    m = np.eye(4)
    m[:3, :3] = rotx(alpha)
    m[0, 3] = a
    return m


def size_of(robot: Robot) -> float:
    """A length the size of the arm, for tolerances."""
    lengths = [abs(j.a) + abs(j.d) for j in robot.joints]
    lengths += [math.dist((0, 0, 0), robot.tool.xyz), math.dist((0, 0, 0), robot.base_xyz)]
    return max([1e-9, *lengths])


def with_base(robot: Robot, base: np.ndarray) -> Robot:
    """``robot`` with frame 0 at ``base`` (world), keeping base_z/base_x:
    base_rpy becomes the turn left after them."""
    axes = base_rotation(robot.base_z, robot.base_x)
    turn = np.eye(4)
    turn[:3, :3] = axes.T @ base[:3, :3]
    turn[:3, 3] = base[:3, 3]
    xyz, rpy = parts(turn, size_of(robot), robot.units)
    return replace(robot, base_xyz=xyz, base_rpy=rpy)


def convert(robot: Robot, convention: str) -> Robot:
    """The same arm in ``convention`` (see the module's docstring)."""
    if convention not in CONVENTIONS:
        raise DhsimError(f"convention {convention!r}: expected standard or modified")
    if convention == robot.convention:
        return robot
    joints = robot.joints
    size = size_of(robot)
    tool = transform(robot.tool.xyz, robot.tool.rpy)
    if convention == "modified":
        pairs = [(0.0, 0.0)] + [(j.a, j.alpha) for j in joints[:-1]]
        last = joints[-1]
        tool = x_link(last.a, last.alpha) @ tool
        new = robot
    else:
        first = joints[0]
        base = transform(robot.base_xyz, robot.base_rpy)
        base[:3, :3] = base_rotation(robot.base_z, robot.base_x) @ base[:3, :3]
        new = (
            robot
            if (first.a, first.alpha) == (0.0, 0.0)
            else with_base(robot, base @ x_link(first.a, first.alpha))
        )
        a_n, alpha_rad = tool_link(tool, PEEL_TOL * size)
        a_n, alpha_n = tidy(a_n, size), tidy(math.degrees(alpha_rad), 360.0)
        tool = np.linalg.inv(x_link(a_n, alpha_n)) @ tool
        pairs = [(j.a, j.alpha) for j in joints[1:]] + [(a_n, alpha_n)]
    xyz, rpy = parts(tool, size, robot.units)
    return replace(
        new,
        convention=convention,
        joints=tuple(
            replace(j, a=a, alpha=alpha) for j, (a, alpha) in zip(joints, pairs, strict=True)
        ),
        tool=Tool(xyz=xyz, rpy=rpy),
    )

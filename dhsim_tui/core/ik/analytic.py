"""Closed-form inverse kinematics for six-axis arms whose geometry allows it.

The arm is read as a product of exponentials: from the frames at home, each
joint's axis (a unit direction and a point, in world coordinates) and the end
effector's home pose M. Then ``FK(q) = e1(Δq1) ··· e6(Δq6) · M`` with
``Δq = q - home``, whatever the convention, offsets, base or tool, so the
geometry is detected from these axes, never from a model's name:

* **spherical wrist** (Pieper): axes 4, 5 and 6 revolute and meeting at one
  point, the wrist centre, which joints 4-6 cannot move. The first three
  joints put it at ``target · M⁻¹ · centre``: when axes 2 and 3 are parallel
  (Puma, IRB 140), joint 1 keeps the centre's height along axis 2 (a cos + b sin
  = c: two shoulders), then a planar two-link (two elbows); when axes 1 and 2
  meet at a point (Stanford), the centre's distance from that point fixes
  joint 3 (two roots), then two rotations about meeting axes (two
  solutions). The wrist's two Euler solutions follow.
* **three parallel axes** 2, 3 and 4 (UR5): the UR closed form — joint 1 from
  the height along those axes of the point where axes 5 and 6 meet, joint 5
  from the height of axis 6's direction, joint 6 from axis 2's direction, and
  a planar three-link for joints 2-4.

Each step is one of the Paden-Kahan sub-problems below, so a pose has up to
eight solutions. Joint values come back as angles wrapped to one turn
around home; limits, the other turns and checking the pose are
:mod:`dhsim_tui.core.ik.solutions`'s business.

The code: :mod:`~dhsim_tui.core.ik.geometry` detects the geometry,
:mod:`~dhsim_tui.core.ik.wrist` and :mod:`~dhsim_tui.core.ik.parallel` hold
the two closed forms, built from :mod:`~dhsim_tui.core.ik.subproblems`,
:mod:`~dhsim_tui.core.ik.planar` and :mod:`~dhsim_tui.core.ik.vectors`;
:mod:`~dhsim_tui.core.ik.labels` words each solution. This module is the
entry point: :func:`detect` and :func:`solve`.


Labels (the words of ``config``), each defined from the geometry so the two
branches of every step always get different words:

* **shoulder right / left**: the wrist centre (UR: the point where axes 5 and
  6 meet) lies on the side of the plane through axis 1 spanned by axes 1 and 2
  toward which ``axis1 × axis2`` points (right), or on the other (left).
* **elbow up / down** (revolute joint 3): the elbow (axis 3) lies above or
  below the line from the shoulder (axis 2) to the wrist (the wrist centre;
  UR: axis 4), "above" meaning along axis 1's direction, all seen in the
  plane perpendicular to axis 2. When that line runs along axis 1, "up" is
  the side ``axis2 × (wrist - shoulder)`` points to.
* **arm forward / reversed** (prismatic joint 3, Stanford): the wrist centre
  lies ahead of the point where axes 1 and 2 meet along joint 3's slide
  direction (forward), or behind it (reversed: the slide passes through it).
* **wrist no flip / flip** (the Robotics Toolbox for Python's n / f): no
  flip when axis 6's direction has a non-negative component along
  ``axis4 × axis5`` (all three where the joints put them), that is when joint
  5 is turned less than half a turn *below* its singular position (where axis
  6 lines up with axis 4 in the same direction); flip otherwise. (The
  toolbox's ``Puma560.ikine_a`` keeps the middle Z-Y-Z Euler angle of the
  wrist in frame 3 ≥ 0 for "n" and, the Puma's α4 being +90°, sets joint 5
  to minus it, which is this rule; read from the joints' axes rather than
  from the sign of the table's x4, it words the Puma's standard and modified
  tables alike: tests/core/test_ik_labels_rtb.py.)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from dhsim_tui.core.ik.geometry import (
    GEOMETRY_TOL,
    SPHERICAL_MEETING,
    SPHERICAL_PARALLEL,
    THREE_PARALLEL,
    Geometry,
    detect,
)
from dhsim_tui.core.ik.parallel import solve_three_parallel
from dhsim_tui.core.ik.right_angle_wrist import solve as right_angle_wrist
from dhsim_tui.core.ik.subproblems import DOUBLE_ROOT
from dhsim_tui.core.ik.vectors import Motion, Vec, compose_motions
from dhsim_tui.core.ik.wrist import solve_spherical_wrist

if TYPE_CHECKING:
    from dhsim_tui.core.model.robot import Robot

__all__ = [
    "DOUBLE_ROOT",
    "GEOMETRY_TOL",
    "SPHERICAL_MEETING",
    "SPHERICAL_PARALLEL",
    "THREE_PARALLEL",
    "Geometry",
    "Motion",
    "Vec",
    "detect",
    "solve",
]

_RAD = 180.0 / math.pi


# -- solving -------------------------------------------------------------------------------
def solve(
    robot: Robot,
    geometry: Geometry,
    target: np.ndarray,
    preferred,
    fits: Callable[[int, float], bool] | None = None,
    *,
    generic: bool = False,
) -> tuple[list[tuple[tuple[float, ...], str]], int]:
    """Every closed-form solution for a 4×4 world target, as (joint values,
    configuration words) pairs — deg / robot units, revolute joints within
    half a turn of home — and how many were dropped early because
    ``fits(joint index, joint value)`` said one of the first three joints
    cannot be within its limits (without ``fits``, limits are not applied).
    ``preferred``: joint values for the angles a singular pose leaves free.
    ``generic``: the general spherical-wrist form even where the fitted
    frames of :mod:`~dhsim_tui.core.ik.right_angle_wrist` apply (the two are
    compared in the tests)."""
    f = np.asarray(target, dtype=float).reshape(-1).tolist()
    if geometry.frames is not None and not generic:
        return right_angle_wrist(geometry.frames, f, geometry.home, tuple(preferred), fits)
    home = geometry.home
    revolute = geometry.revolute
    free = tuple(
        (p - h) / _RAD if rev else p - h
        for p, h, rev in zip(preferred, home, revolute, strict=True)
    )
    dropped = [0]
    # joint 1's verdict for the last t1 (the arm solutions of one shoulder share it)
    last_t1: list = [None, True]

    def arm_fits(t1: float, t2: float, t3: float) -> bool:
        if fits is None:
            return True
        if t1 == last_t1[0]:
            ok = last_t1[1]
        else:
            ok = fits(0, home[0] + (_RAD * math.remainder(t1, 2 * math.pi) if revolute[0] else t1))
            last_t1[0], last_t1[1] = t1, ok
        if not ok:
            dropped[0] += 1
            return False
        for i, t in ((1, t2), (2, t3)):
            if not fits(i, home[i] + (_RAD * math.remainder(t, 2 * math.pi) if revolute[i] else t)):
                dropped[0] += 1
                return False
        return True

    rot = (f[0], f[1], f[2], f[4], f[5], f[6], f[8], f[9], f[10])
    goal = compose_motions((rot, (f[3], f[7], f[11])), geometry.home_inverse)
    if geometry.kind == THREE_PARALLEL:
        deltas = solve_three_parallel(geometry, goal, free)
    else:
        deltas = solve_spherical_wrist(geometry, goal, free, arm_fits)
    tau = 2 * math.pi
    remainder = math.remainder
    out = []
    if all(revolute):
        h0, h1, h2, h3, h4, h5 = home
        for (d0, d1, d2, d3, d4, d5), config in deltas:
            q = (
                h0 + _RAD * remainder(d0, tau),
                h1 + _RAD * remainder(d1, tau),
                h2 + _RAD * remainder(d2, tau),
                h3 + _RAD * remainder(d3, tau),
                h4 + _RAD * remainder(d4, tau),
                h5 + _RAD * remainder(d5, tau),
            )
            out.append((q, config))
        return out, dropped[0]
    for delta, config in deltas:
        q = tuple(
            h + (_RAD * remainder(d, tau) if rev else d)
            for h, d, rev in zip(home, delta, revolute, strict=True)
        )
        out.append((q, config))
    return out, dropped[0]

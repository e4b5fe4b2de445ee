"""The arm's closed-form structure, detected from its D-H table at home
(:mod:`dhsim_tui.core.ik.analytic`): :class:`Geometry` (the six joints as
screw axes, which closed form applies, and the constants each form
precomputes) and :func:`detect`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from dhsim_tui.core.analysis.workspace import reach
from dhsim_tui.core.ik.right_angle_wrist import ArmFrames, arm_frames
from dhsim_tui.core.ik.subproblems import EPS, turn_to_direction
from dhsim_tui.core.ik.vectors import (
    Motion,
    Vec,
    add,
    cross_product,
    dot,
    invert_motion,
    norm,
    scaled,
    sub,
)

if TYPE_CHECKING:
    from dhsim_tui.core.model.robot import Robot

#: axes meet / are parallel within this fraction of the reach (or radians)
GEOMETRY_TOL = 1e-9

SPHERICAL_PARALLEL = "spherical wrist, axes 2 and 3 parallel"
SPHERICAL_MEETING = "spherical wrist, axes 1 and 2 meeting"
THREE_PARALLEL = "axes 2, 3 and 4 parallel"


# -- the arm's geometry ------------------------------------------------------------------
@dataclass(frozen=True)
class Geometry:
    """A six-axis arm at home as screw axes (world coordinates)."""

    kind: str
    axes: tuple[Vec, ...]
    points: tuple[Vec, ...]
    revolute: tuple[bool, ...]
    home: tuple[float, ...]
    #: the end effector's home pose, inverted
    home_inverse: Motion
    #: the wrist centre (spherical wrist) or where axes 5 and 6 meet (UR)
    centre: Vec
    #: where axes 1 and 2 meet (SPHERICAL_MEETING)
    meeting: Vec
    #: joint 5's turn (from home) at which axis 6 lines up with axis 4
    wrist_singular: float
    reach: float
    #: see _wrist_constants
    wrist: tuple = ()
    #: see _parallel_constants
    arm: tuple = ()
    #: see _planar_constants
    planar: tuple = ()
    #: axes 2 and 3 parallel and a right-angled wrist: the fitted frames'
    #: constants (:mod:`dhsim_tui.core.ik.right_angle_wrist`)
    frames: ArmFrames | None = None


def _closest(r1: Vec, w1: Vec, r2: Vec, w2: Vec) -> tuple[float, Vec]:
    """Distance between two non-parallel lines and the midpoint of their closest points."""
    n = cross_product(w1, w2)
    nn = dot(n, n)
    d = sub(r2, r1)
    t1 = dot(cross_product(d, w2), n) / nn
    t2 = dot(cross_product(d, w1), n) / nn
    a = add(r1, scaled(w1, t1))
    b = add(r2, scaled(w2, t2))
    return norm(sub(a, b)), scaled(add(a, b), 0.5)


def _parallel(a: Vec, b: Vec) -> bool:
    return norm(cross_product(a, b)) <= GEOMETRY_TOL


def _meet(geometry_axes, geometry_points, i: int, j: int, size: float) -> Vec | None:
    """Where axes i and j meet, or None (parallel or skew)."""
    w1, w2 = geometry_axes[i], geometry_axes[j]
    if _parallel(w1, w2):
        return None
    distance, point = _closest(geometry_points[i], w1, geometry_points[j], w2)
    return point if distance <= GEOMETRY_TOL * size else None


def _tuple(v) -> Vec:
    return (float(v[0]), float(v[1]), float(v[2]))


def detect(robot: Robot) -> Geometry | None:
    """The arm's closed-form structure, or None when it has none that this
    module solves (cached on the robot, which is immutable)."""
    cached = robot.__dict__.get("_ik_geometry", False)
    if cached is False:
        cached = _detect(robot)
        object.__setattr__(robot, "_ik_geometry", cached)
    return cached


def _detect(robot: Robot) -> Geometry | None:
    if robot.dof != 6:
        return None
    frames = robot.kinematics.frames(robot.home)
    first = 0 if robot.convention == "standard" else 1
    axes = tuple(_tuple(frames[first + i][:3, 2]) for i in range(6))
    points = tuple(_tuple(frames[first + i][:3, 3]) for i in range(6))
    revolute = tuple(j.is_revolute for j in robot.joints)
    size = reach(robot) or 1.0
    end = frames[-1]
    rot = tuple(float(v) for v in end[:3, :3].reshape(-1))
    home_inverse = invert_motion((rot, _tuple(end[:3, 3])))
    origin: Vec = (0.0, 0.0, 0.0)
    kind, centre, meeting = "", origin, origin
    if all(revolute[3:]):
        c45 = _meet(axes, points, 3, 4, size)
        c56 = _meet(axes, points, 4, 5, size)
        spherical = (
            c45 is not None and c56 is not None and norm(sub(c45, c56)) <= GEOMETRY_TOL * size
        )
        if spherical and c45 is not None:
            centre = c45
            m12 = _meet(axes, points, 0, 1, size) if revolute[0] and revolute[1] else None
            if (
                revolute[0]
                and revolute[1]
                and revolute[2]
                and _parallel(axes[1], axes[2])
                and not _parallel(axes[0], axes[1])
                and norm(cross_product(axes[2], sub(centre, points[2]))) > GEOMETRY_TOL * size
            ):
                kind = SPHERICAL_PARALLEL
            elif m12 is not None and (revolute[2] or not _parallel(axes[2], sub(centre, m12))):
                kind, meeting = SPHERICAL_MEETING, m12
    if (
        not kind
        and all(revolute)
        and _parallel(axes[1], axes[2])
        and _parallel(axes[1], axes[3])
        and not _parallel(axes[0], axes[1])
        and not _parallel(axes[4], axes[1])
    ):
        c56 = _meet(axes, points, 4, 5, size)
        if c56 is not None:
            kind, centre = THREE_PARALLEL, c56
    if not kind:
        return None
    # joint 5's singular turn: axis 6 turned about axis 5 onto axis 4
    w4, w5, w6 = axes[3], axes[4], axes[5]
    wrist_singular = turn_to_direction(w5, w6, w4, math.nan)
    return Geometry(
        kind,
        axes,
        points,
        revolute,
        tuple(robot.home),
        home_inverse,
        centre,
        meeting,
        wrist_singular,
        size,
        _wrist_constants(axes) if kind != THREE_PARALLEL else (),
        _parallel_constants(axes, points, centre) if kind == SPHERICAL_PARALLEL else (),
        _planar_constants(axes, points, centre if kind == SPHERICAL_PARALLEL else points[3])
        if kind != SPHERICAL_MEETING
        else (),
        arm_frames(axes, points, centre, home_inverse, wrist_singular, size, GEOMETRY_TOL)
        if kind == SPHERICAL_PARALLEL
        else None,
    )


def _wrist_constants(axes: tuple[Vec, ...]) -> tuple:
    """What sub-problem 2 for the wrist (axes 4, 5 turning axis 6's direction)
    needs that does not depend on the pose."""
    w4, w5, w6 = axes[3], axes[4], axes[5]
    c45 = dot(w4, w5)
    cross = cross_product(w4, w5)
    # joint 6 turns a direction across axis 6 the rest of the way
    x = cross_product(w6, w4) if norm(cross_product(w6, w4)) > 1e-6 else cross_product(w6, w5)
    x = scaled(x, 1.0 / norm(x))
    d56 = dot(w5, w6)
    # w6 as sub-problem 1 about axis 5 sees it (across the axis)
    p6 = (w6[0] - d56 * w5[0], w6[1] - d56 * w5[1], w6[2] - d56 * w5[2])
    small = p6[0] * p6[0] + p6[1] * p6[1] + p6[2] * p6[2] < EPS
    # x as sub-problem 1 about axis 6 sees it
    d6x = dot(w6, x)
    px = (x[0] - d6x * w6[0], x[1] - d6x * w6[1], x[2] - d6x * w6[2])
    x_small = px[0] * px[0] + px[1] * px[1] + px[2] * px[2] < EPS
    return (c45, c45 * c45 - 1.0, d56, cross, dot(cross, cross), x, p6, small, px, x_small)


def _parallel_constants(axes: tuple[Vec, ...], points: tuple[Vec, ...], centre: Vec) -> tuple:
    """What :func:`_position_parallel` needs that does not depend on the pose
    (each worked out as the sub-problems would, to the same digits)."""
    w1, w2, r1 = axes[0], axes[1], points[0]
    return (dot(w2, centre), dot(w2, r1), dot(w2, w1))


def _planar_constants(axes: tuple[Vec, ...], points: tuple[Vec, ...], point: Vec) -> tuple:
    """What :func:`planar_at_fixed_point` needs that does not depend on the pose
    (worked out as :func:`turns_to_distance` and :func:`rotate_about_line` would)."""
    w3, r3 = axes[2], points[2]
    u = sub(point, r3)  # the point from axis 3, across it
    u1 = sub(u, scaled(w3, dot(w3, u)))
    return (point, u, u1, norm(u1), dot(w3, u))

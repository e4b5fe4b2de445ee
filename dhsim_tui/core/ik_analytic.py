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
:mod:`dhsim_tui.core.ik_all`'s business.

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
* **wrist no flip / flip**: joint 5 is less than half a turn above (no flip)
  or below (flip) its singular position, the one where axis 6 lines up with
  axis 4 in the same direction.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dhsim_tui.core.workspace import reach

if TYPE_CHECKING:
    from dhsim_tui.core.model import Robot

Vec = tuple[float, float, float]
#: axes meet / are parallel within this fraction of the reach (or radians)
GEOMETRY_TOL = 1e-9
#: a sub-problem's quantity below this (fraction of the reach) counts as zero
_EPS = 1e-12
#: roots of a step closer than this (radians, or fraction of the reach) are one
#: double root: rounding alone splits a double root by ~1e-8 (a square root of
#: 1e-16), which would list one pose twice
DOUBLE_ROOT = 1e-7
_RAD = 180.0 / math.pi

SPHERICAL_PARALLEL = "spherical wrist, axes 2 and 3 parallel"
SPHERICAL_MEETING = "spherical wrist, axes 1 and 2 meeting"
THREE_PARALLEL = "axes 2, 3 and 4 parallel"


# -- 3-vectors as tuples (a pose costs a few hundred of these: numpy's
#    per-call overhead would dominate) ---------------------------------------
def _sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _scale(a: Vec, k: float) -> Vec:
    return (a[0] * k, a[1] * k, a[2] * k)


def _dot(a: Vec, b: Vec) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a: Vec, b: Vec) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _norm(a: Vec) -> float:
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def _rotate(w: Vec, t: float, v: Vec) -> Vec:
    """``v`` turned by ``t`` radians about the unit direction ``w`` (Rodrigues)."""
    c, s = math.cos(t), math.sin(t)
    w0, w1, w2 = w
    v0, v1, v2 = v
    k = (w0 * v0 + w1 * v1 + w2 * v2) * (1.0 - c)
    return (
        v0 * c + (w1 * v2 - w2 * v1) * s + w0 * k,
        v1 * c + (w2 * v0 - w0 * v2) * s + w1 * k,
        v2 * c + (w0 * v1 - w1 * v0) * s + w2 * k,
    )


def _rotate_about(w: Vec, r: Vec, t: float, p: Vec) -> Vec:
    """Point ``p`` turned by ``t`` about the line through ``r`` along ``w``."""
    return _add(r, _rotate(w, t, _sub(p, r)))


# -- rigid motions as (R rows flat, p) ----------------------------------------
Motion = tuple[tuple[float, ...], Vec]


def _rot_matrix(w: Vec, t: float) -> tuple[float, ...]:
    c, s = math.cos(t), math.sin(t)
    v = 1.0 - c
    x, y, z = w
    return (
        c + x * x * v,
        x * y * v - z * s,
        x * z * v + y * s,
        y * x * v + z * s,
        c + y * y * v,
        y * z * v - x * s,
        z * x * v - y * s,
        z * y * v + x * s,
        c + z * z * v,
    )


def _apply(m: Motion, p: Vec) -> Vec:
    r, t = m
    return (
        r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + t[0],
        r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + t[1],
        r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + t[2],
    )


def _turn(r: tuple[float, ...], v: Vec) -> Vec:
    return (
        r[0] * v[0] + r[1] * v[1] + r[2] * v[2],
        r[3] * v[0] + r[4] * v[1] + r[5] * v[2],
        r[6] * v[0] + r[7] * v[1] + r[8] * v[2],
    )


def _turn_back(r: tuple[float, ...], v: Vec) -> Vec:
    """R^T v."""
    return (
        r[0] * v[0] + r[3] * v[1] + r[6] * v[2],
        r[1] * v[0] + r[4] * v[1] + r[7] * v[2],
        r[2] * v[0] + r[5] * v[1] + r[8] * v[2],
    )


def _mul(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, ...]:
    """The product of two rotations (9 numbers each, row-major), written out."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8 = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8 = b
    return (
        a0 * b0 + a1 * b3 + a2 * b6,
        a0 * b1 + a1 * b4 + a2 * b7,
        a0 * b2 + a1 * b5 + a2 * b8,
        a3 * b0 + a4 * b3 + a5 * b6,
        a3 * b1 + a4 * b4 + a5 * b7,
        a3 * b2 + a4 * b5 + a5 * b8,
        a6 * b0 + a7 * b3 + a8 * b6,
        a6 * b1 + a7 * b4 + a8 * b7,
        a6 * b2 + a7 * b5 + a8 * b8,
    )


def _mul_t(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, ...]:
    """a^T b for two rotations (9 numbers each, row-major)."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8 = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8 = b
    return (
        a0 * b0 + a3 * b3 + a6 * b6,
        a0 * b1 + a3 * b4 + a6 * b7,
        a0 * b2 + a3 * b5 + a6 * b8,
        a1 * b0 + a4 * b3 + a7 * b6,
        a1 * b1 + a4 * b4 + a7 * b7,
        a1 * b2 + a4 * b5 + a7 * b8,
        a2 * b0 + a5 * b3 + a8 * b6,
        a2 * b1 + a5 * b4 + a8 * b7,
        a2 * b2 + a5 * b5 + a8 * b8,
    )


def _compose(a: Motion, b: Motion) -> Motion:
    return (_mul(a[0], b[0]), _apply(a, b[1]))


def _inverse(m: Motion) -> Motion:
    r, p = m
    rt = (r[0], r[3], r[6], r[1], r[4], r[7], r[2], r[5], r[8])
    return (rt, _scale(_turn(rt, p), -1.0))


def _joint_motion(geometry: Geometry, i: int, value: float) -> Motion:
    """e_i(value): a turn (radians) about axis i, or a slide along it."""
    w, r = geometry.axes[i], geometry.points[i]
    if geometry.revolute[i]:
        rot = _rot_matrix(w, value)
        return (rot, _sub(r, _turn(rot, r)))
    return ((1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0), _scale(w, value))


# -- the Paden-Kahan sub-problems -------------------------------------------------
def _sp1(w: Vec, u: Vec, v: Vec, preferred: float) -> float:
    """The turn about ``w`` that takes direction ``u`` to ``v`` (both as seen
    perpendicular to ``w``); ``preferred`` when either lies along ``w``."""
    w0, w1, w2 = w
    u0, u1, u2 = u
    v0, v1, v2 = v
    a = w0 * u0 + w1 * u1 + w2 * u2
    b = w0 * v0 + w1 * v1 + w2 * v2
    u0, u1, u2 = u0 - a * w0, u1 - a * w1, u2 - a * w2
    v0, v1, v2 = v0 - b * w0, v1 - b * w1, v2 - b * w2
    if u0 * u0 + u1 * u1 + u2 * u2 < _EPS or v0 * v0 + v1 * v1 + v2 * v2 < _EPS:
        return preferred
    sine = w0 * (u1 * v2 - u2 * v1) + w1 * (u2 * v0 - u0 * v2) + w2 * (u0 * v1 - u1 * v0)
    return math.atan2(sine, u0 * v0 + u1 * v1 + u2 * v2)


def _cos_sin_equation(a: float, b: float, c: float, preferred: float) -> list[float]:
    """Roots of ``a cos t + b sin t = c``: none, one (tangent) or two."""
    rho = math.hypot(a, b)
    if rho < _EPS:
        return [preferred] if abs(c) < 1e-9 else []
    ratio = c / rho
    if abs(ratio) > 1.0 + 1e-12:
        return []
    ratio = max(-1.0, min(1.0, ratio))
    phi = math.atan2(b, a)
    spread = math.acos(ratio)
    if spread < DOUBLE_ROOT:
        return [phi]
    return [phi + spread, phi - spread]


def _height_turns(w: Vec, r: Vec, p: Vec, n: Vec, c: float, preferred: float) -> list[float]:
    """Turns t about the line (w, r) with ``n · rotate(p) = c``."""
    u = _sub(p, r)
    along = _dot(w, u)
    u1 = _sub(u, _scale(w, along))
    return _cos_sin_equation(
        _dot(n, u1), _dot(n, _cross(w, u1)), c - _dot(n, r) - along * _dot(n, w), preferred
    )


def _sp3(w: Vec, r: Vec, p: Vec, target: Vec, distance: float, preferred: float) -> list[float]:
    """Turns t about the line (w, r) that put ``p`` at ``distance`` from ``target``."""
    u = _sub(p, r)
    v = _sub(target, r)
    u1 = _sub(u, _scale(w, _dot(w, u)))
    v1 = _sub(v, _scale(w, _dot(w, v)))
    along = _dot(w, _sub(p, target))
    d2 = distance * distance - along * along
    nu, nv = _norm(u1), _norm(v1)
    if nu * nv < _EPS:
        close = abs(nu * nu + nv * nv - d2) < 1e-9 * max(1.0, distance * distance)
        return [preferred] if close else []
    theta0 = math.atan2(_dot(w, _cross(u1, v1)), _dot(u1, v1))
    # |R u1 - v1|^2 = nu^2 + nv^2 - 2 nu nv cos(theta0 - t) = d2
    return [
        theta0 - t
        for t in _cos_sin_equation(1.0, 0.0, (nu * nu + nv * nv - d2) / (2 * nu * nv), 0.0)
    ]


def _sp2(w1: Vec, w2: Vec, u: Vec, v: Vec, preferred: tuple[float, float]):
    """Turns (t1, t2) about two meeting axes with ``R1(t1) R2(t2) u = v``
    (directions from their common point): none, one or two pairs."""
    c12 = _dot(w1, w2)
    denominator = c12 * c12 - 1.0
    if abs(denominator) < _EPS:
        return []
    alpha = (c12 * _dot(w2, u) - _dot(w1, v)) / denominator
    beta = (c12 * _dot(w1, v) - _dot(w2, u)) / denominator
    cross = _cross(w1, w2)
    gamma2 = (_dot(u, u) - alpha * alpha - beta * beta - 2 * alpha * beta * c12) / _dot(
        cross, cross
    )
    scale = max(_dot(u, u), 1.0)
    if gamma2 < -1e-10 * scale:
        return []
    gamma = math.sqrt(max(gamma2, 0.0))
    out = []
    for sign in (1.0, -1.0) if gamma > DOUBLE_ROOT * math.sqrt(scale) else (1.0,):
        z = _add(_add(_scale(w1, alpha), _scale(w2, beta)), _scale(cross, sign * gamma))
        t2 = _sp1(w2, u, z, preferred[1])
        t1 = _sp1(w1, _rotate(w2, t2, u), v, preferred[0])
        out.append((t1, t2))
    return out


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


def _closest(r1: Vec, w1: Vec, r2: Vec, w2: Vec) -> tuple[float, Vec]:
    """Distance between two non-parallel lines and the midpoint of their closest points."""
    n = _cross(w1, w2)
    nn = _dot(n, n)
    d = _sub(r2, r1)
    t1 = _dot(_cross(d, w2), n) / nn
    t2 = _dot(_cross(d, w1), n) / nn
    a = _add(r1, _scale(w1, t1))
    b = _add(r2, _scale(w2, t2))
    return _norm(_sub(a, b)), _scale(_add(a, b), 0.5)


def _parallel(a: Vec, b: Vec) -> bool:
    return _norm(_cross(a, b)) <= GEOMETRY_TOL


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
    home_inverse = _inverse((rot, _tuple(end[:3, 3])))
    origin: Vec = (0.0, 0.0, 0.0)
    kind, centre, meeting = "", origin, origin
    if all(revolute[3:]):
        c45 = _meet(axes, points, 3, 4, size)
        c56 = _meet(axes, points, 4, 5, size)
        spherical = (
            c45 is not None and c56 is not None and _norm(_sub(c45, c56)) <= GEOMETRY_TOL * size
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
                and _norm(_cross(axes[2], _sub(centre, points[2]))) > GEOMETRY_TOL * size
            ):
                kind = SPHERICAL_PARALLEL
            elif m12 is not None and (revolute[2] or not _parallel(axes[2], _sub(centre, m12))):
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
    wrist_singular = _sp1(w5, w6, w4, math.nan)
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
    )


# -- solving -------------------------------------------------------------------------------
@dataclass(frozen=True)
class Branch:
    """One closed-form solution: joint values (deg / robot units, revolute ones
    within half a turn of home) and its configuration words."""

    q: tuple[float, ...]
    config: str


def solve(
    robot: Robot,
    geometry: Geometry,
    target: np.ndarray,
    preferred,
    fits: Callable[[int, float], bool] | None = None,
) -> tuple[list[Branch], int]:
    """Every closed-form solution for a 4×4 world target, and how many were
    dropped early because ``fits(joint index, joint value)`` said one of the
    first three joints cannot be within its limits (without ``fits``, limits
    are not applied). ``preferred``: joint values for the angles a singular
    pose leaves free."""
    branches, dropped = solve_raw(robot, geometry, target, preferred, fits)
    return [Branch(q, config) for q, config in branches], dropped


def solve_raw(
    robot: Robot,
    geometry: Geometry,
    target: np.ndarray,
    preferred,
    fits: Callable[[int, float], bool] | None = None,
) -> tuple[list[tuple[tuple[float, ...], str]], int]:
    """:func:`solve` with each solution as a plain (q, config) pair (what
    :mod:`dhsim_tui.core.ik_all` reads: no object per solution)."""
    f = np.asarray(target, dtype=float).reshape(-1).tolist()
    rot = (f[0], f[1], f[2], f[4], f[5], f[6], f[8], f[9], f[10])
    goal = _compose((rot, (f[3], f[7], f[11])), geometry.home_inverse)
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

    if geometry.kind == THREE_PARALLEL:
        deltas = _three_parallel(geometry, goal, free)
    else:
        deltas = _spherical(geometry, goal, free, arm_fits)
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


def _shoulder(g: Geometry, t1: float, point: Vec, w2: Vec | None = None) -> str:
    w1 = g.axes[0]
    if w2 is None:
        w2 = _rotate(w1, t1, g.axes[1])
    side = _dot(_cross(w1, w2), _sub(point, g.points[0]))
    return "shoulder right" if side >= 0.0 else "shoulder left"


def _elbow(g: Geometry, w2: Vec, shoulder: Vec, elbow: Vec, wrist: Vec) -> str:
    line = _sub(wrist, shoulder)
    sigma = _dot(w2, _cross(_sub(elbow, shoulder), line))  # < 0: elbow on w2 × line's side
    up = _dot(g.axes[0], _cross(w2, line))
    if abs(up) <= 1e-9 * _norm(line):
        up = 1.0
    return "elbow up" if -sigma * up >= 0.0 else "elbow down"


def _flip(g: Geometry, t5: float) -> str:
    if math.isnan(g.wrist_singular):
        return ""
    return "wrist no flip" if math.sin(t5 - g.wrist_singular) >= 0.0 else "wrist flip"


def _label(*words: str) -> str:
    return ", ".join([w for w in words if w])


def _wrist_constants(axes: tuple[Vec, ...]) -> tuple:
    """What sub-problem 2 for the wrist (axes 4, 5 turning axis 6's direction)
    needs that does not depend on the pose."""
    w4, w5, w6 = axes[3], axes[4], axes[5]
    c45 = _dot(w4, w5)
    cross = _cross(w4, w5)
    # joint 6 turns a direction across axis 6 the rest of the way
    x = _cross(w6, w4) if _norm(_cross(w6, w4)) > 1e-6 else _cross(w6, w5)
    x = _scale(x, 1.0 / _norm(x))
    d56 = _dot(w5, w6)
    # w6 as sub-problem 1 about axis 5 sees it (across the axis)
    p6 = (w6[0] - d56 * w5[0], w6[1] - d56 * w5[1], w6[2] - d56 * w5[2])
    small = p6[0] * p6[0] + p6[1] * p6[1] + p6[2] * p6[2] < _EPS
    # x as sub-problem 1 about axis 6 sees it
    d6x = _dot(w6, x)
    px = (x[0] - d6x * w6[0], x[1] - d6x * w6[1], x[2] - d6x * w6[2])
    x_small = px[0] * px[0] + px[1] * px[1] + px[2] * px[2] < _EPS
    return (c45, c45 * c45 - 1.0, d56, cross, _dot(cross, cross), x, p6, small, px, x_small)


def _wrist(g: Geometry, rest: tuple[float, ...], free) -> list[tuple]:
    """Joints 4-6 for the rotation ``rest`` left once joints 1-3 are set: the
    two Euler solutions (sub-problem 2 on axis 6's direction, then 1).

    Written out (the sub-problems and turns inline, the same arithmetic in
    the same order): this runs for every arm solution of every pose."""
    c45, denominator, d56, cross, cross2, x, p6, p6_small, px, x_small = g.wrist
    a0, a1, a2 = g.axes[3]
    b0, b1, b2 = g.axes[4]
    w6 = g.axes[5]
    c0, c1, c2 = w6
    r0, r1, r2, r3, r4, r5, r6, r7, r8 = rest
    # v = R w6: where axis 6's direction must go
    v0 = r0 * c0 + r1 * c1 + r2 * c2
    v1 = r3 * c0 + r4 * c1 + r5 * c2
    v2 = r6 * c0 + r7 * c1 + r8 * c2
    d4v = a0 * v0 + a1 * v1 + a2 * v2
    alpha = (c45 * d56 - d4v) / denominator
    beta = (c45 * d4v - d56) / denominator
    gamma2 = (1.0 - alpha * alpha - beta * beta - 2 * alpha * beta * c45) / cross2
    if gamma2 < -1e-10:
        return []
    gamma = math.sqrt(max(gamma2, 0.0))
    x0, x1, x2 = x
    y0 = r0 * x0 + r1 * x1 + r2 * x2
    y1 = r3 * x0 + r4 * x1 + r5 * x2
    y2 = r6 * x0 + r7 * x1 + r8 * x2
    k0, k1, k2 = cross
    free3, free4, free5 = free[3], free[4], free[5]
    # v seen across axis 4 (sub-problem 1's projection, independent of the sign)
    bv = a0 * v0 + a1 * v1 + a2 * v2
    pv0, pv1, pv2 = v0 - bv * a0, v1 - bv * a1, v2 - bv * a2
    v_small = pv0 * pv0 + pv1 * pv1 + pv2 * pv2 < _EPS
    cos, sin, atan2 = math.cos, math.sin, math.atan2
    e0x, e1x, e2x = px
    out = []
    for sign in (1.0, -1.0) if gamma > DOUBLE_ROOT else (1.0,):
        g3 = sign * gamma
        z0 = alpha * a0 + beta * b0 + g3 * k0
        z1 = alpha * a1 + beta * b1 + g3 * k1
        z2 = alpha * a2 + beta * b2 + g3 * k2
        # t5 = _sp1(w5, w6, z, free[4])
        p0, p1, p2 = p6  # w6 across axis 5
        bz = b0 * z0 + b1 * z1 + b2 * z2
        q0, q1, q2 = z0 - bz * b0, z1 - bz * b1, z2 - bz * b2
        if p6_small or q0 * q0 + q1 * q1 + q2 * q2 < _EPS:
            t5 = free4
        else:
            t5 = atan2(
                b0 * (p1 * q2 - p2 * q1) + b1 * (p2 * q0 - p0 * q2) + b2 * (p0 * q1 - p1 * q0),
                p0 * q0 + p1 * q1 + p2 * q2,
            )
        # u = _rotate(w5, t5, w6)
        c, s_ = cos(t5), sin(t5)
        k = (b0 * c0 + b1 * c1 + b2 * c2) * (1.0 - c)
        u0 = c0 * c + (b1 * c2 - b2 * c1) * s_ + b0 * k
        u1 = c1 * c + (b2 * c0 - b0 * c2) * s_ + b1 * k
        u2 = c2 * c + (b0 * c1 - b1 * c0) * s_ + b2 * k
        # t4 = _sp1(w4, u, v, free[3])
        au = a0 * u0 + a1 * u1 + a2 * u2
        u0, u1, u2 = u0 - au * a0, u1 - au * a1, u2 - au * a2
        if u0 * u0 + u1 * u1 + u2 * u2 < _EPS or v_small:
            t4 = free3
        else:
            t4 = atan2(
                a0 * (u1 * pv2 - u2 * pv1)
                + a1 * (u2 * pv0 - u0 * pv2)
                + a2 * (u0 * pv1 - u1 * pv0),
                u0 * pv0 + u1 * pv1 + u2 * pv2,
            )
        # left = _rotate(w5, -t5, _rotate(w4, -t4, y))
        c, s_ = cos(-t4), sin(-t4)
        k = (a0 * y0 + a1 * y1 + a2 * y2) * (1.0 - c)
        e0 = y0 * c + (a1 * y2 - a2 * y1) * s_ + a0 * k
        e1 = y1 * c + (a2 * y0 - a0 * y2) * s_ + a1 * k
        e2 = y2 * c + (a0 * y1 - a1 * y0) * s_ + a2 * k
        c, s_ = cos(-t5), sin(-t5)
        k = (b0 * e0 + b1 * e1 + b2 * e2) * (1.0 - c)
        f0 = e0 * c + (b1 * e2 - b2 * e1) * s_ + b0 * k
        f1 = e1 * c + (b2 * e0 - b0 * e2) * s_ + b1 * k
        f2 = e2 * c + (b0 * e1 - b1 * e0) * s_ + b2 * k
        # t6 = _sp1(w6, x, left, free[5])
        bf = c0 * f0 + c1 * f1 + c2 * f2
        f0, f1, f2 = f0 - bf * c0, f1 - bf * c1, f2 - bf * c2
        if x_small or f0 * f0 + f1 * f1 + f2 * f2 < _EPS:
            t6 = free5
        else:
            t6 = atan2(
                c0 * (e1x * f2 - e2x * f1)
                + c1 * (e2x * f0 - e0x * f2)
                + c2 * (e0x * f1 - e1x * f0),
                e0x * f0 + e1x * f1 + e2x * f2,
            )
        out.append((t4, t5, t6))
    return out


def _arm_rotation(
    g: Geometry, t1: float, t2: float, t3: float, first: tuple[float, ...] | None = None
) -> tuple[float, ...]:
    """The rotation of joints 1-3, as 9 numbers (row-major); ``first``: joint
    1's, when known."""
    r = _rot_matrix(g.axes[0], t1) if first is None else first
    if g.kind == SPHERICAL_PARALLEL:  # axes 2 and 3 parallel: one turn of t2 ± t3
        t = t2 + t3 if _dot(g.axes[1], g.axes[2]) > 0 else t2 - t3
        return _mul(r, _rot_matrix(g.axes[1], t))
    for axis, t in ((1, t2), (2, t3)):
        if g.revolute[axis]:
            r = _mul(r, _rot_matrix(g.axes[axis], t))
    return r


def _spherical(g: Geometry, goal: Motion, free, fits: Callable) -> list[tuple]:
    centre = _apply(goal, g.centre)  # where the wrist centre must go
    out = []
    goal_rotation = goal[0]
    singular = g.wrist_singular
    no_flip = not math.isnan(singular)
    sin = math.sin
    last_t1, first = None, None
    for t1, t2, t3, elbow_word, shoulder_word in _position(g, centre, free):
        if not fits(t1, t2, t3):
            continue
        if t1 != last_t1:
            last_t1, first = t1, _rot_matrix(g.axes[0], t1)
        rest = _mul_t(_arm_rotation(g, t1, t2, t3, first), goal_rotation)
        arm_words = _label(shoulder_word, elbow_word)
        for t4, t5, t6 in _wrist(g, rest, free):
            # _label(shoulder_word, elbow_word, _flip(g, t5)), written out
            if no_flip:
                flip = "wrist no flip" if sin(t5 - singular) >= 0.0 else "wrist flip"
                words = f"{arm_words}, {flip}" if arm_words else flip
            else:
                words = arm_words
            out.append(((t1, t2, t3, t4, t5, t6), words))
    return out


def _position(g: Geometry, centre: Vec, free) -> list[tuple]:
    """Joints 1-3 that put the wrist centre at ``centre`` (with the elbow's and
    the shoulder's words)."""
    if g.kind == SPHERICAL_PARALLEL:
        return _position_parallel(g, centre, free)
    w1, w2, w3 = g.axes[0], g.axes[1], g.axes[2]
    r3 = g.points[2]
    out = []
    # axes 1 and 2 meet at o: joints 1 and 2 keep the distance from o
    o = g.meeting
    distance = _norm(_sub(centre, o))
    if g.revolute[2]:
        slides = _sp3(w3, r3, g.centre, o, distance, free[2])
        moved = [(t3, _rotate_about(w3, r3, t3, g.centre)) for t3 in slides]
    else:
        # |centre0 + t w3 - o|^2 = distance^2: a quadratic in t
        u = _sub(g.centre, o)
        b = _dot(w3, u)
        disc = b * b - (_dot(u, u) - distance * distance)
        if disc < -1e-10 * g.reach * g.reach:
            return []
        root = math.sqrt(max(disc, 0.0))
        ts = [-b + root, -b - root] if root > DOUBLE_ROOT * g.reach else [-b]
        moved = [(t, _add(g.centre, _scale(w3, t))) for t in ts]
    for t3, point in moved:
        if g.revolute[2]:
            word = ""
        else:  # the slide's two roots put the wrist centre ahead of o or behind it
            word = "arm forward" if _dot(_sub(point, o), w3) >= 0.0 else "arm reversed"
        for t1, t2 in _sp2(w1, w2, _sub(point, o), _sub(centre, o), (free[0], free[1])):
            words = _elbow_world(g, t1, t2, centre) if g.revolute[2] else word
            out.append((t1, t2, t3, words, _shoulder(g, t1, centre)))
    return out


def _parallel_constants(axes: tuple[Vec, ...], points: tuple[Vec, ...], centre: Vec) -> tuple:
    """What :func:`_position_parallel` needs that does not depend on the pose
    (each worked out as the sub-problems would, to the same digits)."""
    w1, w2, r1 = axes[0], axes[1], points[0]
    return (_dot(w2, centre), _dot(w2, r1), _dot(w2, w1))


def _planar_constants(axes: tuple[Vec, ...], points: tuple[Vec, ...], point: Vec) -> tuple:
    """What :func:`_planar_fixed` needs that does not depend on the pose
    (worked out as :func:`_sp3` and :func:`_rotate_about` would)."""
    w3, r3 = axes[2], points[2]
    u = _sub(point, r3)  # the point from axis 3, across it
    u1 = _sub(u, _scale(w3, _dot(w3, u)))
    return (point, u, u1, _norm(u1), _dot(w3, u))


def _planar_fixed(g: Geometry, e0: float, e1: float, e2: float, free) -> list[tuple[float, float]]:
    """``_planar(g, 1, (e0, e1, e2), point, free)`` for the arm's fixed point
    (``g.planar``), written out: the sub-problems inline, the same arithmetic
    in the same order."""
    point, (u0, u1, u2), (n0, n1, n2), nu, wbu = g.planar
    b0, b1, b2 = g.axes[1]
    c0, c1, c2 = g.axes[2]
    s0, s1, s2 = g.points[1]
    t0, t1_, t2_ = g.points[2]
    cos, sin, atan2, sqrt = math.cos, math.sin, math.atan2, math.sqrt
    # the foot of target on axis 2
    d0, d1, d2 = e0 - s0, e1 - s1, e2 - s2
    fa = b0 * d0 + b1 * d1 + b2 * d2
    f0, f1, f2 = s0 + b0 * fa, s1 + b1 * fa, s2 + b2 * fa
    x0, x1, x2 = e0 - f0, e1 - f1, e2 - f2
    distance = sqrt(x0 * x0 + x1 * x1 + x2 * x2)
    # _sp3(w3, r3, point, foot, distance, free[2])
    v0, v1, v2 = f0 - t0, f1 - t1_, f2 - t2_
    wv = c0 * v0 + c1 * v1 + c2 * v2
    v0, v1, v2 = v0 - c0 * wv, v1 - c1 * wv, v2 - c2 * wv
    gf0, gf1, gf2 = point[0] - f0, point[1] - f1, point[2] - f2
    along3 = c0 * gf0 + c1 * gf1 + c2 * gf2
    dd = distance * distance - along3 * along3
    nv = sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    if nu * nv < _EPS:  # degenerate: the general path
        return _planar(g, 1, (e0, e1, e2), point, free)
    theta0 = atan2(
        c0 * (n1 * v2 - n2 * v1) + c1 * (n2 * v0 - n0 * v2) + c2 * (n0 * v1 - n1 * v0),
        n0 * v0 + n1 * v1 + n2 * v2,
    )
    # target - r2 across axis 2 (sub-problem 1's projection)
    q0, q1, q2 = d0 - fa * b0, d1 - fa * b1, d2 - fa * b2
    q_small = q0 * q0 + q1 * q1 + q2 * q2 < _EPS
    planar = []
    for t in _cos_sin_equation(1.0, 0.0, (nu * nu + nv * nv - dd) / (2 * nu * nv), 0.0):
        tb = theta0 - t
        # moved = _rotate_about(w3, r3, tb, point)
        c, s_ = cos(tb), sin(tb)
        k = wbu * (1.0 - c)
        m0 = t0 + (u0 * c + (c1 * u2 - c2 * u1) * s_ + c0 * k)
        m1 = t1_ + (u1 * c + (c2 * u0 - c0 * u2) * s_ + c1 * k)
        m2 = t2_ + (u2 * c + (c0 * u1 - c1 * u0) * s_ + c2 * k)
        # ta = _sp1(w2, moved - r2, target - r2, free[1])
        m0, m1, m2 = m0 - s0, m1 - s1, m2 - s2
        bm = b0 * m0 + b1 * m1 + b2 * m2
        m0, m1, m2 = m0 - bm * b0, m1 - bm * b1, m2 - bm * b2
        if m0 * m0 + m1 * m1 + m2 * m2 < _EPS or q_small:
            ta = free[1]
        else:
            ta = atan2(
                b0 * (m1 * q2 - m2 * q1) + b1 * (m2 * q0 - m0 * q2) + b2 * (m0 * q1 - m1 * q0),
                m0 * q0 + m1 * q1 + m2 * q2,
            )
        planar.append((ta, tb))
    return planar


def _position_parallel(g: Geometry, centre: Vec, free) -> list[tuple]:
    """:func:`_position` for SPHERICAL_PARALLEL, written out (the sub-problems
    inline, the same arithmetic in the same order): joint 1 keeps the wrist
    centre's height along axis 2, then joints 2 and 3 are a planar two-link."""
    height, dnr, dnw = g.arm
    a0, a1, a2 = g.axes[0]
    b0, b1, b2 = g.axes[1]
    r1 = g.points[0]
    s0, s1, s2 = g.points[1]
    t0, t1_, t2_ = g.points[2]
    cos, sin, sqrt = math.cos, math.sin, math.sqrt
    # _height_turns(w1, r1, centre, w2, height, -free[0])
    h0, h1, h2 = centre[0] - r1[0], centre[1] - r1[1], centre[2] - r1[2]
    along = a0 * h0 + a1 * h1 + a2 * h2
    p0, p1, p2 = h0 - a0 * along, h1 - a1 * along, h2 - a2 * along
    roots = _cos_sin_equation(
        b0 * p0 + b1 * p1 + b2 * p2,
        b0 * (a1 * p2 - a2 * p1) + b1 * (a2 * p0 - a0 * p2) + b2 * (a0 * p1 - a1 * p0),
        height - dnr - along * dnw,
        -free[0],
    )
    out = []
    for minus_t1 in roots:
        t1 = -minus_t1
        # seen = _rotate_about(w1, r1, minus_t1, centre): in the arm's home plane
        c, s_ = cos(minus_t1), sin(minus_t1)
        k = along * (1.0 - c)
        e0 = r1[0] + (h0 * c + (a1 * h2 - a2 * h1) * s_ + a0 * k)
        e1 = r1[1] + (h1 * c + (a2 * h0 - a0 * h2) * s_ + a1 * k)
        e2 = r1[2] + (h2 * c + (a0 * h1 - a1 * h0) * s_ + a2 * k)
        planar = _planar_fixed(g, e0, e1, e2, free)
        if not planar:
            continue
        # what depends on joint 1 alone: axis 2's direction, the shoulder and the
        # line from it to the wrist centre
        # (each a turn about axis 1 by t1: _rotate written out)
        c, s_ = cos(t1), sin(t1)
        one_c = 1.0 - c
        k = (a0 * b0 + a1 * b1 + a2 * b2) * one_c
        w20 = b0 * c + (a1 * b2 - a2 * b1) * s_ + a0 * k
        w21 = b1 * c + (a2 * b0 - a0 * b2) * s_ + a1 * k
        w22 = b2 * c + (a0 * b1 - a1 * b0) * s_ + a2 * k
        v0, v1, v2 = s0 - r1[0], s1 - r1[1], s2 - r1[2]
        k = (a0 * v0 + a1 * v1 + a2 * v2) * one_c
        sh0 = r1[0] + (v0 * c + (a1 * v2 - a2 * v1) * s_ + a0 * k)
        sh1 = r1[1] + (v1 * c + (a2 * v0 - a0 * v2) * s_ + a1 * k)
        sh2 = r1[2] + (v2 * c + (a0 * v1 - a1 * v0) * s_ + a2 * k)
        # _shoulder: which side of the plane of axes 1 and 2 the wrist centre is
        side = (a1 * w22 - a2 * w21) * h0 + (a2 * w20 - a0 * w22) * h1 + (a0 * w21 - a1 * w20) * h2
        shoulder_word = "shoulder right" if side >= 0.0 else "shoulder left"
        # _elbow: the line from the shoulder to the wrist centre, and "up"
        l0, l1, l2 = centre[0] - sh0, centre[1] - sh1, centre[2] - sh2
        up = a0 * (w21 * l2 - w22 * l1) + a1 * (w22 * l0 - w20 * l2) + a2 * (w20 * l1 - w21 * l0)
        if abs(up) <= 1e-9 * sqrt(l0 * l0 + l1 * l1 + l2 * l2):
            up = 1.0
        for t2, t3 in planar:
            # elbow = _rotate_about(w1, r1, t1, _rotate_about(w2, r2, t2, r3))
            cb, sb = cos(t2), sin(t2)
            v0, v1, v2 = t0 - s0, t1_ - s1, t2_ - s2
            k = (b0 * v0 + b1 * v1 + b2 * v2) * (1.0 - cb)
            v0, v1, v2 = (
                s0 + (v0 * cb + (b1 * v2 - b2 * v1) * sb + b0 * k) - r1[0],
                s1 + (v1 * cb + (b2 * v0 - b0 * v2) * sb + b1 * k) - r1[1],
                s2 + (v2 * cb + (b0 * v1 - b1 * v0) * sb + b2 * k) - r1[2],
            )
            k = (a0 * v0 + a1 * v1 + a2 * v2) * one_c
            x0 = r1[0] + (v0 * c + (a1 * v2 - a2 * v1) * s_ + a0 * k) - sh0
            x1 = r1[1] + (v1 * c + (a2 * v0 - a0 * v2) * s_ + a1 * k) - sh1
            x2 = r1[2] + (v2 * c + (a0 * v1 - a1 * v0) * s_ + a2 * k) - sh2
            sigma = (
                w20 * (x1 * l2 - x2 * l1) + w21 * (x2 * l0 - x0 * l2) + w22 * (x0 * l1 - x1 * l0)
            )
            words = "elbow up" if -sigma * up >= 0.0 else "elbow down"
            out.append((t1, t2, t3, words, shoulder_word))
    return out


def _elbow_world(
    g: Geometry,
    t1: float,
    t2: float,
    centre: Vec,
    w2: Vec | None = None,
    shoulder: Vec | None = None,
) -> str:
    """Elbow words from the current shoulder (axis 2), elbow (axis 3) and wrist
    centre (``w2``, ``shoulder``: axis 2's turned direction and point, when known)."""
    w1 = g.axes[0]
    if w2 is None:
        w2 = _rotate(w1, t1, g.axes[1])
    if shoulder is None:
        shoulder = _rotate_about(w1, g.points[0], t1, g.points[1])
    e1 = _rotate_about(g.axes[1], g.points[1], t2, g.points[2])
    elbow = _rotate_about(w1, g.points[0], t1, e1)
    return _elbow(g, w2, shoulder, elbow, centre)


def _planar(g: Geometry, i: int, target: Vec, point: Vec, free) -> list[tuple[float, float]]:
    """Joints i and i+1 (parallel axes) that take ``point`` to ``target``."""
    wa, wb = g.axes[i], g.axes[i + 1]
    ra, rb = g.points[i], g.points[i + 1]
    # the point on axis i level with the target: joint i keeps the distance to it
    foot = _add(ra, _scale(wa, _dot(wa, _sub(target, ra))))
    distance = _norm(_sub(target, foot))
    out = []
    for tb in _sp3(wb, rb, point, foot, distance, free[i + 1]):
        moved = _rotate_about(wb, rb, tb, point)
        ta = _sp1(wa, _sub(moved, ra), _sub(target, ra), free[i])
        out.append((ta, tb))
    return out


def _three_parallel(g: Geometry, goal: Motion, free) -> list[tuple]:
    """The UR closed form (axes 2, 3, 4 parallel; axes 5 and 6 meet)."""
    w1, w2, w5, w6 = g.axes[0], g.axes[1], g.axes[4], g.axes[5]
    r1 = g.points[0]
    p2, p3, p4 = g.points[1], g.points[2], g.points[3]
    rot = goal[0]
    centre = _apply(goal, g.centre)
    # a direction across axis 4 that joint 4's turn carries
    x = _cross(w2, w5) if _norm(_cross(w2, w5)) > 1e-6 else _cross(w2, w1)
    out = []
    for minus_t1 in _height_turns(w1, r1, centre, w2, _dot(w2, g.centre), -free[0]):
        t1 = -minus_t1
        e1 = _joint_motion(g, 0, t1)
        # axis 6's direction, as joints 2-4 see it, has a fixed height along axis 2
        seen6 = _turn_back(e1[0], _turn(rot, w6))
        up = _turn_back(rot, _turn(e1[0], w2))  # axis 2's direction in the tool's home terms
        after1 = _compose(_inverse(e1), goal)
        shoulder_word = _shoulder(g, t1, centre)
        # for the elbow's words: axis 2 and the shoulder in the world
        turned2 = _turn(e1[0], w2)
        shoulder = _apply(e1, p2)
        for t5 in _height_turns(w5, (0.0, 0.0, 0.0), w6, w2, _dot(w2, seen6), free[4]):
            e5 = _joint_motion(g, 4, t5)
            t6 = _sp1(w6, up, _turn_back(e5[0], w2), free[5])
            e6 = _joint_motion(g, 5, t6)
            rest = _compose(after1, _inverse(_compose(e5, e6)))
            flip = _flip(g, t5)
            at4 = _apply(rest, p4)
            for t2, t3 in _planar_fixed(g, *at4, free):
                e2 = _joint_motion(g, 1, t2)
                # the rotation of (e2 e3)^-1 rest (its translation is not needed)
                left = _mul_t(_mul(e2[0], _rot_matrix(g.axes[2], t3)), rest[0])
                t4 = _sp1(g.axes[3], x, _turn(left, x), free[3])
                # elbow: axis 2, axis 3 and axis 4 points in the world
                elbow = _apply(e1, _apply(e2, p3))
                elbow_word = _elbow(g, turned2, shoulder, elbow, _apply(e1, at4))
                out.append(((t1, t2, t3, t4, t5, t6), _label(shoulder_word, elbow_word, flip)))
    return out

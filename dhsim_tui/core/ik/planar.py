"""Two parallel axes as a planar two-link, for the closed-form IK
(:mod:`dhsim_tui.core.ik.analytic`): the joints that take a point to a
target, in general and written out for the arm's fixed point.
"""

from __future__ import annotations

import math

from dhsim_tui.core.ik.geometry import Geometry
from dhsim_tui.core.ik.subproblems import EPS, solve_cos_sin, turn_to_direction, turns_to_distance
from dhsim_tui.core.ik.vectors import Vec, add, dot, norm, rotate_about_line, scaled, sub


def planar_at_fixed_point(
    g: Geometry, e0: float, e1: float, e2: float, free
) -> list[tuple[float, float]]:
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
    # turns_to_distance(w3, r3, point, foot, distance, free[2])
    v0, v1, v2 = f0 - t0, f1 - t1_, f2 - t2_
    wv = c0 * v0 + c1 * v1 + c2 * v2
    v0, v1, v2 = v0 - c0 * wv, v1 - c1 * wv, v2 - c2 * wv
    gf0, gf1, gf2 = point[0] - f0, point[1] - f1, point[2] - f2
    along3 = c0 * gf0 + c1 * gf1 + c2 * gf2
    dd = distance * distance - along3 * along3
    nv = sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    if nu * nv < EPS:  # degenerate: the general path
        return _planar(g, 1, (e0, e1, e2), point, free)
    theta0 = atan2(
        c0 * (n1 * v2 - n2 * v1) + c1 * (n2 * v0 - n0 * v2) + c2 * (n0 * v1 - n1 * v0),
        n0 * v0 + n1 * v1 + n2 * v2,
    )
    # target - r2 across axis 2 (sub-problem 1's projection)
    q0, q1, q2 = d0 - fa * b0, d1 - fa * b1, d2 - fa * b2
    q_small = q0 * q0 + q1 * q1 + q2 * q2 < EPS
    planar = []
    for t in solve_cos_sin(1.0, 0.0, (nu * nu + nv * nv - dd) / (2 * nu * nv), 0.0):
        tb = theta0 - t
        # moved = rotate_about_line(w3, r3, tb, point)
        c, s_ = cos(tb), sin(tb)
        k = wbu * (1.0 - c)
        m0 = t0 + (u0 * c + (c1 * u2 - c2 * u1) * s_ + c0 * k)
        m1 = t1_ + (u1 * c + (c2 * u0 - c0 * u2) * s_ + c1 * k)
        m2 = t2_ + (u2 * c + (c0 * u1 - c1 * u0) * s_ + c2 * k)
        # ta = turn_to_direction(w2, moved - r2, target - r2, free[1])
        m0, m1, m2 = m0 - s0, m1 - s1, m2 - s2
        bm = b0 * m0 + b1 * m1 + b2 * m2
        m0, m1, m2 = m0 - bm * b0, m1 - bm * b1, m2 - bm * b2
        if m0 * m0 + m1 * m1 + m2 * m2 < EPS or q_small:
            ta = free[1]
        else:
            ta = atan2(
                b0 * (m1 * q2 - m2 * q1) + b1 * (m2 * q0 - m0 * q2) + b2 * (m0 * q1 - m1 * q0),
                m0 * q0 + m1 * q1 + m2 * q2,
            )
        planar.append((ta, tb))
    return planar


def _planar(g: Geometry, i: int, target: Vec, point: Vec, free) -> list[tuple[float, float]]:
    """Joints i and i+1 (parallel axes) that take ``point`` to ``target``."""
    wa, wb = g.axes[i], g.axes[i + 1]
    ra, rb = g.points[i], g.points[i + 1]
    # the point on axis i level with the target: joint i keeps the distance to it
    foot = add(ra, scaled(wa, dot(wa, sub(target, ra))))
    distance = norm(sub(target, foot))
    out = []
    for tb in turns_to_distance(wb, rb, point, foot, distance, free[i + 1]):
        moved = rotate_about_line(wb, rb, tb, point)
        ta = turn_to_direction(wa, sub(moved, ra), sub(target, ra), free[i])
        out.append((ta, tb))
    return out

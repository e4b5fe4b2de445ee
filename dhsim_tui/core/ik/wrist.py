"""The spherical-wrist (Pieper) closed forms (:mod:`dhsim_tui.core.ik.analytic`):
joints 1-3 put the wrist centre in place (axes 2 and 3 parallel, as the Puma
and IRB 140; or axes 1 and 2 meeting, as the Stanford arm), then the wrist's
two Euler solutions give joints 4-6.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from dhsim_tui.core.ik.geometry import SPHERICAL_PARALLEL, Geometry
from dhsim_tui.core.ik.labels import elbow_label_world, joined_label, shoulder_label
from dhsim_tui.core.ik.planar import planar_at_fixed_point
from dhsim_tui.core.ik.subproblems import (
    DOUBLE_ROOT,
    EPS,
    solve_cos_sin,
    turns_to_distance,
    two_axis_turns,
)
from dhsim_tui.core.ik.vectors import (
    Motion,
    Vec,
    add,
    apply_motion,
    dot,
    mul_rotations,
    mul_rotations_t,
    norm,
    rotate_about_line,
    rotation_matrix,
    scaled,
    sub,
)


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
    v_small = pv0 * pv0 + pv1 * pv1 + pv2 * pv2 < EPS
    cos, sin, atan2 = math.cos, math.sin, math.atan2
    e0x, e1x, e2x = px
    out = []
    for sign in (1.0, -1.0) if gamma > DOUBLE_ROOT else (1.0,):
        g3 = sign * gamma
        z0 = alpha * a0 + beta * b0 + g3 * k0
        z1 = alpha * a1 + beta * b1 + g3 * k1
        z2 = alpha * a2 + beta * b2 + g3 * k2
        # t5 = turn_to_direction(w5, w6, z, free[4])
        p0, p1, p2 = p6  # w6 across axis 5
        bz = b0 * z0 + b1 * z1 + b2 * z2
        q0, q1, q2 = z0 - bz * b0, z1 - bz * b1, z2 - bz * b2
        if p6_small or q0 * q0 + q1 * q1 + q2 * q2 < EPS:
            t5 = free4
        else:
            t5 = atan2(
                b0 * (p1 * q2 - p2 * q1) + b1 * (p2 * q0 - p0 * q2) + b2 * (p0 * q1 - p1 * q0),
                p0 * q0 + p1 * q1 + p2 * q2,
            )
        # u = rotate(w5, t5, w6)
        c, s_ = cos(t5), sin(t5)
        k = (b0 * c0 + b1 * c1 + b2 * c2) * (1.0 - c)
        u0 = c0 * c + (b1 * c2 - b2 * c1) * s_ + b0 * k
        u1 = c1 * c + (b2 * c0 - b0 * c2) * s_ + b1 * k
        u2 = c2 * c + (b0 * c1 - b1 * c0) * s_ + b2 * k
        # t4 = turn_to_direction(w4, u, v, free[3])
        au = a0 * u0 + a1 * u1 + a2 * u2
        u0, u1, u2 = u0 - au * a0, u1 - au * a1, u2 - au * a2
        if u0 * u0 + u1 * u1 + u2 * u2 < EPS or v_small:
            t4 = free3
        else:
            t4 = atan2(
                a0 * (u1 * pv2 - u2 * pv1)
                + a1 * (u2 * pv0 - u0 * pv2)
                + a2 * (u0 * pv1 - u1 * pv0),
                u0 * pv0 + u1 * pv1 + u2 * pv2,
            )
        # left = rotate(w5, -t5, rotate(w4, -t4, y))
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
        # t6 = turn_to_direction(w6, x, left, free[5])
        bf = c0 * f0 + c1 * f1 + c2 * f2
        f0, f1, f2 = f0 - bf * c0, f1 - bf * c1, f2 - bf * c2
        if x_small or f0 * f0 + f1 * f1 + f2 * f2 < EPS:
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
    r = rotation_matrix(g.axes[0], t1) if first is None else first
    if g.kind == SPHERICAL_PARALLEL:  # axes 2 and 3 parallel: one turn of t2 ± t3
        t = t2 + t3 if dot(g.axes[1], g.axes[2]) > 0 else t2 - t3
        return mul_rotations(r, rotation_matrix(g.axes[1], t))
    for axis, t in ((1, t2), (2, t3)):
        if g.revolute[axis]:
            r = mul_rotations(r, rotation_matrix(g.axes[axis], t))
    return r


def solve_spherical_wrist(g: Geometry, goal: Motion, free, fits: Callable) -> list[tuple]:
    """The closed form for a spherical wrist (axes 4, 5, 6 meet): each solution
    that ``fits``, with its label."""
    centre = apply_motion(goal, g.centre)  # where the wrist centre must go
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
            last_t1, first = t1, rotation_matrix(g.axes[0], t1)
        rest = mul_rotations_t(_arm_rotation(g, t1, t2, t3, first), goal_rotation)
        arm_words = joined_label(shoulder_word, elbow_word)
        for t4, t5, t6 in _wrist(g, rest, free):
            # joined_label(shoulder_word, elbow_word, flip_label(g, t5)), written out
            if no_flip:
                flip = "wrist no flip" if sin(t5 - singular) <= 0.0 else "wrist flip"
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
    distance = norm(sub(centre, o))
    if g.revolute[2]:
        slides = turns_to_distance(w3, r3, g.centre, o, distance, free[2])
        moved = [(t3, rotate_about_line(w3, r3, t3, g.centre)) for t3 in slides]
    else:
        # |centre0 + t w3 - o|^2 = distance^2: a quadratic in t
        u = sub(g.centre, o)
        b = dot(w3, u)
        disc = b * b - (dot(u, u) - distance * distance)
        if disc < -1e-10 * g.reach * g.reach:
            return []
        root = math.sqrt(max(disc, 0.0))
        ts = [-b + root, -b - root] if root > DOUBLE_ROOT * g.reach else [-b]
        moved = [(t, add(g.centre, scaled(w3, t))) for t in ts]
    for t3, point in moved:
        if g.revolute[2]:
            word = ""
        else:  # the slide's two roots put the wrist centre ahead of o or behind it
            word = "arm forward" if dot(sub(point, o), w3) >= 0.0 else "arm reversed"
        for t1, t2 in two_axis_turns(w1, w2, sub(point, o), sub(centre, o), (free[0], free[1])):
            words = elbow_label_world(g, t1, t2, centre) if g.revolute[2] else word
            out.append((t1, t2, t3, words, shoulder_label(g, t1, centre)))
    return out


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
    # turns_to_height(w1, r1, centre, w2, height, -free[0])
    h0, h1, h2 = centre[0] - r1[0], centre[1] - r1[1], centre[2] - r1[2]
    along = a0 * h0 + a1 * h1 + a2 * h2
    p0, p1, p2 = h0 - a0 * along, h1 - a1 * along, h2 - a2 * along
    roots = solve_cos_sin(
        b0 * p0 + b1 * p1 + b2 * p2,
        b0 * (a1 * p2 - a2 * p1) + b1 * (a2 * p0 - a0 * p2) + b2 * (a0 * p1 - a1 * p0),
        height - dnr - along * dnw,
        -free[0],
    )
    out = []
    for minus_t1 in roots:
        t1 = -minus_t1
        # seen = rotate_about_line(w1, r1, minus_t1, centre): in the arm's home plane
        c, s_ = cos(minus_t1), sin(minus_t1)
        k = along * (1.0 - c)
        e0 = r1[0] + (h0 * c + (a1 * h2 - a2 * h1) * s_ + a0 * k)
        e1 = r1[1] + (h1 * c + (a2 * h0 - a0 * h2) * s_ + a1 * k)
        e2 = r1[2] + (h2 * c + (a0 * h1 - a1 * h0) * s_ + a2 * k)
        planar = planar_at_fixed_point(g, e0, e1, e2, free)
        if not planar:
            continue
        # what depends on joint 1 alone: axis 2's direction, the shoulder and the
        # line from it to the wrist centre
        # (each a turn about axis 1 by t1: rotate written out)
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
        # shoulder_label: which side of the plane of axes 1 and 2 the wrist centre is
        side = (a1 * w22 - a2 * w21) * h0 + (a2 * w20 - a0 * w22) * h1 + (a0 * w21 - a1 * w20) * h2
        shoulder_word = "shoulder right" if side >= 0.0 else "shoulder left"
        # elbow_label: the line from the shoulder to the wrist centre, and "up"
        l0, l1, l2 = centre[0] - sh0, centre[1] - sh1, centre[2] - sh2
        up = a0 * (w21 * l2 - w22 * l1) + a1 * (w22 * l0 - w20 * l2) + a2 * (w20 * l1 - w21 * l0)
        if abs(up) <= 1e-9 * sqrt(l0 * l0 + l1 * l1 + l2 * l2):
            up = 1.0
        for t2, t3 in planar:
            # elbow = rotate_about_line(w1, r1, t1, rotate_about_line(w2, r2, t2, r3))
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

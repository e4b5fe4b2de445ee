"""The closed form for three parallel axes 2, 3 and 4 with axes 5 and 6
meeting (the UR form; :mod:`dhsim_tui.core.ik.analytic`): joint 1 from a
height, joints 5 and 6 from axis 6's and axis 2's directions, then a planar
three-link for joints 2-4.
"""

from __future__ import annotations

from dhsim_tui.core.ik.geometry import Geometry
from dhsim_tui.core.ik.labels import _elbow, _flip, _label, _shoulder
from dhsim_tui.core.ik.planar import _planar_fixed
from dhsim_tui.core.ik.subproblems import _height_turns, _sp1
from dhsim_tui.core.ik.vectors import (
    Motion,
    _apply,
    _compose,
    _cross,
    _dot,
    _inverse,
    _mul,
    _mul_t,
    _norm,
    _rot_matrix,
    _scale,
    _sub,
    _turn,
    _turn_back,
)


def _joint_motion(geometry: Geometry, i: int, value: float) -> Motion:
    """e_i(value): a turn (radians) about axis i, or a slide along it."""
    w, r = geometry.axes[i], geometry.points[i]
    if geometry.revolute[i]:
        rot = _rot_matrix(w, value)
        return (rot, _sub(r, _turn(rot, r)))
    return ((1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0), _scale(w, value))


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

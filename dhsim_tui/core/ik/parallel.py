"""The closed form for three parallel axes 2, 3 and 4 with axes 5 and 6
meeting (the UR form; :mod:`dhsim_tui.core.ik.analytic`): joint 1 from a
height, joints 5 and 6 from axis 6's and axis 2's directions, then a planar
three-link for joints 2-4.
"""

from __future__ import annotations

from dhsim_tui.core.ik.geometry import Geometry
from dhsim_tui.core.ik.labels import elbow_label, flip_label, joined_label, shoulder_label
from dhsim_tui.core.ik.planar import planar_at_fixed_point
from dhsim_tui.core.ik.subproblems import turn_to_direction, turns_to_height
from dhsim_tui.core.ik.vectors import (
    Motion,
    apply_motion,
    compose_motions,
    cross_product,
    dot,
    invert_motion,
    mul_rotations,
    mul_rotations_t,
    norm,
    rotation_matrix,
    scaled,
    sub,
    turn_vector,
    turn_vector_back,
)


def _joint_motion(geometry: Geometry, i: int, value: float) -> Motion:
    """e_i(value): a turn (radians) about axis i, or a slide along it."""
    w, r = geometry.axes[i], geometry.points[i]
    if geometry.revolute[i]:
        rot = rotation_matrix(w, value)
        return (rot, sub(r, turn_vector(rot, r)))
    return ((1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0), scaled(w, value))


def solve_three_parallel(g: Geometry, goal: Motion, free) -> list[tuple]:
    """The UR closed form (axes 2, 3, 4 parallel; axes 5 and 6 meet)."""
    w1, w2, w5, w6 = g.axes[0], g.axes[1], g.axes[4], g.axes[5]
    r1 = g.points[0]
    p2, p3, p4 = g.points[1], g.points[2], g.points[3]
    rot = goal[0]
    centre = apply_motion(goal, g.centre)
    # a direction across axis 4 that joint 4's turn carries
    x = cross_product(w2, w5) if norm(cross_product(w2, w5)) > 1e-6 else cross_product(w2, w1)
    out = []
    for minus_t1 in turns_to_height(w1, r1, centre, w2, dot(w2, g.centre), -free[0]):
        t1 = -minus_t1
        e1 = _joint_motion(g, 0, t1)
        # axis 6's direction, as joints 2-4 see it, has a fixed height along axis 2
        seen6 = turn_vector_back(e1[0], turn_vector(rot, w6))
        up = turn_vector_back(
            rot, turn_vector(e1[0], w2)
        )  # axis 2's direction in the tool's home terms
        after1 = compose_motions(invert_motion(e1), goal)
        shoulder_word = shoulder_label(g, t1, centre)
        # for the elbow's words: axis 2 and the shoulder in the world
        turned2 = turn_vector(e1[0], w2)
        shoulder = apply_motion(e1, p2)
        for t5 in turns_to_height(w5, (0.0, 0.0, 0.0), w6, w2, dot(w2, seen6), free[4]):
            e5 = _joint_motion(g, 4, t5)
            t6 = turn_to_direction(w6, up, turn_vector_back(e5[0], w2), free[5])
            e6 = _joint_motion(g, 5, t6)
            rest = compose_motions(after1, invert_motion(compose_motions(e5, e6)))
            flip = flip_label(g, t5)
            at4 = apply_motion(rest, p4)
            for t2, t3 in planar_at_fixed_point(g, *at4, free):
                e2 = _joint_motion(g, 1, t2)
                # the rotation of (e2 e3)^-1 rest (its translation is not needed)
                left = mul_rotations_t(
                    mul_rotations(e2[0], rotation_matrix(g.axes[2], t3)), rest[0]
                )
                t4 = turn_to_direction(g.axes[3], x, turn_vector(left, x), free[3])
                # elbow: axis 2, axis 3 and axis 4 points in the world
                elbow = apply_motion(e1, apply_motion(e2, p3))
                elbow_word = elbow_label(g, turned2, shoulder, elbow, apply_motion(e1, at4))
                out.append(
                    ((t1, t2, t3, t4, t5, t6), joined_label(shoulder_word, elbow_word, flip))
                )
    return out

"""The configuration words of a closed-form IK solution (shoulder, elbow,
wrist flip), each worked out from the geometry as described in
:mod:`dhsim_tui.core.ik.analytic`.
"""

from __future__ import annotations

import math

from dhsim_tui.core.ik.geometry import Geometry
from dhsim_tui.core.ik.vectors import Vec, cross_product, dot, norm, rotate, rotate_about_line, sub


def shoulder_label(g: Geometry, t1: float, point: Vec, w2: Vec | None = None) -> str:
    """ "shoulder right" or "shoulder left": the side of axis 2 the point lies on."""
    w1 = g.axes[0]
    if w2 is None:
        w2 = rotate(w1, t1, g.axes[1])
    side = dot(cross_product(w1, w2), sub(point, g.points[0]))
    return "shoulder right" if side >= 0.0 else "shoulder left"


def elbow_label(g: Geometry, w2: Vec, shoulder: Vec, elbow: Vec, wrist: Vec) -> str:
    """ "elbow up" or "elbow down": the elbow's side of the shoulder-wrist line."""
    line = sub(wrist, shoulder)
    sigma = dot(w2, cross_product(sub(elbow, shoulder), line))  # < 0: elbow on w2 × line's side
    up = dot(g.axes[0], cross_product(w2, line))
    if abs(up) <= 1e-9 * norm(line):
        up = 1.0
    return "elbow up" if -sigma * up >= 0.0 else "elbow down"


def flip_label(g: Geometry, t5: float) -> str:
    """No flip when joint 5 is turned below its singular position (axis 6 then
    leans toward ``axis4 × axis5``): the Robotics Toolbox's n / f."""
    if math.isnan(g.wrist_singular):
        return ""
    return "wrist no flip" if math.sin(t5 - g.wrist_singular) <= 0.0 else "wrist flip"


def joined_label(*words: str) -> str:
    """The non-empty words joined with commas: a solution's label."""
    return ", ".join([w for w in words if w])


def elbow_label_world(
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
        w2 = rotate(w1, t1, g.axes[1])
    if shoulder is None:
        shoulder = rotate_about_line(w1, g.points[0], t1, g.points[1])
    e1 = rotate_about_line(g.axes[1], g.points[1], t2, g.points[2])
    elbow = rotate_about_line(w1, g.points[0], t1, e1)
    return elbow_label(g, w2, shoulder, elbow, centre)

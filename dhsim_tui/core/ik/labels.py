"""The configuration words of a closed-form IK solution (shoulder, elbow,
wrist flip), each worked out from the geometry as described in
:mod:`dhsim_tui.core.ik.analytic`.
"""

from __future__ import annotations

import math

from dhsim_tui.core.ik.geometry import Geometry
from dhsim_tui.core.ik.vectors import Vec, _cross, _dot, _norm, _rotate, _rotate_about, _sub


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
    """No flip when joint 5 is turned below its singular position (axis 6 then
    leans toward ``axis4 × axis5``): the Robotics Toolbox's n / f."""
    if math.isnan(g.wrist_singular):
        return ""
    return "wrist no flip" if math.sin(t5 - g.wrist_singular) <= 0.0 else "wrist flip"


def _label(*words: str) -> str:
    return ", ".join([w for w in words if w])


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

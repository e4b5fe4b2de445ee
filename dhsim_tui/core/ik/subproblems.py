"""The Paden-Kahan sub-problems the closed-form IK is built from
(:mod:`dhsim_tui.core.ik.analytic`): a turn taking one direction to another,
``a cos t + b sin t = c``, a turn keeping a height, a turn keeping a
distance, and two turns about meeting axes.
"""

from __future__ import annotations

import math

from dhsim_tui.core.ik.vectors import (
    Vec,
    _add,
    _cross,
    _dot,
    _norm,
    _rotate,
    _scale,
    _sub,
)

#: a sub-problem's quantity below this (fraction of the reach) counts as zero
_EPS = 1e-12
#: roots of a step closer than this (radians, or fraction of the reach) are one
#: double root: rounding alone splits a double root by ~1e-8 (a square root of
#: 1e-16), which would list one pose twice
DOUBLE_ROOT = 1e-7


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

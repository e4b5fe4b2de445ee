"""The Paden-Kahan sub-problems the closed-form IK is built from
(:mod:`dhsim_tui.core.ik.analytic`): a turn taking one direction to another,
``a cos t + b sin t = c``, a turn keeping a height, a turn keeping a
distance, and two turns about meeting axes.
"""

from __future__ import annotations

import math

from dhsim_tui.core.ik.vectors import (
    Vec,
    add,
    cross_product,
    dot,
    norm,
    rotate,
    scaled,
    sub,
)

#: a sub-problem's quantity below this (fraction of the reach) counts as zero
EPS = 1e-12
#: roots of a step closer than this (radians, or fraction of the reach) are one
#: double root: rounding alone splits a double root by ~1e-8 (a square root of
#: 1e-16), which would list one pose twice
DOUBLE_ROOT = 1e-7


def turn_to_direction(w: Vec, u: Vec, v: Vec, preferred: float) -> float:
    """The turn about ``w`` that takes direction ``u`` to ``v`` (both as seen
    perpendicular to ``w``); ``preferred`` when either lies along ``w``."""
    w0, w1, w2 = w
    u0, u1, u2 = u
    v0, v1, v2 = v
    a = w0 * u0 + w1 * u1 + w2 * u2
    b = w0 * v0 + w1 * v1 + w2 * v2
    u0, u1, u2 = u0 - a * w0, u1 - a * w1, u2 - a * w2
    v0, v1, v2 = v0 - b * w0, v1 - b * w1, v2 - b * w2
    if u0 * u0 + u1 * u1 + u2 * u2 < EPS or v0 * v0 + v1 * v1 + v2 * v2 < EPS:
        return preferred
    sine = w0 * (u1 * v2 - u2 * v1) + w1 * (u2 * v0 - u0 * v2) + w2 * (u0 * v1 - u1 * v0)
    return math.atan2(sine, u0 * v0 + u1 * v1 + u2 * v2)


def solve_cos_sin(a: float, b: float, c: float, preferred: float) -> list[float]:
    """Roots of ``a cos t + b sin t = c``: none, one (tangent) or two."""
    rho = math.hypot(a, b)
    if rho < EPS:
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


def turns_to_height(w: Vec, r: Vec, p: Vec, n: Vec, c: float, preferred: float) -> list[float]:
    """Turns t about the line (w, r) with ``n · rotate(p) = c``."""
    u = sub(p, r)
    along = dot(w, u)
    u1 = sub(u, scaled(w, along))
    return solve_cos_sin(
        dot(n, u1), dot(n, cross_product(w, u1)), c - dot(n, r) - along * dot(n, w), preferred
    )


def turns_to_distance(
    w: Vec, r: Vec, p: Vec, target: Vec, distance: float, preferred: float
) -> list[float]:
    """Turns t about the line (w, r) that put ``p`` at ``distance`` from ``target``."""
    u = sub(p, r)
    v = sub(target, r)
    u1 = sub(u, scaled(w, dot(w, u)))
    v1 = sub(v, scaled(w, dot(w, v)))
    along = dot(w, sub(p, target))
    d2 = distance * distance - along * along
    nu, nv = norm(u1), norm(v1)
    if nu * nv < EPS:
        close = abs(nu * nu + nv * nv - d2) < 1e-9 * max(1.0, distance * distance)
        return [preferred] if close else []
    theta0 = math.atan2(dot(w, cross_product(u1, v1)), dot(u1, v1))
    # |R u1 - v1|^2 = nu^2 + nv^2 - 2 nu nv cos(theta0 - t) = d2
    return [
        theta0 - t for t in solve_cos_sin(1.0, 0.0, (nu * nu + nv * nv - d2) / (2 * nu * nv), 0.0)
    ]


def two_axis_turns(w1: Vec, w2: Vec, u: Vec, v: Vec, preferred: tuple[float, float]):
    """Turns (t1, t2) about two meeting axes with ``R1(t1) R2(t2) u = v``
    (directions from their common point): none, one or two pairs."""
    c12 = dot(w1, w2)
    denominator = c12 * c12 - 1.0
    if abs(denominator) < EPS:
        return []
    alpha = (c12 * dot(w2, u) - dot(w1, v)) / denominator
    beta = (c12 * dot(w1, v) - dot(w2, u)) / denominator
    cross = cross_product(w1, w2)
    gamma2 = (dot(u, u) - alpha * alpha - beta * beta - 2 * alpha * beta * c12) / dot(cross, cross)
    scale = max(dot(u, u), 1.0)
    if gamma2 < -1e-10 * scale:
        return []
    gamma = math.sqrt(max(gamma2, 0.0))
    out = []
    for sign in (1.0, -1.0) if gamma > DOUBLE_ROOT * math.sqrt(scale) else (1.0,):
        z = add(add(scaled(w1, alpha), scaled(w2, beta)), scaled(cross, sign * gamma))
        t2 = turn_to_direction(w2, u, z, preferred[1])
        t1 = turn_to_direction(w1, rotate(w2, t2, u), v, preferred[0])
        out.append((t1, t2))
    return out

"""3-vectors and rigid motions as plain tuples, for the closed-form IK
(:mod:`dhsim_tui.core.ik.analytic`).

A pose costs a few hundred of these operations: numpy's per-call overhead
would dominate, so each is written out on tuples. A rotation is 9 numbers
(row-major), a rigid motion ``(R, p)``.
"""

from __future__ import annotations

import math

Vec = tuple[float, float, float]


# -- 3-vectors as tuples (a pose costs a few hundred of these: numpy's
#    per-call overhead would dominate) ---------------------------------------
def sub(a: Vec, b: Vec) -> Vec:
    """``a - b``."""
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a: Vec, b: Vec) -> Vec:
    """``a + b``."""
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scaled(a: Vec, k: float) -> Vec:
    """``a`` times the number ``k``."""
    return (a[0] * k, a[1] * k, a[2] * k)


def dot(a: Vec, b: Vec) -> float:
    """The dot product of ``a`` and ``b``."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross_product(a: Vec, b: Vec) -> Vec:
    """The cross product ``a × b``."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a: Vec) -> float:
    """The length of ``a``."""
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def rotate(w: Vec, t: float, v: Vec) -> Vec:
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


def rotate_about_line(w: Vec, r: Vec, t: float, p: Vec) -> Vec:
    """Point ``p`` turned by ``t`` about the line through ``r`` along ``w``."""
    return add(r, rotate(w, t, sub(p, r)))


# -- rigid motions as (R rows flat, p) ----------------------------------------
Motion = tuple[tuple[float, ...], Vec]


def rotation_matrix(w: Vec, t: float) -> tuple[float, ...]:
    """The rotation by ``t`` radians about the unit direction ``w`` (9 numbers, row-major)."""
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


def apply_motion(m: Motion, p: Vec) -> Vec:
    """Point ``p`` moved by the motion ``m`` (rotation, then translation)."""
    r, t = m
    return (
        r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + t[0],
        r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + t[1],
        r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + t[2],
    )


def turn_vector(r: tuple[float, ...], v: Vec) -> Vec:
    """R v: ``v`` turned by the rotation ``r`` (9 numbers, row-major)."""
    return (
        r[0] * v[0] + r[1] * v[1] + r[2] * v[2],
        r[3] * v[0] + r[4] * v[1] + r[5] * v[2],
        r[6] * v[0] + r[7] * v[1] + r[8] * v[2],
    )


def turn_vector_back(r: tuple[float, ...], v: Vec) -> Vec:
    """R^T v."""
    return (
        r[0] * v[0] + r[3] * v[1] + r[6] * v[2],
        r[1] * v[0] + r[4] * v[1] + r[7] * v[2],
        r[2] * v[0] + r[5] * v[1] + r[8] * v[2],
    )


def mul_rotations(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, ...]:
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


def mul_rotations_t(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, ...]:
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


def compose_motions(a: Motion, b: Motion) -> Motion:
    """The motion ``a`` after ``b`` (``a · b``)."""
    return (mul_rotations(a[0], b[0]), apply_motion(a, b[1]))


def invert_motion(m: Motion) -> Motion:
    """The motion that undoes ``m``."""
    r, p = m
    rt = (r[0], r[3], r[6], r[1], r[4], r[7], r[2], r[5], r[8])
    return (rt, scaled(turn_vector(rt, p), -1.0))

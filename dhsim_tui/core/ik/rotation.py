"""The rotation vector between two orientations: :func:`rotation_error` on
numpy matrices, and :func:`rotation_error_floats`, the same in plain floats for
the numerical solver's inner loop (:mod:`dhsim_tui.core.ik.numerical_descent`).
"""

from __future__ import annotations

import math

import numpy as np


def rotation_error(target: np.ndarray, current: np.ndarray) -> np.ndarray:
    """The rotation vector (world frame, radians) that turns ``current`` into ``target``."""
    r = target @ current.T
    v = 0.5 * np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    s = float(np.linalg.norm(v))
    c = (np.trace(r) - 1.0) / 2.0
    angle = math.atan2(s, c)
    if s > 1e-9:
        return v / s * angle
    if c > 0:  # no rotation
        return v
    # a half turn: the axis from the diagonal, signs from the off-diagonal terms
    axis = np.sqrt(np.maximum((np.diag(r) + 1.0) / 2.0, 0.0))
    k = int(np.argmax(axis))
    for i in range(3):
        if i != k and r[k, i] + r[i, k] < 0:
            axis[i] = -axis[i]
    return axis / np.linalg.norm(axis) * math.pi


def rotation_error_floats(goal: list[float], s: tuple[float, ...]) -> tuple[float, float, float]:
    """:func:`rotation_error` of the goal's rows and a state's axes, in plain floats."""
    g00, g01, g02, g10, g11, g12, g20, g21, g22 = goal
    x0, x1, x2, y0, y1, y2, z0, z1, z2 = s[:9]
    # r = goal · currentᵀ; current's rows are (x_k, y_k, z_k)
    r00 = g00 * x0 + g01 * y0 + g02 * z0
    r11 = g10 * x1 + g11 * y1 + g12 * z1
    r22 = g20 * x2 + g21 * y2 + g22 * z2
    vx = 0.5 * ((g20 * x1 + g21 * y1 + g22 * z1) - (g10 * x2 + g11 * y2 + g12 * z2))
    vy = 0.5 * ((g00 * x2 + g01 * y2 + g02 * z2) - (g20 * x0 + g21 * y0 + g22 * z0))
    vz = 0.5 * ((g10 * x0 + g11 * y0 + g12 * z0) - (g00 * x1 + g01 * y1 + g02 * z1))
    size = math.sqrt(vx * vx + vy * vy + vz * vz)
    cosine = (r00 + r11 + r22 - 1.0) / 2.0
    if size > 1e-9:
        k = math.atan2(size, cosine) / size
        return (vx * k, vy * k, vz * k)
    if cosine > 0:
        return (vx, vy, vz)
    current = np.array(s[:9]).reshape(3, 3).T  # a half turn: rare, the matrix way
    return tuple(rotation_error(np.array(goal).reshape(3, 3), current).tolist())

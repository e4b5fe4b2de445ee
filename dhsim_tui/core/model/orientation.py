"""Rotations and orientation read-outs (kinematics reference section 4): OAT
and roll-pitch-yaw.

Everything takes and returns degrees; matrices are numpy arrays.
"""

from __future__ import annotations

import math

import numpy as np

from dhsim_tui.core.model.validation import axis_vector

#: the OAT reference orientation (O = A = T = 0)
OAT_R0 = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])
#: below this, the approach vector counts as vertical (OAT's singular case)
SINGULAR_EPS = 1e-9


def cos_sin(deg: float) -> tuple[float, float]:
    """cos and sin with exact zeros and ones at multiples of 90°."""
    quarter = deg / 90.0
    if quarter == round(quarter):
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[round(quarter) % 4]
    rad = math.radians(deg)
    return (math.cos(rad), math.sin(rad))


def rpy_angles(r: np.ndarray) -> tuple[float, float, float]:
    """Roll, pitch, yaw (radians) with R = Rz(yaw)·Ry(pitch)·Rx(roll), also at
    pitch = ±90°: yaw is read first, then pitch and roll from Rz(-yaw)·R, so
    whatever yaw rounding picks there, the three rebuild R to rounding."""
    r00, r10 = float(r[0, 0]) + 0.0, float(r[1, 0]) + 0.0  # + 0.0: no -0.0
    yaw = 0.0 if math.hypot(r00, r10) < 1e-14 else math.atan2(r10, r00)
    c, s = math.cos(yaw), math.sin(yaw)
    m00 = c * r00 + s * r10
    m11 = c * float(r[1, 1]) - s * float(r[0, 1])
    m12 = c * float(r[1, 2]) - s * float(r[0, 2])
    pitch = math.atan2(-float(r[2, 0]), m00)
    roll = math.atan2(-m12, m11)
    return (roll, pitch, yaw)


def rotx(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def roty(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rotz(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def wrap180(deg: float) -> float:
    """Wrap an angle to (-180, 180]."""
    wrapped = math.fmod(deg, 360.0)
    if wrapped <= -180.0:
        wrapped += 360.0
    elif wrapped > 180.0:
        wrapped -= 360.0
    return wrapped


def base_rotation(base_z: str, base_x: str) -> np.ndarray:
    """B: columns are frame 0's x, y = z × x and z axes in world coordinates."""
    x = np.array(axis_vector(base_x), dtype=float)
    z = np.array(axis_vector(base_z), dtype=float)
    return np.column_stack([x, np.cross(z, x), z])


def base_transform(
    base_z: str,
    base_x: str,
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0),
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> np.ndarray:
    """Frame 0 in world coordinates: translate(xyz) · axes(base_z, base_x) · rpy."""
    base = np.eye(4)
    base[:3, :3] = base_rotation(base_z, base_x)
    if any(rpy):
        base[:3, :3] = base[:3, :3] @ rpy_matrix(*rpy)
    base[:3, 3] = xyz
    return base


def rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """R = Rz(yaw) · Ry(pitch) · Rx(roll)."""
    return rotz(yaw) @ roty(pitch) @ rotx(roll)


def rpy_from_matrix(r: np.ndarray) -> tuple[float, float, float]:
    """Roll, pitch, yaw (degrees) as the Robotics Toolbox teach panel shows them."""
    roll = math.atan2(r[2, 1], r[2, 2])
    pitch = math.atan2(-r[2, 0], math.hypot(r[0, 0], r[1, 0]))
    yaw = math.atan2(r[1, 0], r[0, 0])
    return (math.degrees(roll), math.degrees(pitch), math.degrees(yaw))


def oat_matrix(o: float, a: float, t: float) -> np.ndarray:
    """R(O, A, T) = Rz(O) · R0 · Ry(A) · Rz(T)."""
    return rotz(o) @ OAT_R0 @ roty(a) @ rotz(t)


def oat_from_matrix(r: np.ndarray) -> tuple[float, float, float]:
    """O, A, T (degrees) of a rotation, principal branch A in [-90, 90].

    When the approach vector is vertical only T - O (A = +90) or T + O
    (A = -90) is defined; the reference's rule fixes O = 90.
    """
    horizontal = math.hypot(r[0, 2], r[1, 2])
    if horizontal < SINGULAR_EPS:
        o = 90.0
        spin = math.degrees(math.atan2(r[0, 0], r[0, 1]))
        if r[2, 2] < 0:  # approach points down: A = +90
            return (o, 90.0, wrap180(o + spin))
        return (o, -90.0, wrap180(spin - o))
    a = math.degrees(math.atan2(-r[2, 2], horizontal))
    o = math.degrees(math.atan2(r[0, 2], -r[1, 2]))
    t = math.degrees(math.atan2(r[2, 1], -r[2, 0]))
    return (wrap180(o), a, wrap180(t))

"""The geometric Jacobian in world coordinates and the measures built on it.

Column i is the end effector's velocity (linear over angular) per unit speed
of joint i: a revolute joint turning about axis z through origin o gives
(z × (p − o), z) per radian; a prismatic one sliding along z gives (z, 0) per
unit length. Standard D-H joint i moves about frame i−1's z; modified D-H
joint i about frame i's own z.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.model import Robot
from dhsim_tui.core.workspace import reach

#: the arm counts as singular when its normalised manipulability drops below this
SINGULAR_THRESHOLD = 1e-3
#: warn from this value on
NEAR_SINGULAR = 0.02


def jacobian_from_frames(robot: Robot, frames: np.ndarray) -> np.ndarray:
    """6×n Jacobian from Kinematics.frames(q) (frames 0..n and the tool)."""
    n = robot.dof
    offset = 0 if robot.convention == "standard" else 1
    axes = frames[offset : offset + n, :3, 2]  # (n, 3) joint axes in world
    origins = frames[offset : offset + n, :3, 3]
    lever = frames[-1, :3, 3] - origins
    revolute = np.array([j.is_revolute for j in robot.joints])
    jac = np.zeros((6, n))
    # axes × lever, written out (np.cross costs more than the rest together)
    ax, ay, az = axes.T
    lx, ly, lz = lever.T
    jac[0] = np.where(revolute, ay * lz - az * ly, ax)
    jac[1] = np.where(revolute, az * lx - ax * lz, ay)
    jac[2] = np.where(revolute, ax * ly - ay * lx, az)
    jac[3:] = np.where(revolute, axes.T, 0.0)
    return jac


def jacobian(robot: Robot, q: Sequence[float]) -> np.ndarray:
    """The world-frame geometric Jacobian at joint values q (deg / robot units)."""
    return jacobian_from_frames(robot, robot.kinematics.frames(q))


def task_rank(robot: Robot) -> int:
    """The rank the arm has in general (largest over a few sample poses)."""
    cached = getattr(robot, "_task_rank", None)
    if cached is None:
        cached = max(np.linalg.matrix_rank(j, tol=1e-6) for j in _sample_jacobians(robot))
        object.__setattr__(robot, "_task_rank", int(cached))
    return cached


def _sample_jacobians(robot: Robot) -> list[np.ndarray]:
    """Normalised Jacobians at a few seeded random poses within the limits,
    for the facts that hold in general (rank, which directions can move)."""
    cached = getattr(robot, "_sample_jacobians", None)
    if cached is None:
        rng = np.random.default_rng(0)
        samples = rng.uniform(robot.lower, robot.upper, size=(8, robot.dof))
        cached = [normalised(robot, jacobian(robot, q)) for q in samples]
        object.__setattr__(robot, "_sample_jacobians", cached)
    return cached


def length_scale(robot: Robot) -> float:
    """The arm's characteristic length (its reach), to make lengths dimensionless."""
    return reach(robot) or 1.0


def normalised(robot: Robot, jac: np.ndarray) -> np.ndarray:
    """Dimensionless Jacobian: linear rows per reach, prismatic columns per reach
    (so a gantry and an arm of any size and unit compare)."""
    scale = length_scale(robot)
    out = jac.copy()
    out[:3] /= scale
    prismatic = [i for i, j in enumerate(robot.joints) if not j.is_revolute]
    out[:, prismatic] *= scale
    return out


def controllable_rows(robot: Robot) -> np.ndarray:
    """Which of (x, y, z, rx, ry, rz) the arm can move at all (a SCARA cannot
    tilt, a planar arm cannot leave its plane): rows of the Jacobian that are
    not zero at every sample pose."""
    cached = getattr(robot, "_controllable_rows", None)
    if cached is None:
        size = np.max([np.abs(j).max(axis=1) for j in _sample_jacobians(robot)], axis=0)
        cached = size > 1e-9
        object.__setattr__(robot, "_controllable_rows", cached)
    return cached


@dataclass(frozen=True)
class Dexterity:
    """How well the arm can move here. Both measures use the normalised
    Jacobian and the rank the arm has (a SCARA or planar arm is not
    'singular' merely for having fewer than six joints)."""

    manipulability: float  # Yoshikawa: product of the top-rank singular values
    condition: float  # sigma_max / sigma_rank (inf when singular)
    rank: int

    @property
    def singular(self) -> bool:
        return self.manipulability < SINGULAR_THRESHOLD

    @property
    def near_singular(self) -> bool:
        return self.manipulability < NEAR_SINGULAR


def dexterity(
    robot: Robot, q: Sequence[float] | None = None, *, jac: np.ndarray | None = None
) -> Dexterity:
    if jac is None:
        jac = jacobian(robot, q if q is not None else robot.home)
    jac = normalised(robot, jac)
    rows = controllable_rows(robot)
    if robot.dof < rows.sum():
        # fewer joints than directions it can move in (a planar arm: x, y and
        # the turn): it positions the tool, so measure how well it positions
        rows = rows.copy()
        rows[3:] = False
        rank = min(robot.dof, int(rows.sum()))
    else:
        rank = task_rank(robot)
    sigma = np.linalg.svd(jac[rows], compute_uv=False)[:rank]
    if len(sigma) < rank:
        sigma = np.concatenate([sigma, np.zeros(rank - len(sigma))])
    manip = float(np.prod(sigma))
    condition = float(sigma[0] / sigma[-1]) if sigma[-1] > 1e-12 else float("inf")
    return Dexterity(manip, condition, rank)

"""Inverse kinematics by damped least squares (Levenberg-Marquardt).

Works on the dimensionless Jacobian (lengths per reach) so one tolerance and
one damping suit any arm and unit. Joint limits are respected by clamping
every step. Arms with fewer than six joints solve for the directions they can
move (a SCARA: x, y, z and the turn about z). Restarts from random joint
vectors (seeded: the same call gives the same answer) when the first start
fails; the result says plainly whether it reached the target.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.jacobian import controllable_rows, jacobian_from_frames, length_scale
from dhsim_tui.core.model import Robot

#: position tolerance as a fraction of the reach, and orientation tolerance (rad)
POSITION_TOL = 5e-7
ORIENTATION_TOL = 5e-7
_DEG = math.pi / 180.0
#: the damping that remains at zero error (keeps steps finite at singularities)
DAMPING_BIAS = 1e-6
#: an attempt this close (fraction of the reach) is polished rather than dropped:
#: near a singularity the last digits converge slowly
POLISH_BELOW = 1e-3


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


@dataclass(frozen=True)
class IKResult:
    """``success`` says whether the target was reached; ``q`` is the solution
    (or the closest configuration found), ``position_error`` is in the robot's
    unit and ``orientation_error`` in radians."""

    success: bool
    q: tuple[float, ...]
    position_error: float
    orientation_error: float
    iterations: int
    reason: str = ""
    #: the larger of position error / reach and orientation error (rad): dimensionless
    residual: float = 0.0


class _Problem:
    """One target for one robot: errors and steps in internal units (radians for
    revolute joints, reach fractions for prismatic ones)."""

    def __init__(self, robot: Robot, target: np.ndarray, position_only: bool) -> None:
        self.robot = robot
        self.kin = robot.kinematics
        self.scale = length_scale(robot)
        self.revolute = np.array([j.is_revolute for j in robot.joints])
        self.to_internal = np.where(self.revolute, _DEG, 1.0 / self.scale)
        self.low = np.array(robot.lower) * self.to_internal
        self.high = np.array(robot.upper) * self.to_internal
        rows = controllable_rows(robot).copy()
        if position_only:
            rows[3:] = False
        self.rows = rows
        self.target = target
        self.position_only = position_only

    def limit(self, x: np.ndarray) -> np.ndarray:
        """Into the joint limits: a revolute joint past one limit takes the same
        angle a turn away when that fits (wide-range joints), else it stops."""
        turn = 2 * math.pi
        over = self.revolute & (x > self.high) & (x - turn >= self.low)
        under = self.revolute & (x < self.low) & (x + turn <= self.high)
        x = np.where(over, x - turn, np.where(under, x + turn, x))
        return np.clip(x, self.low, self.high)

    def user(self, x: np.ndarray) -> tuple[float, ...]:
        return tuple((x / self.to_internal).tolist())

    def evaluate(self, x: np.ndarray):
        frames = self.kin.frames(self.user(x))
        pose = frames[-1]
        error = np.empty(6)
        error[:3] = (self.target[:3, 3] - pose[:3, 3]) / self.scale
        error[3:] = 0.0 if self.position_only else rotation_error(self.target[:3, :3], pose[:3, :3])
        return frames, error

    def jacobian(self, frames: np.ndarray) -> np.ndarray:
        jac = jacobian_from_frames(self.robot, frames)
        jac[:3] /= self.scale
        jac[:, ~self.revolute] *= self.scale
        return jac[self.rows]

    def converged(self, error: np.ndarray) -> bool:
        return (
            np.linalg.norm(error[:3][self.rows[:3]]) <= POSITION_TOL
            and np.linalg.norm(error[3:][self.rows[3:]]) <= ORIENTATION_TOL
        )


def _descend(problem: _Problem, x: np.ndarray, max_iter: int, bias: float = DAMPING_BIAS):
    """Sugihara's Levenberg-Marquardt: damping = squared error + a small bias,
    one forward kinematics per iteration, clamped to the joint limits."""
    frames, error = problem.evaluate(x)
    eye = np.eye(len(x))
    for iterations in range(max_iter):
        if problem.converged(error):
            return x, error, iterations, True
        jac = problem.jacobian(frames)
        e = error[problem.rows]
        damping = 0.5 * float(e @ e) + bias
        step = np.linalg.solve(jac.T @ jac + damping * eye, jac.T @ e)
        x = problem.limit(x + step)
        frames, error = problem.evaluate(x)
    return x, error, max_iter, problem.converged(error)


def solve(
    robot: Robot,
    target: np.ndarray,
    start: Sequence[float] | None = None,
    *,
    position_only: bool = False,
    max_iter: int = 100,
    restarts: int = 0,
    seed: int = 0,
) -> IKResult:
    """Joint values that put the end effector at ``target`` (a 4×4 world pose;
    only its position counts when ``position_only``)."""
    problem = _Problem(robot, np.asarray(target, dtype=float), position_only)
    first = np.array(start if start is not None else robot.home, dtype=float)
    x0 = np.clip(first * problem.to_internal, problem.low, problem.high)
    rng = np.random.default_rng(seed)
    best = None
    total = 0
    for attempt in range(restarts + 1):
        if attempt:
            x0 = rng.uniform(problem.low, problem.high)
        x, error, iterations, ok = _descend(problem, x0, max_iter)
        total += iterations
        e = error.copy()
        e[~problem.rows] = 0.0
        score = float(np.linalg.norm(e))
        if best is None or score < best[0]:
            best = (score, x, error, ok)
        if ok:
            break
    score, x, error, ok = best
    if not ok and score < POLISH_BELOW:
        x, error, iterations, ok = _descend(problem, x, 4 * max_iter, bias=1e-12)
        total += iterations
    # judged on every requested direction, including those the arm cannot move:
    # a planar arm asked for a point off its plane has not reached it
    position_error = float(np.linalg.norm(error[:3]) * problem.scale)
    orientation_error = 0.0 if position_only else float(np.linalg.norm(error[3:]))
    ok = (
        position_error <= POSITION_TOL * problem.scale * 2
        and orientation_error <= ORIENTATION_TOL * 2
    )
    reason = "" if ok else _why(robot, problem, x, position_error, orientation_error)
    residual = max(position_error / problem.scale, orientation_error)
    return IKResult(ok, problem.user(x), position_error, orientation_error, total, reason, residual)


def _why(
    robot: Robot, problem: _Problem, x: np.ndarray, position_error: float, orientation_error: float
) -> str:
    at_limit = [
        robot.labels[i]
        for i in range(robot.dof)
        if np.isclose(x[i], problem.low[i]) or np.isclose(x[i], problem.high[i])
    ]
    turn = math.degrees(orientation_error)
    distance = f"closest {position_error:.4g} {robot.units}, {turn:.3g} deg away"
    if at_limit:
        limits = ", ".join(at_limit)
        return f"not reachable within the joint limits ({limits} at a limit; {distance})"
    return f"out of reach ({distance})"

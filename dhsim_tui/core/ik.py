"""Inverse kinematics by damped least squares (Levenberg-Marquardt).

Works on the dimensionless Jacobian (lengths per reach) so one tolerance and
one damping suit any arm and unit. Joint limits are respected by clamping
every step. Arms with fewer than six joints solve for the directions they can
move (a SCARA: x, y, z and the turn about z). Restarts from random joint
vectors (seeded: the same call gives the same answer) when the first start
fails; the result says plainly whether it reached the target, and if not,
which part failed (position or orientation) and why (see ik_reasons).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core import ik_reasons
from dhsim_tui.core.jacobian import controllable_rows, jacobian_from_frames, length_scale, task_rank
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
#: a failed pose is retried with the position rows weighted by these in turn, so
#: the position is held and the orientation comes as close as it can
POSITION_FIRST = (1e2, 1e4)
#: random starts that tell "singular here" (reachable from elsewhere) from "out of reach"
PROBES = 6

#: which part of a target was missed
POSITION = "position"
ORIENTATION = "orientation"


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
    #: on failure, the part missed: POSITION (even when the orientation gives
    #: way) or ORIENTATION (the position is reached, in ``q``)
    failed: str = ""
    #: on failure, why: one of ik_reasons.CAUSES
    cause: str = ""
    #: the joints whose limits stopped it: (index, True when on the upper limit)
    limited: tuple[tuple[int, bool], ...] = ()


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
        #: row weights of the least-squares problem (all 1 but for POSITION_FIRST)
        self.weight = np.ones(6)
        self.rank = min(robot.dof, int(rows.sum()), task_rank(robot))

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

    def full_jacobian(self, frames: np.ndarray) -> np.ndarray:
        """All six rows, dimensionless (linear rows per reach, prismatic columns per reach)."""
        jac = jacobian_from_frames(self.robot, frames)
        jac[:3] /= self.scale
        jac[:, ~self.revolute] *= self.scale
        return jac

    def system(self, frames: np.ndarray, error: np.ndarray):
        """The weighted rows solved for: (Jacobian, error)."""
        w = self.weight[self.rows]
        return self.full_jacobian(frames)[self.rows] * w[:, None], error[self.rows] * w

    def converged(self, error: np.ndarray) -> bool:
        return (
            np.linalg.norm(error[:3][self.rows[:3]]) <= POSITION_TOL
            and np.linalg.norm(error[3:][self.rows[3:]]) <= ORIENTATION_TOL
        )

    def errors(self, error: np.ndarray) -> tuple[float, float]:
        """Position error (robot units) and orientation error (rad), judged on
        every requested direction, including those the arm cannot move: a
        planar arm asked for a point off its plane has not reached it."""
        position = float(np.linalg.norm(error[:3]) * self.scale)
        return position, 0.0 if self.position_only else float(np.linalg.norm(error[3:]))

    def position_reached(self, position_error: float) -> bool:
        return position_error <= POSITION_TOL * self.scale * 2

    def view(self, position_only: bool) -> _Problem:
        """The same target judged on its position only, or on the whole pose."""
        return _Problem(self.robot, self.target, position_only)


def _descend(problem: _Problem, x: np.ndarray, max_iter: int, bias: float = DAMPING_BIAS):
    """Sugihara's Levenberg-Marquardt: damping = squared error + a small bias,
    one forward kinematics per iteration, clamped to the joint limits."""
    frames, error = problem.evaluate(x)
    eye = np.eye(len(x))
    for iterations in range(max_iter):
        if problem.converged(error):
            return x, error, iterations, True
        jac, e = problem.system(frames, error)
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
    with np.errstate(all="ignore"):  # degenerate arms: guarded below, never printed
        return _solve(robot, target, start, position_only, max_iter, restarts, seed)


def _solve(robot, target, start, position_only, max_iter, restarts, seed) -> IKResult:
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
        if not math.isfinite(score):
            continue
        if best is None or score < best[0]:
            best = (score, x, error, ok)
        if ok:
            break
    if best is None:  # nothing finite: an arm too degenerate to compute with
        return IKResult(
            False,
            tuple(first.tolist()),
            math.inf,
            math.inf,
            total,
            "this arm is too small to compute with",
            math.inf,
            POSITION,
            ik_reasons.STOPPED,
        )
    score, x, error, ok = best
    if not ok and score < POLISH_BELOW:
        x, error, iterations, ok = _descend(problem, x, 4 * max_iter, bias=1e-12)
        total += iterations
    position_error, orientation_error = problem.errors(error)
    if problem.position_reached(position_error) and orientation_error <= ORIENTATION_TOL * 2:
        residual = max(position_error / problem.scale, orientation_error)
        return IKResult(
            True, problem.user(x), position_error, orientation_error, total, "", residual
        )
    return _failure(problem, x, error, total, max_iter, probe=restarts == 0, seed=seed)


def _failure(problem: _Problem, x, error, total: int, max_iter: int, probe: bool, seed: int):
    """The closest configuration found, which part failed and why."""
    position_error, _ = problem.errors(error)
    if not problem.position_reached(position_error) and problem.rows[3:].any():
        # the whole pose failed: is the position reachable when the orientation gives way?
        first = problem.view(False)
        x_first, error_first = x, error
        for weight in POSITION_FIRST:
            first.weight[:3] = weight
            x_first, error_first, iterations, _ = _descend(first, x_first, max_iter)
            total += iterations
        x, error, problem = x_first, error_first, first  # the closest position
    position_error, orientation_error = problem.errors(error)
    failed = ORIENTATION if problem.position_reached(position_error) else POSITION
    judge = problem.view(True) if failed == POSITION and not problem.position_only else problem
    frames, judged = judge.evaluate(x)
    diagnosis = ik_reasons.diagnose(
        judge.full_jacobian(frames),
        judged,
        judge.rows,
        x,
        judge.low,
        judge.high,
        judge.rank,
        judge.weight,
    )
    cause = diagnosis.cause
    if cause == ik_reasons.LOST:
        # lost here: singular if the target can be reached from elsewhere (a
        # solve with restarts has already looked there), else out of reach
        reachable = probe and _reachable(judge, x, max_iter, seed)
        cause = ik_reasons.SINGULAR if reachable else ik_reasons.OUT_OF_REACH
    robot = problem.robot
    reason = ik_reasons.explain(
        robot, failed, cause, diagnosis.limited, position_error, orientation_error
    )
    residual = max(position_error / problem.scale, orientation_error)
    return IKResult(
        False,
        problem.user(x),
        position_error,
        orientation_error,
        total,
        reason,
        residual,
        failed,
        cause,
        diagnosis.limited,
    )


def _reachable(problem: _Problem, x: np.ndarray, max_iter: int, seed: int) -> bool:
    """Whether the target can be reached from elsewhere: from a small nudge off
    ``x`` or from a few seeded random starts."""
    problem = problem.view(problem.position_only)  # unweighted
    rng = np.random.default_rng(seed + 1)
    span = problem.high - problem.low
    starts = [problem.limit(x + rng.normal(0.0, 0.05, len(x)) * np.minimum(span, 1.0))]
    starts += [rng.uniform(problem.low, problem.high) for _ in range(PROBES)]
    return any(_descend(problem, start, max_iter)[3] for start in starts)

"""Inverse kinematics by damped least squares (Levenberg-Marquardt).

Works on the dimensionless Jacobian (lengths per reach) so one tolerance and
one damping suit any arm and unit. Joint limits are respected by clamping
every step. Arms with fewer than six joints solve for the directions they can
move (a SCARA: x, y, z and the turn about z). With restarts, when the first
start fails, the solver tries the configurations of a seeded table whose
poses lie nearest the target, then random joint vectors (seeded: the same
call gives the same answer); the result says plainly whether it reached the
target, and if not, which part failed (position or orientation) and why (see
ik_reasons).

Speed: a whole descent is one function compiled for the robot
(:mod:`dhsim_tui.core.ik.step_codegen`): pose, error, normalised Jacobian,
a written-out Cholesky solve of the smaller normal matrix and the clamped
step, in plain Python float locals (numpy's per-call overhead would be most
of the cost at this size), about 9 µs an iteration for a Panda. With
restarts, each start gives up early when it is not getting close (a
checkpoint) or stalls, the table's starts (numerical_starts) usually need
a few iterations, and most random starts ignore the limits until they have
found a solution (:func:`~dhsim_tui.core.ik.numerical_descent.solve_free_start`):
no reachable pose is called unreachable for want of looking
(tests/cli/test_ik_success.py). bench/ik_speed.py measures it.

The target's errors and Jacobian in internal units are
:mod:`dhsim_tui.core.ik.numerical_problem`'s, the descents
:mod:`dhsim_tui.core.ik.numerical_descent`'s.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.ik import reasons as ik_reasons
from dhsim_tui.core.ik.numerical_descent import POLISH_BELOW, levenberg_marquardt, solve_free_start
from dhsim_tui.core.ik.numerical_problem import ORIENTATION_TOL, IkProblem
from dhsim_tui.core.ik.numerical_starts import nearest_starts
from dhsim_tui.core.ik.rotation import rotation_error as rotation_error  # its old home
from dhsim_tui.core.model.kinematics import robot_base
from dhsim_tui.core.model.robot import Robot

#: a failed pose is retried with the position rows weighted by these in turn, so
#: the position is held and the orientation comes as close as it can
POSITION_FIRST = (1e2, 1e4)
#: random starts per restart: a start that stalls gives up within a few
#: iterations (STALL_WINDOW), so several cost less than one full descent did;
#: an arm whose only solution within the limits has a small basin (a Puma's
#: wrist near its limit: 1 start in 16; a Panda with two joints near their
#: limits: 1 in 50) then still finds it
STARTS_PER_RESTART = 6
#: of the random starts, all but every FREE_EVERY-th are free (solve_free_start):
#: on the Puma a free start succeeds more often (63% against 47% on average,
#: 15% against 10% on the hardest targets) in fewer iterations; the clamped
#: ones keep the search honest on arms where a free descent wanders off
FREE_EVERY = 4
#: with restarts, each start's descent has a budget and a checkpoint: there
#: it gives up unless its error (reach fractions, radians) is below a limit.
#: A descent that succeeds is close by then (from home, a Panda or a Puma
#: takes 8 iterations for the median target, from the table's nearest 5),
#: one that fails wanders on for long; cut off early, the next start comes
#: sooner. Tuned on two sets of random targets per arm (bench/ik_speed.py's
#: and another): for a Panda from home, the 95th percentile fell from 45
#: iterations to about 27, the median stayed 9
FIRST_ITER = 12
FIRST_CHECK = (8, 0.04**2)
#: then the table's starts nearest the target (numerical_starts), from
#: TABLE_FROM restarts on (fewer, as the every-solution search asks, keep to
#: random starts for their variety)
TABLE_STARTS = 16
TABLE_ITER = 12
TABLE_CHECK = (5, 0.02**2)
TABLE_FROM = 2
#: random starts that tell "singular here" (reachable from elsewhere) from "out of reach"
PROBES = 6

#: which part of a target was missed
POSITION = "position"
ORIENTATION = "orientation"


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
    only its position counts when ``position_only``).

    The first descent starts at ``start`` (home when None) and, without
    restarts, runs its ``max_iter`` iterations: the answer is the solution
    next to the start (a jog never jumps to another branch). With restarts,
    the first descent gets FIRST_ITER iterations (giving up at its
    checkpoint if far off), then the TABLE_STARTS table configurations
    nearest the target TABLE_ITER each, then each restart is a round of
    STARTS_PER_RESTART seeded random starts; every one gives up when it
    stalls, and if none succeeds the closest is finished."""
    return _solve(robot, target, start, position_only, max_iter, restarts, seed)


def _starts(problem: IkProblem, x0: list[float], max_iter: int, restarts: int, seed: int):
    """A solve's starts with restarts, in order, each as (x, free, iterations
    allowed, checkpoint, squared error allowed there): ``x0``, the table's
    nearest the target, then the seeded random ones."""
    yield (x0, False, min(max_iter, FIRST_ITER), *FIRST_CHECK)
    if restarts >= TABLE_FROM:
        for x in nearest_starts(problem, TABLE_STARTS):
            yield (x, False, min(max_iter, TABLE_ITER), *TABLE_CHECK)
    rng = np.random.default_rng(seed)
    for attempt in range(1, restarts * STARTS_PER_RESTART + 1):
        with np.errstate(all="ignore"):  # limits too wide to compute with: not finite
            x = rng.uniform(problem.low, problem.high).tolist()
        yield x, attempt % FREE_EVERY != 0, max_iter, -1, 0.0  # most free of the limits


def _solve(robot, target, start, position_only, max_iter, restarts, seed) -> IKResult:
    problem = IkProblem(robot, np.asarray(target, dtype=float), position_only)
    setup = problem.setup
    first = [float(v) for v in (start if start is not None else robot.home)]
    bounds = zip(first, setup.to_internal_list, setup.low_list, setup.high_list, strict=True)
    x0 = [min(max(v * k, lo), hi) for v, k, lo, hi in bounds]
    best = None
    total = 0
    give_up = restarts > 0
    if give_up:
        starts = _starts(problem, x0, max_iter, restarts, seed)
    else:
        starts = ((x0, False, max_iter, -1, 0.0),)
    for x_start, free, budget, checkpoint, limit in starts:
        if free:
            found, iterations = solve_free_start(problem, x_start, budget)
            total += iterations
            if found is None:
                continue
            x, error, iterations, ok = found
        else:
            x, error, iterations, ok = levenberg_marquardt(
                problem, x_start, budget, give_up=give_up, checkpoint=checkpoint, limit=limit
            )
            total += iterations
        score = problem.score(error)
        if not math.isfinite(score):
            continue
        if best is None or score < best[0]:
            best = (score, x, error, ok)
        if ok:
            break
    if best is None:  # nothing finite: an arm too degenerate to compute with
        return IKResult(
            False,
            tuple(first),
            math.inf,
            math.inf,
            total,
            "this arm is too small to compute with",
            math.inf,
            POSITION,
            ik_reasons.STOPPED,
        )
    score, x, error, ok = best
    if not ok and restarts > 0:
        # the starts gave up when they stalled: finish the closest one, so a
        # failure is judged where the descent really stops
        x, error, iterations, ok = levenberg_marquardt(problem, x, max_iter)
        total += iterations
        score = problem.score(error)
    if not ok and score < POLISH_BELOW:
        x, error, iterations, ok = levenberg_marquardt(problem, x, 4 * max_iter, bias=1e-12)
        total += iterations
    position_error, orientation_error = problem.errors(error)
    if problem.position_reached(position_error) and orientation_error <= ORIENTATION_TOL * 2:
        residual = max(position_error / problem.scale, orientation_error)
        return IKResult(
            True, problem.user(x), position_error, orientation_error, total, "", residual
        )
    with np.errstate(all="ignore"):  # degenerate arms: guarded, never printed
        return _failure(problem, x, error, total, max_iter, probe=restarts == 0, seed=seed)


def _failure(problem: IkProblem, x, error, total: int, max_iter: int, probe: bool, seed: int):
    """The closest configuration found, which part failed and why."""
    position_error, _ = problem.errors(error)
    x = np.array(x, dtype=float)
    if not problem.position_reached(position_error) and problem.rows[3:].any():
        # the whole pose failed: is the position reachable when the orientation gives way?
        first = problem.view(False)
        x_first, error_first = x.tolist(), error
        for weight in POSITION_FIRST:
            first.weight = np.array([weight, weight, weight, 1.0, 1.0, 1.0])
            x_first, error_first, iterations, _ = levenberg_marquardt(first, x_first, max_iter)
            total += iterations
        x, error, problem = np.array(x_first), error_first, first  # the closest position
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
    cause, limited = diagnosis.cause, diagnosis.limited
    if failed == POSITION and cause != ik_reasons.NO_JOINT and _beyond_reach(problem):
        # no configuration at all comes this far: not a limit's doing
        cause, limited = ik_reasons.OUT_OF_REACH, ()
    elif cause == ik_reasons.LOST:
        # lost here: singular if the target can be reached from elsewhere (a
        # solve with restarts has already looked there), else out of reach
        reachable = probe and _reachable(judge, x, max_iter, seed)
        cause = ik_reasons.SINGULAR if reachable else ik_reasons.OUT_OF_REACH
    robot = problem.robot
    reason = ik_reasons.explain(robot, failed, cause, limited, position_error, orientation_error)
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
        limited,
    )


def _beyond_reach(problem: IkProblem) -> bool:
    """Whether the target lies farther from frame 0's origin than any
    configuration can put the tool: each link moves it by at most |a| + |d|
    (a prismatic joint's d at its largest, offset included), the tool by its
    length."""
    robot = problem.robot
    bound = robot.tool.length
    for joint in robot.joints:
        if joint.is_revolute:
            bound += abs(joint.a) + abs(joint.d)
        else:
            bound += abs(joint.a) + max(
                abs(joint.min + joint.offset), abs(joint.max + joint.offset)
            )
    origin = robot_base(robot)[:3, 3]
    distance = float(np.linalg.norm(problem.target[:3, 3] - origin))
    return distance > bound * (1.0 + 1e-9) + 1e-12


def _reachable(problem: IkProblem, x: np.ndarray, max_iter: int, seed: int) -> bool:
    """Whether the target can be reached from elsewhere: from a small nudge off
    ``x`` or from a few seeded random starts."""
    problem = problem.view(problem.position_only)  # unweighted
    rng = np.random.default_rng(seed + 1)
    span = problem.high - problem.low
    starts = [problem.limit(x + rng.normal(0.0, 0.05, len(x)) * np.minimum(span, 1.0))]
    starts += [rng.uniform(problem.low, problem.high) for _ in range(PROBES)]
    return any(levenberg_marquardt(problem, start.tolist(), max_iter)[3] for start in starts)

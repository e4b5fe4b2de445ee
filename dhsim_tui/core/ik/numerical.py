"""Inverse kinematics by damped least squares (Levenberg-Marquardt).

Works on the dimensionless Jacobian (lengths per reach) so one tolerance and
one damping suit any arm and unit. Joint limits are respected by clamping
every step. Arms with fewer than six joints solve for the directions they can
move (a SCARA: x, y, z and the turn about z). Restarts from random joint
vectors (seeded: the same call gives the same answer) when the first start
fails; the result says plainly whether it reached the target, and if not,
which part failed (position or orientation) and why (see ik_reasons).

Speed: an iteration is one call of the robot's compiled kernel (the pose and
the normalised Jacobian in one pass, jacobian.kernel) and one written-out
Cholesky solve (jacobian.damped_solver), in plain Python floats; numpy's
per-call overhead would be most of the cost at this size. A random start that
stalls gives up after a few iterations, and most random starts ignore the
limits until they have found a solution (:func:`_free_start`), so a solve
with restarts tries many starts cheaply: no reachable pose is called
unreachable for want of looking (tests/test_ik_success.py).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.analysis.jacobian import (
    controllable_rows,
    damped_solver,
    jacobian_from_frames,
    kernel,
    length_scale,
    task_rank,
)
from dhsim_tui.core.ik import reasons as ik_reasons
from dhsim_tui.core.model.kinematics import robot_base
from dhsim_tui.core.model.robot import Robot

#: position tolerance as a fraction of the reach, and orientation tolerance (rad)
POSITION_TOL = 5e-7
ORIENTATION_TOL = 5e-7
_DEG = math.pi / 180.0
#: the damping's bias (keeps steps finite at singularities); it fades with the
#: squared error below it, so that the last digits converge at once even near
#: a singularity (a fixed 1e-6 left descents crawling at an error of 1e-5)
DAMPING_BIAS = 1e-6
#: an attempt this close (fraction of the reach) is polished rather than dropped:
#: near a singularity the last digits converge slowly
POLISH_BELOW = 1e-3
#: a failed pose is retried with the position rows weighted by these in turn, so
#: the position is held and the orientation comes as close as it can
POSITION_FIRST = (1e2, 1e4)
#: random starts per restart: a start that stalls gives up within a few
#: iterations (STALL_WINDOW), so several cost less than one full descent did;
#: an arm whose only solution within the limits has a small basin (a Puma's
#: wrist near its limit: 1 start in 16; a Panda with two joints near their
#: limits: 1 in 50) then still finds it
STARTS_PER_RESTART = 6
#: of the random starts, all but every FREE_EVERY-th are free (_free_start):
#: on the Puma a free start succeeds more often (63% against 47% on average,
#: 15% against 10% on the hardest targets) in fewer iterations; the clamped
#: ones keep the search honest on arms where a free descent wanders off
FREE_EVERY = 4
#: a solution this far past a limit (radians, reach fractions) is on it
LIMIT_SLACK = 1e-9
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


class _Setup:
    """What a solve needs of a robot that no target changes, kept on the robot
    (numpy arrays for the diagnosis, plain lists for the fast loop)."""

    def __init__(self, robot: Robot) -> None:
        self.scale = length_scale(robot)
        self.revolute = np.array([j.is_revolute for j in robot.joints])
        self.to_internal = np.where(self.revolute, _DEG, 1.0 / self.scale)
        self.low = np.array(robot.lower) * self.to_internal
        self.high = np.array(robot.upper) * self.to_internal
        full = controllable_rows(robot).copy()
        position = full.copy()
        position[3:] = False
        self.rows = {False: full, True: position}
        rank = task_rank(robot)
        self.rank = {k: min(robot.dof, int(v.sum()), rank) for k, v in self.rows.items()}
        self.kernel = kernel(robot)
        self.to_user = (1.0 / self.to_internal).tolist()
        self.low_list = self.low.tolist()
        self.high_list = self.high.tolist()
        self.revolute_list = self.revolute.tolist()
        self.dof = robot.dof
        for shared in (self.revolute, self.to_internal, self.low, self.high, full, position):
            shared.flags.writeable = False  # every problem of this robot reads them


def _setup(robot: Robot) -> _Setup:
    cached = robot.__dict__.get("_ik_setup")
    if cached is None:
        cached = _Setup(robot)
        object.__setattr__(robot, "_ik_setup", cached)
    return cached


class _Problem:
    """One target for one robot: errors and steps in internal units (radians for
    revolute joints, reach fractions for prismatic ones)."""

    def __init__(self, robot: Robot, target: np.ndarray, position_only: bool) -> None:
        setup = _setup(robot)
        self.robot = robot
        self.setup = setup
        self.kin = robot.kinematics
        self.scale = setup.scale
        self.revolute = setup.revolute
        self.to_internal = setup.to_internal
        self.low = setup.low
        self.high = setup.high
        self.rows = setup.rows[position_only]
        self.target = target
        self.position_only = position_only
        #: row weights of the least-squares problem (all 1 but for POSITION_FIRST)
        self.weight = np.ones(6)
        self.rank = setup.rank[position_only]
        # the target as plain floats for the fast loop: position per reach, rotation rows
        self.goal = target[:3, 3].tolist()
        self.goal_rotation = target[:3, :3].ravel().tolist()

    def limit(self, x: np.ndarray) -> np.ndarray:
        """Into the joint limits: a revolute joint past one limit takes the same
        angle a turn away when that fits (wide-range joints), else it stops."""
        turn = 2 * math.pi
        over = self.revolute & (x > self.high) & (x - turn >= self.low)
        under = self.revolute & (x < self.low) & (x + turn <= self.high)
        x = np.where(over, x - turn, np.where(under, x + turn, x))
        return np.clip(x, self.low, self.high)

    def user(self, x: np.ndarray) -> tuple[float, ...]:
        """Joint values in the robot's units, within its limits (the way back
        from radians or reach fractions may round a limit a digit past it)."""
        values = (x / self.to_internal).tolist()
        bounds = zip(values, self.robot.lower, self.robot.upper, strict=True)
        return tuple(min(max(v, lo), hi) for v, lo, hi in bounds)

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

    def score(self, error: np.ndarray) -> float:
        """The size of the error in the rows solved for (unweighted)."""
        return math.sqrt(sum(v * v for v, r in zip(error.tolist(), self.rows, strict=True) if r))

    def converged(self, error: np.ndarray) -> bool:
        return (
            np.linalg.norm(error[:3][self.rows[:3]]) <= POSITION_TOL
            and np.linalg.norm(error[3:][self.rows[3:]]) <= ORIENTATION_TOL
        )

    def errors(self, error: np.ndarray) -> tuple[float, float]:
        """Position error (robot units) and orientation error (rad), judged on
        every requested direction, including those the arm cannot move: a
        planar arm asked for a point off its plane has not reached it."""
        e = error.tolist()
        position = math.hypot(*e[:3]) * self.scale
        return position, 0.0 if self.position_only else math.hypot(*e[3:])

    def position_reached(self, position_error: float) -> bool:
        return position_error <= POSITION_TOL * self.scale * 2

    def view(self, position_only: bool) -> _Problem:
        """The same target judged on its position only, or on the whole pose."""
        return _Problem(self.robot, self.target, position_only)


def _rotation_error(goal: list[float], s: tuple[float, ...]) -> tuple[float, float, float]:
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


#: a restart gives up when a window of this many iterations lowers the error
#: by less than STALL_GAIN (it sits in a local minimum, often on a limit)
STALL_WINDOW = 8
STALL_GAIN = 0.5


def _descend(
    problem: _Problem,
    x: np.ndarray,
    max_iter: int,
    bias: float = DAMPING_BIAS,
    give_up: bool = False,
    free: bool = False,
):
    """Sugihara's Levenberg-Marquardt: damping = half the squared error + a
    small bias (no larger than the squared error), one forward kinematics per
    iteration, clamped to the joint limits.

    Plain Python floats throughout: the compiled kernel gives the pose and the
    normalised Jacobian in one pass, the damped step is a written-out Cholesky
    solve of the smaller normal matrix (jacobian.damped_solver). ``give_up``
    stops early when the error stalls (see STALL_WINDOW); ``free`` ignores the
    joint limits (see :func:`_free_start`)."""
    setup = problem.setup
    run, to_user = setup.kernel, setup.to_user
    low, high, revolute = setup.low_list, setup.high_list, setup.revolute_list
    n = setup.dof
    goal, goal_rotation = problem.goal, problem.goal_rotation
    position_only, scale = problem.position_only, problem.scale
    picked = [r for r in range(6) if problem.rows[r]]
    weights = [float(problem.weight[r]) for r in picked]
    plain = len(picked) == 6 and all(w == 1.0 for w in weights)
    solver = damped_solver(len(picked), n)
    pos_rows = [r for r in picked if r < 3]
    rot_rows = [r for r in picked if r >= 3]
    pos_tol2 = POSITION_TOL * POSITION_TOL
    rot_tol2 = ORIENTATION_TOL * ORIENTATION_TOL
    turn = 2 * math.pi
    x = [float(v) for v in x]

    def evaluate(x):
        state, jac = run([a * b for a, b in zip(x, to_user, strict=True)])
        error = [(goal[0] - state[9]) / scale, (goal[1] - state[10]) / scale]
        error.append((goal[2] - state[11]) / scale)
        error += (0.0, 0.0, 0.0) if position_only else _rotation_error(goal_rotation, state)
        return jac, error

    def measure(error):
        """(converged, squared weighted error of the rows solved for)."""
        if plain:
            e0, e1, e2, e3, e4, e5 = error
            position = e0 * e0 + e1 * e1 + e2 * e2
            turn = e3 * e3 + e4 * e4 + e5 * e5
            return position <= pos_tol2 and turn <= rot_tol2, position + turn
        position = sum(error[r] * error[r] for r in pos_rows)
        turn = sum(error[r] * error[r] for r in rot_rows)
        weighted = sum((error[r] * w) ** 2 for r, w in zip(picked, weights, strict=True))
        return position <= pos_tol2 and turn <= rot_tol2, weighted

    def done(x, error, iterations, ok):
        return np.array(x), np.array(error), iterations, ok

    jac, error = evaluate(x)
    window = math.inf
    for iterations in range(max_iter):
        ok, squared = measure(error)
        if ok:
            return done(x, error, iterations, True)
        if plain:
            e = error
        else:
            e = [error[r] * w for r, w in zip(picked, weights, strict=True)]
            jac = [
                v * w for r, w in zip(picked, weights, strict=True) for v in jac[r * n : r * n + n]
            ]
        if give_up and iterations % STALL_WINDOW == 0:
            if squared > STALL_GAIN * window and squared > POLISH_BELOW * POLISH_BELOW:
                break  # stalled: a restart elsewhere does better
            window = squared
        try:
            step = solver(jac, e, 0.5 * squared + min(bias, squared))
        except (ValueError, ZeroDivisionError, OverflowError):
            break  # not finite any more: a degenerate arm
        if free:
            x = [v + dv for v, dv in zip(x, step, strict=True)]
            if not all(math.isfinite(v) for v in x):
                return done(x, [math.inf] * 6, iterations, False)
            jac, error = evaluate(x)
            continue
        moved = []
        for v, dv, lo, hi, rev in zip(x, step, low, high, revolute, strict=True):
            v += dv
            if v > hi:
                v = v - turn if rev and v - turn >= lo else hi
                v = hi if v > hi else v
            elif v < lo:
                v = v + turn if rev and v + turn <= hi else lo
                v = lo if v < lo else v
            if v != v:  # nan: the error is not finite
                return done(x, [math.inf] * 6, iterations, False)
            moved.append(v)
        x = moved
        jac, error = evaluate(x)
    else:
        return done(x, error, max_iter, measure(error)[0])
    return done(x, error, iterations, False)


def _into_limits(problem: _Problem, x: np.ndarray, clamp: bool = False) -> np.ndarray | None:
    """``x`` with each revolute joint turned by whole turns into its limits,
    or None when some joint does not fit (``clamp``: then onto the limit)."""
    out = []
    turn = 2 * math.pi
    for v, lo, hi, rev in zip(
        x.tolist(),
        problem.setup.low_list,
        problem.setup.high_list,
        problem.setup.revolute_list,
        strict=True,
    ):
        if rev and not lo <= v <= hi:
            v = lo + (v - lo) % turn
        if v > hi:
            if v - hi > LIMIT_SLACK and not clamp:
                return None
            v = hi
        elif v < lo:
            if lo - v > LIMIT_SLACK and not clamp:
                return None
            v = lo
        out.append(v)
    return np.array(out)


def _free_start(problem: _Problem, x0: np.ndarray, max_iter: int):
    """One random start solved with the limits ignored, then its solution
    turned into the limits and finished with them.

    A descent clamped to the limits from a random start often ends against a
    limit, on a branch of the arm (shoulder, elbow, wrist) whose solution lies
    past it. Ignored, the limits trap nothing: the descent reaches one of the
    arm's solutions, at random, and that is the answer if whole turns bring it
    within the limits. Where the only solution within the limits lies close to
    one of them (a Puma reaching over with its shoulder near 225°, or its wrist
    near ±100°), a free start finds it up to three times as often as a clamped
    one. Returns _descend's tuple, or None when the solution found does not fit."""
    x, error, iterations, ok = _descend(problem, x0, max_iter, give_up=True, free=True)
    if not ok:
        return None, iterations
    inside = _into_limits(problem, x)
    if inside is None:
        if problem.robot.dof <= problem.rows.sum():
            return None, iterations
        # a redundant arm (a Panda): its solutions form a family, and the one
        # found may slide within the limits; clamped, the descent may find it
        inside = _into_limits(problem, x, clamp=True)
        x, error, more, ok = _descend(problem, inside, max_iter, give_up=True)
    else:
        x, error, more, ok = _descend(problem, inside, max_iter)
    return (x, error, iterations + more, ok), iterations + more


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
    next to the start (a jog never jumps to another branch). Each restart is
    a round of STARTS_PER_RESTART seeded random starts, each of which gives
    up when it stalls."""
    with np.errstate(all="ignore"):  # degenerate arms: guarded below, never printed
        return _solve(robot, target, start, position_only, max_iter, restarts, seed)


def _solve(robot, target, start, position_only, max_iter, restarts, seed) -> IKResult:
    problem = _Problem(robot, np.asarray(target, dtype=float), position_only)
    first = np.array(start if start is not None else robot.home, dtype=float)
    x0 = np.clip(first * problem.to_internal, problem.low, problem.high)
    rng = None
    best = None
    total = 0
    for attempt in range(restarts * STARTS_PER_RESTART + 1):
        if attempt:
            rng = rng or np.random.default_rng(seed)
            x0 = rng.uniform(problem.low, problem.high)
        if attempt % FREE_EVERY:  # most random starts ignore the limits until done
            found, iterations = _free_start(problem, x0, max_iter)
            total += iterations
            if found is None:
                continue
            x, error, iterations, ok = found
        else:
            x, error, iterations, ok = _descend(problem, x0, max_iter, give_up=restarts > 0)
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
    if not ok and restarts > 0:
        # the starts gave up when they stalled: finish the closest one, so a
        # failure is judged where the descent really stops
        x, error, iterations, ok = _descend(problem, x, max_iter)
        total += iterations
        score = problem.score(error)
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


def _beyond_reach(problem: _Problem) -> bool:
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


def _reachable(problem: _Problem, x: np.ndarray, max_iter: int, seed: int) -> bool:
    """Whether the target can be reached from elsewhere: from a small nudge off
    ``x`` or from a few seeded random starts."""
    problem = problem.view(problem.position_only)  # unweighted
    rng = np.random.default_rng(seed + 1)
    span = problem.high - problem.low
    starts = [problem.limit(x + rng.normal(0.0, 0.05, len(x)) * np.minimum(span, 1.0))]
    starts += [rng.uniform(problem.low, problem.high) for _ in range(PROBES)]
    return any(_descend(problem, start, max_iter)[3] for start in starts)

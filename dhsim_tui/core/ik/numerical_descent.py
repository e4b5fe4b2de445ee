"""The numerical IK solver's descents (:mod:`dhsim_tui.core.ik.numerical`):
one damped least-squares descent from a start (:func:`_descend`, clamped to
the joint limits or free of them), and a random start solved with the limits
ignored, then turned into them (:func:`_free_start`).
"""

from __future__ import annotations

import math

import numpy as np

from dhsim_tui.core.analysis.cholesky import damped_solver
from dhsim_tui.core.ik.numerical_problem import ORIENTATION_TOL, POSITION_TOL, _Problem
from dhsim_tui.core.ik.rotation import _rotation_error

#: the damping's bias (keeps steps finite at singularities); it fades with the
#: squared error below it, so that the last digits converge at once even near
#: a singularity (a fixed 1e-6 left descents crawling at an error of 1e-5)
DAMPING_BIAS = 1e-6
#: an attempt this close (fraction of the reach) is polished rather than dropped:
#: near a singularity the last digits converge slowly
POLISH_BELOW = 1e-3
#: a solution this far past a limit (radians, reach fractions) is on it
LIMIT_SLACK = 1e-9
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

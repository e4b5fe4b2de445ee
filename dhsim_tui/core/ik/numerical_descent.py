"""The numerical IK solver's descents (:mod:`dhsim_tui.core.ik.numerical`):
one damped least-squares descent from a start (:func:`levenberg_marquardt`, clamped to
the joint limits or free of them), and a random start solved with the limits
ignored, then turned into them (:func:`solve_free_start`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from dhsim_tui.core.ik.numerical_problem import (
    ORIENTATION_TOL,
    POSITION_TOL,
    UNWEIGHTED,
    IkProblem,
)

#: the damping's bias (keeps steps finite at singularities); it fades with the
#: squared error below it, so that the last digits converge at once even near
#: a singularity (a fixed 1e-6 left descents crawling at an error of 1e-5)
DAMPING_BIAS = 1e-6
#: the damping per squared error (of the dimensionless errors). Sugihara's,
#: 0.5, makes a far start crawl: a Panda from home took 11 iterations for the
#: median target and reached 73% of them; with 0.03, 8 and 79% (and 4.5
#: iterations instead of 4.8 from 5° off); 0.01 to 0.03 did best
DAMPING = 0.03
#: an attempt this close (fraction of the reach) is polished rather than dropped:
#: near a singularity the last digits converge slowly
POLISH_BELOW = 1e-3
#: a solution this far past a limit (radians, reach fractions) is on it
LIMIT_SLACK = 1e-9
#: a restart gives up when a window of this many iterations lowers the error
#: by less than STALL_GAIN (it sits in a local minimum, often on a limit)
STALL_WINDOW = 8
STALL_GAIN = 0.5
#: a robot's descents are compiled with their constants folded in from its
#: FOLD_AFTER-th descent on (until then, as written: quicker to compile)
FOLD_AFTER = 32


def _plan(problem: IkProblem) -> dict:
    """:func:`~dhsim_tui.core.ik.step_codegen.descent_source`'s arguments
    for this problem's rows and weights (but the robot)."""
    setup = problem.setup
    weights = problem.weight.tolist()
    picked = setup.picked[problem.position_only]
    return {
        "position_only": problem.position_only,
        "picked": picked,
        "weights": [weights[r] for r in picked],
        "to_user": setup.to_user,
        "low": setup.low_list,
        "high": setup.high_list,
        "revolute": setup.revolute_list,
        "scale": setup.scale,
        "tolerances": (POSITION_TOL * POSITION_TOL, ORIENTATION_TOL * ORIENTATION_TOL),
        "stall": (STALL_WINDOW, STALL_GAIN, POLISH_BELOW * POLISH_BELOW),
        "damping": DAMPING,
    }


def _compiled(problem: IkProblem) -> Callable:
    """The robot's compiled descent for this problem's rows and weights
    (:mod:`dhsim_tui.core.ik.step_codegen`), kept on the robot's setup:
    unfolded at first (about 4 ms to compile for a Panda), folded once the
    robot has asked for FOLD_AFTER descents (10 ms more, a quarter faster),
    which spares an edited robot's first jog the longer compile."""
    setup = problem.setup
    setup.descent_calls += 1
    if problem.weight is UNWEIGHTED:
        key = problem.position_only
    else:
        key = (problem.position_only, tuple(problem.weight.tolist()))
    run = setup.descents.get(key)
    if run is None or (key in setup.unfolded and setup.descent_calls >= FOLD_AFTER):
        from dhsim_tui.core.ik.step_codegen import compile_descent  # at the first solve

        fold = setup.descent_calls >= FOLD_AFTER
        run = setup.descents[key] = compile_descent(problem.robot, **_plan(problem), fold=fold)
        if fold:
            setup.unfolded.discard(key)
        else:
            setup.unfolded.add(key)
    return run


def levenberg_marquardt(
    problem: IkProblem,
    x: list[float],
    max_iter: int,
    bias: float = DAMPING_BIAS,
    give_up: bool = False,
    free: bool = False,
    checkpoint: int = -1,
    limit: float = 0.0,
) -> tuple[list[float], list[float], int, bool]:
    """Levenberg-Marquardt after Sugihara: damping = DAMPING × the squared
    error + a small bias (no larger than the squared error), one forward
    kinematics per iteration, clamped to the joint limits. ``x`` and the
    answer's joint values are plain floats in internal units; returns (x,
    error, iterations, converged).

    The whole loop is one function compiled for the robot (step_codegen): the
    pose, the error, the normalised Jacobian and a written-out Cholesky solve
    of the smaller normal matrix, in plain Python floats. ``give_up`` stops
    early when the error stalls (see STALL_WINDOW); ``free`` ignores the
    joint limits (see :func:`solve_free_start`). At iteration ``checkpoint`` it
    gives up if the error (unweighted, squared) is still above ``limit``."""
    run = _compiled(problem)
    return run(x, problem.goal, max_iter, bias, give_up, free, checkpoint, limit)


def _into_limits(problem: IkProblem, x: list[float], clamp: bool = False) -> list[float] | None:
    """``x`` with each revolute joint turned by whole turns into its limits,
    or None when some joint does not fit (``clamp``: then onto the limit)."""
    out = []
    turn = 2 * math.pi
    for v, lo, hi, rev in zip(
        x,
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
    return out


def solve_free_start(problem: IkProblem, x0: list[float], max_iter: int):
    """One random start solved with the limits ignored, then its solution
    turned into the limits and finished with them.

    A descent clamped to the limits from a random start often ends against a
    limit, on a branch of the arm (shoulder, elbow, wrist) whose solution lies
    past it. Ignored, the limits trap nothing: the descent reaches one of the
    arm's solutions, at random, and that is the answer if whole turns bring it
    within the limits. Where the only solution within the limits lies close to
    one of them (a Puma reaching over with its shoulder near 225°, or its wrist
    near ±100°), a free start finds it up to three times as often as a clamped
    one. Returns levenberg_marquardt's tuple, or None when the solution found does not fit."""
    x, error, iterations, ok = levenberg_marquardt(problem, x0, max_iter, give_up=True, free=True)
    if not ok:
        return None, iterations
    inside = _into_limits(problem, x)
    if inside is None:
        if problem.robot.dof <= problem.rows.sum():
            return None, iterations
        # a redundant arm (a Panda): its solutions form a family, and the one
        # found may slide within the limits; clamped, the descent may find it
        inside = _into_limits(problem, x, clamp=True)
        x, error, more, ok = levenberg_marquardt(problem, inside, max_iter, give_up=True)
    else:
        x, error, more, ok = levenberg_marquardt(problem, inside, max_iter)
    return (x, error, iterations + more, ok), iterations + more

"""The IK answer a user wants: the solution nearest where the arm is.

:func:`inverse` is what ``dhsim ik``, Cartesian jogging and a program's
linear moves call. Where the arm has a closed form (a spherical wrist, or
axes 2-4 parallel: :mod:`dhsim_tui.core.ik.analytic`) and the whole pose is
asked for, it solves every branch in closed form and answers with the one
within the limits nearest ``start``, checked by forward kinematics
(:func:`dhsim_tui.core.ik.solutions.nearest_closed_form`; about 30 µs for
a Puma). Nearest, measured joint by joint
(radians, fractions of the reach), is the branch the arm is on: a jog or a
sampled line continues it, and a target the arm can only reach on another
branch comes back on the nearest one, whose distance the caller judges (a
jog refuses a swing, the path check reports a jump).

Elsewhere (a Panda, a position-only target, a pose no closed-form solution
reaches) it is the numerical solver
(:func:`dhsim_tui.core.ik.numerical.solve`), which also says why a target
cannot be reached.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from dhsim_tui.core.ik.numerical import IKResult, solve
from dhsim_tui.core.ik.numerical_problem import cached_setup
from dhsim_tui.core.ik.solutions import nearest_closed_form
from dhsim_tui.core.model.robot import Robot

#: the numerical solver's answer, for the closed form's (``iterations``)
CLOSED_FORM_ITERATIONS = 0


def inverse(
    robot: Robot,
    target: np.ndarray,
    start: Sequence[float] | None = None,
    *,
    position_only: bool = False,
    max_iter: int = 100,
    restarts: int = 0,
    seed: int = 0,
    max_change: Sequence[float] | None = None,
) -> IKResult:
    """Joint values that put the end effector at ``target`` (a 4×4 world
    pose; its position alone when ``position_only``), nearest ``start``
    (home when None): the closed form's nearest solution where the arm has
    one, else :func:`~dhsim_tui.core.ik.numerical.solve` with these
    arguments (and when no closed-form solution is within the limits, so
    that the failure says why).

    ``max_change`` (robot units, per joint): a jog or a sampled line asks
    for a continuation; a closed-form answer that moves a joint further
    from ``start`` is another branch, and the numerical solver started at
    ``start`` answers instead: it follows the arm's own branch as far as it
    goes, and says what stops it there (a joint's limit, a singularity)."""
    first = tuple(robot.home if start is None else start)
    if not position_only:
        best = nearest_closed_form(robot, target, first)  # plain floats: math raises
        if best is not None and max_change is not None:
            changes = zip(best.q, first, max_change, strict=True)
            if any(abs(a - b) > most for a, b, most in changes):
                best = None  # another branch: not a continuation
        if best is not None:
            residual = max(best.residual / cached_setup(robot).scale, best.orientation_error)
            return IKResult(
                True,
                best.q,
                best.residual,
                best.orientation_error,
                CLOSED_FORM_ITERATIONS,
                "",
                residual,
            )
    return solve(
        robot,
        target,
        first,
        position_only=position_only,
        max_iter=max_iter,
        restarts=restarts,
        seed=seed,
    )

"""Every inverse-kinematics solution of a pose, not just the nearest one.

:func:`all_solutions` answers in closed form where the arm's geometry allows
it (:mod:`dhsim_tui.core.ik.analytic`: a spherical wrist, or axes 2-4
parallel, detected from the D-H table at home), else by many seeded random
starts of the numerical solver (:func:`dhsim_tui.core.ik.numerical.solve`).

What counts as one solution:

* joint values within the limits;
* two solutions are the same when every prismatic joint agrees and every
  revolute joint agrees modulo 360° (within :data:`SAME_TOL`);
* a revolute joint whose range holds both ``q`` and ``q ± 360°`` (a UR5's
  ±360°) could take either: the solution is listed once, at the turn
  nearest ``start`` (what a user stepping from there would reach), so a
  UR5 pose has at most 8 solutions, not hundreds of copies.

At a singular pose of a closed-form arm (the Puma's wrist with joint 5 at 0,
where only joint 4 + joint 6 matters) the angle the pose leaves free is
taken from ``start``: one solution stands for the continuum.

Every returned solution has been checked by forward kinematics (position
within :data:`~dhsim_tui.core.ik.judge.POSITION_TOL` of the reach,
orientation within :data:`~dhsim_tui.core.ik.judge.ORIENTATION_TOL` rad)
and they are ordered by distance from ``start`` (radians for revolute
joints, fractions of the reach for prismatic ones).

An arm with more joints than the task has directions (a Panda, or any
six-axis arm asked for a position only) has a continuum of solutions:
``family`` is True and the solutions are distinct representatives (at least
:data:`FAMILY_SPACING` apart), not the whole set.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from dhsim_tui.core.analysis.jacobian import controllable_rows, task_rank
from dhsim_tui.core.ik.judge import Judge
from dhsim_tui.core.ik.numerical import solve
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import counted


def _closed_forms():
    """:mod:`dhsim_tui.core.ik.analytic`, imported at the first pose solved
    rather than when this module loads: the closed forms (the geometry
    detected from the D-H table, the wrist and planar families) are a dozen
    modules that the simulator's first frame does not need."""
    from dhsim_tui.core.ik import analytic

    return analytic


#: a closed-form solution further off than this (same units) is polished numerically
POLISH_ABOVE = 1e-9
#: two solutions closer than this (radians / fractions of the reach, on every
#: joint; 1e-3 rad = 0.06°) are one: near a singular pose (a SCARA stretched
#: out) the numerical solver stops ~1e-4 rad short of the one solution, from
#: either side, and a user stepping between such copies would see nothing move
SAME_TOL = 1e-3
#: closed-form solutions are exact to ~1e-12, but at a singular pose rounding
#: splits one solution into two ~1e-8 apart: closer than this, they are one
ANALYTIC_SAME_TOL = 1e-6
#: representatives of a continuous family are at least this far apart (radians
#: / reach fractions, on some joint)
FAMILY_SPACING = math.radians(5.0)
#: random starts of the numerical search (besides ``start``)
NUMERICAL_STARTS = 40
#: the search's seed: the same call gives the same answer
SEED = 20240611


class Solution(NamedTuple):
    """One solution: ``q`` within limits, the configuration's words ("" when
    they mean nothing), the position error (robot units) and the orientation
    error (radians) of FK(q) against the target. (A named tuple: a pose has
    up to 8, made in a few microseconds.)"""

    q: tuple[float, ...]
    config: str
    residual: float
    orientation_error: float


@dataclass(frozen=True)
class Solutions:
    """Every solution (distinct, within limits, nearest to the start first),
    how they were found (``"analytic"`` or ``"numerical"``), whether they are
    representatives of a continuous family, and a one-line note for the user
    (why not analytic, why none)."""

    solutions: tuple[Solution, ...]
    method: str
    family: bool
    note: str = ""


def _task_size(robot: Robot, position_only: bool) -> int:
    """How many independent directions the target fixes for this arm."""
    rows = controllable_rows(robot).copy()
    if position_only:
        rows[3:] = False
    return min(int(rows.sum()), task_rank(robot))


def all_solutions(
    robot: Robot,
    target: np.ndarray,
    start: Sequence[float] | None = None,
    *,
    position_only: bool = False,
) -> Solutions:
    """Every joint vector within limits that puts the end effector at
    ``target`` (a 4×4 world pose; only its position counts when
    ``position_only``), nearest to ``start`` (default: home) first."""
    target = np.asarray(target, dtype=float)
    if target.shape != (4, 4) or not np.isfinite(target).all():
        raise DhsimError(f"ik: the target must be a finite 4×4 transform, got shape {target.shape}")
    first = tuple(map(float, robot.home if start is None else start))
    if len(first) != robot.dof:
        raise DhsimError(
            f"ik: expected {robot.dof} start values for {robot.name!r}, got {len(first)}"
        )
    geometry = None if position_only else _closed_forms().detect(robot)
    if geometry is not None:  # plain floats (math raises, numpy is not used)
        return _analytic(robot, geometry, target, first)
    with np.errstate(all="ignore"):
        family = robot.dof > _task_size(robot, position_only)
        return _numerical(robot, target, first, position_only, family)


def nearest_closed_form(
    robot: Robot, target: np.ndarray, start: Sequence[float]
) -> Solution | None:
    """The closed-form solution within the limits nearest ``start`` (the
    first of :func:`all_solutions`), or None when there is none (or the arm
    has no closed form). Every branch is solved (a few microseconds) but
    only the nearest is checked by forward kinematics, unless it needs the
    numerical polish of a near-singular pose: then every one is."""
    geometry = _closed_forms().detect(robot)
    if geometry is None:
        return None
    target = np.asarray(target, dtype=float)
    start = tuple(start)
    judge = Judge(robot, target, False)
    branches, _ = _closed_forms().solve(robot, geometry, target, start, judge.fits)
    best = None
    for q, config in branches:
        nearest = judge.nearest(q, start)
        if nearest is not None:
            key = (judge.distance(nearest, start), nearest)
            if best is None or key < best[0]:
                best = (key, q, config)
    if best is not None:
        (_, nearest), q, config = best
        position, orientation = judge.errors(q)
        if position <= POLISH_ABOVE * judge.scale and orientation <= POLISH_ABOVE:
            return Solution(nearest, config, position, orientation)
    found = _analytic(robot, geometry, target, start).solutions
    return found[0] if found else None


def _distinct(judge: Judge, items: list, tol: float) -> list:
    """``items`` ((q, ...) tuples) without repeats modulo a turn, first kept
    (:meth:`Judge.same`, written out: this runs for every pair). The last
    joint is compared first: the wrist's differ between most branches."""
    kept: list = []
    joints = tuple(zip(judge.revolute, judge.units, strict=True))
    last = len(joints) - 1
    last_revolute, last_unit = joints[last]
    remainder, tau = math.remainder, 2 * math.pi
    for item in items:
        q = item[0]
        end = q[last]
        for other in kept:
            d = (end - other[0][last]) * last_unit
            if abs(remainder(d, tau) if last_revolute else d) > tol:
                continue  # apart on the last joint: not a repeat
            for x, y, (revolute, unit) in zip(q, other[0], joints, strict=True):
                d = (x - y) * unit
                if revolute:
                    d = remainder(d, tau)
                if abs(d) > tol:
                    break
            else:  # every joint agrees: a repeat
                break
        else:
            kept.append(item)
    return kept


def _finish(judge: Judge, found: list, start, method: str, family: bool, note: str) -> Solutions:
    """Every found (q, config, errors, q's turn within limits nearest the
    start) as one solution at that turn; nearest to the start first."""
    keyed = [
        (judge.distance(nearest, start), nearest, Solution(nearest, config, position, orientation))
        for _, config, (position, orientation), nearest in found
    ]
    keyed.sort(key=lambda item: item[:2])
    return Solutions(tuple(item[2] for item in keyed), method, family, note)


def _analytic(robot: Robot, geometry, target: np.ndarray, start) -> Solutions:
    judge = Judge(robot, target, False)
    branches, outside = _closed_forms().solve(robot, geometry, target, start, judge.fits)
    found = []
    nearest_of, errors_of = judge.nearest, judge.errors
    polish_position = POLISH_ABOVE * judge.scale
    for q, config in branches:
        nearest = nearest_of(q, start)
        if nearest is None:
            outside += 1
            continue
        errors = errors_of(q)
        if errors[0] <= polish_position and errors[1] <= POLISH_ABOVE:  # the usual case
            found.append((q, config, errors, nearest))
            continue
        # near a singularity the closed form loses digits: finish numerically
        with np.errstate(all="ignore"):
            result = solve(robot, target, q, max_iter=20)
        if result.success and judge.same(result.q, q, 1e-3):
            q, errors = result.q, judge.errors(result.q)
            nearest = judge.nearest(q, start)
        if judge.good(errors) and nearest is not None:
            found.append((q, config, errors, nearest))
    found = _distinct(judge, found, ANALYTIC_SAME_TOL)
    note = ""
    if not found:
        if outside:
            note = "every solution has a joint outside its limits"
        else:
            with np.errstate(all="ignore"):
                note = _why_not(robot, target, start, False)
    return _finish(judge, found, start, "analytic", False, note)


def _why_not(robot: Robot, target: np.ndarray, start, position_only: bool) -> str:
    """The numerical solver's account of why a target cannot be reached."""
    result = solve(robot, target, start, position_only=position_only)
    return result.reason or "the target cannot be reached"


def _numerical(
    robot: Robot, target: np.ndarray, start, position_only: bool, family: bool
) -> Solutions:
    judge = Judge(robot, target, position_only)
    rng = np.random.default_rng(SEED)
    starts = [
        start,
        *(tuple(s) for s in rng.uniform(robot.lower, robot.upper, (NUMERICAL_STARTS, robot.dof))),
    ]
    found = []
    first_reason = ""
    for k, s in enumerate(starts):
        result = solve(
            robot, target, s, position_only=position_only, max_iter=60, restarts=1, seed=k
        )
        if not result.success:
            first_reason = first_reason or result.reason
            continue
        q = judge.polish(result.q)
        errors = judge.errors(q)
        nearest = judge.nearest(q, start)
        if judge.good(errors) and nearest is not None:
            found.append((q, "", errors, nearest))
    found = _distinct(judge, found, FAMILY_SPACING if family else SAME_TOL)
    if family:
        why = (
            "the orientation is free"
            if position_only
            else f"{counted(robot.dof, 'joint')} for a {_task_size(robot, False)}-direction pose"
        )
        shown = counted(len(found), "representative")
        note = f"{why}: the solutions form a continuous family; these are {shown}"
    elif position_only:
        note = f"found by {len(starts)} numerical starts; a solution may be missing"
    else:
        note = (
            "no closed form for this geometry (needs six joints with a spherical wrist, or "
            f"axes 2-4 parallel): found by {len(starts)} numerical starts; one may be missing"
        )
    if not found:
        note = first_reason or _why_not(robot, target, start, position_only)
    return _finish(judge, found, start, "numerical", family, note)

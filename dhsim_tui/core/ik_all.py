"""Every inverse-kinematics solution of a pose, not just the nearest one.

:func:`all_solutions` answers in closed form where the arm's geometry allows
it (:mod:`dhsim_tui.core.ik_analytic`: a spherical wrist, or axes 2-4
parallel, detected from the D-H table at home), else by many seeded random
starts of the numerical solver (:func:`dhsim_tui.core.ik.solve`).

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
within :data:`POSITION_TOL` of the reach, orientation within
:data:`ORIENTATION_TOL` rad) and they are ordered by distance from ``start``
(radians for revolute joints, fractions of the reach for prismatic ones).

An arm with more joints than the task has directions (a Panda, or any
six-axis arm asked for a position only) has a continuum of solutions:
``family`` is True and the solutions are distinct representatives (at least
:data:`FAMILY_SPACING` apart), not the whole set.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core import ik_analytic
from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.ik import rotation_error, solve
from dhsim_tui.core.jacobian import controllable_rows, jacobian_from_frames, task_rank
from dhsim_tui.core.model import Robot
from dhsim_tui.core.workspace import reach

#: a returned solution's largest position error (fraction of the reach) and
#: orientation error (radians)
POSITION_TOL = 1e-6
ORIENTATION_TOL = 1e-6
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
_DEG = math.pi / 180.0
#: a value this far (deg / robot units) past a limit is the limit (rounding)
_LIMIT_SLACK = 1e-9


@dataclass(frozen=True)
class Solution:
    """One solution: ``q`` within limits, the configuration's words ("" when
    they mean nothing), the position error (robot units) and the orientation
    error (radians) of FK(q) against the target."""

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
    if target.shape != (4, 4) or not all(map(math.isfinite, target.reshape(-1).tolist())):
        raise DhsimError(f"ik: the target must be a finite 4×4 transform, got shape {target.shape}")
    first = tuple(map(float, robot.home if start is None else start))
    if len(first) != robot.dof:
        raise DhsimError(
            f"ik: expected {robot.dof} start values for {robot.name!r}, got {len(first)}"
        )
    with np.errstate(all="ignore"):
        return _all(robot, target, first, position_only)


def _all(robot: Robot, target: np.ndarray, start: tuple[float, ...], position_only: bool):
    geometry = None if position_only else ik_analytic.detect(robot)
    if geometry is not None:
        return _analytic(robot, geometry, target, start)
    family = robot.dof > _task_size(robot, position_only)
    return _numerical(robot, target, start, position_only, family)


class _Judge:
    """Limits, checks and distances for one robot and target."""

    def __init__(self, robot: Robot, target: np.ndarray, position_only: bool) -> None:
        self.robot = robot
        self.target = target
        self.position_only = position_only
        self.flat = target.reshape(-1).tolist()
        facts = robot.__dict__.get("_ik_all_facts")
        if facts is None:  # the robot is immutable: worked out once
            scale = reach(robot) or 1.0
            revolute = tuple(j.is_revolute for j in robot.joints)
            facts = (
                scale,
                revolute,
                tuple(_DEG if r else 1.0 / scale for r in revolute),
                tuple(
                    (
                        low - _LIMIT_SLACK,
                        high + _LIMIT_SLACK,
                        low,
                        high,
                        # the joint's range can hold an angle and another turn of it
                        r and high - low >= 360.0 - 2 * _LIMIT_SLACK,
                        r,
                    )
                    for r, low, high in zip(revolute, robot.lower, robot.upper, strict=True)
                ),
            )
            object.__setattr__(robot, "_ik_all_facts", facts)
        self.scale, self.revolute, self.units, self.limits = facts

    def errors(self, q: Sequence[float]) -> tuple[float, float]:
        """Position error (robot units) and orientation error (rad) of FK(q)
        (plain floats: this runs for every candidate)."""
        x0, x1, x2, y0, y1, y2, z0, z1, z2, p0, p1, p2 = self.robot.kinematics.state(q)
        t0, t1, t2, t3, t4, t5, t6, t7, t8, t9, t10, t11 = self.flat[:12]
        position = math.sqrt((p0 - t3) ** 2 + (p1 - t7) ** 2 + (p2 - t11) ** 2)
        if self.position_only:
            return position, 0.0
        # E = T R^T (target rotation times the reached one's transpose): its
        # angle from the skew part (sine) and the trace (cosine)
        e00 = t0 * x0 + t1 * y0 + t2 * z0
        e11 = t4 * x1 + t5 * y1 + t6 * z1
        e22 = t8 * x2 + t9 * y2 + t10 * z2
        e01 = t0 * x1 + t1 * y1 + t2 * z1
        e10 = t4 * x0 + t5 * y0 + t6 * z0
        e02 = t0 * x2 + t1 * y2 + t2 * z2
        e20 = t8 * x0 + t9 * y0 + t10 * z0
        e12 = t4 * x2 + t5 * y2 + t6 * z2
        e21 = t8 * x1 + t9 * y1 + t10 * z1
        sine = 0.5 * math.sqrt((e21 - e12) ** 2 + (e02 - e20) ** 2 + (e10 - e01) ** 2)
        return position, math.atan2(sine, 0.5 * (e00 + e11 + e22 - 1.0))

    def polish(self, q: Sequence[float], steps: int = 4) -> tuple[float, ...]:
        """A few Gauss-Newton steps from a numerical solution, down to rounding
        (the solver stops at its tolerance; duplicates are told apart better
        without that slack). Kept only when it is closer."""
        best, best_error = tuple(q), self.errors(q)
        x = np.asarray(q, dtype=float)
        rows = slice(0, 3) if self.position_only else slice(0, 6)
        low, high = np.array(self.robot.lower), np.array(self.robot.upper)
        for _ in range(steps):
            frames = self.robot.kinematics.frames(tuple(x.tolist()))
            error = np.empty(6)
            error[:3] = self.target[:3, 3] - frames[-1][:3, 3]
            error[3:] = rotation_error(self.target[:3, :3], frames[-1][:3, :3])
            jac = jacobian_from_frames(self.robot, frames)
            jac[:, list(self.revolute)] *= _DEG  # per degree
            at_limit = (x <= low) | (x >= high)
            jac[:, at_limit] = 0.0  # a joint on its limit stays there
            step = np.linalg.lstsq(jac[rows], error[rows], rcond=1e-10)[0]
            x = np.clip(x + step, low, high)
            candidate = tuple(x.tolist())
            errors = self.errors(candidate)
            if errors[0] / self.scale + errors[1] < best_error[0] / self.scale + best_error[1]:
                best, best_error = candidate, errors
            else:
                break
        return best

    def good(self, errors: tuple[float, float], factor: float = 1.0) -> bool:
        position, orientation = errors
        return (
            position <= POSITION_TOL * factor * self.scale
            and orientation <= ORIENTATION_TOL * factor
        )

    def nearest(self, q: Sequence[float], start: Sequence[float]) -> tuple[float, ...] | None:
        """The copy of ``q`` within the limits (revolute joints taken a whole
        number of turns either way) nearest ``start``, or None when a joint
        cannot fit. The distance is a sum over joints, so each joint takes its
        own nearest turn (ties: the lower value, as the smallest tuple would)."""
        out: list[float] = []
        append = out.append
        for value, first, unit, (low, high, lowest, highest, wide, revolute) in zip(
            q, start, self.units, self.limits, strict=True
        ):
            if not wide and low <= value <= high:  # the usual case: in range, one turn
                # min(max(value, lowest), highest), written out
                if lowest > value:
                    value = lowest
                append(highest if highest < value else value)
                continue
            if not revolute:
                return None
            k = math.ceil((low - value) / 360.0)
            best = best_cost = None
            turned = value + 360.0 * k
            while turned <= high:
                # min(max(turned, lowest), highest), written out
                v = lowest if lowest > turned else turned
                if highest < v:
                    v = highest
                cost = ((v - first) * unit) ** 2
                if best is None or cost < best_cost or (cost == best_cost and v < best):
                    best, best_cost = v, cost
                k += 1
                turned = value + 360.0 * k
            if best is None:
                return None
            append(best)
        return tuple(out)

    def fits(self, index: int, value: float) -> bool:
        """Whether joint ``index`` can take ``value`` (or, if revolute, a whole
        number of turns from it) within its limits."""
        limits = self.limits[index]
        if limits[0] <= value <= limits[1]:
            return True
        if not self.revolute[index]:
            return False
        low, high = limits[0], limits[1]
        return value + 360.0 * math.ceil((low - value) / 360.0) <= high

    def same(self, a: Sequence[float], b: Sequence[float], tol: float) -> bool:
        """Whether every joint of a and b agrees within ``tol`` (internal
        units), revolute joints modulo a turn."""
        for x, y, revolute, unit in zip(a, b, self.revolute, self.units, strict=True):
            d = (x - y) * unit
            if revolute:
                d = math.remainder(d, 2 * math.pi)
            if abs(d) > tol:
                return False
        return True

    def distance(self, q: Sequence[float], start: Sequence[float]) -> float:
        total = 0
        for x, y, u in zip(q, start, self.units, strict=True):
            total += ((x - y) * u) ** 2
        return math.sqrt(total)


def _distinct(judge: _Judge, items: list, tol: float) -> list:
    """``items`` ((q, ...) tuples) without repeats modulo a turn, first kept
    (:meth:`_Judge.same`, written out: this runs for every pair)."""
    kept: list = []
    joints = tuple(zip(judge.revolute, judge.units, strict=True))
    remainder, tau = math.remainder, 2 * math.pi
    for item in items:
        q = item[0]
        for other in kept:
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


def _finish(judge: _Judge, found: list, start, method: str, family: bool, note: str) -> Solutions:
    """Every found (q, config, errors, q's turn within limits nearest the
    start) as one solution at that turn; nearest to the start first."""
    keyed = [
        (judge.distance(nearest, start), nearest, Solution(nearest, config, position, orientation))
        for _, config, (position, orientation), nearest in found
    ]
    keyed.sort(key=lambda item: item[:2])
    return Solutions(tuple(item[2] for item in keyed), method, family, note)


def _analytic(robot: Robot, geometry, target: np.ndarray, start) -> Solutions:
    judge = _Judge(robot, target, False)
    branches, outside = ik_analytic.solve_raw(robot, geometry, target, start, judge.fits)
    found = []
    for q, config in branches:
        nearest = judge.nearest(q, start)
        if nearest is None:
            outside += 1
            continue
        errors = judge.errors(q)
        if not judge.good(errors, POLISH_ABOVE / POSITION_TOL):
            # near a singularity the closed form loses digits: finish numerically
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
            note = _why_not(robot, target, start, False)
    return _finish(judge, found, start, "analytic", False, note)


def _why_not(robot: Robot, target: np.ndarray, start, position_only: bool) -> str:
    """The numerical solver's account of why a target cannot be reached."""
    result = solve(robot, target, start, position_only=position_only)
    return result.reason or "the target cannot be reached"


def _numerical(
    robot: Robot, target: np.ndarray, start, position_only: bool, family: bool
) -> Solutions:
    judge = _Judge(robot, target, position_only)
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
            else f"{robot.dof} joints for a {_task_size(robot, False)}-direction pose"
        )
        note = (
            f"{why}: the solutions form a continuous family; these are {len(found)} representatives"
        )
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

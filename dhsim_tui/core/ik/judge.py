"""Limits, checks and distances for the solutions of one IK target
(:mod:`dhsim_tui.core.ik.solutions`): which turn of a joint value lies within the
limits nearest the start, the position and orientation errors of FK(q), a
numerical polish, and the distance between two joint vectors.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from operator import le

import numpy as np

from dhsim_tui.core.analysis.jacobian import jacobian_from_frames
from dhsim_tui.core.analysis.workspace import reach
from dhsim_tui.core.ik.rotation import rotation_error
from dhsim_tui.core.model.robot import Robot

#: a returned solution's largest position error (fraction of the reach) and
#: orientation error (radians)
POSITION_TOL = 1e-6
ORIENTATION_TOL = 1e-6
_DEG = math.pi / 180.0
#: a value this far (deg / robot units) past a limit is the limit (rounding)
_LIMIT_SLACK = 1e-9


def _facts(robot: Robot) -> tuple:
    """What :class:`Judge` needs of a robot: the reach, which joints are
    revolute, the units of a distance, the limits (with slack, as given,
    whether a range holds another turn, revolute), whether every joint has
    the same unit, the limits as two tuples, and the joints whose range holds
    another turn."""
    scale = reach(robot) or 1.0
    revolute = tuple(j.is_revolute for j in robot.joints)
    units = tuple(_DEG if r else 1.0 / scale for r in revolute)
    limits = tuple(
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
    )
    return (
        scale,
        revolute,
        units,
        limits,
        len(set(units)) == 1,
        tuple(limit[2] for limit in limits),
        tuple(limit[3] for limit in limits),
        tuple(i for i, limit in enumerate(limits) if limit[4]),
    )


class Judge:
    """Limits, checks and distances for one robot and target."""

    def __init__(self, robot: Robot, target: np.ndarray, position_only: bool) -> None:
        self.robot = robot
        self.target = target
        self.position_only = position_only
        self.flat = target.reshape(-1).tolist()
        facts = robot.__dict__.get("_ik_all_facts")
        if facts is None:  # the robot is immutable: worked out once
            facts = _facts(robot)
            object.__setattr__(robot, "_ik_all_facts", facts)
        (
            self.scale,
            self.revolute,
            self.units,
            self.limits,
            self.one_unit,
            self.lowest,
            self.highest,
            self.wide,
        ) = facts
        self.state = robot.kinematics.state_function()

    def errors(self, q: Sequence[float]) -> tuple[float, float]:
        """Position error (robot units) and orientation error (rad) of FK(q)
        (plain floats: this runs for every candidate)."""
        x0, x1, x2, y0, y1, y2, z0, z1, z2, p0, p1, p2 = self.state(q)
        t0, t1, t2, t3, t4, t5, t6, t7, t8, t9, t10, t11 = self.flat[:12]
        position = math.sqrt((p0 - t3) ** 2 + (p1 - t7) ** 2 + (p2 - t11) ** 2)
        if self.position_only:
            return position, 0.0
        # the angle between the two rotations from their difference:
        # |T - R|_F^2 = 8 sin^2(angle / 2)
        gap = (
            (t0 - x0) ** 2
            + (t4 - x1) ** 2
            + (t8 - x2) ** 2
            + (t1 - y0) ** 2
            + (t5 - y1) ** 2
            + (t9 - y2) ** 2
            + (t2 - z0) ** 2
            + (t6 - z1) ** 2
            + (t10 - z2) ** 2
        )
        return position, 2.0 * math.asin(min(1.0, math.sqrt(0.125 * gap)))

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
        # the usual case, in C: every joint within its limits, and each joint
        # whose range holds another turn less than half a turn from the start
        if all(map(le, self.lowest, q)) and all(map(le, q, self.highest)):
            for i in self.wide:
                if not abs(q[i] - start[i]) < 180.0:
                    break
            else:
                return tuple(q)
        out: list[float] = []
        append = out.append
        ceil, floor = math.ceil, math.floor
        for value, first, (low, high, lowest, highest, wide, revolute) in zip(
            q, start, self.limits, strict=True
        ):
            if not wide and low <= value <= high:  # the usual case: in range, one turn
                pass
            elif not revolute:
                return None
            else:
                # the turns k that fit, and the one nearest the start (the cost
                # grows either side of it, so the nearest that fits is the best)
                fewest = ceil((low - value) / 360.0)
                most = floor((high - value) / 360.0)
                if fewest > most:
                    return None
                k = ceil((first - value) / 360.0 - 0.5)  # a tie goes to the lower value
                value += 360.0 * (fewest if k < fewest else most if k > most else k)
            # min(max(value, lowest), highest), written out
            if lowest > value:
                value = lowest
            append(highest if highest < value else value)
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
        """Radians for revolute joints, fractions of the reach for prismatic ones."""
        if self.one_unit:  # every joint revolute (or every one prismatic): in C
            return math.dist(q, start) * self.units[0]
        total = 0
        for x, y, u in zip(q, start, self.units, strict=True):
            total += ((x - y) * u) ** 2
        return math.sqrt(total)

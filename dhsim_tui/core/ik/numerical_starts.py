"""Where the numerical IK solver (:mod:`dhsim_tui.core.ik.numerical`) restarts
when the first start fails: the configurations of a seeded table whose poses
lie nearest the target.

A random start lands in the basin of a solution within the limits now and
then (one start in four on a Panda, one in fifty for a pose with two joints
near their limits), and a start that fails costs a dozen iterations or more
before it gives up. A configuration whose pose is already near the target's
is usually next to a solution: its descent takes a few iterations. So each
robot keeps a table of :data:`TABLE_SIZE` configurations within its limits
(seeded: the same on every run) and their poses, from one batch of forward
kinematics, built the first time a solve needs it; a solve with restarts
tries the entries nearest its target (position per reach, plus the rotation
matrix's entries weighted by :data:`ROTATION_WEIGHT`) before any random one.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np

from dhsim_tui.core.ik.numerical_problem import IkProblem

#: configurations in a robot's table (a lookup costs a few tens of µs)
TABLE_SIZE = 4096
#: the table's seed (the same table on every run)
TABLE_SEED = 20240611
#: a unit of rotation-matrix entry against a reach of position
ROTATION_WEIGHT = 0.3
#: the share of each joint's range the table spans, about its middle: a
#: start against a limit often stays stuck there (on a Panda, the nearest
#: entry of a table over 80% of the ranges succeeds for 68% of the targets
#: home fails on, of one over the whole ranges for 50%)
TABLE_SPAN = 0.8


class _Table:
    """A robot's seeded configurations (internal units) and their poses as
    features: position per reach, and (for whole poses) the rotation
    matrix's entries, by rows."""

    def __init__(self, problem: IkProblem) -> None:
        robot = problem.robot
        rng = np.random.default_rng(TABLE_SEED)
        lower, upper = np.array(robot.lower), np.array(robot.upper)
        middle, reach = (lower + upper) / 2, (upper - lower) / 2 * TABLE_SPAN
        q = rng.uniform(middle - reach, middle + reach, size=(TABLE_SIZE, robot.dof))
        poses = robot.kinematics.batch(q)
        self.starts = q * problem.to_internal
        position = poses[:, :3, 3] / problem.scale
        rotation = poses[:, :3, :3].reshape(TABLE_SIZE, 9) * ROTATION_WEIGHT
        # |f - t|² = |f|² - 2 f·t + |t|²: the nearest have the least |f|²/2 - f·t,
        # one product with (-f, |f|²/2) and (t, 1); single precision ranks them well
        self.scores = {}
        for position_only, features in ((True, position), (False, np.hstack([position, rotation]))):
            half = 0.5 * np.einsum("ij,ij->i", features, features)
            scores = np.vstack([-features.T, half]).astype(np.float32)
            self.scores[position_only] = np.ascontiguousarray(scores)  # a row per feature
        self.units = [1.0 / problem.scale] * 3 + [ROTATION_WEIGHT] * 9

    def nearest(self, problem: IkProblem, count: int) -> Iterator[list[float]]:
        """The ``count`` configurations whose poses are nearest the target's,
        nearest first, one at a time (most solves need the first only)."""
        goal = problem.goal  # position, then the rotation's rows
        if not all(math.isfinite(v) for v in goal):
            return
        wanted = [v * k for v, k in zip(goal, self.units, strict=True)]
        if problem.position_only:
            wanted = wanted[:3]
        wanted.append(1.0)
        distance = np.array(wanted, dtype=np.float32) @ self.scores[problem.position_only]
        for _ in range(min(count, TABLE_SIZE)):
            k = int(distance.argmin())  # the first of equals: the same every run
            if not math.isfinite(distance[k]):
                return  # not finite: an arm too small to compute with
            distance[k] = math.inf
            yield self.starts[k].tolist()


def nearest_starts(problem: IkProblem, count: int) -> Iterator[list[float]]:
    """Up to ``count`` starts from the robot's table, nearest the target first
    (the table is built on first use and kept on the robot's setup)."""
    setup = problem.setup
    if setup.table is None:
        with np.errstate(all="ignore"):  # an arm too small to compute with: not finite
            setup.table = _Table(problem)
    yield from setup.table.nearest(problem, count)

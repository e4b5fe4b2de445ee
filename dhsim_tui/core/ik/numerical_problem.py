"""One target of the numerical IK solver (:mod:`dhsim_tui.core.ik.numerical`)
for one robot: :class:`IkProblem` measures errors and Jacobians in internal
units (radians for revolute joints, reach fractions for prismatic ones), on
top of :class:`_Setup`, what no target changes, kept on the robot; and the
tolerances a solution must meet.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from dhsim_tui.core.analysis.jacobian import (
    controllable_rows,
    jacobian_from_frames,
    task_rank,
)
from dhsim_tui.core.analysis.workspace import length_scale
from dhsim_tui.core.ik.rotation import rotation_error
from dhsim_tui.core.model.robot import Robot

#: position tolerance as a fraction of the reach, and orientation tolerance (rad)
POSITION_TOL = 5e-7
ORIENTATION_TOL = 5e-7
_DEG = math.pi / 180.0
#: the row weights of an unweighted problem (shared, read only)
UNWEIGHTED = np.ones(6)
UNWEIGHTED.flags.writeable = False


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
        self.to_user = (1.0 / self.to_internal).tolist()
        self.low_list = self.low.tolist()
        self.high_list = self.high.tolist()
        self.revolute_list = self.revolute.tolist()
        self.to_internal_list = self.to_internal.tolist()
        self.lower = list(robot.lower)
        self.upper = list(robot.upper)
        #: the rows solved for, by index (position_only -> rows)
        self.picked = {k: [r for r in range(6) if v[r]] for k, v in self.rows.items()}
        #: the compiled descents (numerical_descent), by (position_only, weights)
        self.descents: dict = {}
        #: the keys of descents compiled unfolded, and how many were asked for
        self.unfolded: set = set()
        self.descent_calls = 0
        #: the seeded table of starts (numerical_starts), built on first use
        self.table = None
        # the generated code's module loads with the first problem, not at start
        from dhsim_tui.core.ik.step_codegen import compile_to_user

        self.to_user_tuple = compile_to_user(
            robot.name, self.to_internal_list, self.lower, self.upper
        )
        self.dof = robot.dof
        for shared in (self.revolute, self.to_internal, self.low, self.high, full, position):
            shared.flags.writeable = False  # every problem of this robot reads them


def cached_setup(robot: Robot) -> _Setup:
    """The robot's solve setup, made once and kept on the robot."""
    cached = robot.__dict__.get("_ik_setup")
    if cached is None:
        with np.errstate(all="ignore"):  # an arm too small to compute with: judged later
            cached = _Setup(robot)
        object.__setattr__(robot, "_ik_setup", cached)
    return cached


class IkProblem:
    """One target for one robot: errors and steps in internal units (radians for
    revolute joints, reach fractions for prismatic ones)."""

    def __init__(self, robot: Robot, target: np.ndarray, position_only: bool) -> None:
        setup = cached_setup(robot)
        self.robot = robot
        self.setup = setup
        self.kin = robot.kinematics
        self.scale = setup.scale
        self.revolute = setup.revolute
        self.to_internal = setup.to_internal
        self.low = setup.low
        self.high = setup.high
        self.rows = setup.rows[position_only]
        self.picked = setup.picked[position_only]
        self.target = target
        self.position_only = position_only
        #: row weights of the least-squares problem (all 1 but for POSITION_FIRST:
        #: a new array then, this one is shared)
        self.weight = UNWEIGHTED
        self.rank = setup.rank[position_only]
        # the target as plain floats for the fast loop: position, then the rotation's rows
        rows = target.tolist()
        self.goal = [rows[0][3], rows[1][3], rows[2][3], *rows[0][:3], *rows[1][:3], *rows[2][:3]]

    def limit(self, x: np.ndarray) -> np.ndarray:
        """Into the joint limits: a revolute joint past one limit takes the same
        angle a turn away when that fits (wide-range joints), else it stops."""
        turn = 2 * math.pi
        over = self.revolute & (x > self.high) & (x - turn >= self.low)
        under = self.revolute & (x < self.low) & (x + turn <= self.high)
        x = np.where(over, x - turn, np.where(under, x + turn, x))
        return np.clip(x, self.low, self.high)

    def user(self, x: Sequence[float]) -> tuple[float, ...]:
        """Joint values in the robot's units, within its limits (the way back
        from radians or reach fractions may round a limit a digit past it)."""
        if isinstance(x, np.ndarray):
            x = x.tolist()
        return self.setup.to_user_tuple(x)

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

    def score(self, error: Sequence[float]) -> float:
        """The size of the error in the rows solved for (unweighted)."""
        return math.sqrt(sum(error[r] * error[r] for r in self.picked))

    def converged(self, error: np.ndarray) -> bool:
        return (
            np.linalg.norm(error[:3][self.rows[:3]]) <= POSITION_TOL
            and np.linalg.norm(error[3:][self.rows[3:]]) <= ORIENTATION_TOL
        )

    def errors(self, error: Sequence[float]) -> tuple[float, float]:
        """Position error (robot units) and orientation error (rad), judged on
        every requested direction, including those the arm cannot move: a
        planar arm asked for a point off its plane has not reached it."""
        e0, e1, e2, e3, e4, e5 = error
        position = math.hypot(e0, e1, e2) * self.scale
        return position, 0.0 if self.position_only else math.hypot(e3, e4, e5)

    def position_reached(self, position_error: float) -> bool:
        return position_error <= POSITION_TOL * self.scale * 2

    def view(self, position_only: bool) -> IkProblem:
        """The same target judged on its position only, or on the whole pose."""
        return IkProblem(self.robot, self.target, position_only)

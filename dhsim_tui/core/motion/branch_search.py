"""The search behind the simulator's ``b``: every solution of the arm for a
tool pose. Its own module, so that every-solution IK loads when ``b`` is
first pressed, not when dhsim starts."""

from __future__ import annotations

import numpy as np

from dhsim_tui.core.analysis.jacobian import controllable_rows
from dhsim_tui.core.ik import solutions as ik_solutions
from dhsim_tui.core.ik.solutions import Solutions
from dhsim_tui.core.model.robot import Robot


def find_solutions(robot: Robot, q: tuple[float, ...], pose: np.ndarray) -> Solutions:
    """Every solution of the arm for ``pose``, found from ``q``. An arm with
    fewer joints than directions it moves in positions its tool (as a jog
    does). Raises one of :data:`SEARCH_ERRORS` when the search fails."""
    position_only = robot.dof < int(controllable_rows(robot).sum())
    with np.errstate(all="ignore"):
        return ik_solutions.all_solutions(robot, pose, q, position_only=position_only)

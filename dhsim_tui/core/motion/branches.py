"""Cycling through the arm's IK branches for one tool pose (the simulator's ``b``).

The solutions of a pose are found once
(:func:`~dhsim_tui.core.motion.branch_search.find_solutions`, slow enough
for a worker) and kept for the last few poses (:class:`BranchCache`); a
:class:`BranchCycle` is the solutions and the one the arm is in or moving to,
and :meth:`BranchCycle.after` the one ``steps`` presses on. Whether the arm
is still in the cycle is :meth:`BranchCycle.holds`: any other move of the arm
starts afresh.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.motion.jog import branch_caption, branch_goal, branch_index

if TYPE_CHECKING:  # the search itself is branch_search's, loaded when b is first pressed
    from dhsim_tui.core.ik.solutions import Solutions

#: how many tool poses' solutions are kept
BRANCH_CACHE = 8
#: what can stop the search for a pose's solutions (or the workspace's
#: sampling): a reason to say, never a crash
SEARCH_ERRORS = (DhsimError, ValueError, ArithmeticError, np.linalg.LinAlgError)


def branch_key(pose: np.ndarray) -> bytes:
    """The tool pose, rounded: the same pose reached again finds its solutions kept."""
    scale = max(float(np.abs(pose[:3, 3]).max()), 1.0)
    rounded = np.round(np.concatenate([pose[:3, :3].ravel(), pose[:3, 3] / scale]), 7)
    return (rounded + 0.0).tobytes()


class BranchCache:
    """The solutions of the last :data:`BRANCH_CACHE` poses, by :func:`branch_key`."""

    def __init__(self, size: int = BRANCH_CACHE) -> None:
        self.size = size
        self._found: OrderedDict[bytes, Solutions] = OrderedDict()

    def get(self, key: bytes) -> Solutions | None:
        return self._found.get(key)

    def put(self, key: bytes, found: Solutions) -> None:
        self._found[key] = found
        while len(self._found) > self.size:
            self._found.popitem(last=False)

    def __len__(self) -> int:
        return len(self._found)


@dataclass(frozen=True)
class BranchCycle:
    """The arm's solutions for one tool pose, and the one it is in or moving to."""

    found: Solutions
    index: int
    labels: tuple[str, ...] = ()  # the joints' labels (Th1 ..), to name whole turns

    @classmethod
    def of(cls, robot: Robot, found: Solutions, q: tuple[float, ...]) -> BranchCycle:
        """The cycle with the arm at ``q`` in the solution it is in (index -1:
        in none of them)."""
        return cls(found, branch_index(robot, found.solutions, q), tuple(robot.labels))

    def after(self, steps: int = 1) -> BranchCycle | None:
        """The cycle ``steps`` solutions on; None when the arm is in the only
        solution there is (nothing to move to)."""
        count = len(self.found.solutions)
        if count == 1 and self.index == 0:
            return None
        return BranchCycle(self.found, (self.index + steps) % count, self.labels)

    @property
    def goal(self) -> tuple[float, ...]:
        return branch_goal(self.found.solutions[self.index].q)

    @property
    def caption(self) -> str:
        return branch_caption(self.found, self.index, self.labels)

    @property
    def note(self) -> str:
        """A short caveat for the status line (the core's note is longer)."""
        if self.found.method == "numerical" and not self.found.family:
            return " (found numerically: one may be missing)"
        return ""

    def holds(self, *where: tuple[float, ...] | None) -> bool:
        """The arm is in the branch it went to, or on its way (``where``: its
        joints, and where a move under way ends)."""
        return self.goal in where

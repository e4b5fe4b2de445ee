"""IK-branch cycling for the control screen (``b``): the arm's other solutions
for the same tool pose, found once per pose in a worker, kept for the last few
poses, and stepped through one press at a time (the tool stays).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from textual import work
from textual.worker import get_current_worker

from dhsim_tui.core.analysis.jacobian import controllable_rows
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.motion.jog import branch_caption, branch_goal, branch_index

#: how many tool poses' IK solutions (b) are kept
BRANCH_CACHE = 8
#: what can stop the search for a pose's solutions or the workspace's sampling
#: (said in the status line, never a crash)
SEARCH_ERRORS = (DhsimError, ValueError, ArithmeticError, np.linalg.LinAlgError)


@dataclass(frozen=True)
class BranchCycle:
    """The arm's solutions for one tool pose (``b``), and the one it is in or
    moving to."""

    found: object  # ik_all.Solutions
    index: int
    labels: tuple[str, ...] = ()  # the joints' labels (Th1 ..), to name whole turns

    @property
    def goal(self) -> tuple[float, ...]:
        return branch_goal(self.found.solutions[self.index].q)

    @property
    def caption(self) -> str:
        return branch_caption(self.found, self.index, self.labels)


class BranchCycling:
    """Mixed into the control screen (before ``SmoothMotion``), which has ``q``,
    ``robot``, ``motion_goal``, ``_go_to``, ``_show_now``, ``say`` and the
    ``_branches``, ``_branch_cache``, ``finding_branches`` and
    ``_branch_presses`` it sets up."""

    def _leave_branch(self) -> bool:
        """Forget the branch cycle once the arm is neither in the branch it
        went to nor on its way there: b then starts afresh from where it is."""
        cycle = self._branches
        if cycle is None or cycle.goal in (self.q, self.motion_goal):
            return False
        self._branches = None
        return True

    def _stop_motion(self) -> bool:
        stopped = super()._stop_motion()
        if stopped and self._leave_branch():  # stopped on the way to a branch
            self._show_now()
        return stopped

    # -- b: the arm's other solutions for the same tool pose -------------------------
    def action_next_branch(self) -> None:
        """The next of the arm's solutions for the tool's pose: the tool stays,
        the arm takes another configuration (smoothly when motion is on). The
        solutions are found once per pose, in a worker; pressed again, ``b``
        goes on to the next; any other move of the arm starts afresh. Pressed
        while they are being found (a few ms to a second), each press counts:
        the arm then goes that many branches on."""
        if self.finding_branches:
            self._branch_presses += 1
            return
        cycle = self._branches
        if cycle is not None and cycle.goal in (self.q, self.motion_goal):
            self._next_branch(cycle.found, cycle.index)
            return
        pose = self.robot.kinematics.pose(self.q)
        key = self._branch_key(pose)
        found = self._branch_cache.get(key)
        if found is not None:
            self._branches_found(self.q, key, found, presses=1)
            return
        self.finding_branches = True
        self._branch_presses = 1
        self.say("finding the arm's solutions for this pose…")
        self._find_branches(self.robot, self.q, pose, key)

    def _branch_key(self, pose: np.ndarray) -> bytes:
        """The tool pose, rounded: the same pose reached again finds its solutions kept."""
        scale = max(float(np.abs(pose[:3, 3]).max()), 1.0)
        rounded = np.round(np.concatenate([pose[:3, :3].ravel(), pose[:3, 3] / scale]), 7)
        return (rounded + 0.0).tobytes()

    @work(thread=True, exclusive=True, group="branches")
    def _find_branches(self, robot: Robot, q: tuple[float, ...], pose, key: bytes) -> None:
        from dhsim_tui.core.ik.solutions import all_solutions

        # an arm with fewer joints than directions it moves in positions its tool (as a jog)
        position_only = robot.dof < int(controllable_rows(robot).sum())
        worker = get_current_worker()
        try:
            with np.errstate(all="ignore"):
                found = all_solutions(robot, pose, q, position_only=position_only)
        except SEARCH_ERRORS as exc:
            if not worker.is_cancelled:
                self.app.call_from_thread(self._branches_failed, str(exc))
            return
        if not worker.is_cancelled:  # (the screen went away meanwhile)
            self.app.call_from_thread(self._branches_found, q, key, found)

    def _branches_failed(self, reason: str) -> None:
        self.finding_branches = False
        self.say(f"no other solutions found: {reason}", error=True)

    def _branches_found(
        self, q: tuple[float, ...], key: bytes, found, presses: int | None = None
    ) -> None:
        """``presses``: how many times b was pressed for this (all of them
        while the solutions were being found, when not given)."""
        self.finding_branches = False
        presses = self._branch_presses if presses is None else presses
        self._branch_cache[key] = found
        while len(self._branch_cache) > BRANCH_CACHE:
            self._branch_cache.pop(next(iter(self._branch_cache)))
        if q != self.q:  # the arm moved while they were being found: b again
            return
        if not found.solutions:
            note = f": {found.note}" if found.note else ""
            self.say(f"no solution found for this pose{note}", error=True)
            return
        self._next_branch(found, branch_index(self.robot, found.solutions, q), presses)

    @staticmethod
    def _note(found) -> str:
        """A short caveat for the status line (the core's note is longer)."""
        if found.method == "numerical" and not found.family:
            return " (found numerically: one may be missing)"
        return ""

    def _next_branch(self, found, index: int, steps: int = 1) -> None:
        """Move to the solution ``steps`` after ``index`` (-1: the arm is in
        none of them)."""
        count = len(found.solutions)
        if count == 1 and index == 0:
            self._branches = BranchCycle(found, 0, tuple(self.robot.labels))
            self._show_now()
            self.say(self._branches.caption + self._note(found))
            return
        self._stop_motion()  # (a move to the branch before: the cycle goes on)
        cycle = BranchCycle(found, (index + steps) % count, tuple(self.robot.labels))
        self._branches = cycle
        self._go_to(cycle.goal, cycle.caption + self._note(found))
        self._show_now()

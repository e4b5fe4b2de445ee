"""The control screen's background jobs, each run in a thread worker and
ending in a message to the screen: b's search for the arm's solutions for a
pose (:func:`find_branches`) and W's sampling of the workspace
(:func:`sample_workspace`). Each computes nothing itself: the core does."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from textual.message import Message
from textual.worker import get_current_worker

from dhsim_tui.core.analysis import workspace
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.motion.branches import SEARCH_ERRORS

#: how many points the workspace cloud (W) has
CLOUD_POINTS = 20000


@dataclass
class BranchesFound(Message):
    """b's search ended: the solutions for the pose the arm had at ``q``."""

    q: tuple[float, ...]
    key: bytes
    found: object


@dataclass
class BranchesFailed(Message):
    """b's search stopped: ``reason`` says why."""

    reason: str


@dataclass
class CloudSampled(Message):
    """W's sampling ended: positions the tool can reach."""

    points: np.ndarray


@dataclass
class CloudFailed(Message):
    """W's sampling stopped: ``reason`` says why."""

    reason: str


def find_branches(
    post: Callable[[Message], object], robot: Robot, q: tuple[float, ...], pose, key: bytes
) -> None:
    """Every solution for ``pose`` (found from ``q``), posted as BranchesFound,
    or BranchesFailed; nothing when the worker was cancelled meanwhile."""
    # every-solution IK loads on the first b, not at start-up (tests/core/test_layers.py)
    from dhsim_tui.core.motion.branch_search import find_solutions

    worker = get_current_worker()
    try:
        message: Message = BranchesFound(q, key, find_solutions(robot, q, pose))
    except SEARCH_ERRORS as exc:
        message = BranchesFailed(str(exc))
    if not worker.is_cancelled:  # (the screen went away meanwhile)
        post(message)


def sample_workspace(post: Callable[[Message], object], robot: Robot) -> None:
    """:data:`CLOUD_POINTS` positions of the tool, posted as CloudSampled, or
    CloudFailed; chunk by chunk, so that W again stops it."""
    worker = get_current_worker()
    chunks = []
    try:
        with np.errstate(all="ignore"):
            for chunk in workspace.position_chunks(robot, CLOUD_POINTS, 0):
                if worker.is_cancelled:
                    return
                chunks.append(chunk)
        message: Message = CloudSampled(np.concatenate(chunks))
    except SEARCH_ERRORS as exc:
        message = CloudFailed(str(exc))
    if not worker.is_cancelled:  # W again, or the screen went away
        post(message)

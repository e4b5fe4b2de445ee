"""IK as dhsim ik, Cartesian jogging and programs' linear moves ask it
(core/ik/nearest.inverse): the closed form's solution nearest the start
where the arm has one, else the numerical solver (issue 20)."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import reference_frames

from dhsim_tui.core import load_robot, reach
from dhsim_tui.core.ik import analytic
from dhsim_tui.core.ik.nearest import inverse
from dhsim_tui.core.ik.numerical import solve
from dhsim_tui.core.ik.rotation import rotation_error
from dhsim_tui.core.ik.solutions import all_solutions

CLOSED_FORM = ["puma560", "puma560_modified", "stanford", "irb140", "ur5"]


def reaches(robot, target, q) -> None:
    """FK by the tests' own D-H product (not dhsim's) puts the tool on the target."""
    pose = reference_frames(robot, q)[-1]
    assert np.linalg.norm(pose[:3, 3] - target[:3, 3]) <= 1e-6 * reach(robot)
    assert np.linalg.norm(rotation_error(target[:3, :3], pose[:3, :3])) <= 1e-6
    assert all(
        lo - 1e-9 <= v <= hi + 1e-9 for v, lo, hi in zip(q, robot.lower, robot.upper, strict=True)
    )


@pytest.mark.parametrize("name", CLOSED_FORM)
def test_a_nearby_start_gets_the_pose_it_came_from(name):
    robot, _ = load_robot(name)
    assert analytic.detect(robot) is not None
    rng = np.random.default_rng(20)
    for _ in range(60):
        q = rng.uniform(robot.lower, robot.upper)
        target = reference_frames(robot, q)[-1]
        start = np.clip(q + rng.normal(0.0, 2.0, robot.dof), robot.lower, robot.upper)
        result = inverse(robot, target, start)
        assert result.success
        reaches(robot, target, result.q)
        # the arm's own branch: the joints it came from, not another solution
        if abs(np.sin(np.radians(q[4]))) > 0.05:  # away from the wrist's singular pose
            assert np.abs(np.subtract(result.q, q)).max() < 1e-5


@pytest.mark.parametrize("name", CLOSED_FORM)
def test_from_home_it_is_the_nearest_of_every_solution(name):
    robot, _ = load_robot(name)
    rng = np.random.default_rng(21)
    for _ in range(40):
        target = reference_frames(robot, rng.uniform(robot.lower, robot.upper))[-1]
        result = inverse(robot, target, robot.home, restarts=30)
        assert result.success
        reaches(robot, target, result.q)
        every = all_solutions(robot, target, robot.home).solutions
        distances = [np.linalg.norm(np.subtract(s.q, robot.home)) for s in every]
        if robot.joints and all(j.is_revolute for j in robot.joints):
            assert np.linalg.norm(np.subtract(result.q, robot.home)) <= min(distances) + 1e-9


def test_without_a_closed_form_it_is_the_numerical_solver():
    robot, _ = load_robot("panda")
    assert analytic.detect(robot) is None
    target = reference_frames(robot, (10, -20, 15, -90, 5, 80, 30))[-1]
    assert inverse(robot, target, robot.home, restarts=3) == solve(
        robot, target, robot.home, restarts=3
    )


def test_a_position_alone_is_the_numerical_solver():
    robot, _ = load_robot("puma560")
    target = reference_frames(robot, (10, -20, 15, 30, 40, 50))[-1]
    assert inverse(robot, target, robot.home, position_only=True) == solve(
        robot, target, robot.home, position_only=True
    )


def test_out_of_reach_says_why():
    robot, _ = load_robot("puma560")
    target = np.eye(4)
    target[:3, 3] = (5000.0, 0.0, 0.0)
    result = inverse(robot, target, robot.home)
    assert not result.success and "reach" in result.reason


def test_a_continuation_never_takes_another_branch():
    # Th5 half a degree short of its limit, the tool tilted on: only another
    # elbow branch reaches that pose, so a jog (max_change) is told why not
    robot, _ = load_robot("puma560")
    q = (0.0, 45.0, -135.0, 0.0, 99.5, 0.0)
    pose = reference_frames(robot, q)[-1]
    tilt = np.eye(4)
    c, s = np.cos(np.radians(-10.0)), np.sin(np.radians(-10.0))
    tilt[:3, :3] = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    target = pose @ tilt
    anywhere = inverse(robot, target, q)
    assert anywhere.success
    reaches(robot, target, anywhere.q)
    assert np.abs(np.subtract(anywhere.q, q)).max() > 30.0  # another branch
    limits = [30.0] * robot.dof
    local = inverse(robot, target, q, max_change=limits)
    assert not local.success and "Th5 is at its limit" in local.reason

"""Jacobian, dexterity and inverse kinematics, checked against FK and finite differences."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import random_q

from dhsim_tui.core import Joint, Robot, load_robot, reach
from dhsim_tui.core.analysis.jacobian import controllable_rows, dexterity, jacobian, task_rank
from dhsim_tui.core.ik.numerical import solve
from dhsim_tui.core.ik.rotation import rotation_error
from dhsim_tui.core.model.orientation import rotx, rpy_matrix
from dhsim_tui.core.motion.jog import cartesian_move, move_pose
from dhsim_tui.core.motion.smooth import interpolate, quintic


def test_jacobian_matches_finite_differences(bundled, rng):
    for _ in range(5):
        q = random_q(bundled, rng)
        jac = jacobian(bundled, q)
        pose = bundled.kinematics.pose(q)
        for i, joint in enumerate(bundled.joints):
            h = 1e-6
            moved = np.array(q, float)
            moved[i] += h
            other = bundled.kinematics.pose(moved)
            per = math.radians(h) if joint.is_revolute else h
            linear = (other[:3, 3] - pose[:3, 3]) / per
            angular = rotation_error(other[:3, :3], pose[:3, :3]) / per
            scale = max(1.0, np.abs(jac[:3, i]).max())
            assert np.allclose(linear, jac[:3, i], atol=1e-4 * scale), (i, linear, jac[:3, i])
            assert np.allclose(angular, jac[3:, i], atol=1e-5), (i, angular, jac[3:, i])


def test_rotation_error_of_known_turns():
    assert np.allclose(rotation_error(rotx(30), np.eye(3)), (math.radians(30), 0, 0))
    half = rotation_error(rpy_matrix(0, 0, 180), np.eye(3))
    assert np.isclose(np.linalg.norm(half), math.pi) and np.allclose(np.abs(half), (0, 0, math.pi))
    assert np.allclose(rotation_error(np.eye(3), np.eye(3)), 0)


@pytest.mark.parametrize(
    "name",
    [
        "puma560",
        "puma560_modified",
        "stanford",
        "irb140",
        "ur5",
        "panda",
        "cobra600",
        "scara_pedestal",
        "planar2",
        "gantry",
    ],
)
def test_fk_of_ik_returns_the_pose(name):
    """Targets made by FK of random joints within limits; solved from home."""
    robot, _ = load_robot(name)
    rng = np.random.default_rng(42)
    size = reach(robot)
    solved = 0
    count = 100
    for k in range(count):
        target = robot.kinematics.pose(rng.uniform(robot.lower, robot.upper))
        result = solve(robot, target, restarts=20, seed=k)
        if not result.success:
            continue
        solved += 1
        robot.check_q(result.q)  # within limits
        reached = robot.kinematics.pose(result.q)
        assert np.linalg.norm(reached[:3, 3] - target[:3, 3]) <= 1e-6 * size
        assert np.linalg.norm(rotation_error(target[:3, :3], reached[:3, :3])) <= 1e-6
    assert solved == count  # every one: they are reachable (tests/cli/test_ik_success.py)


def test_position_only_ignores_orientation():
    robot, _ = load_robot("puma560")
    target = np.eye(4)
    target[:3, 3] = (400.0, 100.0, 300.0)
    result = solve(robot, target, position_only=True, restarts=5)
    assert result.success and result.orientation_error == 0.0
    assert np.allclose(robot.kinematics.position(result.q), (400, 100, 300), atol=1e-3)


@pytest.mark.parametrize(
    ("name", "xyz"),
    [("puma560", (5000.0, 0.0, 0.0)), ("planar2", (1.0, 1.0, 0.5)), ("gantry", (-10.0, 0, 0))],
)
def test_unreachable_targets_are_reported_not_answered(name, xyz):
    robot, _ = load_robot(name)
    target = np.eye(4)
    target[:3, 3] = xyz
    result = solve(robot, target, position_only=True, restarts=5)
    assert not result.success
    assert result.position_error > 1e-3 * reach(robot)
    assert "closest" in result.reason
    robot.check_q(result.q)


def test_limits_are_respected_and_named():
    robot, _ = load_robot("cobra600")  # joint 1 only turns ±50°
    target = np.eye(4)
    target[:3, 3] = (-500.0, 0.0, 387.0)  # behind the base
    result = solve(robot, target, position_only=True, restarts=10)
    assert not result.success
    assert "joint limits" in result.reason or "out of reach" in result.reason
    robot.check_q(result.q)


def test_dexterity_sees_the_wrist_and_elbow_singularities():
    puma, _ = load_robot("puma560")
    assert dexterity(puma, (0, 45, -135, 0, 0, 0)).singular  # theta5 = 0: wrist singular
    assert not dexterity(puma, (0, 45, -135, 0, 45, 0)).near_singular
    planar, _ = load_robot("planar2")
    assert dexterity(planar, (0.0, 0.0)).singular  # stretched out
    assert math.isclose(dexterity(planar, (0.0, 90.0)).manipulability, 0.25, rel_tol=1e-9)
    assert task_rank(planar) == 2 and task_rank(load_robot("cobra600")[0]) == 4
    assert list(controllable_rows(load_robot("cobra600")[0])) == [
        True,
        True,
        True,
        False,
        False,
        True,
    ]


def test_cartesian_jog_keeps_the_tool_on_a_straight_line():
    robot, _ = load_robot("puma560")
    q = (-20.0, 50.0, -170.0, 10.0, 40.0, 0.0)
    start = robot.kinematics.pose(q)
    commanded = start
    for step in range(1, 51):  # 100 mm along world X in 2 mm steps
        commanded = move_pose(commanded, 0, 2.0)
        move = cartesian_move(robot, q, commanded)
        assert move.moved, move.reason
        q = move.q
        now = robot.kinematics.pose(q)
        assert np.allclose(now[:3, 3], start[:3, 3] + (2.0 * step, 0, 0), atol=1e-6 * reach(robot))
        assert np.linalg.norm(rotation_error(start[:3, :3], now[:3, :3])) <= 1e-6


def test_cartesian_jog_refuses_what_it_cannot_reach():
    robot, _ = load_robot("planar2")
    q = (0.0, 0.0)  # stretched out: can't go further along X
    move = cartesian_move(robot, q, move_pose(robot.kinematics.pose(q), 0, 0.1))
    assert not move.moved and move.q == q
    assert move.reason == "out of reach (closest found 0.1 m away)"


def test_quintic_blend():
    assert quintic(0) == 0 and quintic(1) == 1 and quintic(0.5) == 0.5
    h = 1e-6
    assert abs(quintic(h) / h) < 1e-6 and abs((1 - quintic(1 - h)) / h) < 1e-6
    values = [quintic(t / 100) for t in range(101)]
    assert values == sorted(values)
    assert interpolate((0, 10), (10, 30), 1.0) == (10, 30)
    assert interpolate((0, 10), (10, 30), 0.5) == (5, 20)


def test_prismatic_and_modified_jacobian_columns():
    robot = Robot("P", (Joint("prismatic", 0, 0, 0, 0, -100, 100),), base_z="+x", base_x="+y")
    assert np.allclose(jacobian(robot, (10.0,))[:, 0], (1, 0, 0, 0, 0, 0))

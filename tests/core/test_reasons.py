"""Why IK and Cartesian jogging fail, on the bundled robots: the part that
failed (position or orientation) and the cause (reach, a named joint's limit,
a singularity), each checked against the facts it claims."""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
import pytest

from dhsim_tui.core import DhsimError, Joint, Robot, load_robot, reach
from dhsim_tui.core.analysis.jacobian import dexterity, jacobian
from dhsim_tui.core.ik.numerical import ORIENTATION, POSITION, solve
from dhsim_tui.core.ik.reasons import LIMIT, OUT_OF_REACH, SINGULAR, amount
from dhsim_tui.core.ik.rotation import rotation_error
from dhsim_tui.core.model.orientation import rotx
from dhsim_tui.core.motion.jog import cartesian_move, move_pose

PUMA_WRIST_SINGULAR = (0.0, 45.0, -135.0, 0.0, 0.0, 0.0)  # theta5 = 0


def numbers(text: str) -> list[float]:
    return [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", text)]


def no_noise(reason: str) -> None:
    """Every number a person can read: no exponent, no nan, no inf."""
    assert not re.search(r"\de[-+]?\d|nan|inf", reason), reason


def test_a_reachable_pose_is_solved_with_no_reason():
    robot, _ = load_robot("puma560")
    target = robot.kinematics.pose((20.0, 30.0, -100.0, 10.0, 40.0, 30.0))
    result = solve(robot, target, restarts=20)
    assert result.success and result.reason == "" and result.failed == ""


def test_a_position_beyond_reach_is_out_of_reach_with_the_distance():
    robot, _ = load_robot("puma560")
    target = np.eye(4)
    target[:3, 3] = (5000.0, 0.0, 0.0)
    result = solve(robot, target, restarts=5)
    assert not result.success
    assert (result.failed, result.cause) == (POSITION, OUT_OF_REACH)
    assert result.reason.startswith("out of reach (closest found ")
    no_noise(result.reason)
    shown = numbers(result.reason)[0]
    assert shown == round(result.position_error, 2)
    assert shown >= 5000.0 - reach(robot)  # can't be closer than the reach allows
    reached = robot.kinematics.position(result.q)
    assert math.isclose(np.linalg.norm(np.subtract(reached, (5000, 0, 0))), result.position_error)


@pytest.mark.parametrize("name", ["puma560", "panda", "cobra600", "stanford", "gantry"])
@pytest.mark.parametrize("position_only", [True, False])
def test_a_target_past_any_reach_is_out_of_reach_not_a_limit(name, position_only):
    """Farther from frame 0 than the links laid end to end: no joint's limit
    is to blame, however the closest configuration found happens to sit."""
    robot, _ = load_robot(name)
    links = (
        sum(
            abs(j.a) + max(abs(j.d), abs(j.min + j.offset), abs(j.max + j.offset))
            for j in robot.joints
        )
        + robot.tool.length
    )
    target = np.eye(4)
    target[:3, 3] = robot.kinematics.frames(robot.home)[0][:3, 3] + (3 * links, 0.0, 0.0)
    result = solve(robot, target, robot.home, restarts=30, position_only=position_only)
    assert not result.success
    assert (result.failed, result.cause, result.limited) == (POSITION, OUT_OF_REACH, ())
    assert result.reason.startswith("out of reach (closest found ")
    robot.check_q(result.q)


def test_a_jog_past_the_reach_says_out_of_reach():
    robot, _ = load_robot("planar2")
    q = (0.0, 0.0)  # stretched out along X
    move = cartesian_move(robot, q, move_pose(robot.kinematics.pose(q), 0, 0.01))
    assert not move.moved and move.reason == "out of reach (closest found 0.01 m away)"


def test_a_scara_asked_to_tilt_reaches_the_position_and_names_the_orientation():
    robot, _ = load_robot("cobra600")
    target = robot.kinematics.pose((10.0, 20.0, 50.0, 0.0))
    target[:3, :3] = target[:3, :3] @ rotx(30.0)
    result = solve(robot, target, restarts=20)
    assert (result.failed, result.cause) == (ORIENTATION, "no joint")
    assert result.reason == (
        "position reached, but the orientation is 30 deg away: "
        "this arm cannot turn the tool that way"
    )
    pose = robot.kinematics.pose(result.q)  # the claim: the position is reached
    assert np.linalg.norm(pose[:3, 3] - target[:3, 3]) < 1e-6 * reach(robot)
    assert math.isclose(math.degrees(result.orientation_error), 30.0, abs_tol=1e-6)


def test_a_puma_wrist_at_its_limit_names_the_joint_not_the_reach():
    robot, _ = load_robot("puma560")
    q = (0.0, 45.0, -135.0, 0.0, 99.5, 0.0)  # Th5 0.5 deg short of its limit 100
    target = move_pose(robot.kinematics.pose(q), 4, -10.0)  # tilt on, about the tool's y
    result = solve(robot, target, q)  # followed from here, as a jog does
    assert (result.failed, result.cause) == (ORIENTATION, LIMIT)
    assert result.limited == ((4, True),)
    assert result.reason.startswith("position reached, but the orientation is ")
    assert result.reason.endswith(" deg away: Th5 is at its limit 100 deg")
    no_noise(result.reason)
    assert result.q[4] == pytest.approx(100.0)  # the claim: Th5 sits on its limit
    pose = robot.kinematics.pose(result.q)
    assert np.linalg.norm(pose[:3, 3] - target[:3, 3]) < 1e-6 * reach(robot)
    turned = math.degrees(np.linalg.norm(rotation_error(target[:3, :3], pose[:3, :3])))
    assert numbers(result.reason)[0] == round(turned, 2)
    move = cartesian_move(robot, q, target)
    assert not move.moved and move.reason == "Th5 is at its limit 100 deg"
    along = cartesian_move(robot, q, move_pose(robot.kinematics.pose(q), 0, -10.0))
    assert along.reason == "the tool can't keep its orientation there: Th5 is at its limit 100 deg"


def test_stanford_d3_at_its_limit_is_a_limit_not_a_singularity():
    robot, _ = load_robot("stanford")
    q = robot.home  # d3 = 304.8, its minimum; the arm points straight up
    assert q[2] == robot.joints[2].min
    down = move_pose(robot.kinematics.pose(q), 2, -10.0)  # world Z: along d3, inwards
    move = cartesian_move(robot, q, down)
    assert not move.moved and move.q == q
    assert move.reason == "d3 is at its limit 304.8 mm"
    result = solve(robot, down, q)
    assert (result.failed, result.cause, result.limited) == (POSITION, LIMIT, ((2, False),))
    assert result.reason == (
        "not reachable within the joint limits: d3 is at its limit 304.8 mm; "
        "closest found 10 mm away"
    )
    up = cartesian_move(robot, q, move_pose(robot.kinematics.pose(q), 2, 10.0))
    assert up.moved  # outwards is free


def test_the_puma_wrist_singularity_is_called_singular():
    robot, _ = load_robot("puma560")
    q = PUMA_WRIST_SINGULAR
    assert dexterity(robot, q).singular
    target = move_pose(robot.kinematics.pose(q), 1, 1.0)  # world Y: along the lost direction
    move = cartesian_move(robot, q, target)
    assert not move.moved
    assert move.reason == "singular here: the arm can't move the tool that way from this pose"
    # the claim is true: the target is reachable, but only by a sudden turn of the wrist
    far = solve(robot, target, q, restarts=10)
    assert far.success
    assert max(abs(a - b) for a, b in zip(far.q, q, strict=True)) > 30.0
    # and the same step from a healthy wrist just moves
    healthy = (0.0, 45.0, -135.0, 0.0, 45.0, 0.0)
    assert cartesian_move(robot, healthy, move_pose(robot.kinematics.pose(healthy), 1, 1.0)).moved


def test_a_stretched_arm_moving_inwards_is_singular_and_the_target_reachable():
    robot, _ = load_robot("planar2")
    q = (0.0, 0.0)
    target = move_pose(robot.kinematics.pose(q), 0, -0.01)
    move = cartesian_move(robot, q, target)
    assert move.reason == "singular here: the arm can't move the tool that way from this pose"
    assert solve(robot, target, position_only=True, restarts=5).success
    result = solve(robot, target, q, position_only=True)
    assert result.success or result.cause == SINGULAR


@pytest.mark.parametrize(
    ("value", "decimals", "text"),
    [
        (5e-14, 2, "0"),
        (0.0, 2, "0"),
        (120.0, 2, "120"),
        (304.8, 2, "304.8"),
        (0.00052, 2, "0.00052"),
        (0.0049, 2, "0.0049"),
        (4122.987, 2, "4122.99"),
        (-50.0, 2, "-50"),
        (1.5e-9, 5, "0.0000000015"),
    ],
)
def test_amounts_are_rounded_as_people_read_them(value, decimals, text):
    assert amount(value, decimals) == text


def test_no_amount_is_written_with_an_exponent():
    for value in np.logspace(-12, 6, 200):
        assert "e" not in amount(float(value), 2)
    assert "nan" not in amount(float("nan"), 2)


def tiny_robots() -> list[Robot]:
    """Arms with the smallest link lengths the model accepts (and the tiny
    values it may refuse, such as 1e-300, skipped when refused)."""
    robots = []
    for tiny in (1e-300, 1e-30, 1e-12, 1e-9, 1e-6, 1e-5, 1e-3):
        try:
            robots.append(Robot("tiny", (Joint(a=tiny), Joint(a=tiny))))
            robots.append(Robot("tiny+long", (Joint(a=100.0), Joint(a=tiny, d=tiny))))
            robots.append(
                Robot("tiny slide", (Joint("prismatic", 0.0, 0.0, tiny, 90.0, 0.0, tiny),))
            )
        except DhsimError:
            continue
    robots.append(Robot("zero", (Joint(), Joint(alpha=90.0))))  # no length at all
    return robots


def test_tiny_and_zero_lengths_give_no_warnings_and_no_nan():
    robots = tiny_robots()
    assert len(robots) >= 4
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for robot in robots:
            q = tuple(0.5 * (lo + hi) for lo, hi in zip(robot.lower, robot.upper, strict=True))
            jacobian(robot, q)
            dexterity(robot, q)
            for xyz in ((100.0, 50.0, 0.0), (0.0, 0.0, 0.0), (1e-6, 0.0, 0.0)):
                target = np.eye(4)
                target[:3, 3] = xyz
                for position_only in (True, False):
                    result = solve(robot, target, position_only=position_only, restarts=2)
                    no_noise(result.reason)
                    assert all(math.isfinite(v) for v in result.q)
            for row in range(6):
                move = cartesian_move(robot, q, move_pose(robot.kinematics.pose(q), row, 1.0))
                no_noise(move.reason)

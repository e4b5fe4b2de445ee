"""`dhsim convert`: the same arm in the other D-H convention.

The converted robot's forward kinematics is compared with the textbook
product of the *original* robot (tests/robot_strategies.py), at home and at
random joint values: the same pose at every joint value, base, tool,
offsets and limits included.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from robot_strategies import random_q, reference_pose, robots

from dhsim_tui.core.files.library import bundled_names, load_robot
from dhsim_tui.core.interop.convert import convert, rpy_of
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.orientation import rpy_matrix
from dhsim_tui.core.model.robot import Tool
from dhsim_tui.core.model.units import min_length

SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _size(robot) -> float:
    lengths = [abs(j.a) + abs(j.d) + max(abs(j.min), abs(j.max)) for j in robot.joints]
    return sum(lengths) + sum(abs(v) for v in (*robot.base_xyz, *robot.tool.xyz)) + 1.0


def _same_arm(original, converted, seed: int = 0) -> None:
    rng = np.random.default_rng(seed)
    # a length below a nanometre cannot be held, so it may become 0
    tol = max(1e-9 * _size(original), min_length(original.units))
    for q in [original.home] + [random_q(original, rng) for _ in range(10)]:
        np.testing.assert_allclose(
            converted.kinematics.pose(q), reference_pose(original, q), rtol=0, atol=tol
        )


def _other(convention: str) -> str:
    return "modified" if convention == "standard" else "standard"


@pytest.mark.parametrize("name", bundled_names())
def test_every_bundled_robot_converts_exactly_and_back(name):
    robot, _ = load_robot(name)
    other = convert(robot, _other(robot.convention))
    assert other.convention == _other(robot.convention)
    _same_arm(robot, other)
    back = convert(other, robot.convention)
    assert back == robot  # the same table, base, tool, limits and poses
    # what joint values mean is unchanged: limits, poses and home are kept
    assert (other.lower, other.upper, other.poses, other.home) == (
        robot.lower,
        robot.upper,
        robot.poses,
        robot.home,
    )


@pytest.mark.slow  # a long hypothesis run
@SETTINGS
@given(robot=robots())
def test_random_robots_convert_exactly(robot):
    other = convert(robot, _other(robot.convention))
    _same_arm(robot, other)
    back = convert(other, robot.convention)
    _same_arm(robot, back, seed=1)


def _screw_tool(robot):
    """The tool as a screw along z (a flange offset and a turn about z): the
    modified table has no place for the last row's a, alpha, so they ride at
    the front of the tool; only in front of a z screw can they be told apart
    again. With any other tool they come back inside the tool (the forward
    kinematics stays the same: test_random_robots_convert_exactly)."""
    z, yaw = robot.tool.xyz[2], robot.tool.rpy[2]
    return replace(robot, tool=Tool((0.0, 0.0, z), (0.0, 0.0, yaw)))


@pytest.mark.slow  # a long hypothesis run
@SETTINGS
@given(robot=robots().filter(lambda r: r.convention == "standard").map(_screw_tool))
def test_standard_to_modified_to_standard_gives_the_same_table(robot):
    back = convert(convert(robot, "modified"), "standard")
    for before, after in zip(robot.joints, back.joints, strict=True):
        assert after.type == before.type
        assert (after.theta, after.d, after.offset, after.min, after.max) == (
            before.theta,
            before.d,
            before.offset,
            before.min,
            before.max,
        )
        assert after.a == pytest.approx(before.a, abs=1e-9 * _size(robot))
        assert (
            after.alpha == pytest.approx(before.alpha, abs=1e-9)
            or abs(abs(after.alpha - before.alpha) - 360.0) < 1e-9
        )
    assert back.base_xyz == robot.base_xyz and back.base_rpy == robot.base_rpy


def test_the_puma_in_modified_form_matches_craigs_table():
    """Standard → modified shifts a and alpha down one row (reference §1)."""
    puma, _ = load_robot("puma560")
    modified = convert(puma, "modified")
    assert [(j.a, j.alpha) for j in modified.joints] == [(0.0, 0.0)] + [
        (j.a, j.alpha) for j in puma.joints[:-1]
    ]
    assert modified.tool == puma.tool  # the last row's a, alpha are 0: nothing to move


def test_a_first_modified_link_moves_into_the_base():
    robot, _ = load_robot("puma560_modified")
    robot = replace(
        robot, joints=(replace(robot.joints[0], a=100.0, alpha=30.0), *robot.joints[1:])
    )
    standard = convert(robot, "standard")
    assert standard.base_z == robot.base_z and standard.base_height == robot.base_height
    assert standard.base_xyz == (100.0, 0.0, 0.0) and standard.base_rpy == (30.0, 0.0, 0.0)
    _same_arm(robot, standard)


def test_the_same_convention_is_no_change_and_a_bad_one_is_refused():
    robot, _ = load_robot("planar2")
    assert convert(robot, robot.convention) is robot
    with pytest.raises(DhsimError, match="convention 'craig': expected standard or modified"):
        convert(robot, "craig")


@pytest.mark.parametrize("pitch", [90.0, -90.0, 89.9999999, -89.99999])
def test_rpy_rebuilds_a_rotation_at_and_near_gimbal_lock(pitch):
    for roll, yaw in ((30.0, -40.0), (0.0, 0.0), (170.0, 100.0)):
        r = rpy_matrix(roll, pitch, yaw)
        np.testing.assert_allclose(rpy_matrix(*rpy_of(r)), r, rtol=0, atol=1e-12)

"""One arm, one reach (issue 17): the farthest the tool gets from frame 0's
origin within the limits, the same in either convention, found by a method
that converges; checked against closed forms, samples and the conversion."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import reference_frames
from hypothesis import given, settings
from robot_strategies import robots

from dhsim_tui.core import bundled_names, load_robot
from dhsim_tui.core.analysis.workspace import arm_reach, reach, sample_summary, work_area
from dhsim_tui.core.files.library import describe
from dhsim_tui.core.interop.convert import convert


def test_the_puma_reaches_as_far_as_its_straightened_arm_by_hand():
    """Shoulder offset 150.05 across, upper arm 431.8 and forearm
    (431.8, 20.3) in line: the farthest point, worked out by hand."""
    puma, _ = load_robot("puma560")
    forearm = math.hypot(431.8, 20.3)
    assert arm_reach(puma) == pytest.approx(math.hypot(150.05, 431.8 + forearm), rel=1e-9)
    assert "reach 877.01 mm" in describe(puma)


def test_a_gantry_reaches_its_far_corner_and_a_planar_arm_its_length():
    gantry, _ = load_robot("gantry")
    assert arm_reach(gantry) == pytest.approx(math.sqrt(1000**2 + 800**2 + 500**2), rel=1e-12)
    planar, _ = load_robot("planar2")
    assert arm_reach(planar) == pytest.approx(2.0, rel=1e-12)


@pytest.mark.parametrize("name", bundled_names())
def test_the_reach_is_the_same_in_either_convention_and_no_sample_beats_it(name):
    robot, _ = load_robot(name)
    found = arm_reach(robot)
    other = convert(robot, "modified" if robot.convention == "standard" else "standard")
    assert arm_reach(other) == pytest.approx(found, rel=1e-9)
    sampled = sample_summary(robot, 100_000, seed=5)
    assert sampled.reach_reached <= found * (1 + 1e-12) and found <= reach(robot) * (1 + 1e-12)
    # what dhsim workspace prints is this reach, and its own samples come close
    assert sampled.reach == found
    assert sampled.reach_reached >= 0.97 * found
    assert work_area(robot).xmax - robot.base_xyz[0] == pytest.approx(found + robot.mm(30.0))


def test_the_two_bundled_pumas_have_one_reach():
    """The same arm (Armstrong-Khatib-Burdick's lengths differ from the
    standard table's by up to 1.3 mm): 1034 and 1222 mm before, one now."""
    standard, _ = load_robot("puma560")
    modified, _ = load_robot("puma560_modified")
    assert arm_reach(modified) == pytest.approx(arm_reach(standard), rel=0.002)


@settings(max_examples=25, deadline=None)
@given(robots(max_joints=5))
def test_no_joint_vector_within_the_limits_gets_further(robot):
    """Against the textbook FK (conftest): random vectors, and every corner
    of the limits box for small arms, never beat the reach found."""
    found = arm_reach(robot)
    rng = np.random.default_rng(3)
    low, high = np.array(robot.lower), np.array(robot.upper)
    qs = rng.uniform(low, high, size=(400, robot.dof))
    if robot.dof <= 4:
        corners = np.array(np.meshgrid(*zip(low, high, strict=True))).reshape(robot.dof, -1).T
        qs = np.vstack([qs, corners])
    origin = reference_frames(robot, robot.home)[0][:3, 3]
    for q in qs:
        tip = reference_frames(robot, q)[-1][:3, 3]
        assert np.linalg.norm(tip - origin) <= found * (1 + 1e-9) + 1e-9

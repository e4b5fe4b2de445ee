"""Per-joint offsets and the general base transform (issue 10, the model).

The relation: the D-H variable is the joint value plus the offset
(theta = q + offset, d = q + offset); the table's theta/d is the variable at
home, so home q = theta - offset. Frame 0 = translate(base_xyz) ·
axes(base_z, base_x) · rpy(base_rpy). Every kinematic check compares with
the textbook matrix product in tests/robot_strategies.py.
"""

from __future__ import annotations

import shutil
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from robot_strategies import random_q, reference_frames, reference_pose, robots

from dhsim_tui.core.analysis.workspace import work_area
from dhsim_tui.core.files import robotfile
from dhsim_tui.core.files.library import bundled_path, load_robot
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Joint, Robot
from dhsim_tui.scene.wireframe import build_wireframe

SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _close(a: np.ndarray, b: np.ndarray, size: float) -> bool:
    return bool(np.allclose(a, b, rtol=0, atol=1e-9 * max(size, 1.0)))


def _size(robot: Robot) -> float:
    return sum(abs(j.a) + abs(j.d) + max(abs(j.min), abs(j.max)) for j in robot.joints) + 3000


@pytest.mark.slow  # a long hypothesis run
@SETTINGS
@given(robot=robots())
def test_fk_equals_the_textbook_product_with_offsets_and_base(robot):
    rng = np.random.default_rng(7)
    size = _size(robot)
    for q in [robot.home] + [random_q(robot, rng) for _ in range(3)]:
        expected = reference_frames(robot, q)
        assert _close(robot.kinematics.pose(q), expected[-1], size)
        frames = robot.kinematics.frames(q)
        assert _close(frames[: robot.dof + 1], np.array(expected[: robot.dof + 1]), size)
        assert _close(frames[-1], expected[-1], size)


@pytest.mark.slow  # a long hypothesis run
@SETTINGS
@given(robot=robots())
def test_batch_fk_equals_the_textbook_product(robot):
    rng = np.random.default_rng(3)
    qs = np.array([random_q(robot, rng) for _ in range(5)])
    batch = robot.kinematics.batch(qs)
    for q, pose in zip(qs, batch, strict=True):
        assert _close(pose, reference_pose(robot, q), _size(robot))


def test_compiled_chain_equals_the_stepwise_one_with_offsets():
    robot, _ = load_robot("puma560")
    robot = replace(
        robot,
        joints=tuple(
            replace(j, offset=10.0 * i, theta=10.0 * i) for i, j in enumerate(robot.joints)
        ),
        base_xyz=(1.0, 2.0, 3.0),
        base_rpy=(10.0, 20.0, 30.0),
    )
    q = [5.0, 10.0, -20.0, 30.0, 40.0, 50.0]
    first = robot.kinematics.pose(q)
    for _ in range(40):  # past COMPILE_AFTER: the whole chain is compiled
        robot.kinematics.pose(q)
    assert np.array_equal(robot.kinematics.pose(q), first)
    assert _close(first, reference_pose(robot, q), 1000)


def test_an_offset_shifts_the_joint_value_not_the_arm_at_home():
    robot, _ = load_robot("puma560")
    shifted = editing.set_joint_field(robot, 1, "offset", -90.0)
    # the table's theta is still the D-H angle at home, so home is drawn the same ...
    assert shifted.joints[1].theta == 0.0 and shifted.home[1] == 90.0
    assert np.array_equal(shifted.kinematics.pose(shifted.home), robot.kinematics.pose(robot.home))
    # ... and the joint value q = 0 now means theta = -90
    q = list(robot.home)
    expected = robot.kinematics.pose([q[0], -90.0, *q[2:]])
    assert _close(shifted.kinematics.pose(q), expected, 1000)


def test_limits_and_poses_are_in_joint_values():
    robot = Robot(
        name="one",
        joints=(Joint(theta=100.0, offset=90.0, min=-20.0, max=20.0),),
        poses=(("p", (15.0,)),),
    )
    assert robot.home == (10.0,)
    with pytest.raises(DhsimError, match=r"home value 50 deg \(theta - offset\) is outside"):
        Robot(name="one", joints=(Joint(theta=140.0, offset=90.0, min=-20.0, max=20.0),))
    with pytest.raises(DhsimError, match="outside its limits"):
        robot.check_q([25.0])


def test_a_prismatic_offset_is_a_length():
    with pytest.raises(DhsimError, match=r"joints\[1\].offset: .* too small"):
        Robot(name="p", joints=(Joint(type="prismatic", offset=1e-9, d=0.5, min=-1, max=1),))
    robot = Robot(
        name="p", joints=(Joint(type="prismatic", d=150.0, offset=100.0, min=0, max=300),)
    )
    in_cm = editing.set_units(robot, "cm")
    assert in_cm.joints[0].offset == 10.0 and in_cm.joints[0].d == 15.0 and in_cm.home == (5.0,)
    assert in_cm.kinematics.position([20.0]) == (0.0, 0.0, 30.0)  # d = q + offset = 30 cm
    assert robot.kinematics.position([200.0]) == (0.0, 0.0, 300.0)


def test_toggling_the_type_drops_the_offset():
    robot = Robot(name="t", joints=(Joint(theta=30.0, offset=30.0),))
    toggled = editing.toggle_type(robot, 0)
    assert toggled.joints[0].type == "prismatic" and toggled.joints[0].offset == 0.0


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("base_xyz", (0.0, float("nan"), 0.0), r"base_xyz\[2\]"),
        ("base_rpy", (0.0, 0.0), "base_rpy: expected 3 numbers, got 2"),
        ("base_xyz", "abc", "base_xyz: expected 3 numbers"),
        ("base_xyz", (1e-12, 0.0, 0.0), r"base_xyz\[1\]: .* too small"),
    ],
)
def test_a_bad_base_is_refused_naming_the_field(field, value, message):
    robot, _ = load_robot("planar2")
    with pytest.raises(DhsimError, match=message):
        replace(robot, **{field: value})


def test_the_shorthand_base_still_means_what_it_did():
    robot, _ = load_robot("scara_pedestal")
    assert robot.base_is_shorthand
    frames = robot.kinematics.frames(robot.home)
    assert np.array_equal(frames[0][:3, 3], [0.0, 0.0, 0.0])
    wire = build_wireframe(robot, frames)
    assert wire.floor_z == -robot.base_height
    assert np.array_equal(wire.pedestal, [[0, 0, -robot.base_height], [0, 0, 0]])


def test_a_moved_base_moves_the_arm_the_pedestal_and_the_work_area():
    robot, _ = load_robot("puma560")
    moved = editing.set_base(robot, xyz=(100.0, -50.0, 20.0), rpy=(0.0, 0.0, 90.0))
    q = robot.home
    expected = reference_pose(moved, q)
    assert _close(moved.kinematics.pose(q), expected, 1000)
    wire = build_wireframe(moved, moved.kinematics.frames(q))
    assert np.allclose(wire.pedestal, [[100, -50, -671.83], [100, -50, 20]])
    area, before = work_area(moved), work_area(robot)
    assert area.xmin == pytest.approx(before.xmin + 100)
    assert area.ymax == pytest.approx(before.ymax - 50)
    assert area.zmin == -671.83 and area.zmax == pytest.approx(before.zmax + 20)


def test_offsets_and_base_survive_a_save_and_keep_the_comments(tmp_path):
    path = tmp_path / "puma.toml"
    shutil.copy(bundled_path("puma560"), path)
    robot, stamp = robotfile.load_with_stamp(path)
    before = path.read_text()
    changed = editing.set_joint_field(robot, 2, "offset", 12.5)
    changed = editing.set_base(changed, xyz=(1.0, 2.0, 3.0), rpy=(0.0, 90.0, 0.0))
    robotfile.save(changed, path, expect=stamp)
    after = path.read_text()
    assert robotfile.load(path) == changed
    removed = [line for line in before.splitlines() if line not in after.splitlines()]
    added = [line for line in after.splitlines() if line not in before.splitlines()]
    assert removed == []  # every comment and value line is still there
    assert sorted(added) == sorted(
        ["base_xyz = [1.0, 2.0, 3.0]", "base_rpy = [0.0, 90.0, 0.0]", "offset = 12.5"]
    )


def test_a_file_without_offsets_or_base_is_written_without_them():
    robot, _ = load_robot("puma560")
    text = robotfile.dumps(robot)
    assert "offset" not in text and "base_xyz" not in text and "base_rpy" not in text


@pytest.mark.slow  # a long hypothesis run
@SETTINGS
@given(robot=robots())
def test_any_robot_reads_back_equal(robot):
    assert robotfile.loads(robotfile.dumps(robot)) == robot


def test_a_bad_offset_in_a_file_names_it():
    text = bundled_path("puma560").read_text().replace("max = 160.0", 'max = 160.0\noffset = "x"')
    with pytest.raises(DhsimError, match=r"joints\[1\].offset: expected a number"):
        robotfile.loads(text, "f.toml")

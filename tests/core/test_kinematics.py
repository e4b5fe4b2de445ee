"""Forward kinematics against the reference's figures and independent computations."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import random_q, reference_frames

from dhsim_tui.core import DhsimError, Joint, Robot, load_robot, reach, work_area
from dhsim_tui.core.analysis.workspace import arm_reach
from dhsim_tui.core.model.orientation import (
    base_rotation,
    oat_from_matrix,
    oat_matrix,
    rpy_from_matrix,
    rpy_matrix,
)
from dhsim_tui.core.model.robot import AXES

# reference §5: joints (deg) -> exact X Y Z (mm), O A T (deg)
PUMA_TABLE = [
    ((0, 0, 0, 0, 0, 0), (452.10, -150.05, 431.80), (90, -90, 0)),
    ((30, 30, 30, 30, 30, 30), (83.82, -124.87, 449.38), (-45.50, -3.33, -124.29)),
    ((90, 90, 90, 90, 90, 90), (150.05, -20.30, 0.00), (90, 0, 90)),
    ((0, 30, 45, 60, 90, 0), (-37.88, -150.05, 347.27), (-8.50, 28.88, -107.19)),
    ((0, 90, 0, 45, 0, 60), (-431.80, -150.05, 452.10), (-90, 0, -75)),
    ((0, 90, -90, 0, 0, 0), (20.30, -150.05, 863.60), (90, -90, 0)),
]


def angle_diff(a, b):
    return abs((a - b + 180.0) % 360.0 - 180.0)


@pytest.mark.parametrize(("q", "xyz", "oat"), PUMA_TABLE)
def test_puma_reproduces_reference_table(puma, q, xyz, oat):
    pose = puma.kinematics.end_effector(q)
    assert np.allclose(pose.xyz, xyz, atol=0.05)
    assert all(angle_diff(a, b) <= 0.01 for a, b in zip(pose.oat, oat, strict=True)), pose.oat


def test_paper_table_within_its_own_rounding(puma):
    """The paper's Toolbox column (metres, 3 decimals) agrees to half a millimetre."""
    toolbox = {
        (0, 0, 0, 0, 0, 0): (0.452, -0.15, 0.432),
        (30,) * 6: (0.084, -0.125, 0.449),
        (90,) * 6: (0.15, -0.020, 0.0),
        (0, 30, 45, 60, 90, 0): (-0.038, -0.150, 0.347),
        (0, 90, 0, 45, 0, 60): (-0.432, -0.150, 0.452),
    }
    for q, metres in toolbox.items():
        assert np.allclose(np.array(puma.kinematics.position(q)) / 1000.0, metres, atol=0.0006)


def test_matches_plain_matrix_product_on_every_bundled_robot(bundled, rng):
    for _ in range(25):
        q = random_q(bundled, rng)
        expected = reference_frames(bundled, q)
        assert np.allclose(bundled.kinematics.frames(q), expected, atol=1e-9)
        assert np.allclose(bundled.kinematics.pose(q), expected[-1], atol=1e-9)
        assert np.allclose(bundled.kinematics.position(q), expected[-1][:3, 3], atol=1e-9)


def test_batch_matches_plain_product(bundled, rng):
    qs = random_q(bundled, rng, count=40_000)  # more than one internal chunk
    batch = bundled.kinematics.batch(qs)
    assert batch.shape == (40_000, 4, 4)
    for i in (0, 1, 16383, 16384, 39_999):
        assert np.allclose(batch[i], reference_frames(bundled, qs[i])[-1], atol=1e-9)


def test_batch_rejects_wrong_shape(puma):
    with pytest.raises(DhsimError, match=r"shape \(N, 6\)"):
        puma.kinematics.batch(np.zeros((3, 5)))


def test_wrong_joint_count_is_a_clear_error(puma):
    with pytest.raises(DhsimError, match="6 joint values"):
        puma.kinematics.pose((0, 0, 0))


def test_rotations_are_proper(bundled, rng):
    for _ in range(20):
        for frame in bundled.kinematics.frames(random_q(bundled, rng)):
            r = frame[:3, :3]
            assert np.allclose(r.T @ r, np.eye(3), atol=1e-12)
            assert math.isclose(np.linalg.det(r), 1.0, abs_tol=1e-12)
            assert np.allclose(frame[3], (0, 0, 0, 1))


def test_revolute_derivative_matches_axis_cross_lever(puma, rng):
    """Finite differences of FK equal z × (p - o) of the joint's axis (standard D-H:
    joint i turns about frame i-1's z)."""
    h = 1e-6
    for _ in range(10):
        q = random_q(puma, rng)
        frames = puma.kinematics.frames(q)
        p = frames[-1][:3, 3]
        for i in range(puma.dof):
            step = np.array(q, float)
            step[i] += h
            numeric = (np.array(puma.kinematics.position(step)) - p) / math.radians(h)
            z, o = frames[i][:3, 2], frames[i][:3, 3]
            assert np.allclose(numeric, np.cross(z, p - o), atol=1e-3)


def test_prismatic_step_moves_next_origin_along_previous_z(rng):
    for name in ("stanford", "cobra600", "gantry", "scara_pedestal"):
        robot, _ = load_robot(name)
        q = random_q(robot, rng)
        for i, joint in enumerate(robot.joints):
            if joint.is_revolute:
                continue
            moved = np.array(q, float)
            step = 0.25 * (joint.max - q[i])
            moved[i] += step
            before = robot.kinematics.frames(q)
            after = robot.kinematics.frames(moved)
            delta = after[i + 1][:3, 3] - before[i + 1][:3, 3]
            assert np.allclose(delta, step * before[i][:3, 2], atol=1e-9)
            assert np.allclose(after[i + 1][:3, :3], before[i + 1][:3, :3])


def test_modified_prismatic_moves_along_own_z():
    robot = Robot(
        "modified P",
        (Joint(alpha=90.0, a=100.0), Joint("prismatic", 0.0, 0.0, 50.0, -90.0, -400, 400)),
        convention="modified",
    )
    before = robot.kinematics.frames((10.0, 0.0))
    after = robot.kinematics.frames((10.0, 30.0))
    assert np.allclose(after[2][:3, 3] - before[2][:3, 3], 30.0 * before[2][:3, 2])


def test_gantry_tool_is_at_its_joint_values():
    robot, _ = load_robot("gantry")
    assert np.allclose(robot.kinematics.position((120.0, 345.0, 67.0)), (120.0, 345.0, 67.0))


def test_base_rotation_is_proper_for_every_perpendicular_pair():
    pairs = [(z, x) for z in AXES for x in AXES if z[1] != x[1]]
    assert len(pairs) == 24
    for z, x in pairs:
        b = base_rotation(z, x)
        assert math.isclose(np.linalg.det(b), 1.0)
        unit = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}
        sign_x = 1 if x[0] == "+" else -1
        sign_z = 1 if z[0] == "+" else -1
        assert np.allclose(b[:, 0], sign_x * np.array(unit[x[1]]))
        assert np.allclose(b[:, 2], sign_z * np.array(unit[z[1]]))


def test_ceiling_mount_flips_y_and_z(puma, rng):
    """Frame 0's z down and x along +x: B = diag(1, -1, -1) (reference §3)."""
    hanging = replace(puma, base_z="-z", base_x="+x")
    for _ in range(10):
        q = random_q(puma, rng)
        up = np.array(puma.kinematics.position(q))
        down = np.array(hanging.kinematics.position(q))
        assert np.allclose(down, up * (1, -1, -1))


def test_base_height_moves_floor_not_xyz(puma, rng):
    q = random_q(puma, rng)
    low = replace(puma, base_height=0.0)
    high = replace(puma, base_height=250.0)
    assert low.kinematics.position(q) == high.kinematics.position(q)
    assert work_area(low).zmin == 0.0
    assert work_area(high).zmin == -250.0


def test_reach_and_work_area_follow_the_seed(puma):
    """The seed's reach is the sum of the link lengths; the work area is
    30 mm round the arm's own reach (issue 17: the sum is only a bound)."""
    assert math.isclose(reach(puma), 431.8 + 150.05 + 20.3 + 431.8)
    area = work_area(puma)
    side = arm_reach(puma) + 30.0
    assert side < reach(puma)
    assert (area.xmin, area.xmax, area.ymin, area.ymax, area.zmax) == (
        -side,
        side,
        -side,
        side,
        side,
    )
    assert area.zmin == -puma.base_height


def test_reach_counts_prismatic_range_tool_and_units():
    stanford, _ = load_robot("stanford")
    assert math.isclose(reach(stanford), 412 + 154 + 1270 + 263)
    planar, _ = load_robot("planar2")
    assert planar.units == "m"
    assert math.isclose(work_area(planar).xmax, 2.0 + 0.03)  # straight out: the same


def test_reach_bounds_every_sampled_position(bundled, rng):
    qs = random_q(bundled, rng, count=2000)
    distances = np.linalg.norm(bundled.kinematics.batch(qs)[:, :3, 3], axis=1)
    assert distances.max() <= reach(bundled) + 1e-9


# --- orientation read-outs (reference §4) ---------------------------------


def test_oat_worked_example():
    expected = np.array(
        [[0.5732, 0.7392, 0.3536], [0.7392, -0.2803, -0.6124], [-0.3536, 0.6124, -0.7071]]
    )
    assert np.allclose(oat_matrix(30, 45, 60), expected, atol=5e-5)
    assert np.allclose(oat_from_matrix(expected), (30, 45, 60), atol=0.01)


def test_oat_reference_orientation():
    r = oat_matrix(0, 0, 0)
    assert np.allclose(r[:, 2], (0, -1, 0))  # approach along world -Y
    assert np.allclose(r[:, 1], (1, 0, 0))  # orientation along +X
    assert np.allclose(r[:, 0], (0, 0, -1))  # normal along -Z
    assert np.allclose(oat_matrix(0, 90, 0)[:, 2], (0, 0, -1))  # A = +90: straight down


def test_oat_is_zyz_euler(rng):
    from dhsim_tui.core.model.orientation import roty, rotz

    for o, a, t in rng.uniform(-180, 180, size=(50, 3)):
        assert np.allclose(oat_matrix(o, a, t), rotz(o - 90) @ roty(a + 90) @ rotz(t))


def test_oat_round_trip_away_from_singularity(rng):
    for o, a, t in zip(
        rng.uniform(-179, 180, 200),
        rng.uniform(-89, 89, 200),
        rng.uniform(-179, 180, 200),
        strict=True,
    ):
        got = oat_from_matrix(oat_matrix(o, a, t))
        assert all(angle_diff(g, e) < 1e-7 for g, e in zip(got, (o, a, t), strict=True))


@pytest.mark.parametrize("a", [90.0, -90.0])
def test_oat_singular_case_takes_o_90(rng, a):
    for o, t in rng.uniform(-180, 180, size=(20, 2)):
        r = oat_matrix(o, a, t)
        got = oat_from_matrix(r)
        assert got[0] == 90.0 and got[1] == a
        assert np.allclose(oat_matrix(*got), r, atol=1e-9)  # same rotation
        assert -180.0 < got[2] <= 180.0


def test_rpy_round_trip_and_matrix(rng):
    for roll, pitch, yaw in zip(
        rng.uniform(-179, 180, 100),
        rng.uniform(-89, 89, 100),
        rng.uniform(-179, 180, 100),
        strict=True,
    ):
        r = rpy_matrix(roll, pitch, yaw)
        assert np.allclose(rpy_from_matrix(r), (roll, pitch, yaw))
    assert np.allclose(rpy_matrix(0, 0, 90) @ (1, 0, 0), (0, 1, 0))
    assert np.allclose(rpy_matrix(90, 0, 0) @ (0, 1, 0), (0, 0, 1))


def test_tool_rotation_applies_rz_ry_rx_order():
    robot = Robot(
        "tool",
        (Joint(),),
        tool=__import__("dhsim_tui.core", fromlist=["Tool"]).Tool(
            xyz=(0.0, 0.0, 100.0), rpy=(10.0, 20.0, 30.0)
        ),
    )
    pose = robot.kinematics.pose((0.0,))
    assert np.allclose(pose[:3, :3], rpy_matrix(10, 20, 30))
    assert np.allclose(pose[:3, 3], (0, 0, 100))
    assert np.allclose(robot.kinematics.end_effector((0.0,)).rpy, (10, 20, 30))

"""`dhsim import`: D-H robots from URDF and CSV, checked against yourdfpy.

Every URDF check compares dhsim's forward kinematics of the imported robot
(degrees and robot units) with yourdfpy's transform of the tip link in the
base link (radians and metres), a URDF implementation independent of ours.
"""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np
import pytest
import yourdfpy
from hypothesis import HealthCheck, given, settings

from dhsim_tui.core.errors import DhsimError, TipNeeded
from dhsim_tui.core.importer import from_csv, from_urdf, import_file
from dhsim_tui.core.library import load_robot
from dhsim_tui.core.model import UNITS, Robot
from tests.robot_strategies import reference_pose
from tests.test_urdf import CASES as URDF_CASES
from tests.test_urdf import random_trees

URDFS = Path(__file__).resolve().parent / "urdfs"
TOL = 1e-9
#: the chains of tests/test_urdf.py (file, tip, base)
CASES = URDF_CASES


def _yourdfpy(text: str) -> yourdfpy.URDF:
    return yourdfpy.URDF.load(
        io.BytesIO(text.encode("utf-8")), build_scene_graph=True, load_meshes=False
    )


def _moving_names(urdf: yourdfpy.URDF, base: str, tip: str) -> list[str]:
    """The moving joints from base to tip, in order, by yourdfpy's own tree."""
    names = []
    link = tip
    parents = {j.child: j for j in urdf.robot.joints}
    while link != base:
        joint = parents[link]
        if joint.type != "fixed":
            names.append(joint.name)
        link = joint.parent
    return names[::-1]


def _si(robot: Robot, q) -> np.ndarray:
    """Joint values in radians and metres."""
    scale = UNITS[robot.units] / 1000.0
    return np.array(
        [
            math.radians(v) if j.is_revolute else v * scale
            for j, v in zip(robot.joints, q, strict=True)
        ]
    )


def check_against_yourdfpy(robot: Robot, text: str, base: str, tip: str, samples: int = 20):
    urdf = _yourdfpy(text)
    names = _moving_names(urdf, base, tip)
    assert len(names) == robot.dof
    rng = np.random.default_rng(11)
    metres = UNITS[robot.units] / 1000.0
    qs = [np.array(robot.home)] + [rng.uniform(robot.lower, robot.upper) for _ in range(samples)]
    for q in qs:
        urdf.update_cfg(dict(zip(names, _si(robot, q), strict=True)))
        theirs = urdf.get_transform(frame_to=tip, frame_from=base)
        ours = robot.kinematics.pose(q)
        np.testing.assert_allclose(ours[:3, 3] * metres, theirs[:3, 3], rtol=0, atol=TOL)
        np.testing.assert_allclose(ours[:3, :3], theirs[:3, :3], rtol=0, atol=TOL)
        # and the robot's own chain agrees with the textbook product
        np.testing.assert_allclose(ours, reference_pose(robot, q), rtol=0, atol=TOL * 1e3)


@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize("units", ["m", "mm", "in"])
@pytest.mark.parametrize(("name", "tip", "base"), CASES)
def test_hand_written_urdfs_import_exactly(name, tip, base, convention, units):
    path = URDFS / name
    result = import_file(path, tip=tip, base=base, convention=convention, units=units)
    robot = result.robot
    assert robot.convention == convention and robot.units == units
    text = path.read_text()
    urdf = _yourdfpy(text)
    base_link = base or urdf.base_link
    tip_link = tip or next(
        link.name
        for link in urdf.robot.links
        if all(j.parent != link.name for j in urdf.robot.joints)
    )
    check_against_yourdfpy(robot, text, base_link, tip_link)


def test_a_ur5_imports_to_a_dh_table_that_reproduces_it():
    """The issue's 'done when': a standard 6-axis arm, random joint values, 1e-9."""
    result = import_file(URDFS / "ur5.urdf", tip="tool0", units="mm")
    robot = result.robot
    assert robot.type_string == "RRRRRR"
    # the UR5's published lengths appear in the table (mm)
    lengths = sorted({abs(v) for j in robot.joints for v in (j.a, j.d) if v})
    for published in (89.159, 425.0, 392.25, 109.15, 94.65):
        assert any(abs(v - published) < 1e-6 for v in lengths), published
    check_against_yourdfpy(robot, (URDFS / "ur5.urdf").read_text(), "world", "tool0", 200)
    assert any("matches the URDF" in note for note in result.notes)


def test_joint_values_mean_the_same_on_both_sides():
    """q = 0 in dhsim is the URDF's zero pose, whatever the D-H angles are."""
    robot = import_file(URDFS / "ur5.urdf", tip="tool0").robot
    assert robot.home == (0.0,) * 6
    assert robot.has_offsets  # the UR5's URDF zero is not every D-H angle at 0
    check_against_yourdfpy(robot, (URDFS / "ur5.urdf").read_text(), "world", "tool0", 0)


def test_limits_come_from_the_urdf_and_continuous_joints_turn_fully():
    robot = import_file(URDFS / "continuous.urdf").robot
    assert (robot.joints[1].min, robot.joints[1].max) == (-360.0, 360.0)  # "spin"
    assert robot.joints[0].max == pytest.approx(math.degrees(1.0), abs=1e-9)  # "swing"
    text = (URDFS / "ur5.urdf").read_text()
    urdf = _yourdfpy(text)
    robot = import_file(URDFS / "ur5.urdf", tip="tool0").robot
    for joint, name in zip(robot.joints, _moving_names(urdf, "world", "tool0"), strict=True):
        limit = urdf.joint_map[name].limit
        assert joint.min == pytest.approx(math.degrees(limit.lower), abs=1e-9)
        assert joint.max == pytest.approx(math.degrees(limit.upper), abs=1e-9)


def test_a_range_without_zero_gets_a_home_inside_it():
    robot = import_file(URDFS / "range_without_zero.urdf").robot
    for joint, home in zip(robot.joints, robot.home, strict=True):
        assert joint.min <= home <= joint.max
    assert any(h != 0.0 for h in robot.home)


@settings(
    max_examples=60,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
@given(random_trees())
def test_random_chains_import_exactly(case):
    text, tip, base, _values = case
    try:
        result = from_urdf(text, tip=tip, base=base, units="mm")
    except DhsimError as exc:
        message = str(exc)
        # a chain without a moving joint, or one no D-H table reproduces to 1e-9
        assert "no moving joint" in message or "no D-H table reproduces" in message, message
        return
    check_against_yourdfpy(result.robot, text, base, tip, 5)


def test_a_tree_without_tip_lists_its_leaves():
    with pytest.raises(TipNeeded) as caught:
        import_file(URDFS / "ur5.urdf")
    assert set(caught.value.leaves) == {"ee_link", "tool0", "base"}
    assert "choose a tip" in str(caught.value) and str(URDFS / "ur5.urdf") in str(caught.value)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("<robot", "not valid XML"),
        (
            '<robot name="r"><link name="a"/><joint name="j" type="floating"><parent link="a"/>'
            '<child link="b"/></joint><link name="b"/></robot>',
            "'j'",
        ),
        (
            '<robot name="r"><link name="a"/><joint name="j" type="revolute"><parent link="a"/>'
            '<child link="zz"/><limit lower="-1" upper="1"/></joint></robot>',
            "zz",
        ),
        (
            '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
            '<origin xyz="nan 0 0"/><parent link="a"/><child link="b"/>'
            '<limit lower="-1" upper="1"/></joint></robot>',
            "finite",
        ),
    ],
)
def test_bad_urdfs_are_one_line_naming_the_file(tmp_path, text, message):
    path = tmp_path / "bad.urdf"
    path.write_text(text)
    with pytest.raises(DhsimError) as caught:
        import_file(path)
    assert str(caught.value).startswith(str(path)) and message in str(caught.value)
    assert "\n" not in str(caught.value)


def test_other_suffixes_and_binary_files_are_refused(tmp_path):
    path = tmp_path / "arm.sdf"
    path.write_text("<sdf/>")
    with pytest.raises(DhsimError, match=r"imports \.urdf and \.csv files, not \.sdf"):
        import_file(path)
    binary = tmp_path / "arm.urdf"
    binary.write_bytes(b"\xff\xfe<robot/>")
    with pytest.raises(DhsimError, match="not a text file"):
        import_file(binary)


# -- CSV ---------------------------------------------------------------------------------------

HANDOUT = """\
# Puma 560 from a lecture handout
theta,d,a,alpha
0,0,0,90
0,0,431.8,0
0,150.05,20.3,-90
0,431.8,0,90
0,0,0,-90
0,0,0,0
"""


def test_a_handout_table_imports_as_the_puma():
    robot = from_csv(HANDOUT, source="puma.csv").robot
    puma, _ = load_robot("puma560")
    assert robot.units == "mm" and robot.convention == "standard"
    assert [(j.theta, j.d, j.a, j.alpha) for j in robot.joints] == [
        (j.theta, j.d, j.a, j.alpha) for j in puma.joints
    ]
    for q in ([0] * 6, [10, 20, 30, 40, 50, 60]):
        np.testing.assert_allclose(robot.kinematics.pose(q), puma.kinematics.pose(q), atol=1e-12)


def test_csv_units_types_offsets_and_radians_are_read():
    text = "type,theta (rad),d (m),a (m),alpha (rad),offset (deg|m),min (deg|m),max (deg|m)\n"
    text += f"R,{math.pi / 2},0.1,0.2,{-math.pi / 2},90,-90,90\nP,0,0.5,0,0,0.25,0,1\n"
    robot = from_csv(text, units="mm").robot
    first, second = robot.joints
    assert robot.units == "mm"
    assert first.theta == pytest.approx(90.0) and first.alpha == pytest.approx(-90.0)
    assert first.d == pytest.approx(100.0) and first.a == pytest.approx(200.0)
    assert first.offset == 90.0 and robot.home[0] == pytest.approx(0.0)
    assert second.type == "prismatic" and second.offset == pytest.approx(250.0)
    assert (second.min, second.max) == (pytest.approx(0.0), pytest.approx(1000.0))


def test_a_modified_table_is_read_as_declared_or_converted():
    modified = "# convention = modified\n" + HANDOUT
    kept = from_csv(modified, convention="modified").robot
    assert kept.convention == "modified"
    converted = from_csv(modified, convention="standard").robot
    assert converted.convention == "standard"
    for q in ([0] * 6, [10, -20, 30, 40, 50, 60]):
        np.testing.assert_allclose(converted.kinematics.pose(q), kept.kinematics.pose(q), atol=1e-9)
    declared = from_csv(HANDOUT, convention="modified").robot  # no line: the flag declares
    assert declared.convention == "modified"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "no header row"),
        ("theta,d,a\n0,0,0\n", "line 1: the header has no alpha column"),
        ("theta,d,a,alpha,beta\n", "line 1: column 5 'beta' is not one of"),
        ("theta,d,a,alpha\n0,0,x,0\n", "line 2: a: 'x' is not a number"),
        ("theta,d,a,alpha\n0,0,nan,0\n", "line 2: a"),
        ("theta,d,a,alpha\n0,0\n", "line 2: no value in column 'a'"),
        ("type,theta,d,a,alpha\nQ,0,0,0,0\n", "line 2: type 'q' is not R or P"),
        ("theta,d (mm),a (m),alpha\n0,0,0,0\n", "d and a are in different units"),
        ("theta (grad),d,a,alpha\n0,0,0,0\n", "theta (grad): expected deg or rad"),
        ("theta,d,a,alpha\n", "no joint rows"),
        ("theta,d,a,alpha,min,max\n0,0,0,0,10,20\n", "outside"),
        ("# base_xyz = 1, 2\ntheta,d,a,alpha\n0,0,0,0\n", "line 1: base_xyz: expected 3 numbers"),
    ],
)
def test_bad_csv_is_one_line_naming_file_line_and_column(text, message):
    with pytest.raises(DhsimError) as caught:
        from_csv(text, source="arm.csv")
    assert str(caught.value).startswith("arm.csv: ") and message in str(caught.value)
    assert "\n" not in str(caught.value)


def _tilted_pair(tilt: float) -> str:
    """Two revolute joints whose axes are ``tilt`` rad from parallel, 0.4 m apart."""
    return (
        '<robot name="np"><link name="a"/><link name="b"/><link name="c"/><link name="d"/>'
        '<joint name="j1" type="revolute"><parent link="a"/><child link="b"/>'
        '<axis xyz="0 0 1"/><limit lower="-3" upper="3"/></joint>'
        '<joint name="j2" type="revolute"><parent link="b"/><child link="c"/>'
        f'<origin xyz="0.4 0 0" rpy="0 {tilt!r} 0"/><axis xyz="0 0 1"/>'
        '<limit lower="-3" upper="3"/></joint>'
        '<joint name="j3" type="fixed"><parent link="c"/><child link="d"/>'
        '<origin xyz="0.3 0 0"/></joint></robot>'
    )


def test_nearly_parallel_axes_import_exactly_with_a_note():
    text = _tilted_pair(1e-4)
    result = from_urdf(text, source="np.urdf")
    assert any(
        "1.0e-04 rad from parallel" in note and "4e+03 m away" in note for note in result.notes
    )
    check_against_yourdfpy(result.robot, text, "a", "d")


def test_too_nearly_parallel_axes_are_refused_saying_why():
    with pytest.raises(DhsimError) as caught:
        from_urdf(_tilted_pair(1e-7), source="np.urdf")
    message = str(caught.value)
    assert message.startswith("np.urdf: ") and "1.0e-07 rad from parallel" in message
    assert "\n" not in message

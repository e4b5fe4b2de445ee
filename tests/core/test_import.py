"""`dhsim import`: D-H robots from URDF and CSV, checked against yourdfpy.

Every URDF check compares dhsim's forward kinematics of the imported robot
(degrees and robot units) with yourdfpy's transform of the tip link in the
base link (radians and metres), a URDF implementation independent of ours.
"""

from __future__ import annotations

import io
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import yourdfpy
from hypothesis import HealthCheck, given, settings
from robot_strategies import reference_pose

from dhsim_tui.core.files.library import bundled_names, load_robot
from dhsim_tui.core.interop.export import export_text
from dhsim_tui.core.interop.importer import from_csv, from_urdf, import_file
from dhsim_tui.core.model.errors import DhsimError, TipNeeded
from dhsim_tui.core.model.robot import UNITS, Joint, Robot
from tests.core.test_urdf import CASES as URDF_CASES
from tests.core.test_urdf import random_trees

URDFS = Path(__file__).resolve().parents[1] / "urdfs"
TOL = 1e-9
BUNDLED = bundled_names()
#: the chains of tests/core/test_urdf.py (file, tip, base)
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


def check_against_yourdfpy(
    robot: Robot, text: str, base: str, tip: str, samples: int = 20, tol: float = TOL
):
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
        np.testing.assert_allclose(ours[:3, 3] * metres, theirs[:3, 3], rtol=0, atol=tol)
        np.testing.assert_allclose(ours[:3, :3], theirs[:3, :3], rtol=0, atol=tol)
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
    # "swing": limits are the shortest decimals within 1e-9 (relative) of the URDF's
    assert robot.joints[0].max == 57.2957795
    assert robot.joints[0].max == pytest.approx(math.degrees(1.0), rel=1e-9)
    text = (URDFS / "ur5.urdf").read_text()
    urdf = _yourdfpy(text)
    robot = import_file(URDFS / "ur5.urdf", tip="tool0").robot
    for joint, name in zip(robot.joints, _moving_names(urdf, "world", "tool0"), strict=True):
        limit = urdf.joint_map[name].limit
        assert joint.min == pytest.approx(math.degrees(limit.lower), rel=1e-9)
        assert joint.max == pytest.approx(math.degrees(limit.upper), rel=1e-9)


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
    # the import's check holds at its own joint values; its numbers are rounded
    # as far as that allows, so elsewhere the tool may be a hair further off
    check_against_yourdfpy(result.robot, text, base, tip, 5, tol=2 * TOL)


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
        ('# pose "a" = 1, 2\ntheta,d,a,alpha\n0,0,0,0\n', "poses.a: expected 1 joint value"),
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


# -- nearly parallel axes: a rounded π/2 (issue 17, point 7) --------------------------------

#: quarter turns a URDF's author may give every link frame (ROS's UR5 rolls them by 90°)
QUARTER_TURNS = {
    "x": np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]]),
    "y": np.array([[0.0, 0, 1], [0, 1, 0], [-1, 0, 0]]),
    "z": np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]]),
}
#: a D-H table from a URDF written to 10 digits holds no longer number than this
SHORT = 6


def _rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Rz(yaw)·Ry(pitch)·Rx(roll), by its entries."""
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def _rpy_of(r: np.ndarray) -> tuple[float, float, float]:
    pitch = math.atan2(-r[2, 0], math.hypot(r[0, 0], r[1, 0]))
    if abs(math.cos(pitch)) > 1e-9:
        return math.atan2(r[2, 1], r[2, 2]), pitch, math.atan2(r[1, 0], r[0, 0])
    return math.atan2(-r[1, 2], r[1, 1]), pitch, 0.0


def _written(values, digits: int) -> str:
    return " ".join(f"{v:.{digits}g}" for v in values)


def _rewritten(text: str, turn: np.ndarray | None = None, digits: int = 10) -> str:
    """The URDF with every link frame but the root's turned by ``turn`` (joint
    origins and axes changed to match, so the arm is the same) and the numbers
    of every joint origin written to ``digits`` significant digits, as URDFs
    from elsewhere are: the rounding leaves axes meant parallel ~1e-10 apart.
    dhsim's comment is dropped, so the file imports as any URDF."""
    root = ET.fromstring(text)
    roots = {link.get("name") for link in root.findall("link")} - {
        j.find("child").get("link") for j in root.findall("joint")
    }
    turned = np.eye(3) if turn is None else turn

    def change(link: str) -> np.ndarray:
        return np.eye(3) if link in roots else turned

    for joint in root.findall("joint"):
        origin = joint.find("origin")
        xyz = np.array([float(v) for v in origin.get("xyz", "0 0 0").split()])
        rotation = _rpy_matrix(*(float(v) for v in origin.get("rpy", "0 0 0").split()))
        parent = change(joint.find("parent").get("link"))
        child = change(joint.find("child").get("link"))
        origin.set("xyz", _written(parent.T @ xyz, digits))
        origin.set("rpy", _written(_rpy_of(parent.T @ rotation @ child), digits))
        axis = joint.find("axis")
        if axis is not None:
            direction = np.array([float(v) for v in axis.get("xyz").split()])
            axis.set("xyz", _written(child.T @ direction, 17))
    return ET.tostring(root, encoding="unicode")


def _significant(value: float) -> int:
    """How many significant digits ``repr`` gives a number (0 for 0)."""
    if value == 0:
        return 0
    mantissa = repr(abs(float(value))).split("e")[0].replace(".", "")
    return len(mantissa.strip("0"))


def _numbers(robot: Robot) -> list[float]:
    values = [v for j in robot.joints for v in (j.theta, j.d, j.a, j.alpha, j.offset)]
    return [*values, *robot.base_xyz, *robot.base_rpy, *robot.tool.xyz, *robot.tool.rpy]


@pytest.mark.parametrize("turn", [None, "x", "y", "z"])
@pytest.mark.parametrize("name", BUNDLED)
def test_urdfs_written_to_ten_digits_import_with_round_numbers(name, turn):
    """The bundled robots as URDFs from elsewhere: frames turned and numbers
    rounded to 10 digits. Each imports (no axes 4e-10 rad from parallel with
    a common normal 1e9 m away), matches yourdfpy, and its D-H table holds
    the short numbers the arm was made of, not 90.0000000118."""
    robot, _ = load_robot(name)
    text = _rewritten(export_text(robot, "urdf"), QUARTER_TURNS.get(turn))
    assert "dhsim-robot" not in text
    result = from_urdf(text, source=f"{name}.urdf", units=robot.units)
    check_against_yourdfpy(result.robot, text, "world", "tool", 10, tol=2 * TOL)
    assert all(j.alpha % 90.0 == 0.0 for j in result.robot.joints)
    long = [v for v in _numbers(result.robot) if _significant(v) > SHORT]
    assert not long, long
    assert not any("kept, as the URDF has it" in note for note in result.notes)
    parallel = [note for note in result.notes if "imported as parallel" in note]
    assert all("rad from parallel" in note for note in parallel)


def test_the_issues_refused_scara_imports_with_its_axes_parallel():
    """A SCARA's quill written with a rounded π: axes 4.1e-10 rad from
    antiparallel, whose common normal once lay 6e8 m away (and was refused)."""
    robot, _ = load_robot("scara_pedestal")
    text = _rewritten(export_text(robot, "urdf"), QUARTER_TURNS["z"])
    result = from_urdf(text, source="scara.urdf", units="mm")
    (note,) = [n for n in result.notes if "imported as parallel" in n]
    assert "the axes of joints 2 and 3 are 4.1e-10 rad from parallel" in note
    assert result.robot.joints[1].alpha == 180.0
    check_against_yourdfpy(result.robot, text, "world", "tool", tol=2 * TOL)


def test_a_pair_tilted_by_a_rounded_angle_imports_as_parallel():
    text = _tilted_pair(4.1e-10)
    result = from_urdf(text, source="np.urdf")
    first, _second = result.robot.joints
    assert (first.a, first.alpha, first.d) == (0.4, 0.0, 0.0)
    assert any("4.1e-10 rad from parallel" in note for note in result.notes)
    check_against_yourdfpy(result.robot, text, "a", "d", tol=2 * TOL)


def test_a_pair_too_far_from_parallel_for_either_is_refused_saying_both():
    with pytest.raises(DhsimError) as caught:
        from_urdf(_tilted_pair(3e-9), source="np.urdf")
    message = str(caught.value)
    assert message.startswith("np.urdf: no D-H table reproduces this chain to 1e-9: ")
    assert "3.0e-09 rad from parallel" in message
    assert "taken as parallel, the tool is off by" in message and "as skew lines" in message
    assert "\n" not in message


@pytest.mark.parametrize("dof", [12, 32])
def test_long_chains_written_to_ten_digits_import(dof):
    """Long arms of parallel, perpendicular and antiparallel axes, frames
    rolled 90° about x and numbers rounded to 10 digits."""
    rng = np.random.default_rng(dof)
    joints = tuple(
        Joint(
            "revolute",
            0.0,
            float(rng.choice([0.0, 50.0, 120.0])),
            float(rng.choice([0.0, 100.0, 250.0])),
            float(rng.choice([0.0, 0.0, 90.0, -90.0, 180.0])),
            -170.0,
            170.0,
        )
        for _ in range(dof)
    )
    robot = Robot(name="long arm", joints=joints)
    text = _rewritten(export_text(robot, "urdf"), QUARTER_TURNS["x"])
    result = from_urdf(text, source="long.urdf", units="mm")
    assert result.robot.dof == dof
    # the twists are the arm's, to what the rounding left (a long arm's sum of
    # 2e-10 rad tilts leaves no room to round every one of them away)
    for ours, theirs in zip(result.robot.joints[:-1], joints[:-1], strict=True):
        assert ours.alpha == pytest.approx(theirs.alpha, abs=1e-6)
    check_against_yourdfpy(result.robot, text, "world", "tool", 5, tol=2 * TOL)


# -- rounding (issue 17, point 2) ------------------------------------------------------------


def test_numbers_are_the_shortest_that_keep_the_match():
    """Lengths written with 13 digits keep 9 or so: the fewest within 5e-10 m."""
    text = (
        '<robot name="r"><link name="a"/><link name="b"/><link name="c"/>'
        '<joint name="j1" type="revolute"><parent link="a"/><child link="b"/>'
        '<origin xyz="0 0 0.3000000000049"/><axis xyz="0 0 1"/>'
        '<limit lower="-2.8" upper="2.8"/></joint>'
        '<joint name="j2" type="fixed"><parent link="b"/><child link="c"/>'
        '<origin xyz="0.1234567891234 0 0"/></joint></robot>'
    )
    result = from_urdf(text, source="r.urdf")
    (joint,) = result.robot.joints
    assert (joint.a, joint.d) == (0.123456789, 0.3)
    # limits: the shortest decimal within 1e-9 (relative) of the radians converted
    assert (joint.min, joint.max) == (-160.4281826, 160.4281826)
    assert any("rounded to the fewest digits" in note for note in result.notes)
    check_against_yourdfpy(result.robot, text, "a", "c")


# -- the comment header of the robot file (issue 17, point 4) --------------------------------


@pytest.mark.parametrize(
    ("units", "words"),
    [
        ("m", "(degrees instead of radians; lengths in metres, as in the URDF)"),
        ("mm", "(degrees instead of radians, millimetres instead of metres)"),
        ("in", "(degrees instead of radians, inches instead of metres)"),
    ],
)
def test_the_header_names_the_unit_in_words(units, words):
    header = import_file(URDFS / "planar_elbow.urdf", units=units).header
    assert words in header[1]
    assert " m instead of" not in " ".join(header)

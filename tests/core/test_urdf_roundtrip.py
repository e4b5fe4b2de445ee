"""A URDF dhsim exported imports as the very robot (issue 17, point 1).

``dhsim export --format urdf`` writes dhsim's own fields in a comment
(``<!-- dhsim-robot 1: ... -->``); ``dhsim import`` of that file gives back a
robot equal (``==``) to the one exported, name, unit, convention, pedestal,
base, tool, limits and named poses included, as long as the URDF's joints
still match it. The checks here are independent of the code under test: the
file's URDF part must read the same with the comment as without it, both in
a plain XML parser and in yourdfpy; an edited URDF must import as a plain one
(then checked against yourdfpy's forward kinematics, not dhsim's).
"""

from __future__ import annotations

import io
import json
import math
import re
import xml.etree.ElementTree as ET
from dataclasses import replace

import numpy as np
import pytest
import yourdfpy
from hypothesis import HealthCheck, given, settings

from dhsim_tui.core.files.library import bundled_names, load_robot
from dhsim_tui.core.interop.convert import convert
from dhsim_tui.core.interop.export import export_text, to_json, write_export
from dhsim_tui.core.interop.importer import from_urdf, import_file
from dhsim_tui.core.interop.urdf_export import STORED_OPTIONAL_JOINT_FIELDS
from dhsim_tui.core.model.editing import set_units
from dhsim_tui.core.model.robot import Joint, Robot, Tool
from tests.cli.test_export import robots
from tests.core.test_import import check_against_yourdfpy

BUNDLED = bundled_names()
#: the comment dhsim writes, as a reader of the file finds it
STORED = re.compile(r"<!--\s*dhsim-robot 1:(.*?)-->", re.S)


def _stored_json(text: str) -> dict:
    """The JSON object of the file's dhsim comment, read as the format says."""
    (body,) = STORED.findall(text)
    start = body.index("{")
    data, end = json.JSONDecoder().raw_decode(body, start)
    assert not body[end:].strip()
    return data


def _without_comment(text: str) -> str:
    return STORED.sub("", text)


def _yourdfpy(text: str) -> yourdfpy.URDF:
    return yourdfpy.URDF.load(
        io.BytesIO(text.encode("utf-8")), build_scene_graph=True, load_meshes=False
    )


# -- the file ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", BUNDLED)
def test_the_comment_holds_the_json_export(name):
    robot, _ = load_robot(name)
    text = export_text(robot, "urdf")
    assert _stored_json(text) == json.loads(to_json(robot))
    assert text.index("dhsim-robot 1:") < text.index("<robot ")  # before the robot element


@pytest.mark.parametrize("name", ["puma560", "ur5", "gantry", "scara_pedestal"])
def test_other_tools_read_the_file_as_if_the_comment_were_not_there(name):
    robot, _ = load_robot(name)
    text = export_text(robot, "urdf")
    plain = _without_comment(text)
    assert plain != text
    # a plain XML parser: the same tree (comments are not part of it)
    assert ET.tostring(ET.fromstring(text)) == ET.tostring(ET.fromstring(plain))
    # yourdfpy: valid, the same links, joints and forward kinematics
    ours, theirs = _yourdfpy(text), _yourdfpy(plain)
    assert ours.validate()
    assert [link.name for link in ours.robot.links] == [link.name for link in theirs.robot.links]
    assert [j.name for j in ours.robot.joints] == [j.name for j in theirs.robot.joints]
    rng = np.random.default_rng(3)
    for _ in range(3):
        cfg = {j: float(rng.uniform(-1.0, 1.0)) for j in ours.actuated_joint_names}
        ours.update_cfg(cfg)
        theirs.update_cfg(cfg)
        np.testing.assert_array_equal(
            ours.get_transform("tool", "world"), theirs.get_transform("tool", "world")
        )


def test_names_with_dashes_and_odd_characters_fit_in_a_comment():
    robot, _ = load_robot("planar2")
    odd = 'arm -- <b>&amp; "quoted" ---> \ufffe \uffff é 漢 -'
    robot = replace(robot, name=odd, poses=(("--x--", robot.home), ("a->b", robot.home)))
    text = export_text(robot, "urdf")
    (body,) = STORED.findall(text)
    assert "--" not in body and not body.rstrip().endswith("-")
    ET.fromstring(text)  # still well-formed
    assert _stored_json(text)["name"] == odd
    assert from_urdf(text).robot == robot


# -- the round trip ----------------------------------------------------------------------


@pytest.mark.parametrize("name", BUNDLED)
def test_export_then_import_gives_the_same_robot(name, tmp_path):
    robot, _ = load_robot(name)
    path = write_export(robot, "urdf", tmp_path / f"{name}.urdf")
    result = import_file(path)
    assert result.robot == robot
    assert any("restored as dhsim exported them" in note for note in result.notes)
    assert any("matches the URDF" in note for note in result.notes)
    assert result.header[0].startswith(f"Imported by dhsim from {name}.urdf")


def test_the_puma_keeps_its_pedestal_poses_and_millimetres(tmp_path):
    """The issue's case: the pedestal and the named poses came back dropped, in metres."""
    puma, _ = load_robot("puma560")
    robot = import_file(write_export(puma, "urdf", tmp_path / "p.urdf")).robot
    assert robot.units == "mm" and robot.base_height == 671.83
    assert robot.pose_names == ("qz", "qr", "qs", "qn")
    assert (robot.joints[0].min, robot.joints[0].max) == (-160.0, 160.0)


@settings(
    max_examples=60,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
@given(robot=robots())
def test_random_robots_come_back_equal(robot):
    assert from_urdf(export_text(robot, "urdf"), source="r.urdf").robot == robot


def test_units_convention_and_name_asked_for_are_applied(tmp_path):
    puma, _ = load_robot("puma560")
    path = write_export(puma, "urdf", tmp_path / "p.urdf")
    assert import_file(path, units="m").robot == set_units(puma, "m")
    assert import_file(path, convention="modified").robot == convert(puma, "modified")
    assert import_file(path, name="Mine").robot == replace(puma, name="Mine")
    assert import_file(path, units="mm", convention="standard").robot == puma
    robot = import_file(path, units="in", convention="modified").robot
    check_against_yourdfpy(robot, path.read_text(), "world", "tool")


# -- when the stored robot is not used ---------------------------------------------------


def _edited(text: str, old: str, new: str) -> str:
    assert text.count(old) >= 1, old
    return text.replace(old, new, 1)


def _plain_import_of(text: str, remark: str, **names):
    result = from_urdf(text, source="edited.urdf", **names)
    notes = [n for n in result.notes if remark in n]
    assert len(notes) == 1, result.notes
    assert "imported from the URDF's joints alone" in notes[0]
    assert "\n" not in notes[0]
    return result


def test_a_urdf_edited_after_export_imports_as_a_plain_urdf():
    puma, _ = load_robot("puma560")
    text = _edited(export_text(puma, "urdf"), 'xyz="0.4318 ', 'xyz="0.5 ')
    result = _plain_import_of(text, "does not match its joints from link 'world'")
    assert "the tool is off by" in next(n for n in result.notes if "does not match" in n)
    assert result.robot.units == "m" and not result.robot.poses
    check_against_yourdfpy(result.robot, text, "world", "tool")


def test_an_edited_limit_or_joint_type_is_noticed():
    puma, _ = load_robot("puma560")
    text = export_text(puma, "urdf")
    upper = f'upper="{math.radians(160.0)!r}"'
    limited = _edited(text, upper, 'upper="2"')
    result = _plain_import_of(limited, "joint 1's limits differ")
    assert result.robot.joints[0].max == pytest.approx(math.degrees(2.0), rel=1e-9)
    check_against_yourdfpy(result.robot, limited, "world", "tool")
    gantry, _ = load_robot("gantry")
    text = _edited(export_text(gantry, "urdf"), 'type="prismatic"', 'type="revolute"')
    _plain_import_of(text, "joint 1 is revolute in the URDF, prismatic in the robot")


def test_another_chain_of_the_same_file_is_a_plain_import():
    puma, _ = load_robot("puma560")
    text = export_text(puma, "urdf")
    # the Puma has no tool: link6 is where link tool is, so that is the same arm
    assert from_urdf(text, tip="link6").robot == puma
    result = _plain_import_of(text, "5 moving joints, the stored robot has 6", tip="link5")
    assert result.robot.dof == 5 and result.robot.units == "m"
    # the same joints from another base: the tool is off by the base's shift
    raised = replace(puma, base_xyz=(0.0, 0.0, 100.0))
    _plain_import_of(export_text(raised, "urdf"), "the tool is off by 1.0e-01 m", base="link0")


@pytest.mark.parametrize(
    ("damage", "reason"),
    [
        (lambda body: body.replace('"version": 1', '"version": 2'), "not format"),
        (lambda body: body.replace('{"format"', '{"format": 1, "x"', 1), "not format"),
        (lambda body: body.replace("}", "", 1), "not valid JSON"),
        (lambda body: body.replace('"joints": [', '"joints": "no", "x": [', 1), "joints:"),
        (lambda body: body.replace('"name": "Puma 560"', '"name": "\\u001b[2J"'), "control"),
        (lambda body: body.replace('"alpha": 90.0', '"alpha": "ninety"', 1), "joints[1].alpha"),
        (lambda body: body.replace('"alpha": 90.0', '"alpha": 1e999', 1), "joints[1].alpha"),
        (lambda body: body.replace('"min": -160.0, ', "", 1), "joints[1]: no min"),
        (lambda body: body.replace('"qz": [0.0, ', '"qz": [', 1), "poses.qz"),
        (lambda body: "no JSON here", "no JSON object"),
        (lambda body: "[" * 100_000 + "]" * 100_000, "no JSON object"),
        (lambda body: "{" + '"a": [' * 100_000 + "]" * 100_000 + "}", "not valid JSON"),
    ],
)
def test_a_damaged_comment_is_a_plain_import_saying_why(damage, reason):
    puma, _ = load_robot("puma560")
    text = export_text(puma, "urdf")
    (body,) = STORED.findall(text)
    damaged = text.replace(body, " " + damage(body) + " ")
    result = _plain_import_of(damaged, "cannot be read")
    note = next(n for n in result.notes if "cannot be read" in n)
    assert reason in note and "\x1b" not in note and len(note) < 400


def test_a_hand_written_urdf_with_a_dhsim_comment_of_another_robot():
    """The comment pasted into a URDF it does not describe: the URDF wins."""
    gantry, _ = load_robot("gantry")
    comment = STORED.search(export_text(gantry, "urdf")).group(0)
    text = (
        '<?xml version="1.0"?>\n' + comment + '<robot name="one"><link name="a"/><link name="b"/>'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1"/></joint></robot>'
    )
    result = _plain_import_of(text, "1 moving joints, the stored robot has 3")
    assert result.robot.dof == 1


def test_a_stored_robot_is_checked_like_any_robot():
    """Valid JSON, but a robot dhsim would refuse: a plain import, saying why."""
    puma, _ = load_robot("puma560")
    text = export_text(puma, "urdf")
    body = STORED.findall(text)[0]
    broken = body.replace('"base": {"height": 671.83', '"base": {"height": -1.0', 1)
    result = _plain_import_of(text.replace(body, broken), "base_height")
    assert result.robot.base_height == 0.0


def test_the_stored_robot_is_not_the_only_way_to_the_same_arm():
    """Without the comment the same file imports as any URDF: the same arm."""
    puma, _ = load_robot("puma560")
    plain = _without_comment(export_text(puma, "urdf"))
    robot = from_urdf(plain, units="mm").robot
    assert robot != puma and robot.units == "mm" and not robot.poses
    for q in ([0.0] * 6, [10.0, -20.0, 30.0, 40.0, -50.0, 60.0]):
        world = robot.kinematics.pose(q)
        np.testing.assert_allclose(world, puma.kinematics.pose(q), rtol=0, atol=1e-6)
    check_against_yourdfpy(robot, plain, "world", "tool")


def test_joint_dataclass_fields_are_all_stored():
    """Every field of a joint and of a robot rides along (a new field would need the
    comment to carry it, or the round trip would silently lose it)."""
    stored = _stored_json(export_text(load_robot("ur5")[0], "urdf"))
    optional = set(STORED_OPTIONAL_JOINT_FIELDS)  # written when set (vmax, amax)
    assert set(Joint.__dataclass_fields__) == {"type", *stored["parameter_order"], *optional}
    assert set(Robot.__dataclass_fields__) == {
        "name",
        "joints",
        "units",
        "convention",
        "base_height",
        "base_z",
        "base_x",
        "base_xyz",
        "base_rpy",
        "tool",
        "poses",
        "programs",
    }
    assert set(stored) >= {"poses", "programs"}


@pytest.mark.parametrize(("alpha", "tool_z"), [(68.0, 1084.518), (1.0, 1085.473)])
def test_a_kilometre_tool_comes_back_equal(alpha, tool_z):
    """Found by the search above: a 1 km tool's round-off (3e-12 of its
    length) was over the check's absolute 1e-9 m, so the stored robot was
    refused and the extracted one came back with 5 nm offsets."""
    joint = Joint("prismatic", theta=0.0, d=0.0, a=0.0, alpha=alpha, min=-0.001, max=0.001)
    robot = Robot(
        name="far",
        joints=(joint,),
        units="m",
        base_z="+x",
        base_x="+y",
        tool=Tool(xyz=(0.0, 0.0, tool_z)),
    )
    assert from_urdf(export_text(robot, "urdf"), source="r.urdf").robot == robot

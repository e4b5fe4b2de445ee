"""Exports (dhsim_tui.core.interop.export): URDF checked against yourdfpy, CSV and JSON
read back independently, and the atomic, careful write.

The URDF is loaded by yourdfpy, an independent URDF implementation: with the
joints set to dhsim's joint values (in radians / metres), the tool link must
sit where dhsim's FK puts the tool, and link ``link{i}`` must be modified D-H
frame i, for every bundled robot and for random robots (both conventions,
prismatic joints, offsets, a general base, a tool, every unit).
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import stat
import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import yourdfpy
from hypothesis import HealthCheck, given, reject, settings
from hypothesis import strategies as st

from dhsim_tui.core.files.formats import EXPORT_FORMATS, EXPORT_SUFFIXES
from dhsim_tui.core.files.library import bundled_names, load_robot
from dhsim_tui.core.files.programschema import programs_from_data
from dhsim_tui.core.interop.export import (
    export_text,
    to_csv,
    to_json,
    to_urdf,
    write_export,
)
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.orientation import rpy_angles as rpy_radians
from dhsim_tui.core.model.robot import AXES, UNITS, Joint, Robot, Tool
from dhsim_tui.core.model.text import control_character
from dhsim_tui.core.model.validation import perpendicular_axes

BUNDLED = bundled_names()
#: agreement in metres, per metre of the arm's size (and at least this)
TOL = 1e-9
HEADER = (
    "joint,type,theta (deg),d ({u}),a ({u}),alpha (deg),"
    "offset (deg|{u}),min (deg|{u}),max (deg|{u})"
)
COMMENT_KEYS = [
    "format",
    "name",
    "convention",
    "units",
    "base_height",
    "base_z",
    "base_x",
    "base_xyz",
    "base_rpy",
    "tool_xyz",
    "tool_rpy",
]


# -- an independent reference ---------------------------------------------------------
def _rz(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _tz(d: float) -> np.ndarray:
    m = np.eye(4)
    m[2, 3] = d
    return m


def _metres(robot: Robot, value):
    return np.asarray(value, dtype=float) * UNITS[robot.units] / 1000.0


def _in_metres(robot: Robot, matrix: np.ndarray) -> np.ndarray:
    out = np.array(matrix, dtype=float)
    out[:3, 3] = _metres(robot, out[:3, 3])
    return out


def _size_m(robot: Robot) -> float:
    """The largest distance anything can be from the world origin, about."""
    lengths = sum(
        abs(j.a) + abs(j.d) + max(abs(j.min), abs(j.max), abs(j.offset)) for j in robot.joints
    )
    lengths += float(np.linalg.norm(robot.tool.xyz)) + float(np.linalg.norm(robot.base_xyz))
    return float(_metres(robot, lengths))


def _tol(robot: Robot) -> float:
    return TOL * max(1.0, _size_m(robot))


def modified_frames(robot: Robot, q) -> list[np.ndarray]:
    """World transforms of modified D-H frames 0..n and the tool (robot units).

    For a modified robot these are dhsim's own frames. For a standard one,
    modified frame i is standard frame i-1 moved by joint i's screw,
    Rz(theta_i)·Tz(d_i): standard frame i is that times Tx(a_i)·Rx(alpha_i),
    and modified frame i+1 is modified frame i times Rx(alpha_i)·Tx(a_i)·
    Rz(theta_{i+1})·Tz(d_{i+1}), the same screw on standard frame i."""
    frames = list(robot.kinematics.frames(q))
    if robot.convention == "modified":
        return frames
    out = [frames[0]]
    for i, (joint, value) in enumerate(zip(robot.joints, q, strict=True)):
        theta = value + joint.offset if joint.is_revolute else joint.theta
        d = joint.d if joint.is_revolute else value + joint.offset
        out.append(frames[i] @ _rz(theta) @ _tz(d))
    out.append(frames[-1])
    return out


def _load_urdf(path_or_text) -> yourdfpy.URDF:
    if isinstance(path_or_text, Path):
        source = path_or_text
    else:
        source = io.BytesIO(path_or_text.encode("utf-8"))
    return yourdfpy.URDF.load(source, load_meshes=False, build_scene_graph=True)


def _cfg(robot: Robot, q) -> dict[str, float]:
    return {
        f"joint{i}": math.radians(v) if j.is_revolute else float(_metres(robot, v))
        for i, (j, v) in enumerate(zip(robot.joints, q, strict=True), start=1)
    }


def _set(urdf: yourdfpy.URDF, cfg: dict[str, float]) -> None:
    """``urdf.update_cfg(cfg)``, for sure: trimesh's scene graph ignores an
    update that moves a frame by less than 1e-8 (metres, or per unit of the
    rotation), so a small step from the previous configuration would be
    lost; a detour by one radian or metre first makes every joint move."""
    urdf.update_cfg({name: value + 1.0 for name, value in cfg.items()})
    urdf.update_cfg(cfg)


def _random_qs(robot: Robot, rng: np.random.Generator, count: int) -> list[tuple[float, ...]]:
    qs = [robot.home, robot.lower, robot.upper]
    for _ in range(count):
        u = rng.uniform(0.0, 1.0, robot.dof)
        q = [
            min(max(lo + t * (hi - lo), lo), hi)
            for lo, hi, t in zip(robot.lower, robot.upper, u, strict=True)
        ]
        qs.append(tuple(q))
    return qs


def check_urdf_fk(robot: Robot, urdf: yourdfpy.URDF, qs) -> None:
    """yourdfpy's tool and link frames equal dhsim's at every q."""
    tol = _tol(robot)
    n = robot.dof
    for q in qs:
        _set(urdf, _cfg(robot, q))
        tool = urdf.get_transform(frame_to="tool", frame_from="world")
        expected = _in_metres(robot, robot.kinematics.pose(q))
        np.testing.assert_allclose(tool, expected, rtol=0, atol=tol, err_msg=f"tool at q={q}")
        reference = modified_frames(robot, q)
        names = [f"link{i}" for i in range(n + 1)] + ["tool"]
        for name, frame in zip(names, reference, strict=True):
            got = urdf.get_transform(frame_to=name, frame_from="world")
            np.testing.assert_allclose(
                got, _in_metres(robot, frame), rtol=0, atol=tol, err_msg=f"{name} at q={q}"
            )


# -- random robots ----------------------------------------------------------------------
_milli = st.integers(1, 2_000_000).map(lambda k: k / 1000.0)
#: a length: 0, or 0.001..2000 of either sign (never a sub-nanometre leftover)
lengths = st.one_of(st.just(0.0), _milli, _milli.map(lambda v: -v))
angles = st.one_of(
    st.sampled_from([0.0, 90.0, -90.0, 180.0, -180.0, 45.0, 270.0]),
    st.floats(-360.0, 360.0, allow_nan=False),
)
spans = st.floats(0.5, 360.0, allow_nan=False)
#: names as a file may hold them: any printable text, quotes, commas, "=", "#", "<"
names = st.text(
    st.characters(blacklist_categories=("Cc", "Cs", "Cf", "Zl", "Zp"))
    | st.sampled_from("\"',=#<>&- "),
    min_size=1,
    max_size=12,
).filter(lambda s: s.strip() and control_character(s) is None)


@st.composite
def joints(draw) -> Joint:
    a, alpha = draw(lengths), draw(angles)
    if draw(st.booleans()):
        d, offset, home = draw(lengths), draw(angles), draw(angles)
        theta = home + offset
        home = theta - offset  # as the model computes it
        return Joint("revolute", theta, d, a, alpha, home - draw(spans), home + draw(spans), offset)
    theta, offset, home = draw(angles), draw(lengths), draw(lengths)
    d = home + offset
    home = d - offset
    # limits: whole thousandths below and above home (0 or >= 0.001 in size)
    lo = (math.floor(home * 1000) - draw(st.integers(1, 500_000))) / 1000.0
    hi = (math.ceil(home * 1000) + draw(st.integers(1, 500_000))) / 1000.0
    return Joint("prismatic", theta, d, a, alpha, lo, hi, offset)


def _pose(draw, robot_joints) -> tuple[float, ...]:
    return tuple(
        draw(st.floats(j.min, j.max, allow_nan=False)) if draw(st.booleans()) else j.home
        for j in robot_joints
    )


@st.composite
def robots(draw, max_joints: int = 7) -> Robot:
    rows = tuple(draw(st.lists(joints(), min_size=1, max_size=max_joints)))
    base_z = draw(st.sampled_from(AXES))
    base_x = draw(st.sampled_from(perpendicular_axes(base_z)))
    triple = st.tuples(lengths, lengths, lengths)
    turns = st.tuples(angles, angles, angles)
    pose_names = draw(st.lists(names, max_size=3, unique=True))
    try:
        return Robot(
            name=draw(names),
            joints=rows,
            units=draw(st.sampled_from(list(UNITS))),
            convention=draw(st.sampled_from(["standard", "modified"])),
            base_height=draw(_milli | st.just(0.0)),
            base_z=base_z,
            base_x=base_x,
            base_xyz=draw(triple),
            base_rpy=draw(turns),
            tool=Tool(draw(triple), draw(turns)),
            poses=tuple((name, _pose(draw, rows)) for name in pose_names),
        )
    except DhsimError:  # e.g. a length too small for the unit: not this test's business
        reject()


# -- URDF: forward kinematics agree with yourdfpy ------------------------------------
@pytest.mark.parametrize("name", BUNDLED)
def test_urdf_fk_matches_yourdfpy_bundled(name, tmp_path):
    robot, _ = load_robot(name)
    path = write_export(robot, "urdf", tmp_path / f"{name}.urdf")
    urdf = _load_urdf(path)
    assert urdf.validate()
    check_urdf_fk(robot, urdf, _random_qs(robot, np.random.default_rng(7), 6))


@settings(
    max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(robot=robots(), seed=st.integers(0, 2**32 - 1))
def test_urdf_fk_matches_yourdfpy_random(robot, seed, tmp_path):
    path = write_export(robot, "urdf", tmp_path / "random.urdf", overwrite=True)
    urdf = _load_urdf(path)
    check_urdf_fk(robot, urdf, _random_qs(robot, np.random.default_rng(seed), 3))


def test_urdf_fk_would_catch_a_wrong_offset():
    """The comparison is not vacuous: a URDF of a robot with another offset fails it."""
    robot = Robot(
        "r",
        (
            Joint(a=100.0, offset=30.0, theta=30.0),
            Joint("prismatic", alpha=90, d=5.0, offset=5.0, min=-50, max=50),
        ),
    )
    other = Robot(
        "r",
        (
            Joint(a=100.0, offset=0.0),
            Joint("prismatic", alpha=90, d=5.0, offset=5.0, min=-50, max=50),
        ),
    )
    urdf = _load_urdf(to_urdf(other))
    with pytest.raises(AssertionError):
        check_urdf_fk(robot, urdf, [(10.0, 20.0)])


@pytest.mark.parametrize(
    "rpy", [(30.0, 90.0, 20.0), (30.0, -90.0, 20.0), (0.0, 90.0, 0.0), (10.0, 45.0, 170.0)]
)
@pytest.mark.parametrize("alpha", [0.0, 180.0, 90.0, -90.0])
def test_urdf_gimbal_lock_origins(rpy, alpha):
    """Tools and bases at pitch ±90° (where roll and yaw share one axis)."""
    for convention in ("standard", "modified"):
        robot = Robot(
            "gimbal",
            (Joint(a=100.0, alpha=30.0), Joint(a=50.0, alpha=alpha, offset=90.0, theta=90.0)),
            convention=convention,
            base_rpy=rpy,
            tool=Tool((1.0, 2.0, 3.0), rpy),
        )
        check_urdf_fk(robot, _load_urdf(to_urdf(robot)), [(10.0, 20.0), (0.0, 0.0)])


@pytest.mark.slow  # a long hypothesis run
@settings(max_examples=300, deadline=None)
@given(
    roll=angles,
    pitch=st.one_of(st.sampled_from([90.0, -90.0]), angles),
    yaw=angles,
    nudge=st.sampled_from([0.0, 1e-12, -1e-9, 1e-7]),
)
def test_rpy_radians_rebuilds_the_rotation(roll, pitch, yaw, nudge):
    def rot(r, p, y):
        cr, sr, cp, sp, cy, sy = (f(v) for v in (r, p, y) for f in (math.cos, math.sin))
        rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
        ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
        rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
        return rz @ ry @ rx

    matrix = rot(math.radians(roll), math.radians(pitch) + nudge, math.radians(yaw))
    got = rpy_radians(matrix)
    assert all(-math.pi <= v <= math.pi for v in got)
    np.testing.assert_allclose(rot(*got), matrix, rtol=0, atol=1e-13)


# -- URDF: structure -----------------------------------------------------------------
def _joint_elements(text: str) -> dict[str, ET.Element]:
    root = ET.fromstring(text.encode("utf-8"))
    return {j.get("name"): j for j in root.iter("joint")}


@pytest.mark.parametrize("name", BUNDLED)
def test_urdf_structure_and_limits_bundled(name):
    robot, _ = load_robot(name)
    _check_structure(robot, to_urdf(robot))


@settings(max_examples=40, deadline=None)
@given(robot=robots())
def test_urdf_structure_and_limits_random(robot):
    _check_structure(robot, to_urdf(robot))


def _check_structure(robot: Robot, text: str) -> None:
    n = robot.dof
    root = ET.fromstring(text.encode("utf-8"))  # well-formed XML
    assert root.tag == "robot"
    links = [link.get("name") for link in root.findall("link")]
    assert links == ["world", *(f"link{i}" for i in range(n + 1)), "tool"]
    joints = _joint_elements(text)
    assert list(joints) == ["base_joint", *(f"joint{i}" for i in range(1, n + 1)), "tool_joint"]
    assert joints["base_joint"].get("type") == "fixed"
    assert joints["tool_joint"].get("type") == "fixed"
    for i, joint in enumerate(robot.joints, start=1):
        element = joints[f"joint{i}"]
        assert element.get("type") == joint.type
        assert element.find("parent").get("link") == f"link{i - 1}"
        assert element.find("child").get("link") == f"link{i}"
        assert element.find("axis").get("xyz") == "0 0 1"
        limit = element.find("limit")
        lower, upper = float(limit.get("lower")), float(limit.get("upper"))
        if joint.is_revolute:
            expected = (math.radians(joint.min), math.radians(joint.max))
        else:
            expected = tuple(float(_metres(robot, v)) for v in (joint.min, joint.max))
        assert lower == pytest.approx(expected[0], rel=1e-15, abs=0)
        assert upper == pytest.approx(expected[1], rel=1e-15, abs=0)
        assert float(limit.get("effort")) > 0 and float(limit.get("velocity")) > 0
    urdf = _load_urdf(text)
    assert urdf.actuated_joint_names == [f"joint{i}" for i in range(1, n + 1)]
    assert urdf.base_link == "world"
    # the comment names dhsim, the robot's convention and unit, and the placeholders
    comment = text.split("-->")[0]
    assert "dhsim" in comment and robot.convention in comment
    assert f"lengths in {robot.units}" in comment and "placeholder" in comment


@pytest.mark.parametrize(
    ("name", "shown"),
    [
        ("arm <1> & \"two\" 'three'", None),
        ("a--b-", None),
        ("end -->", None),
        ("odd \uffff char", "odd \\uffff char"),
        ("ünïcødé 机器人", None),
    ],
)
def test_urdf_robot_name_is_escaped(name, shown):
    robot = Robot(name, (Joint(a=1.0),))
    text = to_urdf(robot)
    root = ET.fromstring(text.encode("utf-8"))
    assert root.get("name") == (shown or name)
    _load_urdf(text)  # yourdfpy (lxml) reads it too


def _visuals(urdf: yourdfpy.URDF, link: str, material: str):
    return [v for v in urdf.link_map[link].visuals if v.material.name == material]


def _ends(visual) -> tuple[np.ndarray, np.ndarray]:
    origin = visual.origin
    half = visual.geometry.cylinder.length / 2.0 * origin[:3, 2]
    return origin[:3, 3] - half, origin[:3, 3] + half


@pytest.mark.parametrize("name", [*BUNDLED, "random"])
def test_urdf_visuals_follow_the_links(name):
    """Each link's cylinder runs from its origin to the next frame's origin at
    q = 0; a prismatic joint's rail spans its range on the parent link."""
    if name == "random":
        robot = Robot(
            "mixed",
            (
                Joint(
                    "prismatic",
                    theta=30.0,
                    d=10.0,
                    a=20.0,
                    alpha=60.0,
                    offset=5.0,
                    min=-100.0,
                    max=100.0,
                ),
                Joint(d=0.0, a=0.0),
                Joint(a=40.0, alpha=-90.0, offset=15.0, theta=15.0),
            ),
            units="cm",
            tool=Tool((0.0, 3.0, 4.0), (10.0, 0.0, 0.0)),
        )
    else:
        robot, _ = load_robot(name)
    urdf = _load_urdf(to_urdf(robot))
    n = robot.dof
    _set(urdf, {f"joint{i}": 0.0 for i in range(1, n + 1)})
    nexts = [f"link{i}" for i in range(1, n + 1)] + ["tool"]
    drawn = 0
    for i, following in enumerate(nexts):
        link = f"link{i}"
        end = urdf.get_transform(frame_to=following, frame_from=link)[:3, 3]
        cylinders = _visuals(urdf, link, "dhsim_link")
        if np.linalg.norm(end) < 1e-12:
            assert cylinders == [], f"{link}: a cylinder of length 0"
            continue
        assert len(cylinders) == 1, link
        start, stop = _ends(cylinders[0])
        np.testing.assert_allclose(start, 0.0, atol=1e-12)
        np.testing.assert_allclose(stop, end, atol=1e-12)
        assert cylinders[0].geometry.cylinder.radius > 0
        drawn += 1
    for i, joint in enumerate(robot.joints, start=1):
        rails = _visuals(urdf, f"link{i - 1}", "dhsim_rail")
        if joint.is_revolute:
            assert rails == []
            continue
        ends = []
        for value in (joint.min, joint.max):
            _set(urdf, {f"joint{i}": float(_metres(robot, value))})
            ends.append(urdf.get_transform(frame_to=f"link{i}", frame_from=f"link{i - 1}")[:3, 3])
        (rail,) = rails
        start, stop = _ends(rail)
        np.testing.assert_allclose(start, ends[0], atol=1e-12)
        np.testing.assert_allclose(stop, ends[1], atol=1e-12)
        _set(urdf, {f"joint{i}": 0.0})
        drawn += 1
    assert drawn >= 1, "nothing to see"


# -- CSV --------------------------------------------------------------------------------
def _read_csv(text: str):
    """(comment key/values in order, poses, header, rows), parsed independently."""
    comments, poses, table = [], [], []
    lines = text.split("\n")
    assert lines[-1] == "", "the text ends with a newline"
    lines = lines[:-1]
    index = 0
    while lines[index].startswith("#"):
        line = lines[index]
        assert line.startswith("# ")
        if line.startswith("# pose "):
            name, end = json.JSONDecoder().raw_decode(line, len("# pose "))
            rest = line[end:]
            assert rest.startswith(" = ")
            poses.append((name, tuple(float(v) for v in rest[3:].split(", "))))
        else:
            key, sep, value = line[2:].partition(" = ")
            assert sep, line
            comments.append((key, value))
        index += 1
    table = list(csv.reader(io.StringIO("\n".join(lines[index:]) + "\n")))
    assert all(not line.startswith("#") for line in lines[index:])
    return comments, poses, table[0], table[1:]


def _triple_of(value: str) -> tuple[float, float, float]:
    parts = value.split(", ")
    assert len(parts) == 3
    return tuple(float(p) for p in parts)  # type: ignore[return-value]


def _robot_from_csv(text: str) -> Robot:
    comments, poses, header, rows = _read_csv(text)
    values = dict(comments)
    units = values["units"]
    assert ",".join(header) == HEADER.format(u=units)
    joints_ = []
    for number, row in enumerate(rows, start=1):
        assert len(row) == 9
        assert row[0] == str(number)
        assert row[1] in ("R", "P")
        theta, d, a, alpha, offset, lo, hi = (float(v) for v in row[2:])
        kind = "revolute" if row[1] == "R" else "prismatic"
        joints_.append(Joint(kind, theta, d, a, alpha, lo, hi, offset))
    return Robot(
        name=json.loads(values["name"]),
        joints=tuple(joints_),
        units=units,
        convention=values["convention"],
        base_height=float(values["base_height"]),
        base_z=values["base_z"],
        base_x=values["base_x"],
        base_xyz=_triple_of(values["base_xyz"]),
        base_rpy=_triple_of(values["base_rpy"]),
        tool=Tool(_triple_of(values["tool_xyz"]), _triple_of(values["tool_rpy"])),
        poses=tuple(poses),
    )


def _check_csv(robot: Robot) -> None:
    text = to_csv(robot)
    comments, poses, header, rows = _read_csv(text)
    assert [key for key, _ in comments] == COMMENT_KEYS
    values = dict(comments)
    assert values["format"] == "dhsim-dh-table 1"
    assert json.loads(values["name"]) == robot.name
    assert values["convention"] == robot.convention
    assert values["units"] == robot.units
    assert float(values["base_height"]) == robot.base_height
    assert (values["base_z"], values["base_x"]) == (robot.base_z, robot.base_x)
    assert _triple_of(values["base_xyz"]) == tuple(robot.base_xyz)
    assert _triple_of(values["base_rpy"]) == tuple(robot.base_rpy)
    assert _triple_of(values["tool_xyz"]) == tuple(robot.tool.xyz)
    assert _triple_of(values["tool_rpy"]) == tuple(robot.tool.rpy)
    assert poses == [(name, tuple(v)) for name, v in robot.poses]
    assert ",".join(header) == HEADER.format(u=robot.units)
    assert len(rows) == robot.dof
    for number, (row, joint) in enumerate(zip(rows, robot.joints, strict=True), start=1):
        assert row[:2] == [str(number), "R" if joint.is_revolute else "P"]
        expected = [joint.theta, joint.d, joint.a, joint.alpha, joint.offset, joint.min, joint.max]
        assert [float(v) for v in row[2:]] == expected  # exact
    # a D-H table: no programs, no joint speeds (the JSON and the robot file carry those)
    table = tuple(replace(joint, vmax=None, amax=None) for joint in robot.joints)
    assert _robot_from_csv(text) == replace(robot, joints=table, programs=())


@pytest.mark.parametrize("name", BUNDLED)
def test_csv_bundled(name):
    _check_csv(load_robot(name)[0])


@settings(max_examples=100, deadline=None)
@given(robot=robots())
def test_csv_random(robot):
    _check_csv(robot)


def test_csv_header_exactly():
    robot = Robot("x", (Joint(), Joint("prismatic", min=-1.0, max=1.0)), units="in")
    header = to_csv(robot).split("\n")[11]
    assert header == (
        "joint,type,theta (deg),d (in),a (in),alpha (deg),offset (deg|in),min (deg|in),max (deg|in)"
    )


def test_csv_numbers_are_whole_and_names_quoted():
    robot = Robot(
        'a "quoted", name',
        (Joint(theta=0.1 + 0.2, a=431.8, alpha=-90.0, min=-160.0, max=160.0),),
        poses=(('odd, "one" = 1', (0.30000000000000004,)),),
    )
    text = to_csv(robot)
    assert '# name = "a \\"quoted\\", name"' in text
    assert '# pose "odd, \\"one\\" = 1" = 0.30000000000000004' in text
    assert "1,R,0.30000000000000004,0,431.8,-90,0,-160,160\n" in text
    assert _robot_from_csv(text) == replace(robot, programs=())  # a D-H table: no programs


# -- JSON -------------------------------------------------------------------------------
def _no_constants(name):
    raise AssertionError(f"not finite JSON: {name}")


def _check_json(robot: Robot) -> None:
    text = to_json(robot)
    assert text.startswith('{\n  "format": "dhsim-robot",\n  "version": 1,')
    data = json.loads(text, parse_constant=_no_constants)
    assert list(data) == [
        "format",
        "version",
        "name",
        "units",
        "convention",
        "parameter_order",
        "joint_value",
        "base",
        "tool",
        "joints",
        "poses",
        "programs",
    ]
    assert data["format"] == "dhsim-robot" and data["version"] == 1
    assert data["name"] == robot.name
    assert data["units"] == {"length": robot.units, "angle": "deg"}
    assert data["convention"] == robot.convention
    order = ["theta", "d", "a", "alpha", "offset", "min", "max"]
    assert data["parameter_order"] == order
    assert data["joint_value"] == "theta = q + offset (revolute), d = q + offset (prismatic)"
    assert data["base"] == {
        "height": robot.base_height,
        "z": robot.base_z,
        "x": robot.base_x,
        "xyz": list(robot.base_xyz),
        "rpy": list(robot.base_rpy),
    }
    assert list(data["base"]) == ["height", "z", "x", "xyz", "rpy"]
    assert data["tool"] == {"xyz": list(robot.tool.xyz), "rpy": list(robot.tool.rpy)}
    assert len(data["joints"]) == robot.dof
    for got, joint in zip(data["joints"], robot.joints, strict=True):
        speeds = [key for key in ("vmax", "amax") if getattr(joint, key) is not None]
        assert list(got) == ["type", *order, *speeds]
        assert got["type"] == joint.type
        for key in order:
            assert got[key] == getattr(joint, key), key
            assert isinstance(got[key], float)
    assert list(data["poses"].items()) == [(n, list(v)) for n, v in robot.poses]
    rebuilt = Robot(
        name=data["name"],
        joints=tuple(
            Joint(
                j["type"],
                *(j[k] for k in ("theta", "d", "a", "alpha", "min", "max", "offset")),
                vmax=j.get("vmax"),
                amax=j.get("amax"),
            )
            for j in data["joints"]
        ),
        units=data["units"]["length"],
        convention=data["convention"],
        base_height=data["base"]["height"],
        base_z=data["base"]["z"],
        base_x=data["base"]["x"],
        base_xyz=tuple(data["base"]["xyz"]),
        base_rpy=tuple(data["base"]["rpy"]),
        tool=Tool(tuple(data["tool"]["xyz"]), tuple(data["tool"]["rpy"])),
        poses=tuple((n, tuple(v)) for n, v in data["poses"].items()),
        programs=programs_from_data(data["programs"]),
    )
    assert rebuilt == robot


@pytest.mark.parametrize("name", BUNDLED)
def test_json_bundled(name):
    _check_json(load_robot(name)[0])


@settings(max_examples=100, deadline=None)
@given(robot=robots())
def test_json_random(robot):
    _check_json(robot)


# -- export_text and write_export ------------------------------------------------------
def test_formats_and_suffixes():
    assert EXPORT_FORMATS == ("urdf", "csv", "json")
    assert EXPORT_SUFFIXES == {"urdf": ".urdf", "csv": ".csv", "json": ".json"}
    robot = load_robot("puma560")[0]
    assert export_text(robot, "urdf") == to_urdf(robot)
    assert export_text(robot, "csv") == to_csv(robot)
    assert export_text(robot, "json") == to_json(robot)


@pytest.mark.parametrize("bad", ["URDF", "xml", "", "csv\x1b[2J", None])
def test_unknown_format_is_refused(bad):
    robot = load_robot("puma560")[0]
    with pytest.raises(DhsimError) as info:
        export_text(robot, bad)
    message = str(info.value)
    assert "urdf, csv, json" in message
    assert "\n" not in message and "\x1b" not in message


@pytest.mark.parametrize("fmt", EXPORT_FORMATS)
def test_write_export_writes_and_refuses_to_overwrite(fmt, tmp_path):
    robot = load_robot("puma560")[0]
    path = tmp_path / f"puma{EXPORT_SUFFIXES[fmt]}"
    assert write_export(robot, fmt, str(path)) == path
    assert path.read_text(encoding="utf-8") == export_text(robot, fmt)
    other = load_robot("stanford")[0]
    with pytest.raises(DhsimError) as info:
        write_export(other, fmt, path)
    assert str(path) in str(info.value) and "exists" in str(info.value)
    assert "\n" not in str(info.value)
    assert path.read_text(encoding="utf-8") == export_text(robot, fmt)  # untouched
    path.chmod(0o640)
    write_export(other, fmt, path, overwrite=True)
    assert path.read_text(encoding="utf-8") == export_text(other, fmt)
    assert stat.S_IMODE(path.stat().st_mode) == 0o640  # the replaced file's mode kept
    assert sorted(p.name for p in tmp_path.iterdir()) == [path.name]  # no temporary left


@pytest.mark.parametrize("overwrite", [False, True])
def test_write_export_refuses_a_folder(overwrite, tmp_path):
    folder = tmp_path / "out.urdf"
    folder.mkdir()
    with pytest.raises(DhsimError) as info:
        write_export(load_robot("puma560")[0], "urdf", folder, overwrite=overwrite)
    assert str(folder) in str(info.value) and "folder" in str(info.value)
    assert list(folder.iterdir()) == []


def test_write_export_unknown_format_writes_nothing(tmp_path):
    with pytest.raises(DhsimError):
        write_export(load_robot("puma560")[0], "yaml", tmp_path / "x.yaml")
    assert list(tmp_path.iterdir()) == []


def test_write_export_is_atomic(tmp_path, monkeypatch):
    """A failure while writing leaves the old file whole and no temporary behind."""
    robot = load_robot("puma560")[0]
    path = tmp_path / "puma.json"
    path.write_text("old", encoding="utf-8")

    def broken(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", broken)
    with pytest.raises(DhsimError) as info:
        write_export(robot, "json", path, overwrite=True)
    assert str(path) in str(info.value) and "No space left" in str(info.value)
    assert path.read_text(encoding="utf-8") == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["puma.json"]


def test_write_export_os_errors_name_the_path(tmp_path):
    robot = load_robot("puma560")[0]
    missing = tmp_path / "no such folder" / "arm.urdf"
    with pytest.raises(DhsimError) as info:
        write_export(robot, "urdf", missing)
    assert str(missing) in str(info.value)
    afile = tmp_path / "file"
    afile.write_text("x", encoding="utf-8")
    inside = afile / "arm.urdf"
    with pytest.raises(DhsimError) as info:
        write_export(robot, "urdf", inside)
    assert str(inside) in str(info.value)
    with pytest.raises(DhsimError) as info:
        write_export(robot, "urdf", str(tmp_path / "nul\x00name.urdf"))
    assert "nul\\x00name.urdf" in str(info.value)
    if os.geteuid() != 0:  # root may write anywhere
        locked = tmp_path / "locked"
        locked.mkdir()
        locked.chmod(0o500)
        try:
            with pytest.raises(DhsimError) as info:
                write_export(robot, "urdf", locked / "arm.urdf")
            assert str(locked / "arm.urdf") in str(info.value)
        finally:
            locked.chmod(0o700)


def test_write_export_follows_a_symlink(tmp_path):
    robot = load_robot("puma560")[0]
    real = tmp_path / "real.csv"
    real.write_text("old", encoding="utf-8")
    link = tmp_path / "link.csv"
    link.symlink_to(real)
    with pytest.raises(DhsimError):
        write_export(robot, "csv", link)
    write_export(robot, "csv", link, overwrite=True)
    assert link.is_symlink()
    assert real.read_text(encoding="utf-8") == to_csv(robot)

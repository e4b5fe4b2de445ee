"""Hypothesis fuzzing of robot files: junk text, junk bytes and near-valid
documents only ever load as a valid robot or raise RobotFileError; valid
random robots round-trip exactly."""

from __future__ import annotations

import copy
import math
from pathlib import Path

import pytest
import tomli_w
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from dhsim_tui.core.files.robotfile import dumps, load, loads, save
from dhsim_tui.core.files.robotschema import robot_to_dict
from dhsim_tui.core.model.errors import RobotFileError
from dhsim_tui.core.model.robot import AXES, CONVENTIONS, MIN_LENGTH_MM, UNITS, Joint, Robot, Tool

ROBOTS_DIR = Path(__file__).resolve().parents[2] / "robots"
BUNDLED_FILES = sorted(ROBOTS_DIR.glob("*.toml"))
BUNDLED_TEXT = [p.read_text(encoding="utf-8") for p in BUNDLED_FILES]

FUZZ = settings(
    max_examples=200,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)


def check_outcome(path: Path | None, load_it) -> Robot | None:
    """Run ``load_it``; it must return a valid robot or raise RobotFileError."""
    try:
        robot = load_it()
    except RobotFileError as exc:
        message = str(exc)
        assert message.strip()
        if path is not None:
            assert message.startswith(str(path)), message
        return None
    assert_valid(robot)
    return robot


def assert_valid(robot: Robot) -> None:
    """What a loaded robot must satisfy, checked independently of the validator."""
    assert isinstance(robot, Robot)
    assert isinstance(robot.name, str) and robot.name.strip()
    assert robot.units in ("mm", "cm", "m", "in")
    assert robot.convention in ("standard", "modified")
    assert math.isfinite(robot.base_height) and robot.base_height >= 0
    assert robot.base_z in AXES and robot.base_x in AXES
    assert robot.base_z[1] != robot.base_x[1]
    assert 1 <= robot.dof <= 32
    for name in (robot.name, *robot.pose_names):
        assert not any(_steers_terminal(c) for c in name), ascii(name)
    lengths = [robot.base_height, *robot.tool.xyz]
    for joint in robot.joints:
        lengths += [joint.d, joint.a]
        if joint.type == "prismatic":
            lengths += [joint.min, joint.max]
    for value in lengths:  # 0, or at least a nanometre
        assert value == 0 or abs(value) * UNITS[robot.units] >= MIN_LENGTH_MM * (1 - 1e-9)
    for joint in robot.joints:
        assert joint.type in ("revolute", "prismatic")
        numbers = (joint.theta, joint.d, joint.a, joint.alpha, joint.min, joint.max)
        assert all(isinstance(v, float) and math.isfinite(v) for v in numbers)
        assert joint.min < joint.max
        home = joint.theta if joint.type == "revolute" else joint.d
        assert joint.min <= home <= joint.max
    for value in (*robot.tool.xyz, *robot.tool.rpy):
        assert math.isfinite(value)
    for _, values in robot.poses:
        assert len(values) == robot.dof
        for joint, value in zip(robot.joints, values, strict=True):
            assert joint.min <= value <= joint.max


def _steers_terminal(char: str) -> bool:
    """C0, DEL, C1, bidi overrides and isolates, zero-width marks, surrogates
    (written out here, independently of dhsim_tui.core.model.text)."""
    code = ord(char)
    return (
        code < 0x20
        or 0x7F <= code < 0xA0
        or 0x200B <= code <= 0x200F
        or 0x202A <= code <= 0x202E
        or 0x2066 <= code <= 0x2069
        or 0xD800 <= code <= 0xDFFF
    )


# -- (a) arbitrary text and bytes ----------------------------------------------

TOML_PIECES = [
    "name = ",
    '"arm"',
    "[[joints]]",
    "[tool]",
    "[poses]",
    "theta = ",
    "d = ",
    "a = ",
    "alpha = ",
    "min = ",
    "max = ",
    "type = ",
    '"revolute"',
    '"prismatic"',
    "units = ",
    '"cm"',
    "base_z = ",
    '"-x"',
    "[",
    "]",
    "{",
    "}",
    ",",
    "=",
    '"',
    "'",
    "\n",
    " ",
    "#",
    ".",
    "0",
    "1e400",
    "nan",
    "-inf",
    "90.0",
    "true",
    "1979-05-27",
    "\\u0000",
    "\ufeff",
    "\r\n",
]

toml_ish = st.lists(st.sampled_from(TOML_PIECES) | st.text(max_size=5), max_size=60).map("".join)


@st.composite
def nested_text(draw) -> str:
    """Arrays or inline tables nested up to 2000 deep (tomllib recurses on them)."""
    opener, closer = draw(st.sampled_from([("[", "]"), ("{a = ", "}"), ("[{b = ", "}]")]))
    depth = draw(st.integers(0, 2000))
    key = draw(st.sampled_from(["name", "joints", "tool", "poses", "x"]))
    tail = closer * depth if draw(st.booleans()) else ""
    return f'{key} = {opener * depth}"v"{tail}\n'


@st.composite
def edited_robot_text(draw) -> str:
    """A bundled robot file with a few characters inserted, deleted or replaced."""
    text = draw(st.sampled_from(BUNDLED_TEXT))
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, len(text)))
        cut = draw(st.integers(0, 6))
        insert = draw(st.sampled_from(TOML_PIECES) | st.text(max_size=3))
        text = text[:at] + insert + text[at + cut :]
    return text


@pytest.mark.slow  # a long hypothesis run
@FUZZ
@given(text=st.text() | toml_ish | nested_text() | edited_robot_text())
def test_arbitrary_text_loads_or_raises_robot_file_error(tmp_path, text):
    path = tmp_path / "fuzz.toml"
    path.write_bytes(text.encode("utf-8", "surrogatepass"))
    check_outcome(path, lambda: load(path))
    check_outcome(None, lambda: loads(text, "fuzz"))


@st.composite
def edited_robot_bytes(draw) -> bytes:
    data = bytearray(draw(st.sampled_from(BUNDLED_TEXT)).encode())
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, len(data) - 1))
        data[at] = draw(st.integers(0, 255))
    return bytes(data)


@pytest.mark.slow  # a long hypothesis run
@FUZZ
@given(raw=st.binary(max_size=2000) | edited_robot_bytes())
def test_arbitrary_bytes_load_or_raise_robot_file_error(tmp_path, raw):
    path = tmp_path / "fuzz.toml"
    path.write_bytes(raw)
    check_outcome(path, lambda: load(path))


# -- (b) near-valid documents --------------------------------------------------

near_valid = st.sampled_from(
    [
        "revolute",
        "prismatic",
        "mm",
        "in",
        "standard",
        "modified",
        "+z",
        "-x",
        "+y",
        "",
        0,
        -0.0,
        180.0,
        -180.0,
        400.0,
        1e6,
        1e6 + 1,
    ]
)
# integers beyond what a float can hold (TOML integers are unbounded)
huge_ints = st.sampled_from([10**400, -(10**400), 2**1024]) | st.integers(min_value=2**1023)
scalars = st.one_of(
    st.integers(),
    huge_ints,
    st.floats(),  # nan, inf, -0.0, subnormals, huge
    st.floats(-2e6, 2e6),
    st.text(max_size=12),
    st.booleans(),
    near_valid,
)
junk = st.recursive(
    scalars,
    lambda children: (
        st.lists(children, max_size=5) | st.dictionaries(st.text(max_size=8), children, max_size=4)
    ),
    max_leaves=10,
)


def _paths(value, prefix=()):
    """Every path into the nested dict/list document."""
    if isinstance(value, dict):
        for key, child in value.items():
            yield (*prefix, key)
            yield from _paths(child, (*prefix, key))
    elif isinstance(value, list):
        for index, child in enumerate(value):
            yield (*prefix, index)
            yield from _paths(child, (*prefix, index))


BASE_DOCS = [robot_to_dict(load(path)) for path in BUNDLED_FILES]


@st.composite
def mutated_document(draw) -> dict:
    data = copy.deepcopy(draw(st.sampled_from(BASE_DOCS)))
    paths = list(_paths(data))
    path = draw(st.sampled_from(paths))
    *parents, last = path
    parent = data
    for step in parents:
        parent = parent[step]
    operation = draw(st.sampled_from(["replace", "replace", "delete", "add"]))
    if operation == "replace":
        parent[last] = draw(junk)
    elif operation == "delete":
        del parent[last]
    else:
        target = parent[last] if isinstance(parent[last], dict | list) else parent
        if isinstance(target, dict):
            target[draw(st.text(min_size=1, max_size=8))] = draw(junk)
        else:
            target.append(draw(junk))
    return data


@pytest.mark.slow  # a long hypothesis run
@FUZZ
@given(data=mutated_document())
def test_near_valid_documents_load_or_raise_robot_file_error(tmp_path, data):
    path = tmp_path / "fuzz.toml"
    path.write_text(tomli_w.dumps(data), encoding="utf-8")
    check_outcome(path, lambda: load(path))


def test_mutation_fuzz_reaches_both_outcomes(tmp_path):
    # guard against a fuzzer that only ever produces one kind of document
    outcomes = set()

    @settings(max_examples=60, deadline=None, database=None, derandomize=True)
    @given(data=mutated_document())
    def run(data):
        try:
            loads(tomli_w.dumps(data))
            outcomes.add("robot")
        except RobotFileError:
            outcomes.add("error")

    run()
    assert outcomes == {"robot", "error"}


# -- (c) valid random robots round-trip exactly --------------------------------

finite = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)
#: a length: 0 or at least 1e-5 (a nanometre is 1e-6 mm, 1e-9 m: fine in every unit)
length = finite.map(lambda v: 0.0 if abs(v) < 1e-5 else v)
unit = st.floats(0.0, 1.0)


@st.composite
def joints(draw) -> Joint:
    joint_type = draw(st.sampled_from(["revolute", "prismatic"]))
    variable = length if joint_type == "prismatic" else finite
    low, home, high = sorted(draw(st.tuples(variable, variable, variable)))  # home may be a limit
    assume(low < high)
    fixed = draw(st.tuples(finite, length, length, finite))
    if joint_type == "revolute":
        theta, d = home, fixed[1]
    else:
        theta, d = fixed[0], home
    return Joint(joint_type, theta, d, fixed[2], fixed[3], low, high)


# any text a file can hold, except control characters, which names forbid
names = (
    st.text(st.characters(exclude_categories=("Cs",)), min_size=1, max_size=20)
    .map(lambda text: "".join(c for c in text if not _steers_terminal(c)))
    .filter(str.strip)
)


@st.composite
def robots(draw) -> Robot:
    joint_list = tuple(draw(st.lists(joints(), min_size=1, max_size=8)))
    base_z = draw(st.sampled_from(AXES))
    base_x = draw(st.sampled_from([a for a in AXES if a[1] != base_z[1]]))
    if draw(st.booleans()):
        tool = Tool(
            xyz=draw(st.tuples(length, length, length)),
            rpy=draw(st.tuples(finite, finite, finite)),
        )
    else:
        tool = Tool()
    pose_names = draw(st.lists(names, max_size=3, unique=True))
    poses = []
    for pose_name in pose_names:
        assume(pose_name.strip())
        fractions = draw(st.lists(unit, min_size=len(joint_list), max_size=len(joint_list)))
        values = tuple(
            min(max(j.min + f * (j.max - j.min), j.min), j.max)
            for j, f in zip(joint_list, fractions, strict=True)
        )
        poses.append((pose_name, values))
    return Robot(
        name=draw(names),
        joints=joint_list,
        units=draw(st.sampled_from(sorted(UNITS))),
        convention=draw(st.sampled_from(CONVENTIONS)),
        base_height=draw(st.floats(0, 1e6).map(lambda v: 0.0 if v < 1e-5 else v)),
        base_z=base_z,
        base_x=base_x,
        tool=tool,
        poses=tuple(poses),
    )


def _exact(value):
    """Floats compared bit for bit (so 0.1 + 0.2 must not come back as 0.3)."""
    if isinstance(value, float):
        return value.hex() if value != 0 else "0"
    if isinstance(value, tuple | list):
        return tuple(_exact(v) for v in value)
    return value


def _fields(robot: Robot):
    return (
        robot.name,
        robot.units,
        robot.convention,
        _exact(robot.base_height),
        robot.base_z,
        robot.base_x,
        _exact(robot.tool.xyz),
        _exact(robot.tool.rpy),
        tuple((name, _exact(values)) for name, values in robot.poses),
        tuple((j.type, *_exact((j.theta, j.d, j.a, j.alpha, j.min, j.max))) for j in robot.joints),
    )


# fewer examples: each one fsyncs a real file and a robot takes long to generate
@settings(FUZZ, max_examples=100)
@given(robot=robots())
def test_valid_random_robot_round_trips_exactly(tmp_path, robot):
    path = save(robot, tmp_path / "random.toml")
    again = load(path)
    assert again == robot
    assert _fields(again) == _fields(robot)
    assert loads(dumps(robot)) == robot
    assert [p.name for p in tmp_path.iterdir()] == ["random.toml"]

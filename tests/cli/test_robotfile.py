"""Robot files: strict loading with one clear message per problem, the
schema's defaults, exact round trips and atomic saving.

Test documents are built as plain dicts and written with tomli-w (or as
literal TOML text), never with the module under test, so a writer bug cannot
hide a reader bug.
"""

from __future__ import annotations

import copy
import errno
import os
import tempfile
from pathlib import Path

import pytest
import tomli_w

from dhsim_tui.core.files.library import bundled_names, bundled_path
from dhsim_tui.core.files.robotfile import dumps, load, loads, save
from dhsim_tui.core.files.tomlparse import MAX_STRING_CHARS, tomllib
from dhsim_tui.core.model.errors import DhsimError, RobotFileError
from dhsim_tui.core.model.robot import Joint, Robot, Tool

ROBOTS_DIR = Path(__file__).resolve().parents[2] / "robots"
BUNDLED_STEMS = sorted(p.stem for p in ROBOTS_DIR.glob("*.toml"))

# A valid three-joint robot (R, R, P) exercising every optional section.
VALID = {
    "name": "Test arm",
    "units": "mm",
    "convention": "standard",
    "base_height": 100.0,
    "base_z": "+z",
    "base_x": "+x",
    "tool": {"xyz": [0.0, 0.0, 50.0], "rpy": [0.0, 0.0, 0.0]},
    "poses": {"ready": [0.0, 90.0, 100.0], "low": [10.0, -45.0, 0.0]},
    "joints": [
        {
            "type": "revolute",
            "theta": 0.0,
            "d": 300.0,
            "a": 0.0,
            "alpha": 90.0,
            "min": -170.0,
            "max": 170.0,
        },
        {
            "type": "revolute",
            "theta": 0.0,
            "d": 0.0,
            "a": 400.0,
            "alpha": 0.0,
            "min": -90.0,
            "max": 135.0,
        },
        {
            "type": "prismatic",
            "theta": 0.0,
            "d": 50.0,
            "a": 0.0,
            "alpha": 0.0,
            "min": 0.0,
            "max": 200.0,
        },
    ],
}

#: a number tomli-w writes verbatim, replaced by raw TOML text afterwards
PLACEHOLDER = 987654.125


def doc() -> dict:
    return copy.deepcopy(VALID)


def write(folder: Path, content: str | bytes | dict, name: str = "robot.toml") -> Path:
    path = folder / name
    if isinstance(content, dict):
        content = tomli_w.dumps(content)
    if isinstance(content, str):
        content = content.encode("utf-8")
    path.write_bytes(content)
    return path


def rejection(path: Path) -> str:
    """Load ``path``, expecting the project's error; return its message."""
    with pytest.raises(RobotFileError) as info:
        load(path)
    message = str(info.value)
    assert isinstance(info.value, DhsimError)
    assert message.startswith(str(path)), message
    assert "\n" not in message, message
    return message


def assert_names(message: str, *fragments: str) -> None:
    for fragment in fragments:
        assert fragment in message, f"{fragment!r} not in {message!r}"


# -- the valid document itself ----------------------------------------------


def test_valid_document_loads_with_every_field(tmp_path):
    robot = load(write(tmp_path, doc()))
    assert robot.name == "Test arm"
    assert robot.units == "mm"
    assert robot.base_height == 100.0
    assert robot.dof == 3
    assert robot.type_string == "RRP"
    assert robot.joints[1] == Joint("revolute", 0.0, 0.0, 400.0, 0.0, -90.0, 135.0)
    assert robot.joints[2] == Joint("prismatic", 0.0, 50.0, 0.0, 0.0, 0.0, 200.0)
    assert robot.tool == Tool(xyz=(0.0, 0.0, 50.0), rpy=(0.0, 0.0, 0.0))
    assert robot.poses == (("ready", (0.0, 90.0, 100.0)), ("low", (10.0, -45.0, 0.0)))
    assert robot.home == (0.0, 0.0, 50.0)


# -- malformed TOML ----------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "line"),
    [
        ('name = "x"\nunits = "mm"\nbase_height = = 3\n', 3),
        ('name = "x"\n\n\n\nunits = "mm\n', 5),  # unterminated string
        ('name = "x"\nname = "y"\n', 2),  # duplicate key
        ('name = "x"\n[[joints]]\ntheta = 0\nd = 0 a = 1\n', 4),
        ('name = "x"\n[poses\n', 2),
    ],
)
def test_malformed_toml_names_the_line(tmp_path, text, line):
    message = rejection(write(tmp_path, text))
    assert_names(message, "not valid TOML", f"line {line}")


def test_deeply_nested_toml_is_a_robot_file_error_not_a_recursion_error(tmp_path):
    # tomllib recurses into nested arrays; a small hostile file used to escape
    # as RecursionError (a traceback in the CLI).
    # (an array may span lines; an inline table may not, so it stays under the
    # line bound: 1,500 levels are 9,000 characters, past the recursion limit)
    depth = 5000
    message = rejection(write(tmp_path, "name = " + "[\n" * depth + "]\n" * depth))
    assert_names(message, "not valid TOML", "nested too deeply")
    depth = 1500
    inline = "tool = " + "{a = " * depth + "1" + "}" * depth + "\n"
    assert_names(
        rejection(write(tmp_path, inline, "inline.toml")), "not valid TOML", "nested too deeply"
    )


def test_empty_file_is_missing_name(tmp_path):
    assert_names(rejection(write(tmp_path, "")), "missing key 'name'")


# -- missing and unknown keys ------------------------------------------------


def _without(path: tuple, data: dict | None = None) -> dict:
    data = doc() if data is None else data
    *parents, last = path
    target = data
    for key in parents:
        target = target[key]
    del target[last]
    return data


@pytest.mark.parametrize(
    ("path", "fragments"),
    [
        (("name",), ["missing key 'name'"]),
        (("joints",), ["missing key 'joints'"]),
        (("joints", 0, "theta"), ["joints[1]", "missing key 'theta'"]),
        (("joints", 1, "d"), ["joints[2]", "missing key 'd'"]),
        (("joints", 2, "a"), ["joints[3]", "missing key 'a'"]),
        (("joints", 2, "alpha"), ["joints[3]", "missing key 'alpha'"]),
    ],
)
def test_missing_required_key(tmp_path, path, fragments):
    assert_names(rejection(write(tmp_path, _without(path))), *fragments)


@pytest.mark.parametrize(
    ("where", "key", "fragments"),
    [
        ((), "colour", ["colour: unknown key"]),
        ((), "nmae", ["nmae: unknown key", "did you mean 'name'"]),
        ((), "base_hieght", ["base_hieght: unknown key", "did you mean 'base_height'"]),
        (("joints", 2), "alhpa", ["joints[3].alhpa: unknown key", "did you mean 'alpha'"]),
        (("joints", 0), "thetta", ["joints[1].thetta", "did you mean 'theta'"]),
        (("joints", 1), "ofset", ["joints[2].ofset: unknown key", "did you mean 'offset'"]),
        (("tool",), "xzy", ["tool.xzy: unknown key", "did you mean 'xyz'"]),
    ],
)
def test_unknown_key_is_caught_with_a_suggestion(tmp_path, where, key, fragments):
    data = doc()
    target = data
    for step in where:
        target = target[step]
    target[key] = 1.0
    assert_names(rejection(write(tmp_path, data)), *fragments)


def test_unknown_key_without_a_close_match_lists_the_allowed_ones(tmp_path):
    data = doc()
    data["joints"][0]["zzzzzz"] = 1.0
    message = rejection(write(tmp_path, data))
    assert_names(message, "joints[1].zzzzzz", "allowed", "theta", "alpha", "min", "max")


# -- wrong types ---------------------------------------------------------------


def _set(data: dict, path: tuple, value) -> dict:
    *parents, last = path
    target = data
    for key in parents:
        target = target[key]
    target[last] = value
    return data


@pytest.mark.parametrize(
    ("path", "value", "fragments"),
    [
        (("joints", 2, "alpha"), "90", ["joints[3].alpha", "expected a number", "'90'"]),
        (("joints", 0, "theta"), "zero", ["joints[1].theta", "expected a number"]),
        (("joints", 1, "a"), True, ["joints[2].a", "expected a number", "boolean true"]),
        (("joints", 1, "min"), False, ["joints[2].min", "boolean false"]),
        (("joints", 0, "max"), [170.0], ["joints[1].max", "expected a number", "list"]),
        (("joints", 0, "d"), {"v": 1.0}, ["joints[1].d", "expected a number", "table"]),
        (("base_height",), "100", ["base_height", "expected a number"]),
        (("base_height",), True, ["base_height", "boolean"]),
        (("tool", "xyz", 1), "x", ["tool.xyz[2]", "expected a number"]),
        (("tool", "rpy", 0), True, ["tool.rpy[1]", "boolean"]),
        (("poses", "ready", 1), "90", ["poses.ready[2]", "expected a number"]),
        (("poses", "low", 2), False, ["poses.low[3]", "boolean"]),
        # a table where a list belongs
        (("tool", "xyz"), {"x": 0.0, "y": 0.0, "z": 1.0}, ["tool.xyz", "list of 3 numbers"]),
        (("poses", "ready"), {"a": 1.0}, ["poses.ready", "list"]),
        (("joints",), {"theta": 0.0}, ["joints", "array of tables"]),
        # a list or scalar where a table belongs
        (("tool",), [1.0, 2.0, 3.0], ["tool", "expected a table"]),
        (("poses",), [0.0, 0.0, 0.0], ["poses", "expected a table"]),
        (("joints",), [1, 2, 3], ["joints[1]", "expected a table"]),
        (("joints",), "RRP", ["joints", "array of tables"]),
        # strings that must be strings
        (("name",), 5, ["name", "text"]),
        (("units",), 1, ["units", "not one of"]),
        (("convention",), ["standard"], ["convention", "text"]),
        (("base_z",), 3, ["base_z", "text"]),
        (("base_x",), True, ["base_x", "text"]),
        (("joints", 1, "type"), 1, ["joints[2].type", "not one of"]),
    ],
)
def test_wrong_type(tmp_path, path, value, fragments):
    assert_names(rejection(write(tmp_path, _set(doc(), path, value))), *fragments)


@pytest.mark.parametrize(
    ("raw", "fragments"),
    [
        ("1979-05-27", ["joints[2].alpha", "expected a number", "date"]),
        ("07:32:00", ["joints[2].alpha", "expected a number", "time"]),
    ],
)
def test_toml_dates_are_not_numbers(tmp_path, raw, fragments):
    data = _set(doc(), ("joints", 1, "alpha"), PLACEHOLDER)
    text = tomli_w.dumps(data).replace(repr(PLACEHOLDER), raw)
    assert_names(rejection(write(tmp_path, text)), *fragments)


# -- numbers out of the world -----------------------------------------------


@pytest.mark.parametrize(
    ("path", "raw", "fragments"),
    [
        (("joints", 2, "alpha"), "nan", ["joints[3].alpha", "NaN"]),
        (("joints", 0, "theta"), "-nan", ["joints[1].theta", "NaN"]),
        (("joints", 1, "a"), "inf", ["joints[2].a", "out of range"]),
        (("joints", 1, "a"), "-inf", ["joints[2].a", "out of range"]),
        (("joints", 1, "d"), "1e400", ["joints[2].d", "out of range"]),
        (("joints", 0, "max"), "+inf", ["joints[1].max", "out of range"]),
        (("joints", 0, "min"), "-1e400", ["joints[1].min", "out of range"]),
        (("base_height",), "inf", ["base_height", "out of range"]),
        (("base_height",), "nan", ["base_height", "NaN"]),
        (("tool", "xyz", 2), "1e400", ["tool.xyz[3]", "out of range"]),
        (("poses", "ready", 0), "nan", ["poses.ready[1]", "NaN"]),
        (("joints", 1, "a"), "1e7", ["joints[2].a", "out of range"]),
        (("joints", 1, "a"), "1" + "0" * 30, ["joints[2].a", "out of range"]),
        (("joints", 1, "a"), "-" + "9" * 400, ["joints[2].a", "out of range"]),
    ],
)
def test_non_finite_and_huge_numbers(tmp_path, path, raw, fragments):
    data = _set(doc(), path, PLACEHOLDER)
    text = tomli_w.dumps(data).replace(repr(PLACEHOLDER), raw)
    assert raw in text
    assert_names(rejection(write(tmp_path, text)), *fragments)


def test_integer_too_long_for_python_is_a_robot_file_error(tmp_path):
    # more digits than int() accepts (4300): tomllib raises a bare ValueError
    data = _set(doc(), ("joints", 1, "a"), PLACEHOLDER)
    text = tomli_w.dumps(data).replace(repr(PLACEHOLDER), "9" * 5000)
    assert_names(rejection(write(tmp_path, text)), "not valid TOML")


# -- limits and home values --------------------------------------------------


def test_min_greater_than_max(tmp_path):
    data = doc()
    data["joints"][1].update(min=100.0, max=50.0)
    assert_names(rejection(write(tmp_path, data)), "joints[2]", "min (100)", "max (50)")


def test_min_equal_to_max(tmp_path):
    data = doc()
    data["joints"][2].update(d=50.0, min=50.0, max=50.0)
    assert_names(rejection(write(tmp_path, data)), "joints[3]", "min (50)", "less than max (50)")


def test_revolute_home_outside_limits(tmp_path):
    data = doc()
    data["joints"][0]["theta"] = 175.0
    message = rejection(write(tmp_path, data))
    assert_names(message, "joints[1].theta", "175", "-170..170", "deg")


def test_prismatic_home_outside_limits(tmp_path):
    data = doc()
    data["joints"][2]["d"] = -5.0
    message = rejection(write(tmp_path, data))
    assert_names(message, "joints[3].d", "-5", "0..200", "mm")


def test_home_outside_default_limits(tmp_path):
    data = doc()
    del data["joints"][2]["min"]
    del data["joints"][2]["max"]
    data["joints"][2]["d"] = 500.0
    data["poses"] = {}
    message = rejection(write(tmp_path, data))
    assert_names(message, "joints[3].d", "500", "-400..400")


def test_home_on_a_limit_is_accepted(tmp_path):
    data = doc()
    data["joints"][0]["theta"] = 170.0
    data["joints"][2]["d"] = 0.0
    robot = load(write(tmp_path, data))
    assert robot.home == (170.0, 0.0, 0.0)


# -- base, units, convention ---------------------------------------------------


@pytest.mark.parametrize(
    ("base_z", "base_x"),
    [("+z", "+z"), ("+z", "-z"), ("-y", "+y"), ("+x", "+x"), ("-x", "+x")],
)
def test_parallel_base_axes(tmp_path, base_z, base_x):
    data = doc()
    data.update(base_z=base_z, base_x=base_x)
    message = rejection(write(tmp_path, data))
    assert_names(message, "base_x", "parallel", repr(base_z))


@pytest.mark.parametrize(
    ("key", "value"),
    [
        ("units", "ft"),
        ("units", "MM"),
        ("units", ""),
        ("convention", "craig"),
        ("convention", "Standard"),
        ("base_z", "up"),
        ("base_z", "z"),
        ("base_x", "+w"),
    ],
)
def test_unknown_choice(tmp_path, key, value):
    data = doc()
    data[key] = value
    message = rejection(write(tmp_path, data))
    assert_names(message, f"{key}:", repr(value), "not one of")


def test_unknown_joint_type(tmp_path):
    data = doc()
    data["joints"][1]["type"] = "linear"
    message = rejection(write(tmp_path, data))
    assert_names(message, "joints[2].type", "'linear'", "'revolute'", "'prismatic'")


@pytest.mark.parametrize("height", [-1.0, -0.001, -1000])
def test_negative_base_height(tmp_path, height):
    data = doc()
    data["base_height"] = height
    message = rejection(write(tmp_path, data))
    assert_names(message, "base_height", f"{height:g}", ">= 0")


@pytest.mark.parametrize("name", ["", "   ", "tab\there", "line\nbreak"])
def test_bad_names(tmp_path, name):
    data = doc()
    data["name"] = name
    assert_names(rejection(write(tmp_path, data)), "name:")


@pytest.mark.parametrize(("key", "values"), [("xyz", [0.0, 1.0]), ("rpy", [0.0, 0.0, 0.0, 0.0])])
def test_tool_vector_of_wrong_length(tmp_path, key, values):
    data = doc()
    data["tool"][key] = values
    assert_names(rejection(write(tmp_path, data)), f"tool.{key}", "3 numbers")


# -- poses --------------------------------------------------------------------


@pytest.mark.parametrize("values", [[0.0, 0.0], [0.0, 0.0, 0.0, 0.0], []])
def test_pose_of_wrong_length(tmp_path, values):
    data = doc()
    data["poses"]["ready"] = values
    message = rejection(write(tmp_path, data))
    assert_names(message, "poses.ready", "expected 3 joint values", f"got {len(values)}")


def test_pose_outside_limits(tmp_path):
    data = doc()
    data["poses"]["low"] = [10.0, 150.0, 0.0]
    message = rejection(write(tmp_path, data))
    assert_names(message, "poses.low", "Th2", "150", "-90..135")


def test_prismatic_pose_outside_limits(tmp_path):
    data = doc()
    data["poses"]["ready"] = [0.0, 0.0, 250.0]
    message = rejection(write(tmp_path, data))
    assert_names(message, "poses.ready", "d3", "250", "0..200 mm")


def test_pose_with_empty_name(tmp_path):
    data = doc()
    data["poses"][""] = [0.0, 0.0, 0.0]
    assert_names(rejection(write(tmp_path, data)), "poses", "name")


# -- joint count ---------------------------------------------------------------


def _joints(count: int) -> dict:
    data = doc()
    data["poses"] = {}
    joint = {"theta": 0.0, "d": 0.0, "a": 10.0, "alpha": 0.0}
    data["joints"] = [dict(joint) for _ in range(count)]
    return data


@pytest.mark.parametrize("count", [0, 33, 100])
def test_joint_count_out_of_range(tmp_path, count):
    message = rejection(write(tmp_path, _joints(count)))
    assert_names(message, "joints", "1 to 32", f"has {count}")


@pytest.mark.parametrize("count", [1, 32])
def test_joint_count_bounds_are_accepted(tmp_path, count):
    assert load(write(tmp_path, _joints(count))).dof == count


def test_first_bad_joint_is_named_among_many(tmp_path):
    data = _joints(20)
    data["joints"][16]["alpha"] = "ninety"
    assert_names(rejection(write(tmp_path, data)), "joints[17].alpha")


# -- the file itself -----------------------------------------------------------


def test_non_utf8_bytes(tmp_path):
    path = write(tmp_path, b'name = "Bad \xff\xfe arm"\n')
    assert_names(rejection(path), "UTF-8", "byte 12")  # 0-based offset of \xff


def test_latin1_file(tmp_path):
    path = write(tmp_path, tomli_w.dumps(doc()).replace("Test arm", "Bra\u00e7o").encode("latin-1"))
    assert_names(rejection(path), "UTF-8")


def test_folder_instead_of_file(tmp_path):
    folder = tmp_path / "robot.toml"
    folder.mkdir()
    assert_names(rejection(folder), "folder")


def test_missing_file(tmp_path):
    assert_names(rejection(tmp_path / "nowhere.toml"), "no such file")


def test_missing_parent_folder(tmp_path):
    assert_names(rejection(tmp_path / "no" / "such" / "robot.toml"), "no such file")


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0, reason="root reads any file")
def test_unreadable_file_by_permissions(tmp_path):
    path = write(tmp_path, doc())
    path.chmod(0)
    try:
        assert_names(rejection(path), "permission denied")
    finally:
        path.chmod(0o644)


def test_unreadable_file(tmp_path, monkeypatch):
    # the same failure as chmod 000 for a normal user (the tests may run as root)
    path = write(tmp_path, doc())

    def denied(name, *args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied", str(name))

    monkeypatch.setattr(os, "open", denied)
    assert_names(rejection(path), "permission denied")


def test_other_read_error(tmp_path, monkeypatch):
    path = write(tmp_path, doc())

    def broken(*args, **kwargs):
        raise OSError(errno.EIO, "Input/output error")

    monkeypatch.setattr(os, "open", broken)
    assert_names(rejection(path), "cannot read", "Input/output error")


def test_oversized_file_is_refused_before_parsing(tmp_path):
    path = write(tmp_path, "# " + "x" * 2_000_000 + "\n" + tomli_w.dumps(doc()))
    assert_names(rejection(path), "too large")


def test_one_byte_order_mark_is_accepted_and_two_are_refused(tmp_path):
    text = tomli_w.dumps(doc())
    assert load(write(tmp_path, b"\xef\xbb\xbf" + text.encode("utf-8"))).name == "Test arm"
    assert loads("\ufeff" + text).name == "Test arm"
    path = write(tmp_path, b"\xef\xbb\xbf" * 2 + text.encode("utf-8"))
    assert_names(rejection(path), "two byte order marks", "may have one")
    with pytest.raises(RobotFileError, match="two byte order marks"):
        loads("\ufeff\ufeff" + text)
    # a bad byte after the mark is named by its place in the file
    assert_names(rejection(write(tmp_path, b"\xef\xbb\xbfname = '\xff'\n")), "byte 11")


URDF_TEXT = '<?xml version="1.0"?>\n<robot name="arm"><link name="base"/></robot>\n'


@pytest.mark.parametrize(
    ("name", "content", "fragments"),
    [
        ("arm.urdf", URDF_TEXT, ["arm.urdf: a URDF, not a dhsim robot file", "-o "]),
        ("arm.URDF", "garbage", ["a URDF", "dhsim import "]),
        ("arm.xml", URDF_TEXT, ["XML (a URDF?)", "import ", "arm.urdf -o "]),
        ("arm", '<robot name="arm"/>', ["XML (a URDF?)", "arm.urdf -o "]),
        ("arm.toml", "\ufeff  <robot/>", ["XML", "arm.urdf -o ", "arm-imported.toml"]),
        ("dh.csv", "theta,d,a,alpha\n0,0,100,0\n", ["a CSV file", "if it is a D-H table"]),
    ],
)
def test_a_urdf_or_a_csv_is_named_with_the_command_that_imports_it(
    tmp_path, name, content, fragments
):
    path = write(tmp_path, content, name)
    message = rejection(path)
    assert_names(message, *fragments)
    command = message[message.index("dhsim import ") :]
    source, target = command.removeprefix("dhsim import ").split(" -o ")
    assert Path(target).suffix == ".toml" and Path(target) != path
    assert Path(source).suffix.lower() in (".urdf", ".csv")
    assert Path(source).parent == path.parent == Path(target).parent


def test_the_import_command_is_quoted_for_the_shell(tmp_path):
    import shlex

    path = write(tmp_path, URDF_TEXT, "my arm.urdf")
    message = rejection(path)
    words = shlex.split(message[message.index("dhsim import ") :])
    assert words == ["dhsim", "import", str(path), "-o", str(tmp_path / "my arm.toml")]


def test_a_good_robot_file_named_csv_still_loads(tmp_path):
    # the suffix alone does not refuse a good robot file
    assert load(write(tmp_path, doc(), "arm.csv")).name == "Test arm"


def test_a_name_or_pose_name_longer_than_the_bound_is_refused(tmp_path):
    from dhsim_tui.core.model.validation import MAX_NAME_CHARS

    def spread(text: str) -> str:  # a TOML string of short lines (line continuations)
        lines = [text[i : i + 80] for i in range(0, len(text), 80)]
        return '"""' + "\\\n".join(lines) + '"""'

    data = doc()
    data["name"] = PLACEHOLDER
    fits = tomli_w.dumps(data).replace(repr(PLACEHOLDER), spread("n" * MAX_NAME_CHARS))
    assert len(load(write(tmp_path, fits)).name) == MAX_NAME_CHARS
    for length in (MAX_NAME_CHARS + 1, 900_000):
        text = tomli_w.dumps(data).replace(repr(PLACEHOLDER), spread("n" * length))
        message = rejection(write(tmp_path, text))
        if length > MAX_STRING_CHARS:  # the scan refuses it before the parser reads it
            assert_names(message, "line 1: a multi-line string of more than")
            assert len(message) < 300
            continue
        assert_names(message, f"name: a robot name has at most {MAX_NAME_CHARS} characters")
        assert f"this one has {length}" in message and len(message) < 300
    data = doc()
    data["poses"]["p" * (MAX_NAME_CHARS + 1)] = [0.0, 0.0, 0.0]
    message = rejection(write(tmp_path, data))
    assert_names(message, "a pose name has at most", " … ")
    assert len(message) < 400


def test_a_long_key_or_value_from_the_file_is_quoted_shortened(tmp_path):
    from dhsim_tui.core.model.text import SHOWN_CHARS

    key = "k" * 3000 + "END"
    message = rejection(write(tmp_path, f'name = "x"\n{key} = 1\n'))
    assert_names(message, "kkkk … ", "kkkEND: unknown key")
    assert len(message) < len(str(tmp_path)) + SHOWN_CHARS + 200
    data = doc()
    data["units"] = "u" * 5000
    message = rejection(write(tmp_path, data))
    assert_names(message, "units: the text 'uuu", " … ", "is not one of 'mm'")
    assert len(message) < len(str(tmp_path)) + SHOWN_CHARS + 200


def test_path_with_nul_byte_is_a_robot_file_error():
    with pytest.raises(RobotFileError):
        load("robot\x00.toml")


def test_loads_names_its_source():
    with pytest.raises(RobotFileError, match=r"^here\.toml: joints\[1\]: missing key 'alpha'"):
        loads('name = "x"\n[[joints]]\ntheta = 0\nd = 0\na = 1\n', "here.toml")


# -- defaults -----------------------------------------------------------------

MINIMAL = """\
name = "Minimal"

[[joints]]
theta = 10.0
d = 0.0
a = 100.0
alpha = 0.0

[[joints]]
type = "prismatic"
theta = 0.0
d = 0.0
a = 0.0
alpha = 0.0
"""


def test_defaults(tmp_path):
    robot = load(write(tmp_path, MINIMAL))
    assert robot.name == "Minimal"
    assert robot.units == "mm"
    assert robot.convention == "standard"
    assert robot.base_height == 0.0
    assert (robot.base_z, robot.base_x) == ("+z", "+x")
    assert robot.tool.xyz == (0.0, 0.0, 0.0)
    assert robot.tool.rpy == (0.0, 0.0, 0.0)
    assert robot.poses == ()
    assert robot.joints[0].type == "revolute"
    assert robot.joints[0].theta == 10.0
    assert (robot.joints[0].min, robot.joints[0].max) == (-180.0, 180.0)
    assert (robot.joints[1].min, robot.joints[1].max) == (-400.0, 400.0)


@pytest.mark.parametrize(
    ("units", "span"),
    [("mm", 400.0), ("cm", 40.0), ("m", 0.4), ("in", 400.0 / 25.4)],
)
def test_default_prismatic_limits_in_the_robots_unit(tmp_path, units, span):
    robot = load(write(tmp_path, f'units = "{units}"\n' + MINIMAL))
    assert robot.units == units
    revolute, prismatic = robot.joints
    assert (revolute.min, revolute.max) == (-180.0, 180.0)  # degrees do not scale
    assert prismatic.min == pytest.approx(-span, rel=1e-12)
    assert prismatic.max == pytest.approx(span, rel=1e-12)


def test_default_limit_in_inches_rejects_a_home_just_past_it(tmp_path):
    # 15.75 in = 400.05 mm, just beyond the ±400 mm default; 15.74 in is inside
    text = 'units = "in"\n' + MINIMAL.replace("d = 0.0\na = 0.0", "d = 15.75\na = 0.0")
    assert "d = 15.75" in text
    assert_names(rejection(write(tmp_path, text)), "joints[2].d", "15.75")
    inside = load(write(tmp_path, text.replace("15.75", "15.74"), "inside.toml"))
    assert inside.home == (10.0, 15.74)


def test_one_limit_given_keeps_the_other_default(tmp_path):
    text = MINIMAL.replace("alpha = 0.0\n\n[[joints]]", "alpha = 0.0\nmin = -20.0\n\n[[joints]]")
    robot = load(write(tmp_path, text))
    assert (robot.joints[0].min, robot.joints[0].max) == (-20.0, 180.0)


def test_empty_tool_table_is_the_identity(tmp_path):
    robot = load(write(tmp_path, MINIMAL.replace('name = "Minimal"', 'name = "M"\n[tool]\n', 1)))
    assert robot.tool == Tool()


def test_integers_are_accepted_as_numbers(tmp_path):
    text = MINIMAL.replace("theta = 10.0", "theta = 10").replace("a = 100.0", "a = 100")
    robot = load(write(tmp_path, text))
    assert robot.joints[0].theta == 10.0
    assert isinstance(robot.joints[0].theta, float)


# -- round trips -----------------------------------------------------------------


def test_bundled_robots_are_the_files_in_robots_folder():
    assert bundled_names() == BUNDLED_STEMS
    assert len(BUNDLED_STEMS) >= 10


@pytest.mark.parametrize("stem", BUNDLED_STEMS)
def test_bundled_robot_round_trips_through_a_file(tmp_path, stem):
    original = load(bundled_path(stem))
    stamp = save(original, tmp_path / f"{stem}.toml")
    saved = tmp_path / f"{stem}.toml"
    assert stamp.path == saved.resolve()
    assert stamp.size == len(saved.read_bytes())
    again = load(saved)
    assert again == original
    # and once more, from the copy: the written form is stable
    assert save(again, tmp_path / "second.toml").path.read_bytes() == saved.read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([f"{stem}.toml", "second.toml"])


@pytest.mark.parametrize("stem", BUNDLED_STEMS)
def test_bundled_robot_round_trips_through_text(stem):
    original = load(ROBOTS_DIR / f"{stem}.toml")
    text = dumps(original)
    assert loads(text) == original
    # the text is ordinary TOML another reader agrees with
    parsed = tomllib.loads(text)
    assert parsed["name"] == original.name
    assert len(parsed["joints"]) == original.dof


def test_round_trip_keeps_awkward_values():
    robot = Robot(
        name='Quote " and \\ back\u00e9\u4e2d',
        units="in",
        convention="modified",
        base_height=0.1 + 0.2,
        base_z="-y",
        base_x="+z",
        tool=Tool(xyz=(1e-7, -0.0, 1 / 3), rpy=(-180.0, 89.999999999, 1e-300)),
        poses=(("z", (1 / 7, 2e-5)), ("with space.and dot", (-1 / 3, 15.748))),
        joints=(
            Joint("revolute", 1 / 7, 0.30000000000000004, -2.5e-7, 90.0, -180.0, 179.99),
            Joint("prismatic", -90.0, 15.748031496062993, 0.0, -45.0, -15.748031496062993, 15.75),
        ),
    )
    assert loads(dumps(robot)) == robot


# -- atomic saving ----------------------------------------------------------------


@pytest.fixture
def two_robots():
    first = load(ROBOTS_DIR / "puma560.toml")
    second = load(ROBOTS_DIR / "planar2.toml")
    return first, second


def test_save_replaces_an_existing_file(tmp_path, two_robots):
    first, second = two_robots
    path = save(first, tmp_path / "arm.toml").path
    save(second, path)
    assert load(path) == second
    assert [p.name for p in tmp_path.iterdir()] == ["arm.toml"]


def test_save_writes_a_temporary_file_in_the_same_folder_then_fsyncs_then_renames(
    tmp_path, two_robots, monkeypatch
):
    robot, _ = two_robots
    events: list[tuple] = []
    real_mkstemp, real_fsync, real_replace = tempfile.mkstemp, os.fsync, os.replace

    def mkstemp(*args, **kwargs):
        fd, name = real_mkstemp(*args, **kwargs)
        events.append(("mkstemp", Path(name).parent, fd))
        return fd, name

    def fsync(fd):
        events.append(("fsync", fd))
        return real_fsync(fd)

    def replace(src, dst):
        events.append(("replace", Path(src), Path(dst), Path(src).read_text("utf-8")))
        return real_replace(src, dst)

    monkeypatch.setattr(tempfile, "mkstemp", mkstemp)
    monkeypatch.setattr(os, "fsync", fsync)
    monkeypatch.setattr(os, "replace", replace)
    target = tmp_path / "arm.toml"
    save(robot, target)

    names = [event[0] for event in events]
    assert names.index("mkstemp") < names.index("fsync") < names.index("replace")
    _, folder, fd = events[names.index("mkstemp")]
    assert folder == tmp_path
    assert ("fsync", fd) in events  # the temporary file's own descriptor
    _, src, dst, content = events[names.index("replace")]
    assert src.parent == tmp_path and src != target
    assert dst == target
    assert loads(content) == robot  # the file was complete before the rename


@pytest.mark.parametrize("failing", ["replace", "fsync"])
def test_failed_save_leaves_the_old_file_untouched(tmp_path, two_robots, monkeypatch, failing):
    old, new = two_robots
    path = save(old, tmp_path / "arm.toml").path
    before = path.read_bytes()

    def fail(*args, **kwargs):
        raise OSError(errno.EIO, "Input/output error")

    monkeypatch.setattr(os, failing, fail)
    with pytest.raises(RobotFileError) as info:
        save(new, path)
    message = str(info.value)
    assert_names(message, str(path), "cannot save", "Input/output error")
    monkeypatch.undo()
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["arm.toml"]
    assert load(path) == old


def test_failed_write_leaves_the_old_file_untouched(tmp_path, two_robots, monkeypatch):
    old, new = two_robots
    path = save(old, tmp_path / "arm.toml").path
    before = path.read_bytes()
    real_fdopen = os.fdopen

    class Full:
        def __init__(self, handle):
            self.handle = handle

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self.handle.close()

        def write(self, text):
            self.handle.write(text[: len(text) // 2])
            raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "fdopen", lambda *a, **k: Full(real_fdopen(*a, **k)))
    with pytest.raises(RobotFileError, match="No space left on device"):
        save(new, path)
    monkeypatch.undo()
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["arm.toml"]


def test_save_into_a_read_only_folder(tmp_path, two_robots, monkeypatch):
    robot, _ = two_robots

    def denied(*args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied", kwargs.get("dir"))

    monkeypatch.setattr(tempfile, "mkstemp", denied)
    target = tmp_path / "arm.toml"
    with pytest.raises(RobotFileError) as info:
        save(robot, target)
    assert_names(str(info.value), str(target), "cannot save", "permission denied")
    assert "\n" not in str(info.value)
    assert list(tmp_path.iterdir()) == []


def test_save_into_a_missing_folder(tmp_path, two_robots):
    robot, _ = two_robots
    target = tmp_path / "missing" / "arm.toml"
    with pytest.raises(RobotFileError) as info:
        save(robot, target)
    assert_names(str(info.value), str(target), "does not exist")
    assert not (tmp_path / "missing").exists()


def test_save_over_a_folder(tmp_path, two_robots):
    robot, _ = two_robots
    folder = tmp_path / "arm.toml"
    folder.mkdir()
    with pytest.raises(RobotFileError, match="folder"):
        save(robot, folder)
    assert folder.is_dir() and list(folder.iterdir()) == []
    assert [p.name for p in tmp_path.iterdir()] == ["arm.toml"]


def test_save_to_a_relative_path(tmp_path, two_robots, monkeypatch):
    robot, _ = two_robots
    monkeypatch.chdir(tmp_path)
    save(robot, "arm.toml")
    assert load(tmp_path / "arm.toml") == robot
    assert [p.name for p in tmp_path.iterdir()] == ["arm.toml"]


def test_saved_file_is_utf8_with_unix_newlines(tmp_path):
    robot = Robot(name="Bra\u00e7o rob\u00f3tico", joints=(Joint(a=1.0),))
    raw = save(robot, tmp_path / "arm.toml").path.read_bytes()
    assert "Bra\u00e7o".encode() in raw
    assert b"\r" not in raw
    assert load(tmp_path / "arm.toml") == robot


@pytest.mark.parametrize("name", ["\ud800", "bell\x07", "del\x7f"])
def test_names_a_file_cannot_hold_are_rejected(name, tmp_path):
    """Found by hypothesis: a lone surrogate got past validation and broke save()."""
    from dhsim_tui.core import DhsimError, Joint, Robot

    with pytest.raises(DhsimError, match="name"):
        Robot(name, (Joint(),))
    with pytest.raises(DhsimError, match="poses"):
        Robot("ok", (Joint(),), poses=((name, (0.0,)),))

"""Robot files built to hurt the parser are refused before it sees them.

Python's TOML parser (tomllib) spends time and memory growing with the
square of a key's dotted parts: a 200 KB file holding one key of 100,000
parts took 42 s and hit a 6 GB cap; a ``[header]`` of 100,000 parts 14 s.
The loader scans the text first (comments and strings passed over whole)
and refuses a key path of more than MAX_KEY_PARTS parts or a line of more
than MAX_LINE_CHARS characters, naming the line. The scan must never refuse
what a robot file legitimately holds: dots in names, numbers and dates,
quoted keys holding dots, long-ish lines of poses.
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
import tomli_w
from hypothesis import given, settings
from hypothesis import strategies as st
from waiting import HANG

from dhsim_tui.cli.main import _open
from dhsim_tui.core.files import robotfile
from dhsim_tui.core.files.robotfile import load, loads, render, save
from dhsim_tui.core.files.tomlparse import (
    MAX_KEY_PARTS,
    MAX_LINE_CHARS,
    _hostile,
    tomllib,  # tomli on Python 3.10
)
from dhsim_tui.core.model.errors import RobotFileError

ROBOTS_DIR = Path(__file__).resolve().parents[2] / "robots"
BUNDLED_FILES = sorted(ROBOTS_DIR.glob("*.toml"))
ARM = 'name = "arm"\n[[joints]]\ntheta = 0.0\nd = 0.0\na = 100.0\nalpha = 0.0\n'
#: the issue's files: one line of 100,000 dotted parts after the name
PARTS = 100_000
HOSTILE = {
    "key": 'name = "n"\n' + ".".join(["a"] * PARTS) + " = 1\n",
    "header": 'name = "n"\n[' + ".".join(["a"] * PARTS) + "]\n",
    "array-header": 'name = "n"\n[[' + ".".join(["a"] * PARTS) + "]]\n",
}


def refusal(text: str) -> str:
    with pytest.raises(RobotFileError) as caught:
        loads(text, "arm.toml")
    message = str(caught.value)
    assert "\n" not in message
    return message


# -- the issue's files, in a fresh interpreter: refused in one line, in little memory ----
# (how long a refusal takes is bench/hostile_inputs.py's figure, not a test's bound)

MEASURE = textwrap.dedent(
    """
    import contextlib, io, json, resource, sys
    from pathlib import Path
    from dhsim_tui.cli.main import main
    from dhsim_tui.core.files.robotfile import load_with_stamp, save, RobotFileError
    from dhsim_tui.core.files.library import load_robot

    def rss():
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux

    with contextlib.redirect_stdout(io.StringIO()):
        main(["check", "puma560"])  # warm: whatever loads on first use is loaded
    puma, _ = load_robot("puma560")
    results = {}
    for name in sys.argv[1:]:
        path = Path(name)
        before = rss()
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            code = main(["check", str(path)])
        try:
            load_with_stamp(path)  # how the simulator and the editor open a file
            opened = "loaded"
        except RobotFileError as exc:
            opened = str(exc)
        save(puma, path)  # saving over such a file reads it first
        results[path.stem] = {
            "code": code, "err": err.getvalue(), "opened": opened,
            "growth_kib": rss() - before,
        }
    print(json.dumps(results))
    """
)


def test_the_issues_hostile_files_are_refused_in_one_line_in_little_memory(tmp_path):
    paths = []
    for name, text in HOSTILE.items():
        path = tmp_path / f"{name}.toml"
        path.write_text(text, encoding="utf-8")
        paths.append(str(path))
    cap = 4 << 30  # a regression fails the test, not the machine

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))

    done = subprocess.run(
        [sys.executable, "-c", MEASURE, *paths],
        capture_output=True,
        text=True,
        timeout=2 * HANG,  # a hang guard only: the parser took 42 s on such a file
        preexec_fn=limit,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    results = json.loads(done.stdout)
    for name in HOSTILE:
        result = results[name]
        assert result["code"] == 2
        lines = result["err"].strip().splitlines()
        assert len(lines) == 1, result["err"]
        cause = f"line 2: a key path of more than {MAX_KEY_PARTS} dotted parts"
        assert f"{name}.toml: {cause}" in lines[0]
        assert len(lines[0]) < 300  # the key is quoted shortened, not 200 KB of it
        assert "line 2" in result["opened"]
        # the parser grew by gigabytes on such a file; the refusal by almost nothing
        assert result["growth_kib"] < 100 * 1024, result["growth_kib"]
    # the save replaced every hostile file with a fresh, loadable document
    for path in paths:
        assert load(path).name == "Puma 560"


def test_the_simulator_opens_files_through_the_same_refusal(tmp_path):
    path = tmp_path / "key.toml"
    path.write_text(HOSTILE["key"], encoding="utf-8")
    with pytest.raises(RobotFileError, match="line 2: a key path of more than 16 dotted parts"):
        _open(str(path))  # what `dhsim ROBOT` and `dhsim edit ROBOT` call before the UI


# -- the bound: 16 parts pass the scan, 17 do not, wherever the key is ------------------


@pytest.mark.parametrize(
    "template",
    [
        "{key} = 1\n",  # a dotted key
        "[{key}]\nx = 1\n",  # a table header
        "[[{key}]]\nx = 1\n",  # an array-of-tables header
        "x = {{ {key} = 1 }}\n",  # a key in an inline table
        "x = [{{ {key} = 1 }}]\n",  # ... in an array
    ],
)
def test_a_key_of_16_parts_is_parsed_and_17_is_refused(template):
    at_bound = template.format(key=".".join(["a"] * MAX_KEY_PARTS))
    assert _hostile(at_bound) is None
    assert isinstance(tomllib.loads(at_bound), dict)  # and it is TOML the parser reads
    too_deep = template.format(key=".".join(["a"] * (MAX_KEY_PARTS + 1)))
    message = refusal("# a comment\n" + too_deep)
    assert f"arm.toml: line 2: a key path of more than {MAX_KEY_PARTS} dotted parts" in message


def test_quoted_parts_and_spaces_around_dots_count_as_toml_counts_them():
    parts = ['"a.b.c"', "'d.e'", "f", '"g\\"h.i"', "j-k", "0"] * 3  # 18 parts
    spaced = " . ".join(parts[:MAX_KEY_PARTS]) + " = 1\n"
    assert _hostile(spaced) is None
    assert tomllib.loads(spaced)
    assert "line 1" in refusal("\t.\t".join(parts[: MAX_KEY_PARTS + 1]) + " = 1\n")


@pytest.mark.parametrize(
    "text",
    [
        # dots inside strings, comments and multi-line strings are no key parts
        'name = "' + "a." * 500 + 'b"\n',
        "name = '" + "a." * 500 + "b'\n",
        'name = "arm"  # ' + "a." * 500 + "b\n",
        "# " + "a." * 500 + "b\n" + 'name = "arm"\n',
        'name = """\\\n' + "a." * 500 + 'b"""\n',
        "name = '''" + "a." * 500 + "b'''\n",
        'name = """x""" # ' + "a." * 500 + "\n",
        'name = "say \\"' + "a." * 100 + '\\" twice"\n',
        'name = """ends in quotes: ""' + "a." * 100 + '"""""\n',
        # numbers and dates have dots but no more than two parts
        'name = "arm"\nx = [1.5, -2.25e-3, +3.0, 1979-05-27T07:32:00.999999-07:00]\n',
        'name = "arm"\nx = 07:32:00.25\n',
    ],
    ids=lambda text: text[:24],
)
def test_dots_that_are_not_key_parts_are_not_counted(text):
    assert _hostile(text) is None
    assert isinstance(tomllib.loads(text), dict)


def test_after_a_quote_that_opens_no_string_the_scan_stops_as_the_parser_does():
    # the parser fails at line 2; nothing after it is parsed, so nothing after
    # it is refused for its keys either: the TOML error is the one reported
    text = 'name = "arm\n' + ".".join(["a"] * 40) + " = 1\n"
    assert _hostile(text) is None
    assert "not valid TOML" in refusal(text)


# -- lines ----------------------------------------------------------------------------


def test_a_line_of_the_bound_loads_and_one_more_character_is_refused():
    comment = "#" + "x" * (MAX_LINE_CHARS - 1)
    assert load_text(ARM + comment + "\n").name == "arm"
    message = refusal(ARM + comment + "x\n")
    assert f"line 7 is {MAX_LINE_CHARS + 1} characters long" in message
    assert f"at most {MAX_LINE_CHARS}" in message


def load_text(text: str):
    return loads(text, "arm.toml")


def test_the_longest_lines_dhsim_itself_writes_fit_well_within_the_bound():
    # 32 joints, a pose of 32 values each written in full, and the longest name
    from dhsim_tui.core.model.robot import Joint, Robot
    from dhsim_tui.core.model.validation import MAX_NAME_CHARS

    joints = tuple(Joint(min=-179.99999999999997, max=179.99999999999997) for _ in range(32))
    values = tuple(-123.45678901234567 for _ in range(32))
    robot = Robot(name="n" * MAX_NAME_CHARS, joints=joints, poses=(("p" * MAX_NAME_CHARS, values),))
    text = robotfile.dumps(robot)
    assert max(len(line) for line in text.splitlines()) < MAX_LINE_CHARS / 4
    assert loads(text) == robot


# -- what dhsim reads and writes is never refused -----------------------------------------


@pytest.mark.parametrize("path", BUNDLED_FILES, ids=lambda p: p.stem)
def test_every_bundled_robot_passes_the_scan_and_loads(path):
    text = path.read_text(encoding="utf-8")
    assert _hostile(text) is None
    assert load(path).dof >= 1


def test_saving_over_a_hostile_file_or_from_a_hostile_text_writes_a_fresh_document(tmp_path):
    robot = load(BUNDLED_FILES[0])
    text = render(robot, HOSTILE["key"])  # tomlkit is not given it: a fresh document
    assert loads(text) == robot and "a.a" not in text
    path = tmp_path / "arm.toml"
    path.write_text(HOSTILE["header"], encoding="utf-8")
    save(robot, path)
    assert load(path) == robot


# -- against the parser itself: documents tomli_w writes, with random keys and strings ---

key_text = st.text(st.characters(exclude_categories=("Cs",)), min_size=1, max_size=6)
string_text = st.text(
    st.sampled_from(list("ab.\"'#\\\n\t =[]{}")) | st.characters(exclude_categories=("Cs",)),
    max_size=12,
)
scalars = (
    string_text
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.integers(-(10**6), 10**6)
    | st.booleans()
    | st.lists(st.floats(allow_nan=False, allow_infinity=False), max_size=4)
)


@st.composite
def nested(draw) -> tuple[dict, int]:
    """A document whose deepest table header has ``depth`` parts, with random
    keys and strings (dots, quotes, hashes, backslashes) beside the spine."""
    depth = draw(st.integers(1, 2 * MAX_KEY_PARTS))
    spine = draw(st.lists(key_text, min_size=depth, max_size=depth))
    leaf: dict = draw(st.dictionaries(key_text, scalars, min_size=1, max_size=3))
    for key in reversed(spine):
        siblings = draw(st.dictionaries(key_text.filter(lambda k, key=key: k != key), scalars))
        leaf = {**siblings, key: leaf}
    return leaf, depth


@pytest.mark.slow  # a long hypothesis run
@settings(max_examples=150, deadline=None)
@given(document=nested(), multiline=st.booleans())
def test_the_scan_refuses_exactly_the_documents_with_a_too_deep_header(document, multiline):
    data, depth = document
    text = tomli_w.dumps(data, multiline_strings=multiline)
    assert tomllib.loads(text) == data  # the text is the document (ground truth)
    problem = _hostile(text)
    if depth <= MAX_KEY_PARTS:
        assert problem is None, (problem, text)
    else:
        assert problem is not None and "dotted parts" in problem, text
        line = int(problem.split()[1].rstrip(":"))
        # (lines as TOML counts them: at "\n" only, where splitlines() also breaks at \x85)
        assert text.split("\n")[line - 1].startswith("["), (line, text)


bare_part = st.from_regex(r"[A-Za-z0-9_-]{1,5}", fullmatch=True)
basic_part = st.text(st.characters(exclude_categories=("Cs", "Cc")), max_size=5).map(
    lambda s: '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'
)
literal_part = st.text(
    st.characters(exclude_categories=("Cs", "Cc"), exclude_characters="'"), max_size=5
).map(lambda s: f"'{s}'")
dot = st.sampled_from([".", " .", ". ", " . ", "\t.\t"])


@pytest.mark.slow  # a long hypothesis run
@settings(max_examples=150, deadline=None)
@given(
    parts=st.lists(bare_part | basic_part | literal_part, min_size=1, max_size=24),
    dots=st.lists(dot, min_size=24, max_size=24),
    comment=st.text(
        st.sampled_from(list("ab.\"'#\\ =[]{}")) | st.characters(exclude_categories=("Cs", "Cc")),
        max_size=12,
    ),
)
def test_a_dotted_key_is_refused_exactly_when_it_has_too_many_parts(parts, dots, comment):
    key = parts[0] + "".join(d + p for d, p in zip(dots, parts[1:], strict=False))
    text = f"{key} = 1  # {comment}\n"
    data = tomllib.loads(text)  # ground truth: the parser reads len(parts) levels
    depth = 0
    while isinstance(data, dict):
        (data,) = data.values()
        depth += 1
    assert depth == len(parts)
    assert (_hostile(text) is None) == (len(parts) <= MAX_KEY_PARTS), text

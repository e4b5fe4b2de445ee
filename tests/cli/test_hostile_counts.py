"""Robot files within the 1 MB limit that hold more of something than any
robot needs are refused by the scan before the TOML parser sees them.

The fault campaign's files, each under 1 MB: 26,000 table headers of 16
parts each took the parser 3 s and 400 MB before the schema said "unknown
key"; 40,000 poses took seconds to open (15 s in the simulator); an 800 KB
multi-line string cost the scan itself 90 MB (Python's ``re`` keeps state
for each repetition of a group), a 990 KB one-line string as much. The scan
now counts, outside strings and comments, table headers, poses, programs,
keys (each dotted part) and values in lists (by their commas), bounds
multi-line strings, and keeps its own state small; each refusal names the
line. Tests check the outcome and the memory in a fresh interpreter, never
the time (bench/hostile_inputs.py times them).
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import textwrap

import pytest
from waiting import HANG

from dhsim_tui.core.files.robotfile import dumps, load, loads
from dhsim_tui.core.files.tomlparse import (
    MAX_KEYS,
    MAX_POSES,
    MAX_PROGRAMS,
    MAX_STRING_CHARS,
    MAX_TABLE_HEADERS,
    MAX_VALUES,
    _hostile,
    tomllib,
)
from dhsim_tui.core.model.errors import RobotFileError
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.model.robot import Joint, Robot

ARM = "[[joints]]\ntheta = 0.0\nd = 0.0\na = 100.0\nalpha = 0.0\n"
LIMIT = 990_000  # under the 1 MB a robot file may have
SIXTEEN = ".a" * 15  # 15 more parts: 16 in all, the most a key may have


def filled(head: str, line, tail: str = "") -> str:
    """``head``, then ``line(i)`` for i = 0, 1, ... while the text stays under LIMIT."""
    parts, size, i = [head], len(head) + len(tail), 0
    while size + len(line(i)) <= LIMIT:
        parts.append(line(i))
        size += len(line(i))
        i += 1
    return "".join(parts) + tail


#: the campaign's files and the line each is refused at, with why
CAMPAIGN = {
    "headers": (
        filled('name = "n"\n', lambda i: f"[h{i}{SIXTEEN}]\n"),
        f"line {(MAX_KEYS - 1) // 16 + 2}: more than {MAX_KEYS:,} keys",  # name: 1 key
    ),
    "few-part-headers": (
        filled('name = "n"\n', lambda i: f"[h{i}.a]\n"),
        f"line {MAX_TABLE_HEADERS + 2}: more than {MAX_TABLE_HEADERS:,} table headers",
    ),
    "dotted-keys": (
        filled('name = "n"\n', lambda i: f"k{i}{SIXTEEN} = 0\n"),
        f"line {(MAX_KEYS - 1) // 16 + 2}: more than {MAX_KEYS:,} keys",  # name: 1 key
    ),
    "poses": (
        'name = "n"\n[poses]\n' + "".join(f"p{i} = [0]\n" for i in range(40_000)) + ARM,
        f"line {MAX_POSES + 3}: more than {MAX_POSES:,} poses",
    ),
    "programs": (
        'name = "n"\n[programs]\n' + "".join(f"g{i} = []\n" for i in range(40_000)) + ARM,
        f"line {MAX_PROGRAMS + 3}: more than {MAX_PROGRAMS:,} programs",
    ),
    "values": (
        'name = "n"\nx = [\n' + ("0," * 4000 + "\n") * 120 + "]\n" + ARM,
        f"line {MAX_VALUES // 4000 + 3}: more than {MAX_VALUES:,} values in lists",
    ),
    "multi-line-string": (
        'name = """' + ("x" * 70 + "\n") * 11_000 + '"""\n' + ARM,
        f"line 1: a multi-line string of more than {MAX_STRING_CHARS:,} characters",
    ),
    "literal-string": (
        "name = '''" + ("x" * 70 + "\n") * 11_000 + "'''\n" + ARM,
        f"line 1: a multi-line string of more than {MAX_STRING_CHARS:,} characters",
    ),
    "one-line-string": (
        'name = "' + "x" * 980_000 + '"\n' + ARM,
        "line 1 is 980009 characters long",
    ),
}

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
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
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


@pytest.mark.parametrize("name", CAMPAIGN)
def test_the_campaigns_files_are_refused_in_one_line_in_little_memory(tmp_path, name):
    # one file to an interpreter: the peak resident size is measured afresh
    text, cause = CAMPAIGN[name]
    assert len(text.encode()) < 1_000_000  # within the file limit
    path = tmp_path / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    cap = 4 << 30  # a regression fails the test, not the machine

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))

    done = subprocess.run(
        [sys.executable, "-c", MEASURE, str(path)],
        capture_output=True,
        text=True,
        timeout=2 * HANG,  # a hang guard only
        preexec_fn=limit,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    result = json.loads(done.stdout)[name]
    assert result["code"] == 2, result
    lines = result["err"].strip().splitlines()
    assert len(lines) == 1, result["err"][:500]
    assert f"{name}.toml: {cause}" in lines[0]
    assert len(lines[0]) < 400
    assert cause in result["opened"], result["opened"][:500]
    # the parser grew by 400 MB to 1 GB on the headers, the old scan by 90 MB on a string
    assert result["growth_kib"] < 40 * 1024, result["growth_kib"]
    assert load(path).name == "Puma 560"  # the save replaced it with a fresh, loadable file


# -- each bound: what reaches it passes, one more is refused, naming the line ------------


def refused(text: str) -> str:
    with pytest.raises(RobotFileError) as caught:
        loads(text, "arm.toml")
    message = str(caught.value)
    assert "\n" not in message and len(message) < 400
    return message


def pose_names(count: int) -> list[str]:
    """Pose names as files hold them: bare, quoted with dots, '=', '#', brackets."""
    kinds = ["p{i}", '"p {i}.x"', "'q=[{i}]'", '"#{i} \\"x\\""', '"é{i}"']
    return [kinds[i % len(kinds)].format(i=i) for i in range(count)]


def test_poses_up_to_the_bound_load_and_one_more_is_refused_naming_its_line():
    lines = [f"{name} = [{i % 90}]\n" for i, name in enumerate(pose_names(MAX_POSES + 1))]
    head = 'name = "arm"\n[poses]\n'
    robot = loads(head + "".join(lines[:MAX_POSES]) + ARM)
    assert len(robot.poses) == MAX_POSES
    message = refused(head + "".join(lines) + ARM)
    assert f"arm.toml: line {MAX_POSES + 3}: more than {MAX_POSES:,} poses" in message
    # dotted at the top and under a header written with quotes and spaces
    dotted = 'name = "arm"\n' + "".join(f"poses . {line}" for line in lines) + ARM
    assert f"line {MAX_POSES + 2}: more than" in refused(dotted)
    quoted = 'name = "arm"\n[ "poses" ]\n' + "".join(lines) + ARM
    assert f"line {MAX_POSES + 3}: more than" in refused(quoted)


def test_programs_up_to_the_bound_load_and_one_more_is_refused():
    lines = [f"g{i} = [{{ wait = 0.5 }}]\n" for i in range(MAX_PROGRAMS + 1)]
    head = 'name = "arm"\n[programs]\n'
    robot = loads(head + "".join(lines[:MAX_PROGRAMS]) + ARM)
    assert len(robot.programs) == MAX_PROGRAMS
    message = refused(head + "".join(lines) + ARM)
    assert f"line {MAX_PROGRAMS + 3}: more than {MAX_PROGRAMS:,} programs" in message
    # a program written as an array of tables counts once, however many steps
    steps = "".join("[[programs.demo]]\nwait = 0.5\n" for _ in range(50))
    assert len(loads('name = "arm"\n' + steps + ARM).program("demo").steps) == 50


def test_table_headers_up_to_the_bound_pass_and_one_more_is_refused():
    headers = [f"[t{i}]\n" for i in range(MAX_TABLE_HEADERS + 1)]
    assert _hostile("".join(headers[:MAX_TABLE_HEADERS])) is None
    problem = _hostile("".join(headers))
    assert problem is not None
    assert problem.startswith(f"line {MAX_TABLE_HEADERS + 1}: more than 1,000 table headers")


def test_keys_up_to_the_bound_pass_and_one_more_is_refused_each_part_counted():
    plain = [f"k{i} = 1\n" for i in range(MAX_KEYS + 1)]
    assert _hostile("".join(plain[:MAX_KEYS])) is None
    assert _hostile("".join(plain)).startswith(f"line {MAX_KEYS + 1}: more than 10,000 keys")
    dotted = [f"k{i}.x = 1\n" for i in range(MAX_KEYS // 2 + 1)]
    assert _hostile("".join(dotted[: MAX_KEYS // 2])) is None
    assert _hostile("".join(dotted)).startswith(f"line {MAX_KEYS // 2 + 1}: more than")

    def inline(tables: int) -> str:  # x, then a and b in each inline table
        return "x = [\n" + "{ a = 1, b = 2 },\n" * tables + "]\n"

    assert _hostile(inline((MAX_KEYS - 1) // 2)) is None
    problem = _hostile(inline(MAX_KEYS // 2))
    assert problem is not None and problem.startswith(f"line {MAX_KEYS // 2 + 1}: more than")


def test_values_up_to_the_bound_pass_and_one_more_is_refused():
    def array(commas: int) -> str:
        rows = ["0," * 1000 + "\n"] * (commas // 1000) + ["0," * (commas % 1000)]
        return "x = [\n" + "".join(rows) + "0]\n"

    text = array(MAX_VALUES)
    assert _hostile(text) is None
    assert len(tomllib.loads(text)["x"]) == MAX_VALUES + 1
    problem = _hostile(array(MAX_VALUES + 1))
    assert problem == (
        f"line {MAX_VALUES // 1000 + 2}: more than {MAX_VALUES:,} values in lists and inline "
        "tables (counted by their commas); a robot file has far fewer"
    )


def test_commas_headers_and_keys_in_strings_and_comments_are_not_counted():
    comment = "# " + "a = 1, " * 1000 + "\n"
    string = "".join(f'x{j} = """' + "\n[h]\na = 1, 2, 3" * 500 + '"""\n' for j in range(3))
    literal = "".join(f"y{j} = '''" + "\n[[h]]\nb.c = [1, 2]" * 500 + "'''\n" for j in range(3))
    basic = 'z = "' + ", [a] b = 1" * 900 + '"\n'
    text = comment * 100 + string + literal + basic
    assert text.count(",") > MAX_VALUES and text.count("\n[") > MAX_TABLE_HEADERS
    assert _hostile(text) is None
    assert isinstance(tomllib.loads(text), dict)


@pytest.mark.parametrize("quotes", ['"""', "'''"])
def test_a_multi_line_string_of_the_bound_passes_and_one_more_character_is_refused(quotes):
    def text(chars: int) -> str:
        body = ("n" * 99 + "\n") * (chars // 100) + "n" * (chars % 100)
        return f"x = {quotes}{body}{quotes}\n"

    assert _hostile(text(MAX_STRING_CHARS)) is None
    assert len(tomllib.loads(text(MAX_STRING_CHARS))["x"]) == MAX_STRING_CHARS
    problem = _hostile(text(MAX_STRING_CHARS + 1))
    assert problem is not None
    assert problem.startswith(f"line 1: a multi-line string of more than {MAX_STRING_CHARS:,}")
    # one never closed is the parser's to report when it is short
    short = f"x = {quotes}never closed\n"
    assert _hostile(short) is None
    assert "not valid TOML" in refused(short)


def test_a_robot_at_every_bound_dhsim_itself_writes_loads_back():
    joints = tuple(Joint(a=10.0) for _ in range(32))
    values = tuple(float(i % 7) for i in range(32))
    names = ["a.b", "x = y", "#1", "[p]", "q'", *(f"pose {i}" for i in range(MAX_POSES - 5))]
    poses = tuple((name, values) for name in names)
    steps = (Step("joint", "a.b"), Step("joint", values, speed=50), Step("wait", seconds=1))
    programs = tuple(Program(f"program {i}", steps) for i in range(20))
    robot = Robot(name="n" * 1000, joints=joints, poses=poses, programs=programs)
    text = dumps(robot)
    assert _hostile(text) is None
    assert loads(text) == robot

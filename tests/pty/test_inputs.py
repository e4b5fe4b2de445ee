"""Every input gets a message, never a traceback or a terminal control:
control characters in names (refused), in paths and arguments (escaped on
output); long paths, unreadable and deleted folders, an empty argument;
lengths too small to compute with; no numpy warning; the last-resort handler;
limit messages that show the difference."""

from __future__ import annotations

import dataclasses
import errno
import json
import math
import os
import pathlib
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st
from pty_screen import dhsim_command
from waiting import HANG

import dhsim_tui.cli.kinematics as cli_kinematics
import dhsim_tui.cli.main as cli
from dhsim_tui.cli.main import main
from dhsim_tui.core import DhsimError, Joint, Robot, RobotFileError, Tool, load, load_robot, loads
from dhsim_tui.core.files.library import describe
from dhsim_tui.core.model.validation import fmt

#: characters that steer a terminal: C0, ESC, DEL, C1 (CSI), bidi override, zero-width
CONTROLS = ["\x1b", "\x07", "\x7f", "\x9b", "\u202e", "\u200b", "\u2066"]
ESCAPED = {
    "\x1b": "\\x1b",
    "\x07": "\\x07",
    "\x7f": "\\x7f",
    "\x9b": "\\x9b",
    "\u202e": "\\u202e",
    "\u200b": "\\u200b",
    "\u2066": "\\u2066",
}
ARM = "[[joints]]\ntheta = 0\nd = 0\na = 100\nalpha = 0\n"
CLEAR = "\x1b[2J"  # ESC [ 2 J: clears the screen


def toml_string(text: str) -> str:
    """``text`` as a TOML basic string, everything but printable ASCII escaped."""
    out = []
    for char in text:
        code = ord(char)
        if char in '"\\':
            out.append("\\" + char)
        elif 0x20 <= code < 0x7F:
            out.append(char)
        else:
            out.append(f"\\u{code:04x}" if code <= 0xFFFF else f"\\U{code:08x}")
    return '"' + "".join(out) + '"'


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def assert_one_line(code: int, err: str, expected_code: int = 2) -> None:
    assert code == expected_code, err
    assert len(err.strip().splitlines()) == 1, err
    assert "Traceback" not in err


def assert_no_control(data: bytes) -> None:
    """Nothing in ``data`` steers a terminal: no C0 but newline, no DEL, no C1,
    no bidi override or zero-width mark."""
    assert all(byte >= 0x20 or byte == 0x0A for byte in data), data
    text = data.decode("utf-8")
    bad = [c for c in text if c == "\x7f" or 0x80 <= ord(c) < 0xA0 or c in ESCAPED]
    assert not bad, (bad, text)


def dhsim(*argv: str | bytes, **kwargs) -> subprocess.CompletedProcess[bytes]:
    """The real console script, stdin from /dev/null, output as bytes."""
    kwargs.setdefault("timeout", HANG)
    return subprocess.run(
        [dhsim_command(), *argv], stdin=subprocess.DEVNULL, capture_output=True, **kwargs
    )


# -- control characters in names are refused, with the field named ---------------------


@pytest.mark.parametrize("char", CONTROLS, ids=[ESCAPED[c] for c in CONTROLS])
def test_robot_name_with_a_control_character_is_refused(char):
    with pytest.raises(DhsimError) as caught:
        Robot(name=f"arm{char}[2J", joints=(Joint(a=100.0),))
    assert str(caught.value) == (
        f"name: a robot name may not hold control characters ({ESCAPED[char]})"
    )


@pytest.mark.parametrize("char", CONTROLS, ids=[ESCAPED[c] for c in CONTROLS])
def test_pose_name_with_a_control_character_is_refused(char):
    with pytest.raises(DhsimError) as caught:
        Robot(name="arm", joints=(Joint(a=100.0),), poses=((f"x{char}[2J", (0.0,)),))
    assert str(caught.value) == (
        f'poses."x{ESCAPED[char]}[2J": a pose name may not hold control characters '
        f"({ESCAPED[char]})"
    )


def test_an_edit_cannot_bring_a_control_character_in():
    robot, _ = load_robot("puma560")
    with pytest.raises(DhsimError, match="name: a robot name may not hold"):
        dataclasses.replace(robot, name="Puma\x1b]0;owned\x07")
    with pytest.raises(DhsimError, match=r'poses\."evil\\x1b\[H"'):
        dataclasses.replace(robot, poses=(*robot.poses, ("evil\x1b[H", robot.home)))


def test_plain_names_in_any_script_still_load():
    robot = loads(f'name = {toml_string("Roboter ä 机器人 🤖")}\n[poses]\n"bereit ü" = [5]\n' + ARM)
    assert robot.name == "Roboter ä 机器人 🤖"
    assert robot.pose_names == ("bereit ü",)


@pytest.mark.parametrize(
    ("document", "message"),
    [
        (f"name = {toml_string('x' + CLEAR)}\n" + ARM, "name: a robot name may not hold control"),
        (
            'name = "x"\n[poses]\n' + toml_string("up\u202edown") + " = [0]\n" + ARM,
            'poses."up\\u202edown": a pose name may not hold control characters (\\u202e)',
        ),
    ],
)
def test_robot_file_with_a_control_character_names_file_and_field(tmp_path, document, message):
    path = tmp_path / "evil.toml"
    path.write_text(document, encoding="utf-8")
    with pytest.raises(RobotFileError) as caught:
        load(path)
    assert str(caught.value).startswith(f"{path}: ")
    assert message in str(caught.value)


# -- what the CLI prints never holds a control character -------------------------------


def test_cli_escapes_control_characters_from_paths_files_and_arguments(tmp_path):
    good = tmp_path / "a\x1b[2Jb\u202ec\x9b.toml"  # a valid robot under a hostile name
    good.write_text('name = "Fine"\n' + ARM, encoding="utf-8")
    evil_keys = tmp_path / "keys.toml"  # an unknown key and a pose name with escapes
    evil_keys.write_text(
        'name = "x"\n' + toml_string("k\x1b]0;title\x07") + " = 1\n" + ARM, encoding="utf-8"
    )
    evil_pose = tmp_path / "pose.toml"  # a bad pose whose name holds an escape
    evil_pose.write_text(
        'name = "x"\n[poses]\n' + toml_string("p" + CLEAR) + ' = ["a"]\n' + ARM, encoding="utf-8"
    )
    evil_name = tmp_path / "name.toml"
    evil_name.write_text("name = " + toml_string("n\x1b[2J\u202e") + "\n" + ARM, encoding="utf-8")
    runs = [
        (["check", str(good)], 0),
        (["fk", str(good), "--json"], 0),
        (["check", str(evil_keys)], 2),
        (["fk", str(evil_pose)], 2),
        (["check", str(evil_name)], 2),
        (["check", str(tmp_path / "missing\x1b[2J\u202e.toml")], 2),
        (["fk", "puma560", "--pose", "\x1b]0;owned\x07"], 2),
        (["fk", "puma560", "--q", "0,\x1b[2J,0,0,0,0"], 2),
        (["fk", "puma560", "--bogus\x1b[2J\u202e"], 2),
        (["check", "\x9b31m"], 2),
    ]
    for argv, status in runs:
        result = dhsim(*argv)
        assert result.returncode == status, (argv, result.stderr)
        assert b"Traceback" not in result.stderr
        assert_no_control(result.stdout)
        assert_no_control(result.stderr)
    shown = dhsim("check", str(good)).stdout.decode()
    assert "a\\x1b[2Jb\\u202ec\\x9b.toml" in shown  # the path, escaped but whole


def test_cli_escapes_a_path_that_is_not_utf8(tmp_path):
    # a file name with a raw C1 byte (0x9b, the 8-bit CSI): argv holds a lone surrogate
    raw = os.fsencode(tmp_path) + b"/r\x9b2J.toml"
    with open(raw, "w", encoding="utf-8") as handle:
        handle.write('name = "Raw"\n' + ARM)
    for argv in (["check", raw], ["fk", raw + b"x"]):
        result = dhsim(*argv)
        assert b"Traceback" not in result.stderr
        assert_no_control(result.stdout)
        assert_no_control(result.stderr)
    assert b"r\\udc9b2J.toml" in dhsim("check", raw).stdout


# -- paths, folders and arguments that cannot be used -------------------------------------


@pytest.mark.parametrize("command", ["check", "fk"])
def test_a_name_longer_than_255_bytes_gets_a_message(capsys, tmp_path, command):
    code, out, err = run(capsys, command, str(tmp_path / ("a" * 300 + ".toml")))
    assert_one_line(code, err)
    assert "path is too long" in err and out == ""


def test_a_path_longer_than_4096_bytes_gets_a_message(capsys):
    code, _, err = run(capsys, "check", "/".join(["d" * 200] * 25))
    assert_one_line(code, err)
    assert "path is too long" in err


def test_a_folder_that_cannot_be_read_gets_a_message(capsys, tmp_path, monkeypatch):
    # root reads every folder, so the refusal is simulated where the system reports it
    locked = tmp_path / "locked"
    real_stat = os.stat

    def stat(path, *args, **kwargs):
        if str(path).startswith(str(locked) + os.sep):
            raise PermissionError(errno.EACCES, "Permission denied", str(path))
        return real_stat(path, *args, **kwargs)

    monkeypatch.setattr(os, "stat", stat)
    if hasattr(pathlib, "_NormalAccessor"):  # Python 3.10: pathlib kept its own os.stat
        monkeypatch.setattr(pathlib._NormalAccessor, "stat", staticmethod(stat))
    code, _, err = run(capsys, "check", str(locked / "arm.toml"))
    assert_one_line(code, err)
    assert f"{locked / 'arm.toml'}: cannot read: permission denied" in err


@pytest.mark.skipif(os.geteuid() == 0, reason="root can read any folder")
def test_a_real_folder_without_permissions_gets_a_message(tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    (locked / "arm.toml").write_text('name = "x"\n' + ARM, encoding="utf-8")
    locked.chmod(0)
    try:
        result = dhsim("check", str(locked / "arm.toml"))
    finally:
        locked.chmod(0o755)
    assert result.returncode == 2 and b"permission denied" in result.stderr
    assert len(result.stderr.splitlines()) == 1


@pytest.mark.parametrize("argument", ["", "   "])
def test_an_empty_robot_argument_gets_a_message(capsys, argument):
    code, out, err = run(capsys, "check", argument)
    assert out == ""
    assert_one_line(code, err)
    assert f"the robot argument {argument!r} is empty" in err and "puma560" in err


def _in_deleted_folder(tmp_path: Path):
    gone = tmp_path / "gone"
    gone.mkdir()

    def enter_and_delete() -> None:  # runs in the child, before dhsim starts
        os.chdir(gone)
        os.rmdir(gone)

    return enter_and_delete


@pytest.mark.parametrize(
    "argv", [["check", "puma560"], ["fk", "puma560", "--json"], ["list"]], ids=" ".join
)
def test_bundled_robots_work_in_a_deleted_working_folder(tmp_path, argv):
    result = dhsim(*argv, preexec_fn=_in_deleted_folder(tmp_path))
    assert (result.returncode, result.stderr) == (0, b""), result.stderr
    assert b"Puma 560" in result.stdout


def test_a_relative_path_in_a_deleted_working_folder_gets_a_message(tmp_path):
    result = dhsim("check", "./arm.toml", preexec_fn=_in_deleted_folder(tmp_path))
    assert result.returncode == 2
    assert result.stderr.decode() == (
        "dhsim: error: ./arm.toml: no such file: the working folder was deleted, so a "
        "relative path finds nothing; give the full path or a bundled robot's name\n"
    )


# -- lengths too small to compute with ----------------------------------------------------


@pytest.mark.parametrize(
    ("document", "field", "shown"),
    [
        (
            "name = 'x'\n[[joints]]\ntheta = 0\nd = 0\na = 1e-300\nalpha = 0\n",
            "joints[1].a",
            "1e-300 mm",
        ),
        (
            "name = 'x'\n[[joints]]\ntheta = 0\nd = -5e-7\na = 1\nalpha = 0\n",
            "joints[1].d",
            "-5e-07 mm",
        ),
        ("name = 'x'\nunits = 'm'\nbase_height = 1e-12\n" + ARM, "base_height", "1e-12 m"),
        ("name = 'x'\n[tool]\nxyz = [0, 1e-9, 0]\n" + ARM, "tool.xyz[2]", "1e-09 mm"),
        (
            "name = 'x'\n[[joints]]\ntype = 'prismatic'\ntheta = 0\nd = 0\na = 0\nalpha = 0\n"
            "min = 0\nmax = 1e-200\n",
            "joints[1].max",
            "1e-200 mm",
        ),
    ],
)
def test_a_length_below_a_nanometre_is_refused(document, field, shown):
    with pytest.raises(RobotFileError) as caught:
        loads(document, "tiny.toml")
    message = str(caught.value)
    assert message.startswith(f"tiny.toml: {field}: {shown} is too small to compute with")
    assert "a length is 0 or at least 1 nanometre" in message


@pytest.mark.parametrize(("units", "bound"), [("mm", 1e-6), ("cm", 1e-7), ("m", 1e-9)])
def test_zero_and_a_nanometre_are_allowed(units, bound):
    robot = Robot(
        name="small",
        units=units,
        joints=(Joint(a=bound, d=-bound), Joint(a=0.0, d=0.0)),
        base_height=bound,
        tool=Tool(xyz=(bound, 0.0, -bound)),
    )
    assert robot.joints[0].a == bound
    with pytest.raises(DhsimError, match="too small"):
        dataclasses.replace(robot, base_height=bound / 2)


def test_angles_may_be_tiny():
    # only lengths have a lower bound: an angle of 1e-300 deg is just a small angle
    robot = Robot(name="x", joints=(Joint(a=1.0, alpha=1e-300, theta=1e-300),))
    assert robot.joints[0].alpha == 1e-300


# -- no numpy warning, ever; the last resort ------------------------------------------------

SMALL_M = """name = "small"
units = "m"
base_height = 1e-9
[tool]
xyz = [1e-9, 0, 1e-9]
[[joints]]
theta = 0
d = 1e-9
a = 1e-9
alpha = 90
[[joints]]
type = "prismatic"
theta = 0
d = 1e-9
a = 1e-9
alpha = 0
min = 0
max = 1e-9
"""


def _huge_robot() -> str:
    lines = ['name = "huge"', 'units = "m"', "base_height = 1e6", "[tool]"]
    lines += ["xyz = [1e6, -1e6, 1e6]", "rpy = [1e6, -1e6, 1e6]"]
    for i in range(32):
        prismatic = i % 5 == 2
        lines += [
            "[[joints]]",
            f'type = "{"prismatic" if prismatic else "revolute"}"',
            "theta = -1e6" if prismatic else "theta = 1e6",
            "d = 0" if prismatic else "d = 1e6",
            "a = -1e6\nalpha = 1e6\nmin = -1e6\nmax = 1e6",
        ]
    return "\n".join(lines) + "\n"


TINY = "name = 'tiny'\n[[joints]]\ntheta = 0\nd = 0\na = 1e-300\nalpha = 0\n"


def test_no_numpy_warning_with_tiny_or_huge_values(tmp_path):
    small, huge, tiny = tmp_path / "small.toml", tmp_path / "huge.toml", tmp_path / "tiny.toml"
    small.write_text(SMALL_M, encoding="utf-8")
    huge.write_text(_huge_robot(), encoding="utf-8")
    tiny.write_text(TINY, encoding="utf-8")
    commands = []
    for robot in (str(small), str(huge)):
        commands += [
            ["check", robot],
            ["fk", robot],
            ["fk", robot, "--json"],
            ["ik", robot, "--xyz", "1e-9,1e-9,1e-9"],
            ["ik", robot, "--xyz", "1e-9,0,0", "--oat", "10,20,30"],
            ["ik", robot, "--xyz", "1e6,1e6,1e6", "--oat", "10,20,30"],
        ]
    commands += [["ik", str(tiny), "--xyz", "1,0,0"], ["ik", "puma560", "--xyz", "1e-300,0,0"]]
    # every command in one interpreter where any warning is an error ...
    script = textwrap.dedent(
        f"""
        import contextlib, io, json
        from dhsim_tui.cli.main import main
        results = []
        for argv in {commands!r}:
            err = io.StringIO()
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                code = main(argv)
            results.append([argv, code, err.getvalue()])
        print(json.dumps(results))
        """
    )
    inner = subprocess.run(  # every command in one run, some on a 32-joint robot: long
        [sys.executable, "-W", "error", "-c", script],
        capture_output=True,
        text=True,
        timeout=5 * HANG,
    )
    assert inner.returncode == 0 and inner.stderr == "", inner.stderr
    for argv, code, err in json.loads(inner.stdout):
        # 3: ik found no solution; 1 would be a warning turned into an error
        assert code in (0, 2, 3), (argv, err)
        assert "Warning" not in err and "internal error" not in err, (argv, err)
        assert len(err.splitlines()) <= 1, (argv, err)
    outcome = {tuple(argv): (code, err) for argv, code, err in json.loads(inner.stdout)}
    code, err = outcome[("ik", str(tiny), "--xyz", "1,0,0")]
    assert code == 2 and "joints[1].a: 1e-300 mm is too small to compute with" in err
    # ... and the real script, warnings as errors through the environment
    result = dhsim(
        "ik", str(small), "--xyz", "1e-9,0,0", env={**os.environ, "PYTHONWARNINGS": "error"}
    )
    assert result.returncode == 3 and b"Warning" not in result.stderr  # 3: no solution
    assert len(result.stderr.splitlines()) == 1


def test_an_unexpected_error_is_one_line_and_status_1(capsys, monkeypatch):
    def broken(robot):
        raise RuntimeError("boom \x1b[2J")

    monkeypatch.setattr(cli, "describe", broken)
    code, out, err = run(capsys, "check", "puma560")
    assert_one_line(code, err, expected_code=1)
    assert out == ""
    assert err == "dhsim: internal error: RuntimeError: boom \\x1b[2J\n"


def test_an_unexpected_error_in_the_real_process_exits_1_without_traceback():
    script = (
        "import sys, dhsim_tui.cli.main as c, dhsim_tui.cli.library as library\n"
        "library.describe = lambda robot: 1 / 0\n"  # what 'dhsim list' calls
        "sys.exit(c.main(['list']))\n"
    )
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, timeout=HANG)
    assert result.returncode == 1
    assert result.stderr == b"dhsim: internal error: ZeroDivisionError: division by zero\n"


def test_ctrl_c_still_exits_130(capsys, monkeypatch):
    def interrupted(robot):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "describe", interrupted)
    assert run(capsys, "check", "puma560") == (130, "", "")


def test_a_closed_pipe_is_quiet():
    # the reader is gone before dhsim writes a byte: no noise, no error status
    reader, writer = os.pipe()
    os.close(reader)
    try:
        result = subprocess.run(
            [dhsim_command(), "list"], stdout=writer, stderr=subprocess.PIPE, timeout=HANG
        )
    finally:
        os.close(writer)
    assert (result.returncode, result.stderr) == (0, b"")


# -- numbers are shown whole ----------------------------------------------------------------


@pytest.mark.parametrize(
    ("value", "shown"),
    [
        (160.0000000001, "160.0000000001"),
        (431.8, "431.8"),
        (-90.0, "-90"),
        (1e6, "1e+06"),
        (70.125, "70.125"),
        (0.089459, "0.089459"),
        (0.1 + 0.2, "0.30000000000000004"),
        (123456789.0, "123456789"),
        (1e-300, "1e-300"),
        (-0.0, "0"),
    ],
)
def test_fmt_shows_the_number_whole(value, shown):
    assert fmt(value) == shown


@given(st.floats(allow_nan=False))
def test_fmt_reads_back_as_the_same_number(value):
    assert float(fmt(value)) == value


@pytest.mark.parametrize(
    ("q", "shown"),
    [
        (
            "160.0000000001,0,0,0,0,0",
            "Th1 = 160.0000000001 deg is outside its limits -160..160 deg",
        ),
        (
            "0,0,0,0,-100.00000000000001,0",
            "Th5 = -100.00000000000001 deg is outside its limits -100..100 deg",
        ),
    ],
)
def test_limit_messages_show_the_difference(capsys, q, shown):
    code, _, err = run(capsys, "fk", "puma560", "--q", q)
    assert_one_line(code, err)
    assert shown in err


def test_home_outside_limits_by_a_hair_shows_the_difference():
    with pytest.raises(DhsimError) as caught:
        Robot(name="x", joints=(Joint(a=1.0, theta=90.00000000001, min=0.0, max=90.0),))
    assert "home value 90.00000000001 deg is outside the joint's limits 0..90 deg" in str(
        caught.value
    )


def test_fk_shows_the_joint_values_it_used_whole(capsys):
    code, out, _ = run(capsys, "fk", "puma560", "--q", "12.3456789,0,0,0,0,0.000001234")
    assert code == 0
    assert "Th1 12.3456789" in out and "Th6 1.234e-06" in out


def test_fk_columns_of_a_huge_robot_never_run_together(capsys, tmp_path):
    path = tmp_path / "huge.toml"
    path.write_text(_huge_robot(), encoding="utf-8")
    code, out, _ = run(capsys, "fk", str(path))
    assert code == 0
    lines = out.splitlines()
    xyz_row = lines[lines.index(next(x for x in lines if x.split()[:3] == ["X", "Y", "Z"])) + 1]
    assert len(xyz_row.split()) == 3, xyz_row
    assert all(math.isfinite(float(cell)) for cell in xyz_row.split())


def test_describe_shows_a_tiny_reach_whole():
    robot = loads(SMALL_M)
    summary = describe(robot)
    assert "reach 3.74166e-09 m" in summary  # sqrt(14) nm, 6 significant digits, not "0"
    assert "reach 877.01 mm" in describe(load_robot("puma560")[0])


def test_a_name_the_terminal_cannot_encode_is_escaped_not_a_crash(tmp_path):
    # an ASCII-only terminal (a C locale without UTF-8) and a robot named in Chinese
    path = tmp_path / "arm.toml"
    path.write_text(f"name = {toml_string('机器人')}\n" + ARM, encoding="utf-8")
    result = dhsim("check", str(path), env={**os.environ, "PYTHONIOENCODING": "ascii"})
    assert (result.returncode, result.stderr) == (0, b"")
    assert b"ok  \\u673a\\u5668\\u4eba: 1 joint, R," in result.stdout


def test_a_solution_that_lost_precision_is_refused_not_printed(capsys, monkeypatch):
    # numpy warnings are silenced in the CLI, so a non-finite answer must be caught
    real_inverse = cli_kinematics.inverse

    def lossy(*args, **kwargs):
        result = real_inverse(*args, **kwargs)
        return dataclasses.replace(result, q=(math.nan,) * len(result.q))

    monkeypatch.setattr(cli_kinematics, "inverse", lossy)
    code, out, err = run(capsys, "ik", "planar2", "--xyz", "1,1,0")
    assert_one_line(code, err, expected_code=3)  # 3: no solution
    assert out == "" and "the solver lost precision" in err
    # with --json the answer is an object on stdout saying why, never the NaN
    code, out, err = run(capsys, "ik", "planar2", "--xyz", "1,1,0", "--json")
    assert (code, err) == (3, "")
    answer = json.loads(out)
    assert answer["solved"] is False and answer["reason"] == "the solver lost precision"
    assert "q" not in answer and "nan" not in out.lower()

"""The ``dhsim`` command line: fk / check / list output, exit codes and the
one-line error contract. Most tests call ``main`` in-process (fast); a few
run the real interpreter to prove exit codes, the absence of tracebacks and
that the scripting commands never import the UI libraries."""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from pty_screen import PtyScreen, dhsim_command
from waiting import HANG

from dhsim_tui.cli.main import main
from dhsim_tui.core import bundled_names

ROOT = Path(__file__).resolve().parents[2]
#: the robots dhsim ships, by its own list (not whatever lies in the checkout's robots/)
BUNDLED_STEMS = sorted(bundled_names())

# The Puma 560 of the reference (§5): theta, d, a, alpha (mm, deg)
PUMA_DH = [
    (0.0, 0.0, 0.0, 90.0),
    (0.0, 0.0, 431.8, 0.0),
    (0.0, 150.05, 20.3, -90.0),
    (0.0, 431.8, 0.0, 90.0),
    (0.0, 0.0, 0.0, -90.0),
    (0.0, 0.0, 0.0, 0.0),
]
PAPER_Q = "0,30,45,60,90,0"
PAPER_XYZ = (-37.88, -150.05, 347.27)
PAPER_OAT = (-8.50, 28.88, -107.19)


def puma_fk(q_deg) -> np.ndarray:
    """Standard D-H by hand (reference §1), world = frame 0, no tool."""
    t = np.eye(4)
    for (theta0, d, a, alpha), q in zip(PUMA_DH, q_deg, strict=True):
        th, al = math.radians(theta0 + q), math.radians(alpha)
        ct, st, ca, sa = math.cos(th), math.sin(th), math.cos(al), math.sin(al)
        t = t @ np.array(
            [
                [ct, -st * ca, st * sa, a * ct],
                [st, ct * ca, -ct * sa, a * st],
                [0.0, sa, ca, d],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
    return t


def oat_of(r: np.ndarray) -> tuple[float, float, float]:
    """OAT by the reference's formulas (§4), non-singular branch."""
    horizontal = math.hypot(r[0, 2], r[1, 2])
    assert horizontal > 1e-6, "singular case not handled by this helper"
    a = math.degrees(math.atan2(-r[2, 2], horizontal))
    o = math.degrees(math.atan2(r[0, 2], -r[1, 2]))
    t = math.degrees(math.atan2(r[2, 1], -r[2, 0]))
    return o, a, t


def rpy_of(r: np.ndarray) -> tuple[float, float, float]:
    roll = math.degrees(math.atan2(r[2, 1], r[2, 2]))
    pitch = math.degrees(math.atan2(-r[2, 0], math.hypot(r[0, 0], r[1, 0])))
    yaw = math.degrees(math.atan2(r[1, 0], r[0, 0]))
    return roll, pitch, yaw


def angle_diff(a: float, b: float) -> float:
    return abs((a - b + 180.0) % 360.0 - 180.0)


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def table_rows(out: str) -> tuple[list[str], list[str]]:
    """The number rows under the ``X Y Z`` and ``O A T`` headers."""
    lines = out.splitlines()
    xyz_header = next(i for i, line in enumerate(lines) if line.split()[:3] == ["X", "Y", "Z"])
    oat_header = next(i for i, line in enumerate(lines) if line.split()[:3] == ["O", "A", "T"])
    return lines[xyz_header + 1].split(), lines[oat_header + 1].split()


# -- fk ----------------------------------------------------------------------------


def test_fk_paper_row_plain(capsys):
    code, out, err = run(capsys, "fk", "puma560", "--q", PAPER_Q)
    assert (code, err) == (0, "")
    xyz, oat = table_rows(out)
    assert xyz == ["-37.88", "-150.05", "347.27"]
    assert oat == ["-8.50", "28.88", "-107.19"]
    assert "Puma 560" in out
    assert "(mm)" in out and "(deg)" in out
    assert "Th3 45" in out  # the joint values it used


def test_fk_paper_row_json(capsys):
    code, out, err = run(capsys, "fk", "puma560", "--q", PAPER_Q, "--json")
    assert (code, err) == (0, "")
    assert out.count("\n") == 1  # one object on one line
    data = json.loads(out)
    assert set(data) == {"robot", "units", "q", "xyz", "oat", "rpy", "T"}
    assert data["robot"] == "Puma 560"
    assert data["units"] == "mm"
    assert data["q"] == [0, 30, 45, 60, 90, 0]
    matrix = np.array(data["T"], dtype=float)
    assert matrix.shape == (4, 4)
    expected = puma_fk([0, 30, 45, 60, 90, 0])
    np.testing.assert_allclose(matrix, expected, atol=1e-6)
    np.testing.assert_allclose(data["xyz"], expected[:3, 3], atol=1e-6)
    for got, want in zip(data["oat"], oat_of(expected[:3, :3]), strict=True):
        assert angle_diff(got, want) < 1e-6
    for got, want in zip(data["rpy"], rpy_of(expected[:3, :3]), strict=True):
        assert angle_diff(got, want) < 1e-6
    # and it agrees with the plain table's figures
    _, plain, _ = run(capsys, "fk", "puma560", "--q", PAPER_Q)
    xyz, oat = table_rows(plain)
    assert [f"{v:.2f}" for v in data["xyz"]] == xyz
    assert [f"{v:.2f}" for v in data["oat"]] == oat
    for got, want in zip(data["xyz"] + data["oat"], PAPER_XYZ + PAPER_OAT, strict=True):
        assert abs(got - want) < 0.005 + 1e-9


def test_fk_named_pose(capsys):
    code, out, _ = run(capsys, "fk", "puma560", "--pose", "qr")
    assert code == 0
    xyz, oat = table_rows(out)
    assert xyz == ["20.30", "-150.05", "863.60"]  # reference §5, the ready pose
    assert oat == ["90.00", "-90.00", "0.00"]
    code, out, _ = run(capsys, "fk", "puma560", "--pose", "qr", "--json")
    data = json.loads(out)
    assert data["q"] == [0, 90, -90, 0, 0, 0]
    np.testing.assert_allclose(data["T"], puma_fk([0, 90, -90, 0, 0, 0]), atol=1e-6)


def test_fk_defaults_to_home(capsys):
    code, out, _ = run(capsys, "fk", "puma560")
    assert code == 0
    xyz, oat = table_rows(out)
    assert xyz == ["452.10", "-150.05", "431.80"]  # reference §5, all zeros
    assert oat == ["90.00", "-90.00", "0.00"]
    data = json.loads(run(capsys, "fk", "puma560", "--json")[1])
    assert data["q"] == [0, 0, 0, 0, 0, 0]


@pytest.mark.parametrize("argv", [["--q", "-10,20,0,0,0,0"], ["--q=-10,20,0,0,0,0"]])
def test_fk_negative_values(capsys, argv):
    code, out, err = run(capsys, "fk", "puma560", *argv, "--json")
    assert (code, err) == (0, "")
    data = json.loads(out)
    assert data["q"] == [-10, 20, 0, 0, 0, 0]
    np.testing.assert_allclose(data["T"], puma_fk([-10, 20, 0, 0, 0, 0]), atol=1e-6)
    code, out, _ = run(capsys, "fk", "puma560", *argv)
    assert code == 0 and "Th1 -10" in out


def test_fk_values_with_spaces_and_integers(capsys):
    code, out, _ = run(capsys, "fk", "puma560", "--q", " 0, 30,45 ,60,90, 0", "--json")
    assert code == 0
    np.testing.assert_allclose(json.loads(out)["xyz"], puma_fk([0, 30, 45, 60, 90, 0])[:3, 3])


def test_fk_on_another_robot_in_metres(capsys):
    # planar two-link arm, 1 m links: at (90, -90) deg the tip is at (1, 1, 0) m
    code, out, _ = run(capsys, "fk", "planar2", "--q", "90,-90", "--json")
    assert code == 0
    data = json.loads(out)
    assert data["units"] == "m"
    np.testing.assert_allclose(data["xyz"], [1.0, 1.0, 0.0], atol=1e-9)
    assert "(m)" in run(capsys, "fk", "planar2", "--q", "90,-90")[1]


def test_fk_on_a_robot_file_path(capsys, tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(
        'name = "Stick"\nunits = "cm"\n[[joints]]\ntheta = 0\nd = 0\na = 50\nalpha = 0\n',
        encoding="utf-8",
    )
    code, out, _ = run(capsys, "fk", str(path), "--q", "90", "--json")
    assert code == 0
    data = json.loads(out)
    assert data["robot"] == "Stick" and data["units"] == "cm"
    np.testing.assert_allclose(data["xyz"], [0.0, 50.0, 0.0], atol=1e-9)


def test_fk_prismatic_value_in_robot_units(capsys):
    # Stanford arm: moving d3 by 100 mm slides everything beyond joint 3
    # (the wrist and tool, not rotated) 100 mm along z2, so the end effector
    # moves exactly 100 mm, whatever that axis's direction.
    home = json.loads(run(capsys, "fk", "stanford", "--json")[1])
    q = list(home["q"])
    q[2] += 100.0
    moved = json.loads(run(capsys, "fk", "stanford", "--q", ",".join(map(str, q)), "--json")[1])
    step = np.subtract(moved["xyz"], home["xyz"])
    assert np.linalg.norm(step) == pytest.approx(100.0, abs=1e-9)


# -- check and list -------------------------------------------------------------


def test_check_bundled(capsys):
    code, out, err = run(capsys, "check", "puma560")
    assert (code, err) == (0, "")
    assert out.count("\n") == 1
    assert out.startswith("ok")
    # the arm straightened: hypot(150.05, 431.8 + hypot(431.8, 20.3)), not the
    # seed's sum of |a| + |d| (1033.95, a bound: issue 17)
    for fragment in ("Puma 560", "6 joints", "RRRRRR", "reach 877.01", "mm", "puma560.toml"):
        assert fragment in out, fragment


def test_check_type_string_with_prismatic_joints(capsys):
    assert "RRPRRR" in run(capsys, "check", "stanford")[1]
    assert "RRPR" in run(capsys, "check", "cobra600")[1]
    assert "PPP" in run(capsys, "check", "gantry")[1]


def test_check_file_path(capsys, tmp_path):
    path = tmp_path / "two.toml"
    path.write_text(
        'name = "Two"\n'
        "[[joints]]\ntheta = 0\nd = 10\na = 100\nalpha = 0\n"
        '[[joints]]\ntype = "prismatic"\ntheta = 0\nd = 0\na = 0\nalpha = 0\nmin = 0\nmax = 50\n',
        encoding="utf-8",
    )
    code, out, _ = run(capsys, "check", str(path))
    assert code == 0
    for fragment in ("Two", "2 joints", "RP", str(path)):
        assert fragment in out, fragment


def listed_bundled(out: str) -> list[str]:
    """``dhsim list``'s bundled group: the indented lines after "bundled:"
    (the "yours (LIBRARY):" group comes first)."""
    lines = out.splitlines()
    assert "bundled:" in lines, out
    group = lines[lines.index("bundled:") + 1 :]
    assert all(line.startswith("  ") for line in group), out
    return group


def test_list_shows_every_bundled_robot(capsys):
    code, out, err = run(capsys, "list")
    assert (code, err) == (0, "")
    library = Path(os.environ["XDG_DATA_HOME"]) / "dhsim" / "robots"
    assert out.splitlines()[0] == (
        f"yours ({library}): none yet ('dhsim new NAME' saves one there)"
    )  # each test's own, empty library
    lines = listed_bundled(out)
    assert len(BUNDLED_STEMS) >= 10
    assert [line.split()[0] for line in lines] == BUNDLED_STEMS
    puma = next(line for line in lines if line.split()[0] == "puma560")
    assert "Puma 560" in puma and "6 joints" in puma


def test_help_and_version(capsys):
    code, out, _ = run(capsys, "--help")
    assert code == 0 and "dhsim fk ROBOT" in out
    code, out, _ = run(capsys, "--version")
    assert code == 0 and re.fullmatch(r"dhsim \d+\.\d+\.\d+\S*\n", out)


# -- bad input: one line on stderr, exit 2 ---------------------------------------


def assert_one_line_error(code: int, out: str, err: str, *fragments: str) -> None:
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in err, f"{fragment!r} not in {err!r}"


@pytest.mark.parametrize(
    ("argv", "fragments"),
    [
        # --q with the wrong count
        (["fk", "puma560", "--q", "0,30,45,60,90"], ["--q", "expected 6", "got 5"]),
        (["fk", "puma560", "--q", "0,0,0,0,0,0,0"], ["--q", "expected 6", "got 7"]),
        (["fk", "planar2", "--q", "10"], ["--q", "expected 2", "Th1, Th2", "got 1"]),
        # non-numbers
        (["fk", "puma560", "--q", "0,x,45,60,90,0"], ["--q", "item 2", "'x'", "not a number"]),
        (["fk", "puma560", "--q", "0,,0,0,0,0"], ["--q", "item 2", "empty"]),
        (["fk", "puma560", "--q", "0;0;0;0;0;0"], ["--q", "item 1", "not a number"]),
        (["fk", "puma560", "--q", "nan,0,0,0,0,0"], ["--q", "item 1", "nan", "not a finite"]),
        (["fk", "puma560", "--q", "0,0,0,0,0,inf"], ["--q", "item 6", "inf"]),
        (["fk", "puma560", "--q", "0,0,-1e400,0,0,0"], ["--q", "item 3", "1e400"]),
        # outside the limits, naming the joint and its limits
        (["fk", "puma560", "--q", "0,0,0,200,0,0"], ["--q", "Th4", "200", "-110..170 deg"]),
        (["fk", "puma560", "--q", "-161,0,0,0,0,0"], ["Th1", "-161", "-160..160 deg"]),
        (["fk", "stanford", "--q", "0,0,2000,0,0,0"], ["d3", "2000", "304.8..1270 mm"]),
        # named poses
        (["fk", "puma560", "--pose", "bogus"], ["bogus", "qz", "qr", "qs", "qn"]),
        (["fk", "puma560", "--pose", "qr", "--q", "0,0,0,0,0,0"], ["--q", "--pose"]),
        # argparse's own complaints
        (["fk", "puma560", "--bogus"], ["--bogus"]),
        (["fk", "puma560", "--q"], ["--q", "expected one argument"]),
        (["fk"], ["robot"]),
        (["check"], ["robot"]),
        (["list", "extra"], ["extra"]),
        (["--bogus"], ["--bogus"]),
        # robots that do not exist
        (["fk", "no_such_robot"], ["no_such_robot", "puma560"]),
        (["check", "no_such_robot.toml"], ["no_such_robot.toml"]),
    ],
)
def test_bad_input(capsys, argv, fragments):
    code, out, err = run(capsys, *argv)
    assert_one_line_error(code, out, err, *fragments)


BROKEN_TOML = 'name = "Broken"\nunits = "mm"\n[[joints]]\ntheta = = 0\n'


@pytest.mark.parametrize("command", ["fk", "check"])
def test_bad_robot_file(capsys, tmp_path, command):
    path = tmp_path / "broken.toml"
    path.write_text(BROKEN_TOML, encoding="utf-8")
    code, out, err = run(capsys, command, str(path))
    assert_one_line_error(code, out, err, str(path), "line 4")


@pytest.mark.parametrize(
    ("text", "fragments"),
    [
        ('name = "x"\n[[joints]]\ntheta = 0\nd = 0\na = 1\nalhpa = 0\n', ["joints[1].alhpa"]),
        ('name = "x"\n[[joints]]\ntheta = 0\nd = 0\na = nan\nalpha = 0\n', ["joints[1].a", "NaN"]),
        ('name = "x"\njoints = []\n', ["joints", "1 to 32"]),
        ("x = " + "[" * 3000 + "]" * 3000 + "\n", ["not valid TOML"]),
    ],
)
def test_invalid_robot_file_names_file_and_field(capsys, tmp_path, text, fragments):
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    code, out, err = run(capsys, "fk", str(path))
    assert_one_line_error(code, out, err, str(path), *fragments)


def test_non_utf8_robot_file(capsys, tmp_path):
    path = tmp_path / "binary.toml"
    path.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00")
    code, out, err = run(capsys, "check", str(path))
    assert_one_line_error(code, out, err, str(path), "UTF-8")


def test_folder_as_robot(capsys, tmp_path):
    code, out, err = run(capsys, "fk", str(tmp_path))
    assert_one_line_error(code, out, err, str(tmp_path), "folder")


# -- the real interpreter ------------------------------------------------------------


def dhsim(*argv: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "dhsim_tui", *argv],
        capture_output=True,
        text=True,
        timeout=HANG,
        cwd=cwd,
    )


def test_subprocess_fk_prints_the_paper_figures():
    result = dhsim("fk", "puma560", "--q", PAPER_Q)
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    for figure in PAPER_XYZ + PAPER_OAT:
        assert f"{figure:.2f}" in result.stdout


def test_subprocess_bad_inputs_exit_2_without_traceback(tmp_path):
    broken = tmp_path / "broken.toml"
    broken.write_text(BROKEN_TOML, encoding="utf-8")
    nested = tmp_path / "nested.toml"
    nested.write_text("x = " + "[" * 3000 + "]" * 3000 + "\n", encoding="utf-8")
    commands = [
        ["fk", str(broken)],
        ["fk", str(nested)],
        ["fk", "puma560", "--q", "0,0,0,200,0,0"],
        ["fk", "puma560", "--bogus"],
    ]
    script = textwrap.dedent(
        f"""
        import contextlib, io, json, sys
        from dhsim_tui.cli.main import main
        results = []
        for argv in {commands!r}:
            err = io.StringIO()
            with contextlib.redirect_stderr(err):
                code = main(argv)
            results.append([code, err.getvalue()])
        print(json.dumps(results))
        """
    )
    # one real `python -m dhsim_tui` run for the exit status itself ...
    result = dhsim("fk", str(broken))
    assert result.returncode == 2
    assert result.stdout == ""
    assert "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1
    assert str(broken) in result.stderr and "line 4" in result.stderr
    # ... and the rest in one fresh interpreter
    inner = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=HANG
    )
    assert inner.returncode == 0, inner.stderr
    assert "Traceback" not in inner.stderr
    for code, err in json.loads(inner.stdout):
        assert code == 2
        assert len(err.strip().splitlines()) == 1, err
        assert "Traceback" not in err


UI_LIBRARIES = ("textual", "plotext", "rich")


def test_scripting_commands_do_not_import_ui_libraries():
    import importlib.util

    # the check below means something only if the libraries are installed
    assert all(importlib.util.find_spec(name) for name in UI_LIBRARIES)
    script = textwrap.dedent(
        f"""
        import contextlib, io, sys
        from dhsim_tui.cli.main import main
        for argv in (
            ["fk", "puma560", "--q", "{PAPER_Q}"],
            ["fk", "puma560", "--pose", "qr", "--json"],
            ["fk", "puma560", "--q", "0,0,0,999,0,0"],
            ["check", "stanford"],
            ["list"],
            ["no_such_robot"],
        ):
            with contextlib.redirect_stdout(io.StringIO()), \\
                    contextlib.redirect_stderr(io.StringIO()):
                main(argv)
        loaded = sorted({{m.split(".")[0] for m in sys.modules}} & set({UI_LIBRARIES!r}))
        print(",".join(loaded))
        """
    )
    result = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=HANG
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "", f"UI libraries imported: {result.stdout.strip()}"


# --- dhsim ik --------------------------------------------------------------


def test_ik_reaches_the_papers_pose_and_fk_agrees(capsys):
    code, out, err = run(capsys, "fk", "puma560", "--q", PAPER_Q, "--json")
    fk = json.loads(out)
    xyz = ",".join(repr(v) for v in fk["xyz"])
    oat = ",".join(repr(v) for v in fk["oat"])
    code, out, err = run(capsys, "ik", "puma560", "--xyz", xyz, "--oat", oat, "--json")
    assert code == 0 and err == ""
    answer = json.loads(out)
    assert set(answer) >= {"q", "xyz", "oat", "residual"}
    assert answer["residual"] < 1e-6
    code, out, _ = run(capsys, "fk", "puma560", "--q", ",".join(map(repr, answer["q"])), "--json")
    again = json.loads(out)
    assert all(abs(a - b) < 1e-3 for a, b in zip(again["xyz"], fk["xyz"], strict=True))
    assert all(abs(a - b) < 1e-4 for a, b in zip(again["oat"], fk["oat"], strict=True))


def test_ik_position_only_plain_output(capsys):
    code, out, err = run(capsys, "ik", "planar2", "--xyz", "1,1,0")
    assert code == 0 and err == "" and "Th1" in out and "Th2" in out and "residual" in out


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        # no solution is exit 3, not 2: tests/cli/test_conventions.py
        (("ik", "puma560", "--xyz", "1,2"), "--xyz: expected 3 numbers"),
        (("ik", "puma560", "--xyz", "1,2,a"), "--xyz: item 3 ('a') is not a number"),
        (("ik", "puma560", "--xyz", "1,2,3", "--oat", "1,2"), "--oat: expected 3 angles"),
        (("ik", "puma560", "--xyz", "1,2,3", "--from", "0,0"), "--from: expected 6 joint"),
        (("ik", "puma560"), "the following arguments are required: --xyz"),
    ],
)
def test_ik_bad_input_exits_2_with_one_line(capsys, argv, message):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert message in err and len(err.strip().splitlines()) == 1


# --- the simulator needs a terminal; the scripting commands don't ----------------------

NEEDS_TERMINAL = (
    "dhsim: the simulator needs an interactive terminal (over SSH use ssh -t); "
    "fk, ik, check, list, import, export, convert, workspace, draw and run work without one\n"
)
#: a bare word that is no robot is an unknown command (tests/cli/test_conventions.py)
INTERACTIVE_ARGV = [[], ["puma560"], ["edit", "puma560"], ["new"], ["no_such_robot.toml"]]


def dhsim_script() -> str:
    """The installed console script beside this interpreter (what a user runs)."""
    return dhsim_command()


@pytest.mark.parametrize("argv", INTERACTIVE_ARGV, ids=lambda a: " ".join(a) or "bare")
def test_simulator_without_a_terminal_exits_2_at_once(argv):
    # stdin from /dev/null, stdout a pipe: before the fix this never returned (timeout)
    result = subprocess.run(
        [dhsim_script(), *argv],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=HANG,
    )
    assert (result.returncode, result.stdout, result.stderr) == (2, "", NEEDS_TERMINAL)


@pytest.mark.parametrize("tty_side", ["stdin", "stdout"])
def test_simulator_needs_both_stdin_and_stdout_to_be_a_terminal(tty_side):
    main_fd, terminal_fd = os.openpty()
    try:
        streams = {"stdin": subprocess.DEVNULL, "stdout": subprocess.PIPE}
        streams[tty_side] = terminal_fd
        result = subprocess.run(
            [dhsim_script(), "puma560"],
            **streams,
            stderr=subprocess.PIPE,
            text=True,
            timeout=HANG,
        )
    finally:
        os.close(terminal_fd)
        os.close(main_fd)
    assert result.returncode == 2
    assert result.stderr == NEEDS_TERMINAL


def test_no_terminal_check_comes_before_loading_textual():
    script = textwrap.dedent(
        """
        import contextlib, io, sys
        from dhsim_tui.cli.main import main
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            codes = [main(argv) for argv in ([], ["edit", "stanford"], ["new", "arm"])]
        loaded = sorted({m.split(".")[0] for m in sys.modules} & {"textual", "rich"})
        print(codes, loaded, err.getvalue().count("interactive terminal"))
        """
    )
    result = subprocess.run(
        [sys.executable, "-c", script],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=HANG,
    )
    assert result.stdout.strip() == "[2, 2, 2] [] 3", result.stderr


@pytest.mark.parametrize(
    "argv",
    [["fk", "puma560", "--q", PAPER_Q], ["ik", "planar2", "--xyz", "1,1,0"], ["check", "ur5"]],
)
def test_scripting_commands_work_without_a_terminal(argv):
    result = subprocess.run(
        [dhsim_script(), *argv],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=HANG,
    )
    assert (result.returncode, result.stderr) == (0, ""), result.stderr
    assert result.stdout.strip()


def test_list_works_without_a_terminal():
    result = subprocess.run(
        [dhsim_script(), "list"], stdin=subprocess.DEVNULL, capture_output=True, timeout=HANG
    )
    assert (result.returncode, result.stderr) == (0, b"")
    assert [line.split()[0] for line in listed_bundled(result.stdout.decode())] == BUNDLED_STEMS


def test_simulator_in_a_terminal_refuses_a_bad_robot_before_any_ui():
    with PtyScreen(["no_such_robot.toml"]) as shell:  # a bare word: an unknown command
        status = shell.wait_exit()
        raw = shell.raw_bytes()
        shown = shell.screen_text()
    assert status == 2
    assert "no_such_robot.toml: no such file" in shown
    assert b"\x1b[?1049h" not in raw  # the alternate screen was never entered


def test_simulator_in_a_terminal_names_a_urdf_and_the_command_that_imports_it(tmp_path):
    urdf = tmp_path / "arm.urdf"
    urdf.write_bytes((ROOT / "tests" / "urdfs" / "planar_elbow.urdf").read_bytes())
    with PtyScreen([str(urdf)]) as shell:
        status = shell.wait_exit()
        raw = shell.raw_bytes()
        shown = " ".join(shell.screen_text().split())  # the line as the terminal wrapped it
    assert status == 2
    assert "a URDF, not a dhsim robot file" in shown and "dhsim import" in shown
    assert "not valid TOML" not in shown
    assert b"\x1b[?1049h" not in raw

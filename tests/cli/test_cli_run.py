"""``dhsim run ROBOT PROGRAM`` and ``dhsim import --program`` as a user runs
them: the report, the exit statuses (0 clean, 3 problems, 2 bad input in one
line), the CSV against ``dhsim fk`` at each row's joints, the JSON, the plot,
and a trajectory CSV read back as a program."""

from __future__ import annotations

import csv
import io
import json
import math
from dataclasses import replace

import numpy as np
import pytest

from dhsim_tui.cli.main import MAIN_HELP, main
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.files.robotfile import dumps, load
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.motion.trajectory import sample


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def rows_of(text: str) -> list[dict]:
    body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    return list(csv.DictReader(io.StringIO(body)))


@pytest.fixture
def problem_robot(tmp_path):
    """A Puma file with a program that puts Th1 on its limit and one that is clean."""
    puma, _ = load_robot("puma560")
    programs = (
        Program("limit", (Step("joint", (160, 0, 0, 0, 0, 0)), Step("wait", seconds=0.1))),
        Program("fine", (Step("joint", "qn"),)),
    )
    path = tmp_path / "arm.toml"
    path.write_text(dumps(replace(puma, programs=programs)), encoding="utf-8")
    return path


def test_the_report_lists_the_duration_the_steps_and_says_clean(capsys):
    code, out, err = run(capsys, "run", "puma560", "demo")
    assert (code, err) == (0, "")
    puma, _ = load_robot("puma560")
    trajectory = sample(puma, puma.program("demo"))
    lines = out.splitlines()
    assert lines[0] == (
        f"Puma 560: program 'demo', 5 steps, {trajectory.duration:.3f} s at 100 Hz "
        f"({len(trajectory.time)} samples)"
    )
    assert lines[1].split() == ["step", "start", "length", "move"]
    for line, span in zip(lines[2:7], trajectory.spans, strict=True):
        number, start, _, length, _, *words = line.split()
        assert int(number) == span.number
        assert float(start) == pytest.approx(span.start, abs=5e-4)
        assert float(length) == pytest.approx(span.duration, abs=5e-4)
        assert " ".join(words) == span.step.describe()
    assert lines[7:] == ["the path is clean: no problems found"]


def test_problems_are_listed_with_step_time_and_kind_and_exit_3(capsys, problem_robot):
    code, out, err = run(capsys, "run", str(problem_robot), "limit")
    assert code == 3 and err == ""
    assert "1 problem:" in out
    line = out.splitlines()[-1]
    assert line.startswith("  step 2, ") and "limit: Th1 at its upper limit 160 deg" in line
    assert run(capsys, "run", str(problem_robot), "fine")[0] == 0


def test_json_is_one_object_with_the_same_facts(capsys, problem_robot):
    code, out, _ = run(capsys, "run", str(problem_robot), "limit", "--json")
    assert code == 3 and len(out.strip().splitlines()) == 1
    data = json.loads(out)
    assert data["robot"] == "Puma 560" and data["program"] == "limit" and data["units"] == "mm"
    assert data["rate"] == 100 and data["clean"] is False
    assert [s["step"] for s in data["steps"]] == [1, 2]
    assert data["steps"][0]["q_end"] == [160, 0, 0, 0, 0, 0]
    assert data["duration"] == pytest.approx(data["steps"][1]["start"] + 0.1)
    # every 10 ms of the move, the wait's first and last grid point, the end
    assert data["samples"] == math.ceil(data["steps"][1]["start"] * 100) + 2 + 1
    (problem,) = data["problems"]
    assert problem["kind"] == "limit" and problem["subject"] == "Th1" and problem["step"] == 2
    assert set(problem) == {"kind", "step", "time", "until", "subject", "detail"}


def test_every_csv_row_is_dhsim_fk_at_its_joints(capsys, tmp_path):
    out = tmp_path / "demo.csv"
    code, stdout, err = run(capsys, "run", "puma560", "demo", "--csv", str(out), "--rate", "20")
    assert code == 0 and err == "" and f"wrote {out}" in stdout
    text = out.read_text(encoding="utf-8")
    assert text.startswith("time,step,move,q1,q2,q3,q4,q5,q6,x,y,z,o,a,t,mu\n")
    rows = rows_of(text)
    assert 150 < len(rows) < 170
    for row in rows:
        q = ",".join(row[f"q{i}"] for i in range(1, 7))
        code, fk, _ = run(capsys, "fk", "puma560", "--q", q, "--json")
        assert code == 0
        pose = json.loads(fk)
        assert np.allclose([float(row[k]) for k in "xyz"], pose["xyz"], atol=1e-6, rtol=0)
        assert np.allclose([float(row[k]) for k in "oat"], pose["oat"], atol=1e-6, rtol=0)


def test_csv_to_stdout_sends_the_report_to_stderr(capsys):
    code, out, err = run(capsys, "run", "puma560", "demo", "--csv", "-", "--rate", "10")
    assert code == 0
    assert out.startswith("time,step,move,") and len(rows_of(out)) == 80 - 3  # the wait: 2 of 5
    assert err.startswith("Puma 560: program 'demo'")


def test_an_existing_csv_needs_force(capsys, tmp_path):
    out = tmp_path / "t.csv"
    out.write_text("keep me\n")
    code, stdout, err = run(capsys, "run", "puma560", "demo", "--csv", str(out))
    assert code == 2 and stdout == "" and "--force replaces it" in err
    assert out.read_text() == "keep me\n"
    code, _, _ = run(capsys, "run", "puma560", "demo", "--csv", str(out), "--force")
    assert code == 0 and out.read_text().startswith("time,step,move,")


def test_the_start_and_the_rate(capsys):
    code, out, _ = run(capsys, "run", "puma560", "demo", "--from", "qn", "--rate", "10", "--json")
    data = json.loads(out)
    assert code == 0 and data["start"] == [0, 45, -180, 0, 45, 0] and data["rate"] == 10
    assert data["steps"][0]["length"] == 0.0  # already at qn
    code, out, _ = run(capsys, "run", "puma560", "demo", "--from", "-10,45,-170,0,40,0", "--json")
    assert code == 0 and json.loads(out)["start"] == [-10, 45, -170, 0, 40, 0]


def test_the_plot_draws_the_joints_and_the_tool_speed(capsys, problem_robot):
    code, out, err = run(capsys, "run", str(problem_robot), "limit", "--plot")
    assert code == 3 and err == ""
    assert "\x1b[" not in out  # not a terminal: no colour
    assert "joints (deg) against time" in out and "tool speed (mm/s)" in out
    assert "time (s)" in out
    for label in ("Th1", "Th6", "problem"):
        assert label in out


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["run", "puma560"], "the following arguments are required: program"),
        (["run", "nosuchrobot", "demo"], "nosuchrobot"),
        (["run", "puma560", "nosuch"], "no program named 'nosuch' (programs: demo)"),
        (["run", "puma560", "demo", "--rate", "0"], "give 1 to 10000 samples a second"),
        (["run", "puma560", "demo", "--rate", "abc"], "'abc' is not a number"),
        (["run", "puma560", "demo", "--rate", "10", "--rate", "20"], "given more than once"),
        (["run", "puma560", "demo", "--from", "1,2"], "--from"),
        (["run", "puma560", "demo", "--from", "500,0,0,0,0,0"], "outside"),
        (["run", "puma560", "demo", "--from", "nosuchpose"], "--from: item 1"),
        (["run", "puma560", "demo", "--json", "--plot"], "not allowed with argument"),
        (["run", "puma560", "demo", "--csv", "-", "--json"], "can't share it with --json"),
        (["run", "puma560", "demo", "--csv", ""], "the file name is empty"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, argv, words):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert words in err and err.count("\n") == 1, err


def test_the_help_names_the_command(capsys):
    assert "dhsim run ROBOT PROGRAM" in MAIN_HELP
    code, out, _ = run(capsys, "run", "--help")
    assert code == 0 and "exit status 0" in out.lower().replace("\n", " ")


# -- dhsim import --program ------------------------------------------------------------


def test_import_program_reads_a_run_back_into_the_robot_file(capsys, tmp_path):
    trajectory_csv = tmp_path / "tour.csv"
    assert run(capsys, "run", "puma560", "demo", "--csv", str(trajectory_csv))[0] == 0
    out = tmp_path / "puma.toml"
    code, stdout, err = run(
        capsys, "import", "--program", str(trajectory_csv), "puma560", "-o", str(out)
    )
    assert code == 0, err
    assert "program 'tour', 5 steps" in stdout and f"wrote {out}" in stdout
    text = out.read_text(encoding="utf-8")
    assert text.startswith("# Unimation Puma 560")  # the bundled file's comments kept
    robot = load(out)
    assert robot.program_names == ("demo", "tour")
    assert [s.move for s in robot.program("tour").steps] == [
        "joint",
        "joint",
        "wait",
        "joint",
        "joint",
    ]
    code, report, _ = run(capsys, "run", str(out), "tour")
    assert code == 0 and "the path is clean" in report


def test_import_program_prints_the_robot_file_without_o(capsys, tmp_path):
    path = tmp_path / "two.csv"
    path.write_text("time,q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0,0\n9,0,45,-180,0,45,0\n")
    code, out, err = run(capsys, "import", str(path), "puma560", "--program", "--name", "slow")
    assert code == 0 and "program 'slow', 1 step" in err
    assert "slow = [" in out and "[programs]" in out


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["import", "--program", "t.csv"], "name the robot to add it to"),
        (["import", "t.csv", "puma560"], "a second file is read only with --program"),
        (["import", "--program", "t.csv", "puma560", "--tip", "x"], "--tip does not go"),
        (["import", "--program", "t.csv", "puma560", "--name", "demo"], "has a program named"),
        (["import", "--program", "missing.csv", "puma560"], "missing.csv"),
        (["import", "--program", "bad.csv", "puma560"], "no column q6"),
        (["import", "--program", "t.csv", "puma560", "-o", "x.txt"], "ends in .toml"),
    ],
)
def test_import_program_bad_input_is_one_line(capsys, tmp_path, monkeypatch, argv, words):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "t.csv").write_text("q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0\n")
    (tmp_path / "bad.csv").write_text("q1,q2,q3,q4,q5\n0,0,0,0,0\n")
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert words in err and err.count("\n") == 1, err

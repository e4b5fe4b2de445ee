"""A trajectory as CSV (core.motion.trajectory_csv) and back as a program:
every row's x, y, z and o, a, t are the reference's FK at that row's joints,
mu the manipulability of a numerical Jacobian; a CSV read back replays the
program's waypoints in about the same time."""

from __future__ import annotations

import csv
import io
import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import reference_frames

from dhsim_tui.core import load_robot
from dhsim_tui.core.analysis.workspace import length_scale
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.program import MAX_STEPS, Program, Step
from dhsim_tui.core.motion.trajectory import sample
from dhsim_tui.core.motion.trajectory_csv import column_units, csv_text, program_from_csv

#: the OAT reference orientation and R(O, A, T) = Rz(O) R0 Ry(A) Rz(T), from the reference
R0 = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])


def _rz(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def _ry(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def oat_rotation(o, a, t):
    return _rz(o) @ R0 @ _ry(a) @ _rz(t)


def read(text: str) -> tuple[list[str], list[dict]]:
    lines = text.splitlines()
    comments = [line for line in lines if line.startswith("#")]
    rows = list(csv.DictReader(io.StringIO("\n".join(lines[len(comments) :]))))
    return comments, rows


@pytest.fixture(scope="module")
def demo():
    robot, _ = load_robot("puma560")
    return robot, sample(robot, robot.program("demo"))


def test_the_header_row_comes_first_and_names_the_columns(demo):
    robot, trajectory = demo
    text = csv_text(trajectory)
    comments, rows = read(text)
    assert comments == [] and text.startswith("time,step,move,q1,")
    units = column_units(robot)
    assert (units["time"], units["q1"], units["q6"], units["x"]) == ("s", "deg", "deg", "mm")
    assert (units["o"], units["mu"]) == ("deg", None)
    assert (
        list(rows[0])
        == list(units)
        == [
            "time",
            "step",
            "move",
            *(f"q{i}" for i in range(1, 7)),
            *"xyz",
            *"oat",
            "mu",
        ]
    )
    assert len(rows) == len(trajectory.time)
    assert [int(r["step"]) for r in rows] == trajectory.step.tolist()
    assert {r["move"] for r in rows} == {"joint", "linear", "wait"}
    assert [float(r["time"]) for r in rows] == pytest.approx(trajectory.time.tolist(), abs=1e-9)


def test_every_row_is_the_reference_fk_at_its_joints(demo):
    robot, trajectory = demo
    _, rows = read(csv_text(trajectory))
    reach = length_scale(robot)
    for row in rows:
        q = [float(row[f"q{i}"]) for i in range(1, 7)]
        pose = reference_frames(robot, q)[-1]
        xyz = [float(row[k]) for k in "xyz"]
        assert np.allclose(xyz, pose[:3, 3], atol=1e-6 * reach, rtol=0), row["time"]
        rotation = oat_rotation(*(float(row[k]) for k in "oat"))
        assert np.allclose(rotation, pose[:3, :3], atol=1e-9), row["time"]


def numerical_manipulability(robot, q, h=1e-6):
    """sqrt det(J Jᵀ) of the Jacobian by central differences of the reference FK,
    linear rows per reach (revolute joints, per radian)."""
    columns = []
    for i in range(robot.dof):
        step = np.zeros(robot.dof)
        step[i] = math.degrees(h)
        ahead = reference_frames(robot, np.array(q) + step)[-1]
        behind = reference_frames(robot, np.array(q) - step)[-1]
        linear = (ahead[:3, 3] - behind[:3, 3]) / (2 * h) / length_scale(robot)
        turn = ahead[:3, :3] @ behind[:3, :3].T
        angular = np.array(
            [turn[2, 1] - turn[1, 2], turn[0, 2] - turn[2, 0], turn[1, 0] - turn[0, 1]]
        )
        columns.append(np.concatenate([linear, angular / 2 / (2 * h)]))
    jac = np.array(columns).T
    return math.sqrt(max(np.linalg.det(jac @ jac.T), 0.0))


def test_mu_is_the_manipulability(demo):
    robot, trajectory = demo
    _, rows = read(csv_text(trajectory))
    for row in rows[::60]:
        q = [float(row[f"q{i}"]) for i in range(1, 7)]
        assert float(row["mu"]) == pytest.approx(numerical_manipulability(robot, q), abs=1e-7)


def test_a_csv_read_back_replays_the_waypoints_in_about_the_same_time(demo):
    robot, trajectory = demo
    program = program_from_csv(robot, csv_text(trajectory), "replay", "demo.csv")
    assert program.name == "replay"
    assert [s.move for s in program.steps] == ["joint", "joint", "wait", "joint", "joint"]
    again = sample(replace(robot, programs=(program,)), program)
    for original, replayed in zip(trajectory.spans, again.spans, strict=True):
        # a move's end lies between two rows: its target is the last row before
        # it (a fraction of a degree off, the arm slowing to rest), or exact
        # when a wait follows
        assert np.allclose(original.q_end, replayed.q_end, atol=0.05)
        assert replayed.duration == pytest.approx(original.duration, abs=0.02)
    assert program.steps[1].to == pytest.approx(trajectory.spans[1].q_end, abs=1e-6)
    assert program.steps[2].seconds == pytest.approx(0.5, abs=0.011)


def test_without_a_step_column_every_row_is_a_waypoint(puma):
    text = (
        "time,q1,q2,q3,q4,q5,q6\n"
        "0,0,0,0,0,0,0\n"
        "5,0,45,-90,0,45,0\n"
        "7,0,45,-90,0,45,0\n"
        "8,0,45,-180,0,45,0\n"
    )
    program = program_from_csv(puma, text, "by-hand")
    first, wait, last = program.steps
    assert first.move == "joint" and first.to == (0, 45, -90, 0, 45, 0)
    # the speed that takes 5 s: 90 deg at 90 deg/s x p %, reached at 360 deg/s²
    top = 0.9 * first.speed
    assert 90 / top + top / 360 == pytest.approx(5.0, abs=0.01)
    assert wait == Step("wait", seconds=2.0)
    # 90 deg in a second is beyond 100 %: the default, as fast as it goes
    assert last == Step("joint", (0, 45, -180, 0, 45, 0))
    # without a time column: the default speed
    no_time = program_from_csv(puma, "q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0\n0,10,0,0,0,0\n", "x")
    assert no_time.steps == (Step("joint", (0, 10, 0, 0, 0, 0)),)


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("", "no header row"),
        ("# only a comment\n", "no header row"),
        ("time,q1,q2,q3,q4,q5\n0,0,0,0,0,0\n", "no column q6"),
        ("q1,q2,q3,q4,q5,q6,q7\n0,0,0,0,0,0,0\n", "column q7, but the robot has 6 joints"),
        ("q1,q2,q3,q4,q5,q6\n", "no rows after the header"),
        ("q1,q2,q3,q4,q5,q6\n0,0,abc,0,0,0\n", "row 2, q3: 'abc' is not a number"),
        ("q1,q2,q3,q4,q5,q6\n0,0,nan,0,0,0\n", "row 2, q3: not a finite number"),
        ("q1,q2,q3,q4,q5,q6\n0,0,0\n", "row 2: no value for q4"),
        ("q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0\n170,0,0,0,0,0\n", "row 3: Th1 = 170 deg is outside"),
        ("# units: time s, q1 mm\nq1,q2,q3,q4,q5,q6\n0,0,0,0,0,0\n", "q1 is in mm in the file"),
    ],
)
def test_a_csv_that_does_not_fit_is_one_sentence(puma, text, words):
    with pytest.raises(DhsimError) as raised:
        program_from_csv(puma, text, "x", "t.csv")
    message = str(raised.value)
    assert message.startswith("t.csv") and words in message and "\n" not in message


def test_too_many_waypoints_are_refused(puma):
    rows = "".join(f"{i * 0.01:.2f},0,{i % 2},0,0,0\n" for i in range(MAX_STEPS + 2))
    with pytest.raises(DhsimError, match="every tenth"):
        program_from_csv(puma, "q1,q2,q3,q4,q5,q6\n" + rows, "x", "t.csv")


def test_an_empty_program_round_trips(puma):
    trajectory = sample(puma, Program("nothing"), start=(0, 45, -180, 0, 45, 0))
    program = program_from_csv(puma, csv_text(trajectory), "nothing")
    assert program.steps == ()

"""The path check (core.motion.path_check): each kind of problem is found on a
program made to have it, with its step, time and joint or frame, and none on
the bundled demo; a clean check means no sample is faster than a joint's top
speed (finite differences here); random programs on random robots never
crash the runner."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from conftest import reference_frames
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from robot_strategies import robots

from dhsim_tui.core.analysis.workspace import length_scale
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.program import Program, Step, top_speed
from dhsim_tui.core.model.robot import Tool
from dhsim_tui.core.motion.path_check import (
    FLOOR,
    JUMP,
    KINDS,
    LIMIT,
    REACH,
    SINGULAR,
    SPEED,
    check_path,
    runs,
)
from dhsim_tui.core.motion.trajectory import sample


def problems_of(robot, *steps, start=None, rate=100.0):
    program = Program("p", tuple(steps))
    trajectory = sample(replace(robot, programs=(program,)), program, rate, start)
    return trajectory, check_path(trajectory)


def only(problems, kind):
    return [p for p in problems if p.kind == kind]


def assert_placed(trajectory, problems):
    """Every problem's step is the one its times are in, in time order."""
    assert [p.time for p in problems] == sorted(p.time for p in problems)
    for problem in problems:
        assert problem.kind in KINDS and problem.detail
        assert problem.time <= problem.until
        if not trajectory.spans:  # no steps: the start pose alone, "step 0"
            assert problem.step == 0 and problem.time == problem.until == 0.0
            continue
        span = trajectory.spans[problem.step - 1]
        # (the last sample, at the first k / rate not before the end, is the last step's)
        end = trajectory.time[-1] if span is trajectory.spans[-1] else span.end
        assert span.start - 1e-9 <= problem.time <= problem.until <= end + 1e-9


def speeds_within_limits(trajectory) -> bool:
    """Finite differences of the samples, against each joint's top speed."""
    robot = trajectory.robot
    dt = np.diff(trajectory.time)[:, None]
    speed = np.abs(np.diff(trajectory.q, axis=0)) / dt
    tops = np.array([top_speed(j, robot.units) for j in robot.joints])
    return bool(np.all(speed <= tops * (1 + 1e-6)))


def test_the_demo_is_clean_and_within_the_speeds(puma):
    trajectory = sample(puma, puma.program("demo"))
    assert check_path(trajectory) == ()
    assert speeds_within_limits(trajectory)
    assert not trajectory.failures
    assert len(trajectory.spans) == len(puma.program("demo").steps)


def test_a_joint_at_its_limit(puma):
    trajectory, problems = problems_of(
        puma, Step("joint", (160, 0, 0, 0, 0, 0)), Step("wait", seconds=0.2)
    )
    found = only(problems, LIMIT)
    # the move reaches the limit at its end, between samples; the wait sits on it
    wait = trajectory.spans[1]
    on_it = trajectory.time[trajectory.time >= wait.start]
    assert [(p.step, p.subject, p.time, p.until) for p in found] == [
        (2, "Th1", on_it[0], on_it[-1])
    ]
    assert "Th1 at its upper limit 160 deg" in found[0].detail
    assert_placed(trajectory, problems)


def test_a_joint_faster_than_its_top_speed(puma):
    # near the straight elbow a slow tool needs a fast elbow
    trajectory, problems = problems_of(
        puma, Step("linear", "qn", speed=100.0), start=(0, 45, -90, 0, 45, 0)
    )
    found = only(problems, SPEED)
    assert [(p.step, p.subject) for p in found] == [(1, "Th3")]
    # the Puma has no vmax: the message says the 90 deg/s is the default
    assert "over the default top speed 90 deg/s (no vmax)" in found[0].detail
    assert not speeds_within_limits(trajectory)
    dt = np.diff(trajectory.time)
    fast = np.abs(np.diff(trajectory.q[:, 2])) / dt > 90.0
    first = trajectory.time[1:][fast][0]
    assert found[0].time == first
    assert_placed(trajectory, problems)


def test_a_speed_problem_names_a_given_top_speed_as_the_robots(puma):
    joints = list(puma.joints)
    joints[2] = replace(joints[2], vmax=60.0)
    faster = replace(puma, joints=tuple(joints))
    _, problems = problems_of(
        faster, Step("linear", "qn", speed=100.0), start=(0, 45, -90, 0, 45, 0)
    )
    (found,) = only(problems, SPEED)
    assert "over its top speed 60 deg/s" in found.detail
    assert "default" not in found.detail and "vmax" not in found.detail


def test_each_problem_names_its_subject_once_and_its_kind_once(puma):
    """The status line shows ``message``, ``dhsim run`` ``kind: detail``:
    neither says "Th3 Th3" or "singular: singular"."""
    _, problems = problems_of(
        puma,
        Step("linear", "qn", speed=100.0),
        Step("joint", (160, 45, -150, 0, 0, 0)),
        Step("wait", seconds=0.1),
        Step("linear", (160, 40, -140, 0, 0, 0)),
        start=(0, 45, -90, 0, 45, 0),
    )
    assert {p.kind for p in problems} >= {LIMIT, SPEED, SINGULAR}
    for problem in problems:
        assert problem.message.count(problem.subject) <= 1 or problem.subject == "tool"
        assert not problem.message.startswith(f"{problem.subject} {problem.subject}")
        assert f"{problem.kind}: {problem.kind}" not in f"{problem.kind}: {problem.detail}"
        if problem.kind != SINGULAR:
            assert problem.message == problem.detail
            assert problem.message.startswith(problem.subject)
    speed = only(problems, SPEED)[0]
    assert speed.message.startswith(f"{speed.subject} at ") and " deg/s, over " in speed.message
    singular = only(problems, SINGULAR)[0]
    assert singular.message.startswith("singular in a linear move, manipulability ")
    assert singular.detail.startswith("in a linear move")


def test_a_linear_move_that_leaves_the_reachable_space(puma):
    trajectory, problems = problems_of(
        puma, Step("joint", "qn"), Step("linear", (150, 45, -180, 0, 45, 0))
    )
    found = only(problems, REACH)
    assert len(found) == 1 and found[0].step == 2 and found[0].subject == "tool"
    assert "reachable" in found[0].detail and "Th3" in found[0].detail
    assert found[0].until == trajectory.spans[1].end
    assert_placed(trajectory, problems)


def test_a_linear_move_that_cannot_go_on_without_a_jump(puma):
    # the approach vector passes close by the wrist's singular direction: Th4
    # and Th6 would flip together (the larger swing is named)
    trajectory, problems = problems_of(
        puma, Step("joint", (0, 30, -150, 89, 20, -89)), Step("linear", (0, 30, -150, -89, 20, 89))
    )
    found = only(problems, JUMP)
    assert len(found) == 1 and found[0].step == 2 and found[0].subject in ("Th4", "Th6")
    assert "jumping" in found[0].detail
    failure = trajectory.failures[0]
    held = trajectory.q[trajectory.time >= failure.time]
    assert np.all(held == held[0])  # the arm stops there
    assert_placed(trajectory, problems)


def test_a_singularity_in_a_linear_move(puma):
    # the wrist straight (Th5 = 0) all along the line
    trajectory, problems = problems_of(
        puma, Step("joint", (0, 45, -150, 0, 0, 0)), Step("linear", (0, 40, -140, 0, 0, 0))
    )
    found = only(problems, SINGULAR)
    assert [(p.step, p.subject) for p in found] == [(2, "arm")]
    assert "below 0.001" in found[0].detail
    assert_placed(trajectory, problems)


def test_a_singular_pose_in_a_joint_move_is_no_problem(puma):
    # home has the wrist straight; a joint move through it is harmless
    _, problems = problems_of(puma, Step("joint", "qn"), Step("joint", "qz"))
    assert not only(problems, SINGULAR)


def frame_z(robot, q):
    return reference_frames(robot, q)[:, 2, 3]


def test_frames_below_the_floor(puma):
    # the forearm hanging down reaches 431.8 mm below the shoulder: under a
    # floor level with it, not under the pedestal's floor 671.83 mm down
    down = (0, 0, -180, 0, 45, 0)
    _, problems = problems_of(puma, Step("joint", down))
    assert not only(problems, FLOOR)
    floored = replace(puma, base_height=0.0, tool=Tool((0.0, 0.0, 50.0)))
    trajectory, problems = problems_of(floored, Step("joint", down))
    found = only(problems, FLOOR)
    # frames 0..6 and the tool at every sample, by the reference
    heights = np.array([frame_z(floored, q) for q in trajectory.q])
    names = [f"frame {i}" for i in range(7)] + ["tool"]
    tolerance = 1e-6 * length_scale(floored)
    under = [
        name for name, column in zip(names, heights.T, strict=True) if column.min() < -tolerance
    ]
    assert {"frame 3", "frame 6", "tool"} <= set(under)
    assert sorted(p.subject for p in found) == sorted(under)
    tool = next(p for p in found if p.subject == "tool")
    assert f"{-heights[:, -1].min():.2f} mm below the floor" in tool.detail
    below = np.flatnonzero(heights[:, -1] < -tolerance)
    assert (tool.time, tool.until) == (trajectory.time[below[0]], trajectory.time[below[-1]])
    assert_placed(trajectory, problems)


def test_runs_break_at_gaps_and_at_steps():
    mask = np.array([0, 1, 1, 0, 1, 1, 1, 1], dtype=bool)
    step = np.array([1, 1, 1, 1, 1, 1, 2, 2])
    assert runs(mask, step) == [(1, 2), (4, 5), (6, 7)]
    assert runs(np.zeros(3, dtype=bool), np.ones(3)) == []


# -- random programs on random robots -------------------------------------------------


@st.composite
def programs(draw):
    """A robot with top speeds that keep moves short, a program of up to four
    steps to targets within its limits, a rate and a start."""
    robot = draw(robots(max_joints=4))
    joints = tuple(replace(j, vmax=j.max - j.min, amax=4 * (j.max - j.min)) for j in robot.joints)
    robot = replace(robot, joints=joints)

    def within():
        return tuple(j.min + draw(st.floats(0, 1)) * (j.max - j.min) for j in robot.joints)

    steps = []
    for _ in range(draw(st.integers(0, 4))):
        kind = draw(st.sampled_from(["joint", "linear", "wait"]))
        if kind == "wait":
            steps.append(Step("wait", seconds=draw(st.floats(0, 0.5))))
        elif kind == "joint":
            steps.append(Step("joint", within(), speed=draw(st.floats(1, 100))))
        else:
            speed = length_scale(robot) * draw(st.floats(0.2, 2))
            steps.append(Step("linear", within(), speed=speed))
    program = Program("random", tuple(steps))
    return replace(robot, programs=(program,)), program, draw(st.floats(10, 100)), within()


@settings(
    max_examples=60,
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(programs())
def test_random_programs_on_random_robots_never_crash_the_runner(case):
    robot, program, rate, start = case
    try:
        trajectory = sample(robot, program, rate, start)
    except DhsimError:
        return  # refused in one sentence (too long to sample): fine
    problems = check_path(trajectory)
    count = len(trajectory.time)
    assert trajectory.q.shape == (count, robot.dof) and trajectory.pose.shape == (count, 4, 4)
    assert np.all(np.isfinite(trajectory.q)) and np.all(np.isfinite(trajectory.pose))
    low, high = np.array(robot.lower), np.array(robot.upper)
    assert np.all(trajectory.q >= low) and np.all(trajectory.q <= high)
    assert_placed(trajectory, problems)
    if not only(problems, SPEED):
        assert speeds_within_limits(trajectory)
    assert not only(problems, LIMIT) or any(
        np.any(trajectory.q[:, i] <= j.min + 1e-9) or np.any(trajectory.q[:, i] >= j.max - 1e-9)
        for i, j in enumerate(robot.joints)
    )

"""Programs sampled as a controller would (core.motion.trajectory), checked
from outside: the tool poses by the reference's own FK (tests/conftest.py),
speeds and accelerations by finite differences, the line and the rotation
by plain geometry."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import reference_frames

from dhsim_tui.core.analysis.workspace import length_scale
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.profiles import LINEAR_ACCELERATION_MM
from dhsim_tui.core.model.program import Program, Step, top_acceleration, top_speed
from dhsim_tui.core.motion.trajectory import MAX_SAMPLES, REACH, sample

QN = (0.0, 45.0, -180.0, 0.0, 45.0, 0.0)


def played(robot, *steps, rate=100.0, start=None):
    program = Program("p", tuple(steps))
    return sample(replace(robot, programs=(program,)), program, rate, start)


def spans_of(trajectory, move):
    for span in trajectory.spans:
        picked = np.flatnonzero(trajectory.step == span.number)
        if span.move == move and len(picked) > 2:
            yield span, picked


# -- the samples ---------------------------------------------------------------------


def test_samples_are_k_over_rate_and_end_at_the_program_end(puma):
    trajectory = played(puma, Step("joint", "qn"), Step("wait", seconds=0.333), rate=50.0)
    duration = trajectory.duration
    k = np.round(trajectory.time * 50.0).astype(int)
    assert np.array_equal(trajectory.time, k / 50.0)  # on the rate's grid
    last = math.ceil(duration * 50.0 - 1e-6)
    assert k[-1] == last and duration <= trajectory.time[-1] < duration + 1 / 50.0
    assert tuple(trajectory.q[-1]) == QN
    assert list(np.unique(trajectory.step)) == [1, 2]
    assert np.all(np.diff(trajectory.step) >= 0)
    # each sample in the step whose time it is (the last: the program's end)
    for time, number in zip(trajectory.time[:-1], trajectory.step[:-1], strict=True):
        span = trajectory.spans[number - 1]
        assert span.start <= time < span.end
    # the move has every grid point; the wait only its first and last, then the end
    move, wait = trajectory.spans
    in_move = [i for i in range(last + 1) if i / 50.0 < move.end]
    in_wait = [i for i in range(last) if move.end <= i / 50.0 < wait.end]
    assert list(k) == [*in_move, in_wait[0], in_wait[-1], last]


def test_a_wait_costs_no_samples_beyond_its_ends(puma):
    trajectory = played(puma, Step("wait", seconds=3590.0), Step("joint", "qn"), rate=100.0)
    wait, _ = trajectory.spans
    in_wait = trajectory.time[trajectory.step == 1]
    assert list(in_wait) == [0.0, math.ceil(wait.end * 100 - 1e-9) / 100 - 0.01]
    in_move = np.round(trajectory.time[trajectory.step == 2] * 100).astype(int)
    assert np.array_equal(in_move, np.arange(in_move[0], in_move[-1] + 1))
    assert len(trajectory.time) == 2 + len(in_move)
    assert np.all(trajectory.q[:2] == trajectory.q[0])  # the wait holds the start


def test_every_pose_is_the_reference_fk_at_its_joints(puma):
    trajectory = played(puma, Step("joint", "qn"), Step("linear", (0, 45, -135, 0, 45, 0)))
    for i in range(0, len(trajectory.time), 7):
        expected = reference_frames(puma, trajectory.q[i])[-1]
        assert np.allclose(trajectory.pose[i], expected, atol=1e-9 * length_scale(puma))


def test_a_wait_holds_the_pose(puma):
    trajectory = played(puma, Step("joint", "qn"), Step("wait", seconds=0.5))
    held = trajectory.q[trajectory.step == 2]
    assert len(held) == 3  # its first and last grid point (it holds between), the end
    assert np.all(held == np.array(QN))
    wait = trajectory.spans[1]
    times = trajectory.time[trajectory.step == 2][:2]
    assert times[0] - 0.01 < wait.start <= times[0] and times[1] < wait.end <= times[1] + 0.01


def test_a_program_without_steps_is_its_start(puma):
    trajectory = sample(puma, Program("empty"), start=QN)
    assert trajectory.duration == 0.0 and len(trajectory.time) == 1
    assert tuple(trajectory.q[0]) == QN and trajectory.step[0] == 0


def test_a_move_to_where_the_arm_is_takes_no_time(puma):
    trajectory = played(puma, Step("joint", "qn"), Step("joint", "qn"), Step("wait", seconds=0.1))
    assert trajectory.spans[1].duration == 0.0
    assert 2 not in set(trajectory.step.tolist())
    assert trajectory.spans[2].start == trajectory.spans[0].end


def test_bad_rates_starts_and_lengths_are_refused(puma):
    for rate in (0.0, -5.0, 0.5, 1e6, float("nan")):
        with pytest.raises(DhsimError, match="rate"):
            played(puma, Step("wait", seconds=1.0), rate=rate)
    with pytest.raises(DhsimError, match="outside"):
        played(puma, Step("wait", seconds=1.0), start=(500, 0, 0, 0, 0, 0))
    # over an hour: the robot itself refuses the program, naming the step
    with pytest.raises(DhsimError, match=r"step 2: the wait takes 3600 s, .* at most 3600 s"):
        played(puma, Step("wait", seconds=3600.0), Step("wait", seconds=3600.0))
    # an hour at 1 kHz: refused before any sample is made
    with pytest.raises(DhsimError, match=f"at most {MAX_SAMPLES // 1000} s .*lower the rate"):
        played(puma, Step("wait", seconds=3600.0), rate=1000.0)


# -- joint moves ---------------------------------------------------------------------


def joint_limits(robot, percent):
    share = (percent if percent is not None else 100.0) / 100.0
    speeds = np.array([top_speed(j, robot.units) * share for j in robot.joints])
    accelerations = np.array([top_acceleration(j, robot.units) for j in robot.joints])
    return speeds, accelerations


@pytest.mark.parametrize("percent", [None, 50.0, 7.5])
def test_joint_moves_start_and_stop_every_joint_together(puma, percent):
    goal = (30.0, 60.0, -150.0, 100.0, -20.0, 200.0)
    trajectory = played(puma, Step("joint", "qn"), Step("joint", goal, speed=percent))
    for span, picked in spans_of(trajectory, "joint"):
        start, end = np.array(span.q_start), np.array(span.q_end)
        moving = np.flatnonzero(start != end)
        progress = (trajectory.q[picked][:, moving] - start[moving]) / (end - start)[moving]
        # one shared progress: every joint is the same share of its way at each sample
        assert np.ptp(progress, axis=1).max() < 1e-9
        share = progress[:, 0]
        # ... which leaves 0 at the step's start and reaches 1 only at its end
        started = trajectory.time[picked] > span.start
        assert np.all(share[started] > 0) and np.all(share[~started] == 0)
        arrived = trajectory.time[picked] >= span.end
        assert np.all(share[~arrived] < 1)
        assert np.all(np.diff(share) >= 0)


def shortest(distance: float, speed: float, acceleration: float) -> float:
    """The least time to go ``distance`` from rest to rest (textbook bang-coast-bang)."""
    if distance >= speed * speed / acceleration:
        return distance / speed + speed / acceleration
    return 2 * math.sqrt(distance / acceleration)


@pytest.mark.parametrize("percent", [None, 50.0, 7.5])
def test_joint_moves_keep_the_speed_and_acceleration_limits(puma, percent):
    goal = (30.0, 60.0, -150.0, 100.0, -20.0, 200.0)
    trajectory = played(puma, Step("joint", goal, speed=percent), rate=1000.0)
    speeds, accelerations = joint_limits(puma, percent)
    dt = 1 / 1000.0
    velocity = np.diff(trajectory.q, axis=0) / dt
    assert np.all(np.abs(velocity) <= speeds * (1 + 1e-9))
    acceleration = np.diff(trajectory.q, n=2, axis=0) / dt**2
    assert np.all(np.abs(acceleration) <= accelerations * (1 + 1e-6) + 1e-6)
    # the pace is set by the slowest joint (the Puma's all have the same limits)
    distance = np.abs(np.array(goal) - np.array(puma.home))
    alone = [shortest(d, v, a) for d, v, a in zip(distance, speeds, accelerations, strict=True)]
    assert trajectory.duration == pytest.approx(max(alone), rel=1e-9)
    # and that joint runs at its top speed (or its top acceleration all the way)
    slowest = int(np.argmax(alone))
    peak = np.abs(velocity[:, slowest]).max()
    assert peak == pytest.approx(
        min(speeds[slowest], math.sqrt(distance[slowest] * accelerations[slowest])), rel=2e-3
    )


def test_joint_moves_use_the_joints_own_top_speeds(puma):
    slow = tuple(replace(j, vmax=10.0, amax=20.0) for j in puma.joints)
    robot = replace(puma, joints=slow)
    trajectory = played(robot, Step("joint", (0, 45, 0, 0, 0, 0)))
    # 45 deg at 10 deg/s, 0.5 s to reach it at 20 deg/s²: 4.5 s + 0.5 s
    assert trajectory.duration == pytest.approx(5.0)


# -- linear moves --------------------------------------------------------------------


def rotation_vector(r: np.ndarray) -> np.ndarray:
    """The rotation vector of a rotation matrix (angle below pi), by the textbook formula."""
    angle = math.acos(max(-1.0, min(1.0, (np.trace(r) - 1) / 2)))
    if angle < 1e-12:
        return np.zeros(3)
    axis = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    return axis / (2 * math.sin(angle)) * angle


LINEAR = (
    Step("joint", "qn"),
    Step("linear", (0, 45, -135, 0, 45, 0), speed=150.0),
    Step("linear", (-30, 40, -150, 0, 50, 0)),
    Step("linear", (20, 50, -160, 30, 40, -30), speed=400.0),
)


@pytest.mark.parametrize("rate", [100.0, 250.0, 7.0])
def test_linear_moves_stay_on_their_line_and_turn_on_the_shortest_rotation(puma, rate):
    trajectory = played(puma, *LINEAR, rate=rate)
    assert not trajectory.failures
    reach = length_scale(puma)
    for span, picked in spans_of(trajectory, "linear"):
        first = reference_frames(puma, span.q_start)[-1]
        last = reference_frames(puma, span.step.to)[-1]
        line = last[:3, 3] - first[:3, 3]
        turn = rotation_vector(last[:3, :3] @ first[:3, :3].T)
        assert np.linalg.norm(turn) < math.pi
        shares = []
        for i in picked:
            pose = reference_frames(puma, trajectory.q[i])[-1]
            offset = pose[:3, 3] - first[:3, 3]
            share = float(offset @ line / (line @ line))
            off_line = np.linalg.norm(offset - share * line)
            assert off_line <= 1e-6 * reach, (span.number, i, off_line)
            # the rotation so far is the same share of the whole turn, about its axis
            so_far = rotation_vector(pose[:3, :3] @ first[:3, :3].T)
            assert np.allclose(so_far, share * turn, atol=2e-6), (span.number, i)
            shares.append(share)
        assert shares[0] >= -1e-9 and np.all(np.diff(shares) >= -1e-9)


def test_linear_moves_keep_the_tool_speed_and_start_and_end_at_rest(puma):
    trajectory = played(puma, *LINEAR)
    dt = 0.01
    slack = 2 * 1e-6 * length_scale(puma) / dt  # the IK's tolerance, twice, over a sample
    for span, picked in spans_of(trajectory, "linear"):
        speed = span.step.speed or 250.0
        times = trajectory.time[picked]
        points = np.array([reference_frames(puma, trajectory.q[i])[-1][:3, 3] for i in picked])
        steps = np.linalg.norm(np.diff(points, axis=0), axis=1) / dt
        assert steps.max() <= speed * 1.001 + slack
        # from rest and back to rest, no faster than the acceleration allows
        assert steps[0] <= LINEAR_ACCELERATION_MM * (times[1] - span.start) + slack
        assert steps[-1] <= LINEAR_ACCELERATION_MM * (span.end - times[-2]) + slack


def test_linear_moves_never_change_branch(puma):
    trajectory = played(puma, *LINEAR)
    jumps = np.abs(np.diff(trajectory.q, axis=0)).max()
    assert jumps < 3.0  # degrees between samples 10 ms apart


def test_a_slow_rate_solves_in_between_and_ends_where_a_fast_one_does(puma):
    fast = played(puma, *LINEAR, rate=100.0)
    slow = played(puma, *LINEAR, rate=2.0)
    for a, b in zip(fast.spans, slow.spans, strict=True):
        assert a.duration == b.duration
        assert np.allclose(a.q_end, b.q_end, atol=1e-6)


def test_a_failed_linear_move_holds_and_the_next_step_starts_there(puma):
    # the straight line from one side to the other would need Th3 past its limit
    trajectory = played(
        puma, Step("joint", "qn"), Step("linear", (150, 45, -180, 0, 45, 0)), Step("joint", "qn")
    )
    assert len(trajectory.failures) == 1
    failure = trajectory.failures[0]
    assert failure.step == 2 and failure.kind == REACH and "limit" in failure.reason
    span = trajectory.spans[1]
    assert span.start < failure.time < span.end
    after = trajectory.q[(trajectory.step == 2) & (trajectory.time >= failure.time)]
    assert len(after) > 1 and np.all(after == after[0])
    assert trajectory.spans[2].q_start == span.q_end == tuple(after[0])
    assert tuple(trajectory.q[-1]) == QN

"""A program sampled a piece at a time (core.motion.trajectory.Sampling): the
pieces add up to the whole, the first samples come before the rest is
solved, and a long program never holds more than its samples."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.motion import trajectory as trajectory_module
from dhsim_tui.core.motion.path_check import check_path
from dhsim_tui.core.motion.playback import Playback
from dhsim_tui.core.motion.trajectory import CHUNK, Sampling, sample

QN = (0.0, 45.0, -180.0, 0.0, 45.0, 0.0)


@pytest.fixture(scope="module")
def puma():
    return load_robot("puma560")[0]


def demo(puma) -> Program:
    return puma.program("demo")


def test_the_pieces_add_up_to_the_whole_program(puma):
    whole = sample(puma, demo(puma))
    sampling = Sampling(puma, demo(puma))
    progress, seen = [sampling.progress], 0
    while sampling.advance():
        part = sampling.trajectory()
        assert not part.complete and part.ready == sampling.ready
        n = len(part.time)
        assert n >= seen  # it only grows, and is the start of the whole
        assert np.array_equal(part.time, whole.time[:n])
        assert np.array_equal(part.q, whole.q[:n]) and np.array_equal(part.pose, whole.pose[:n])
        seen = n
        progress.append(sampling.progress)
    assert progress == sorted(progress) and progress[0] == 0.0 and sampling.progress == 1.0
    done = sampling.trajectory()
    assert done.complete and done.ready == done.duration == whole.duration
    for name in ("time", "step", "move", "q", "pose"):
        assert np.array_equal(getattr(done, name), getattr(whole, name)), name
    assert check_path(done) == check_path(whole)


def test_a_long_linear_move_gives_its_first_samples_after_one_chunk_of_solves(puma, monkeypatch):
    solves = []
    real = trajectory_module.inverse

    def counted(*args, **kwargs):
        solves.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(trajectory_module, "inverse", counted)
    slow = Program("slow", (Step("linear", (0, 45, -135, 0, 45, 0), speed=2.0),))
    sampling = Sampling(puma, slow, start=QN)  # about 165 s: 16,500 solves
    assert sampling.planned > 100
    while not len(sampling.trajectory().time):
        assert sampling.advance()
    assert 0 < len(solves) <= CHUNK
    first = sampling.trajectory()
    assert 0 < first.ready < sampling.planned and not first.complete
    # played so far, it holds at the last sample made, never at the move's end
    playback = Playback(first, ())
    assert not playback.done
    assert playback.at(sampling.planned) == tuple(first.q[-1])


def test_a_wait_of_an_hour_costs_three_samples(puma):
    hour = Program("hour", (Step("wait", seconds=3600.0),))
    trajectory = sample(puma, hour, start=QN)
    assert len(trajectory.time) == 3 and trajectory.duration == 3600.0
    assert list(trajectory.time) == [0.0, 3599.99, 3600.0]
    assert Playback(trajectory, ()).at(1800.0) == QN


def test_a_long_program_is_checked_in_no_more_memory_than_its_samples(puma):
    # a joint move of nearly an hour at 100 Hz: 330,000 samples; its arrays are
    # the trajectory's, and the check needs only a share of them on top (it
    # once held one 4x4 per frame and sample: 8 times the trajectory)
    slow = Program("slow", (Step("joint", (90, 0, -90, 0, 0, 0), speed=0.03),))
    tracemalloc.start()
    try:
        trajectory = sample(puma, slow, start=QN)
        held, peak = tracemalloc.get_traced_memory()
        size = (
            sum(a.nbytes for a in (trajectory.time, trajectory.step, trajectory.move, trajectory.q))
            + trajectory.pose.nbytes
        )
        assert len(trajectory.time) > 300_000
        assert peak < 1.5 * size  # sampling: the samples and chunks of work
        tracemalloc.reset_peak()
        check_path(trajectory)
        _, peak = tracemalloc.get_traced_memory()
        assert peak - held < 0.5 * size
    finally:
        tracemalloc.stop()


def test_step_texts_have_no_negative_zero_or_float_noise():
    step = Step("joint", (10.000000000000002, -0.0, -90.0, 431.8, 1e-12, 2.0), speed=49.99999999)
    assert step.describe() == "joint to [10, 0, -90, 431.8, 0, 2] at 50%"
    assert Step("wait", seconds=0.30000000000000004).describe() == "wait 0.3 s"

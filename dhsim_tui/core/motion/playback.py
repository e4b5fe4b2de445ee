"""Playing a sampled program (:mod:`.trajectory`) in real time: where the arm
is at a time, the steps' starts to seek to and the next problem.

The simulator keeps a :class:`Playback` and a clock; at each frame it asks
:meth:`Playback.at` for the joints. Between two samples the joints are
interpolated linearly (samples are 1/rate apart, far closer than a frame).
"""

from __future__ import annotations

import numpy as np

from dhsim_tui.core.motion.path_check import Problem
from dhsim_tui.core.motion.trajectory import Trajectory


class Playback:
    """A trajectory, its problems, and the time played so far."""

    def __init__(self, trajectory: Trajectory, problems: tuple[Problem, ...]) -> None:
        self.trajectory = trajectory
        self.problems = problems
        self.time = 0.0

    @property
    def duration(self) -> float:
        return self.trajectory.duration

    @property
    def done(self) -> bool:
        return self.trajectory.complete and self.time >= self.duration

    @property
    def ready(self) -> float:
        """How far it can play (s): the samples made so far."""
        return self.trajectory.ready

    def at(self, time: float) -> tuple[float, ...]:
        """The joints at ``time`` (clamped to the trajectory), interpolated
        between the samples around it."""
        times = self.trajectory.time
        q = self.trajectory.q
        spans = self.trajectory.spans
        # (a failed move holds where it stopped; a program still being sampled ends later)
        ended = spans and self.trajectory.complete and not self.trajectory.failures
        if ended and time >= self.duration:  # the end, exactly (past the last sample)
            return tuple(float(v) for v in spans[-1].q_end)
        if len(times) == 0:
            return ()
        t = min(max(time, float(times[0])), float(times[-1]))
        after = int(np.searchsorted(times, t, side="left"))
        if after <= 0:
            return tuple(float(v) for v in q[0])
        before = after - 1
        span = float(times[after] - times[before])
        share = 0.0 if span <= 0 else (t - float(times[before])) / span
        return tuple(float(v) for v in q[before] + (q[after] - q[before]) * share)

    def step_at(self, time: float) -> int:
        """The step (1-based) playing at ``time``; 0 when there is none."""
        for span in self.trajectory.spans:
            if span.start <= time < span.end:
                return span.number
        return self.trajectory.spans[-1].number if self.trajectory.spans else 0

    def seek_step(self, steps: int) -> float:
        """The start of the step ``steps`` before (< 0) or after the one
        playing (the end after the last); the time played becomes it."""
        spans = self.trajectory.spans
        if not spans:
            return self.time
        starts = [span.start for span in spans] + [self.duration]
        current = max(i for i, start in enumerate(starts[:-1]) if start <= self.time + 1e-9)
        index = min(max(current + steps, 0), len(starts) - 1)
        self.time = starts[index]
        return self.time

    def next_problem(self) -> Problem | None:
        """The first problem after the time played (wrapping to the first);
        the time played becomes its start."""
        if not self.problems:
            return None
        later = [p for p in self.problems if p.time > self.time + 1e-9]
        problem = later[0] if later else self.problems[0]
        self.time = problem.time
        return problem

    def problems_per_step(self) -> dict[int, int]:
        marks: dict[int, int] = {}
        for problem in self.problems:
            marks[problem.step] = marks.get(problem.step, 0) + 1
        return marks

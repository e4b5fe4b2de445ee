"""A program played as a controller would: its samples in time.

:func:`sample` turns a :class:`~dhsim_tui.core.model.program.Program` into a
:class:`Trajectory`: at ``rate`` samples a second (times ``k / rate``), the
step each sample is in, its move, the joints and the tool's pose.

- A **joint move** interpolates the joints along one trapezoidal profile
  (:func:`~dhsim_tui.core.model.profiles.joint_profile`): every joint
  starts and stops together, none faster than its top speed times the move's
  percentage or its top acceleration.
- A **linear move** takes the tool point along the straight line to the
  target pose's tool point on a trapezoidal profile in path length (the
  step's speed, :data:`~dhsim_tui.core.model.profiles.LINEAR_ACCELERATION_MM`)
  and turns it on the shortest rotation (a rotation vector scaled along the
  path: the same as slerp). The joints come from IK at every sample, the
  solution nearest the previous sample's joints
  (:func:`dhsim_tui.core.ik.nearest.inverse`: the closed form where the arm
  has one, else the numerical solver started there), so the arm never
  changes branch; at a rate below :data:`IK_RATE` it is solved at that rate in
  between as well. When IK fails, or a joint would jump (a revolute joint
  more than :data:`~dhsim_tui.core.motion.jog.MAX_JOINT_JUMP_DEG` in one
  solve, a prismatic one more than :data:`JUMP_SHARE` of the reach), the
  arm holds where it is for the rest of the move and a :class:`Failure`
  records it; the next step starts from there.
- A **wait** holds the pose.

The program starts from ``start`` (the robot's home unless given). The last
sample is the program's end, at the first ``k / rate`` not before it.
Checking the samples is :mod:`~dhsim_tui.core.motion.path_check`'s.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from dhsim_tui.core.analysis.jacobian import controllable_rows, manipulability
from dhsim_tui.core.analysis.workspace import length_scale
from dhsim_tui.core.ik.nearest import inverse
from dhsim_tui.core.ik.reasons import amount
from dhsim_tui.core.ik.rotation import rotation_error
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.profiles import (
    Trapezoid,
    blend,
    joint_profile,
    line_poses,
    linear_profile,
)
from dhsim_tui.core.model.program import Program, Step, linear_speed, target_joints
from dhsim_tui.core.model.program_timing import MAX_SAMPLES as TIMING_MAX_SAMPLES
from dhsim_tui.core.model.program_timing import check_timing
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.motion.jog import MAX_JOINT_JUMP_DEG

#: samples a second by default, and the range accepted
DEFAULT_RATE = 100.0
MIN_RATE = 1.0
MAX_RATE = 10_000.0
#: the most samples a trajectory may have (an hour at 100 Hz), and the most
#: IK solves a program's linear moves may take (the program's length is
#: checked against it in closed form before sampling: program_timing)
MAX_SAMPLES = TIMING_MAX_SAMPLES
#: linear moves are solved at least this often a second (between samples too)
IK_RATE = 100.0
#: IK iterations a solve may take from the previous sample's joints
IK_ITERATIONS = 40
#: a prismatic joint moving more than this share of the reach in one solve jumps
JUMP_SHARE = 0.1
#: a failed linear move: IK found no solution, or only one past a jump
REACH, JUMP = "reach", "jump"


@dataclass(frozen=True)
class Span:
    """Where a step lies in time: its number (1-based), start, duration and
    the joints it starts and ends at."""

    number: int
    step: Step
    start: float
    duration: float
    q_start: tuple[float, ...]
    q_end: tuple[float, ...]

    @property
    def end(self) -> float:
        return self.start + self.duration

    @property
    def move(self) -> str:
        return self.step.move


@dataclass(frozen=True)
class Failure:
    """A linear move that could not go on: at ``time`` (in step ``step``) IK
    found no solution (``kind`` REACH; ``reason`` is the solver's, what
    stopped it) or only one past a jump of joint ``joint`` (JUMP; ``reason``
    is the jump's size in the joint's unit). The arm holds from there."""

    step: int
    time: float
    kind: str
    reason: str
    joint: int | None = None


@dataclass(frozen=True, eq=False)
class Trajectory:
    """A program's samples: ``time`` (s), ``step`` (1-based; 0 for a program
    without steps), ``move`` ("joint", "linear" or "wait"), ``q`` (N×dof,
    deg or robot units) and ``pose`` (N×4×4, the tool in the world).

    A wait holds the pose, so it has samples only at its ends (the grid's
    first and last point in it): the times are on the rate's grid, but
    not every grid point is a sample. ``complete`` is False for the part
    of a program sampled so far (:class:`Sampling`): its samples end at
    :attr:`ready`, its last step may go on past them."""

    robot: Robot
    program: Program
    rate: float
    spans: tuple[Span, ...]
    time: np.ndarray
    step: np.ndarray
    move: np.ndarray
    q: np.ndarray
    pose: np.ndarray
    failures: tuple[Failure, ...] = field(default=())
    complete: bool = True

    @property
    def duration(self) -> float:
        return self.spans[-1].end if self.spans else 0.0

    @property
    def ready(self) -> float:
        """How far the samples go (s): the duration once complete."""
        if self.complete:
            return self.duration
        return float(self.time[-1]) if len(self.time) else 0.0

    @property
    def xyz(self) -> np.ndarray:
        return self.pose[:, :3, 3]

    @cached_property
    def mu(self) -> np.ndarray:
        """The manipulability at every sample (the pose panel's measure)."""
        out = np.empty(len(self.q))
        for first in range(0, len(self.q), CHUNK):  # Python floats a chunk at a time
            rows = self.q[first : first + CHUNK].tolist()
            out[first : first + len(rows)] = [manipulability(self.robot, q) for q in rows]
        return out

    @cached_property
    def tool_speed(self) -> np.ndarray:
        """The tool point's speed (robot units/s), each sample's from the one
        before by finite differences (0 at the first)."""
        speed = np.zeros(len(self.time))
        if len(self.time) > 1:
            gaps = np.linalg.norm(np.diff(self.xyz, axis=0), axis=1)
            speed[1:] = gaps / np.diff(self.time)
        return speed


#: samples (or a linear move's IK solves) made at a time: the unit of work of
#: :meth:`Sampling.advance`, and of the arrays made at once
CHUNK = 4096


def sample(
    robot: Robot,
    program: Program,
    rate: float = DEFAULT_RATE,
    start: Sequence[float] | None = None,
) -> Trajectory:
    """Play ``program`` on ``robot`` from ``start`` (home when None) at ``rate``
    samples a second. Raises :class:`DhsimError` for a bad rate or start, or a
    program too long to sample (more than :data:`MAX_SAMPLES`)."""
    sampling = Sampling(robot, program, rate, start)
    while sampling.advance():
        pass
    return sampling.trajectory()


class Sampling:
    """A program being sampled, a piece at a time: :meth:`advance` plans the
    next step, or the next :data:`CHUNK` IK solves of a linear move, and
    :meth:`trajectory` gives the samples so far (all of them once
    :attr:`done`). A caller can play the first seconds while the rest is
    made, show :attr:`progress`, and stop between two pieces.

    The program's length is checked in closed form when it is made
    (:func:`~dhsim_tui.core.model.program_timing.check_timing`), so a
    program too long is refused before any sample exists."""

    def __init__(
        self,
        robot: Robot,
        program: Program,
        rate: float = DEFAULT_RATE,
        start: Sequence[float] | None = None,
    ) -> None:
        if not isinstance(rate, int | float) or not MIN_RATE <= rate <= MAX_RATE:
            raise DhsimError(
                f"rate: give {MIN_RATE:g} to {MAX_RATE:g} samples a second, not {rate}"
            )
        q = tuple(float(v) for v in robot.check_q(robot.home if start is None else start))
        #: the program's duration (s) as planned, in closed form (a failed
        #: linear move can make the real one differ)
        self.planned = check_timing(robot, program, float(rate), q)
        self.robot, self.program, self.rate = robot, program, float(rate)
        self.start = q
        self.done = False
        self._sampler = _Sampler(robot, program, float(rate))
        self._pieces = self._sampler.blocks(q)
        self._blocks: list[_Block] = []
        self._ready = 0.0

    @property
    def progress(self) -> float:
        """The share of the program sampled so far, 0 to 1."""
        if self.done:
            return 1.0
        return min(self._ready / self.planned, 1.0) if self.planned > 0 else 0.0

    @property
    def ready(self) -> float:
        """How far the samples go so far (s)."""
        return self._ready

    def advance(self) -> bool:
        """Make the next piece; False once every sample is made."""
        if self.done:
            return False
        with np.errstate(all="ignore"):  # degenerate arms: guarded, never printed
            block = next(self._pieces, None)
        if block is None:
            self.done = True
            return False
        if len(block.index):
            self._blocks.append(block)
            self._ready = float(block.index[-1]) / self.rate
        return True

    def trajectory(self) -> Trajectory:
        """The samples made so far: every one, ending at the program's end,
        once :attr:`done`."""
        robot, spans = self.robot, tuple(self._sampler.spans)
        blocks = list(self._blocks)
        if self.done:
            blocks = _with_end(blocks, spans, self.rate, self.start)
        if blocks:
            index = np.concatenate([b.index for b in blocks])
            number = np.concatenate([np.broadcast_to(b.number, len(b.index)) for b in blocks])
            q = np.concatenate([b.q for b in blocks])
            if not self.done:  # kept as one block: the next call adds to it, no copy kept
                self._blocks = [_Block(index, number, q)]
        else:  # nothing sampled yet
            index, number, q = (
                np.zeros(0, np.int64),
                np.zeros(0, np.int64),
                np.zeros((0, robot.dof)),
            )
        moves = np.array(["wait", *(span.move for span in spans)])
        with np.errstate(all="ignore"):
            pose = robot.kinematics.batch(q) if len(q) else np.zeros((0, 4, 4))
        return Trajectory(
            robot,
            self.program,
            self.rate,
            spans,
            index / self.rate,
            number,
            moves[number],
            q,
            pose,
            tuple(self._sampler.failures),
            self.done,
        )


@dataclass(frozen=True)
class _Block:
    """Consecutive samples: their grid points ``k`` (times ``k / rate``), the
    step's number (0: none; or one per sample, for the samples so far kept
    as one block) and the joints (len×dof)."""

    index: np.ndarray
    number: int | np.ndarray
    q: np.ndarray


def _with_end(blocks: list[_Block], spans: tuple[Span, ...], rate: float, start) -> list[_Block]:
    """The blocks with the program's last sample: at the first grid point not
    before its end, with the last step's number and end joints."""
    total = spans[-1].end if spans else 0.0
    last = max(0, math.ceil(total * rate - 1e-6))
    number = spans[-1].number if spans else 0
    q_end = np.array([spans[-1].q_end if spans else start], dtype=float)
    end = _Block(np.array([last], dtype=np.int64), number, q_end)
    if not blocks or int(blocks[-1].index[-1]) < last:
        return [*blocks, end]
    final = blocks[-1]  # its last sample is the program's end: it takes the end's values
    if len(final.index) == 1:
        return [*blocks[:-1], end]
    numbers = final.number if np.isscalar(final.number) else final.number[:-1]
    head = _Block(final.index[:-1], numbers, final.q[:-1])
    return [*blocks[:-1], head, end]


class _Sampler:
    """One run of :class:`Sampling`: the steps planned in order, each from
    where the one before really ended, their samples made as they are."""

    def __init__(self, robot: Robot, program: Program, rate: float) -> None:
        self.robot = robot
        self.program = program
        self.rate = rate
        self.fine = max(1, math.ceil(IK_RATE / rate - 1e-9))  # IK solves per sample interval
        self.solves = 0
        self.failures: list[Failure] = []
        self.spans: list[Span] = []
        rows = controllable_rows(robot)
        self.position_only = robot.dof < int(rows.sum())
        scale = length_scale(robot)
        self.jump = np.array(
            [MAX_JOINT_JUMP_DEG if j.is_revolute else JUMP_SHARE * scale for j in robot.joints]
        )

    def blocks(self, q: tuple[float, ...]) -> Iterator[_Block]:
        """Every step's samples, a block at a time (an empty block after a
        step without samples, so each piece of work is one)."""
        now = 0.0
        for number, step in enumerate(self.program.steps, start=1):
            if step.is_wait:
                span = Span(number, step, now, float(step.seconds), q, q)
                yield from self._wait(span)
            elif step.move == "joint":
                goal = target_joints(self.robot, self.program.name, number, step)
                piece = joint_profile(self.robot, q, goal, step.speed)
                span = Span(number, step, now, piece.duration, q, tuple(goal))
                yield from self._joint(span, piece)
            else:
                span = yield from self._linear(number, step, now, q)
            now, q = span.end, span.q_end

    def _grid(self, span: Span) -> np.ndarray:
        """The grid points ``k`` whose times ``k / rate`` lie in the span
        (``start <= t < end``), exactly as those times compare."""
        return np.arange(self._first_at(span.start), self._first_at(span.end), dtype=np.int64)

    def _first_at(self, time: float) -> int:
        """The first grid point not before ``time``."""
        k = max(0, math.ceil(time * self.rate))
        while k > 0 and (k - 1) / self.rate >= time:
            k -= 1
        while k / self.rate < time:
            k += 1
        return k

    def _check_size(self, duration: float) -> None:
        if duration * self.rate > MAX_SAMPLES or self.solves > MAX_SAMPLES:
            raise DhsimError(
                f"programs.{self.program.name}: {duration:g} s or more at {self.rate:g} Hz is "
                f"more than {MAX_SAMPLES} samples; lower the rate or shorten the program"
            )

    def _wait(self, span: Span) -> Iterator[_Block]:
        """A wait's samples: the first and last grid point in it (it holds)."""
        self._check_size(span.end)
        self.spans.append(span)
        grid = self._grid(span)
        ends = np.unique(grid[[0, -1]]) if len(grid) else grid
        yield _Block(ends, span.number, np.tile(np.array(span.q_start), (len(ends), 1)))

    def _joint(self, span: Span, profile: Trapezoid) -> Iterator[_Block]:
        self._check_size(span.end)
        self.spans.append(span)
        grid = self._grid(span)
        first, last = np.array(span.q_start), np.array(span.q_end)
        for at in range(0, max(len(grid), 1), CHUNK):
            part = grid[at : at + CHUNK]
            local = part / self.rate - span.start
            yield _Block(part, span.number, blend(first, last, profile.position(local)))

    # -- linear moves: IK along the line -------------------------------------------------
    def _linear(self, number: int, step: Step, now: float, q: tuple[float, ...]):
        """A linear move's samples, :data:`CHUNK` IK solves at a time; returns
        its span (its end joints are where the walk ended)."""
        robot = self.robot
        goal = target_joints(robot, self.program.name, number, step)
        first, last = robot.kinematics.pose(q), robot.kinematics.pose(goal)
        turn = rotation_error(last[:3, :3], first[:3, :3])  # world rotation vector, rad
        length = float(np.linalg.norm(last[:3, 3] - first[:3, 3]))
        degrees = math.degrees(float(np.linalg.norm(turn)))
        speed = linear_speed(step, robot.units)
        profile = linear_profile(robot, length, degrees, speed)
        self.solves += math.ceil(profile.duration * self.rate * self.fine) + 1
        self._check_size(now + profile.duration)  # before the fine grid is built
        duration = profile.duration
        indices = self._walk_indices(now, duration)  # fine points strictly inside
        times = np.append(indices / (self.rate * self.fine) - now, duration)
        if duration <= 0.0:
            times = times[:0]
        planned = Span(number, step, now, duration, q, tuple(goal))
        self.spans.append(planned)  # until the walk is over: where it is meant to end
        grid = self._grid(planned)
        fine_points = grid * self.fine
        walk = _Walk(self, number, now, q, times)
        sent = 0  # samples of the grid given so far
        while True:
            done = walk.solve(
                lambda part: line_poses(first, last, turn, profile.position(part)), CHUNK
            )
            # the samples whose fine points are solved (or held after a failure)
            solved = (
                len(fine_points)
                if done
                else int(
                    np.searchsorted(fine_points, indices[walk.count - 1], side="right")
                    if walk.count
                    else 0
                )
            )
            if solved > sent or done:
                part = grid[sent:solved]
                held = walk.out[walk.count - 1] if walk.count else np.array(q)
                if done:
                    span = Span(number, step, now, duration, q, tuple(held.tolist()))
                    self.spans[-1] = span
                joints = self._linear_joints(planned, part, indices, walk.out, held)
                yield _Block(part, number, joints)
                sent = solved
            if done:
                return span

    def _linear_joints(
        self, span: Span, part: np.ndarray, indices, walked, held: np.ndarray
    ) -> np.ndarray:
        """The joints at grid points ``part``: the start's at the move's start,
        else the walk's at the same fine point (``held``, where the walk is,
        for one the fine grid's rounding misses)."""
        local = part / self.rate - span.start
        out = np.where((local <= 0.0)[:, None], np.array(span.q_start), held)
        if not len(part) or not len(indices):
            return out
        fine_points = part * self.fine
        where = np.minimum(np.searchsorted(indices, fine_points), len(indices) - 1)
        found = indices[where] == fine_points
        out[found] = walked[where[found]]
        return out

    def _walk_indices(self, start: float, duration: float) -> np.ndarray:
        """The fine grid's points ``j / (rate · fine)`` strictly inside the move
        (its end is solved as well, after them)."""
        fine_rate = self.rate * self.fine
        first = math.floor(start * fine_rate)
        last = math.ceil((start + duration) * fine_rate) + 1
        indices = np.arange(first, last, dtype=np.int64)
        local = indices / fine_rate - start
        return indices[(local > 0.0) & (local < duration)]


class _Walk:
    """A linear move's IK walk along its poses, each solve from the one
    before; held from the first that fails or jumps (recorded)."""

    def __init__(self, sampler: _Sampler, number: int, start: float, q, times: np.ndarray):
        self.sampler = sampler
        self.number = number
        self.start = start
        self.times = times
        self.out = np.empty((len(times), sampler.robot.dof))
        self.previous = tuple(q)
        self.count = 0  # solves made (the rest held after a failure)
        self.jump = sampler.jump.tolist()

    def solve(self, targets, most: int) -> bool:
        """The next ``most`` solves (poses from ``targets(times)``); True when
        the walk is over."""
        sampler, robot = self.sampler, self.sampler.robot
        part = self.times[self.count : self.count + most]
        for offset, target in enumerate(targets(part)):
            i = self.count + offset
            result = inverse(
                robot,
                target,
                self.previous,
                max_iter=IK_ITERATIONS,
                position_only=sampler.position_only,
                max_change=self.jump,
            )
            failure = None
            if not result.success:
                failure = Failure(
                    self.number, self.start + float(part[offset]), REACH, result.reason
                )
            else:
                over = np.abs(np.subtract(result.q, self.previous)) - sampler.jump
                if over.max() > 0.0:
                    joint = int(np.argmax(over))
                    change = abs(result.q[joint] - self.previous[joint])
                    failure = Failure(
                        self.number,
                        self.start + float(part[offset]),
                        JUMP,
                        amount(change, 2),
                        joint,
                    )
            if failure is not None:
                sampler.failures.append(failure)
                self.out[i:] = self.previous
                self.count = len(self.times)
                return True
            self.previous = result.q
            self.out[i] = self.previous
        self.count += len(part)
        return self.count >= len(self.times)

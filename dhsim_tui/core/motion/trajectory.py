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
from collections.abc import Sequence
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
    deg or robot units) and ``pose`` (N×4×4, the tool in the world)."""

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

    @property
    def duration(self) -> float:
        return self.spans[-1].end if self.spans else 0.0

    @property
    def xyz(self) -> np.ndarray:
        return self.pose[:, :3, 3]

    @cached_property
    def mu(self) -> np.ndarray:
        """The manipulability at every sample (the pose panel's measure)."""
        return np.array([manipulability(self.robot, q) for q in self.q.tolist()])

    @cached_property
    def tool_speed(self) -> np.ndarray:
        """The tool point's speed (robot units/s), each sample's from the one
        before by finite differences (0 at the first)."""
        speed = np.zeros(len(self.time))
        if len(self.time) > 1:
            gaps = np.linalg.norm(np.diff(self.xyz, axis=0), axis=1)
            speed[1:] = gaps / np.diff(self.time)
        return speed


def sample(
    robot: Robot,
    program: Program,
    rate: float = DEFAULT_RATE,
    start: Sequence[float] | None = None,
) -> Trajectory:
    """Play ``program`` on ``robot`` from ``start`` (home when None) at ``rate``
    samples a second. Raises :class:`DhsimError` for a bad rate or start, or a
    program too long to sample (more than :data:`MAX_SAMPLES`)."""
    if not isinstance(rate, int | float) or not MIN_RATE <= rate <= MAX_RATE:
        raise DhsimError(f"rate: give {MIN_RATE:g} to {MAX_RATE:g} samples a second, not {rate}")
    q = tuple(float(v) for v in robot.check_q(robot.home if start is None else start))
    check_timing(robot, program, float(rate), q)  # in closed form: refused before sampling
    with np.errstate(all="ignore"):  # degenerate arms: guarded, never printed
        return _Sampler(robot, program, float(rate)).run(q)


class _Sampler:
    """One run of :func:`sample`: the steps planned in order, each from where
    the one before really ended, then the samples read off them."""

    def __init__(self, robot: Robot, program: Program, rate: float) -> None:
        self.robot = robot
        self.program = program
        self.rate = rate
        self.fine = max(1, math.ceil(IK_RATE / rate - 1e-9))  # IK solves per sample interval
        self.solves = 0
        self.failures: list[Failure] = []
        rows = controllable_rows(robot)
        self.position_only = robot.dof < int(rows.sum())
        scale = length_scale(robot)
        self.jump = np.array(
            [MAX_JOINT_JUMP_DEG if j.is_revolute else JUMP_SHARE * scale for j in robot.joints]
        )

    def run(self, q: tuple[float, ...]) -> Trajectory:
        start = q
        spans: list[Span] = []
        pieces: list = []  # per step: None (wait), a Trapezoid (joint), a walk (linear)
        now = 0.0
        for number, step in enumerate(self.program.steps, start=1):
            if step.is_wait:
                span, piece = Span(number, step, now, float(step.seconds), q, q), None
            elif step.move == "joint":
                goal = target_joints(self.robot, self.program.name, number, step)
                piece = joint_profile(self.robot, q, goal, step.speed)
                span = Span(number, step, now, piece.duration, q, tuple(goal))
            else:
                span, piece = self._linear(number, step, now, q)
            self._check_size(span.end)
            spans.append(span)
            pieces.append(piece)
            now, q = span.end, span.q_end
        return self._samples(start, spans, pieces)

    def _check_size(self, duration: float) -> None:
        if duration * self.rate > MAX_SAMPLES or self.solves > MAX_SAMPLES:
            raise DhsimError(
                f"programs.{self.program.name}: {duration:g} s or more at {self.rate:g} Hz is "
                f"more than {MAX_SAMPLES} samples; lower the rate or shorten the program"
            )

    # -- linear moves: IK along the line -------------------------------------------------
    def _linear(self, number: int, step: Step, now: float, q: tuple[float, ...]):
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
        indices = self._walk_indices(now, profile.duration)
        times = np.append(indices / (self.rate * self.fine) - now, profile.duration)
        if profile.duration <= 0.0:
            times = times[:0]
        targets = line_poses(first, last, turn, profile.position(times))
        walked = self._follow(number, now, q, times, targets)
        end = tuple(walked[-1].tolist()) if len(walked) else q
        return Span(number, step, now, profile.duration, q, end), (indices, walked)

    def _walk_indices(self, start: float, duration: float) -> np.ndarray:
        """The fine grid's points ``j / (rate · fine)`` strictly inside the move
        (its end is solved as well, after them)."""
        fine_rate = self.rate * self.fine
        first = math.floor(start * fine_rate)
        last = math.ceil((start + duration) * fine_rate) + 1
        indices = np.arange(first, last, dtype=np.int64)
        local = indices / fine_rate - start
        return indices[(local > 0.0) & (local < duration)]

    def _follow(self, number: int, start: float, q, times: np.ndarray, targets: np.ndarray):
        """Joints along ``targets`` by IK, each from the one before; held from
        the first that fails or jumps (recorded)."""
        robot = self.robot
        out = np.empty((len(times), robot.dof))
        previous = tuple(q)
        jump = self.jump.tolist()
        for i, target in enumerate(targets):
            result = inverse(
                robot,
                target,
                previous,
                max_iter=IK_ITERATIONS,
                position_only=self.position_only,
                max_change=jump,
            )
            failure = None
            if not result.success:
                failure = Failure(number, start + float(times[i]), REACH, result.reason)
            else:
                over = np.abs(np.subtract(result.q, previous)) - self.jump
                if over.max() > 0.0:
                    joint = int(np.argmax(over))
                    change = abs(result.q[joint] - previous[joint])
                    failure = Failure(
                        number, start + float(times[i]), JUMP, amount(change, 2), joint
                    )
            if failure is not None:
                self.failures.append(failure)
                out[i:] = previous
                return out
            previous = result.q
            out[i] = previous
        return out

    # -- the samples -------------------------------------------------------------------
    def _samples(self, start: tuple[float, ...], spans: list[Span], pieces: list) -> Trajectory:
        robot, rate = self.robot, self.rate
        total = spans[-1].end if spans else 0.0
        count = max(0, math.ceil(total * rate - 1e-6)) + 1
        time = np.arange(count) / rate
        q = np.empty((count, robot.dof))
        if not spans:
            q[:] = start
            step = np.zeros(count, dtype=np.int64)
            move = np.full(count, "wait")
        else:
            ends = np.array([span.end for span in spans])
            which = np.minimum(np.searchsorted(ends, time, side="right"), len(spans) - 1)
            which[-1] = len(spans) - 1  # the last sample is the program's end
            for index, (span, piece) in enumerate(zip(spans, pieces, strict=True)):
                picked = np.flatnonzero(which == index)
                if len(picked):
                    q[picked] = self._span_joints(span, piece, picked, time[picked] - span.start)
            q[-1] = spans[-1].q_end
            step = which + 1
            move = np.array([span.move for span in spans])[which]
        return Trajectory(
            robot,
            self.program,
            rate,
            tuple(spans),
            time,
            step,
            move,
            q,
            robot.kinematics.batch(q),
            tuple(self.failures),
        )

    def _span_joints(self, span: Span, piece, picked: np.ndarray, local: np.ndarray):
        if piece is None:  # a wait
            return np.broadcast_to(np.array(span.q_start), (len(picked), self.robot.dof))
        if isinstance(piece, Trapezoid):  # a joint move
            return blend(np.array(span.q_start), np.array(span.q_end), piece.position(local))
        indices, walked = piece  # a linear move: the IK walk at the samples' fine points
        fine_points = picked * self.fine
        where = np.minimum(np.searchsorted(indices, fine_points), max(len(indices) - 1, 0))
        found = indices[where] == fine_points if len(indices) else np.zeros(len(picked), dtype=bool)
        out = np.where((local <= 0.0)[:, None], np.array(span.q_start), np.array(span.q_end))
        if found.any():
            out[found] = walked[where[found]]
        return out

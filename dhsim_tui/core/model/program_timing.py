"""How long a program takes, in closed form, before anything is sampled.

Each move's duration is its speed profile's
(:mod:`~dhsim_tui.core.model.profiles`: a few square roots), from the
pose the step before ends at as planned; a wait's is its seconds. A program
that would take longer than :data:`MAX_DURATION`, or more samples than
:data:`MAX_SAMPLES` at the rate it is played at, is refused here, naming the
step that crosses the limit and how long it takes: ``dhsim check``, loading,
importing and playing all refuse it in well under a second and in no memory,
where sampling first took minutes and gigabytes.

Speeds have floors that no real program comes near (:data:`MIN_JOINT_PERCENT`,
:data:`MIN_LINEAR_SPEED_MM`, and :data:`MIN_TOP_SPEED` / :data:`MIN_TOP_ACCELERATION`
for a joint's ``vmax`` / ``amax``), so a duration is never a division by a
denormal.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.profiles import joint_profile, linear_profile
from dhsim_tui.core.model.program import (
    Program,
    Step,
    linear_speed,
    step_where,
    target_joints,
)
from dhsim_tui.core.model.units import mm_to_unit

#: the longest a program may take (s): an hour
MAX_DURATION = 3600.0
#: the most samples a played program may have (an hour at 100 Hz); the
#: longest program at the highest rate must still fit, so the rate decides
MAX_SAMPLES = 360_000
#: the slowest joint move: this share of each joint's top speed (percent)
MIN_JOINT_PERCENT = 0.01
#: the slowest linear move (mm/s, in the robot's unit)
MIN_LINEAR_SPEED_MM = 0.01
#: the least top speed and acceleration a joint may be given (deg/s and deg/s²,
#: or mm/s and mm/s² in the robot's unit)
MIN_TOP_SPEED = 0.01
MIN_TOP_ACCELERATION = 0.01


def step_durations(robot, program: Program, start: Sequence[float] | None = None) -> list[float]:
    """Each step's duration (s), in closed form, each move from where the
    one before ends as planned (its target; the first from ``start``, home
    when None). Raises what a bad target raises."""
    q = tuple(float(v) for v in (robot.home if start is None else start))
    durations = []
    for number, step in enumerate(program.steps, start=1):
        if step.is_wait:
            durations.append(float(step.seconds))
            continue
        goal = target_joints(robot, program.name, number, step)
        durations.append(move_duration(robot, step, q, goal))
        q = goal
    return durations


def move_duration(robot, step: Step, start: Sequence[float], goal: Sequence[float]) -> float:
    """A joint or linear move's duration (s) from ``start`` to ``goal``."""
    if step.move == "joint":
        return joint_profile(robot, start, goal, step.speed).duration
    first = robot.kinematics.pose(tuple(start))
    last = robot.kinematics.pose(tuple(goal))
    length = float(np.linalg.norm(last[:3, 3] - first[:3, 3]))
    speed = linear_speed(step, robot.units)
    return linear_profile(robot, length, _turn_degrees(first, last), speed).duration


def _turn_degrees(first: np.ndarray, last: np.ndarray) -> float:
    """The angle (degrees) of the rotation from ``first``'s to ``last``'s
    orientation (from the skew part and the trace: exact near 0 and 180)."""
    r = first[:3, :3].T @ last[:3, :3]
    skew = math.hypot(r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1])
    return math.degrees(math.atan2(0.5 * skew, 0.5 * (float(np.trace(r)) - 1.0)))


def check_timing(
    robot, program: Program, rate: float | None = None, start: Sequence[float] | None = None
) -> float:
    """The program's duration (s), or :class:`DhsimError` naming the step
    where it passes :data:`MAX_DURATION` (or, at ``rate``, :data:`MAX_SAMPLES`)."""
    limit = MAX_DURATION if rate is None else min(MAX_DURATION, MAX_SAMPLES / rate)
    total = 0.0
    for number, seconds in enumerate(step_durations(robot, program, start), start=1):
        total += seconds
        if total > limit:
            where = step_where(program.name, number)
            step = program.steps[number - 1]
            what = "the wait" if step.is_wait else f"this {step.move} move"
            if limit < MAX_DURATION:
                bound = (
                    f"at {rate:g} Hz a program may take at most {limit:g} s "
                    f"({MAX_SAMPLES} samples); lower the rate"
                )
            else:
                bound = f"a program may take at most {MAX_DURATION:g} s"
            raise DhsimError(
                f"{where}: {what} takes {_seconds(seconds)}, so the program would take "
                f"{_seconds(total)} by its end; {bound}"
            )
    return total


def _seconds(value: float) -> str:
    return f"{value:.4g} s" if value < 1e6 else f"{value:.3e} s"


def check_program_speeds(robot) -> None:
    """Raise :class:`DhsimError` on a move slower than the floors above."""
    units = robot.units
    slowest = mm_to_unit(MIN_LINEAR_SPEED_MM, units)
    for program in robot.programs:
        for number, step in enumerate(program.steps, start=1):
            if step.is_wait or step.speed is None:
                continue
            where = step_where(program.name, number, "speed")
            if step.move == "joint" and step.speed < MIN_JOINT_PERCENT:
                raise DhsimError(
                    f"{where}: {step.speed:g} % is slower than any program needs; "
                    f"a joint move's speed is at least {MIN_JOINT_PERCENT:g} % of the top speed"
                )
            if step.move == "linear" and step.speed < slowest:
                raise DhsimError(
                    f"{where}: {step.speed:g} {units}/s is slower than any program needs; "
                    f"a linear move's speed is at least {slowest:g} {units}/s"
                )


def check_programs_timing(robot) -> None:
    """Every program's speeds above the floors and duration within the
    limit, each from home (as ``dhsim run`` starts it)."""
    check_program_speeds(robot)
    for program in robot.programs:
        check_timing(robot, program)

"""Speed profiles for a program's moves (:mod:`~dhsim_tui.core.motion.trajectory`
samples them; :mod:`~dhsim_tui.core.model.program_timing` times a program
with them in closed form, before anything is sampled).

Every move is a path parameter ``s`` going from 0 to 1 along a trapezoidal
speed profile: a constant acceleration up to a top speed, a cruise, the
same deceleration down to rest (a triangle when the move is too short to
reach the top speed). Whatever follows ``s`` (the joints of a joint move,
the tool of a linear move) starts and stops with it, so every joint of a
joint move starts and stops together.

- A **joint move** is the fastest such profile in which no joint goes faster
  than its top speed times the move's percentage, nor accelerates faster
  than its top acceleration (:func:`joint_profile`); the joint that needs
  longest sets the pace, the others are slowed to finish with it.
- A **linear move** keeps the tool point's speed at most the step's speed
  (robot units a second) and its acceleration at most
  :data:`LINEAR_ACCELERATION_MM`; the tool's turn at most
  :data:`TURN_SPEED` and :data:`TURN_ACCELERATION` (:func:`linear_profile`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from dhsim_tui.core.model.program import (
    JOINT_SPEED_PERCENT,
    top_acceleration,
    top_speed,
)
from dhsim_tui.core.model.units import mm_to_unit

#: a linear move's tool acceleration and deceleration (mm/s², in the robot's
#: unit): the default 250 mm/s is reached in a quarter of a second
LINEAR_ACCELERATION_MM = 1000.0
#: the most a linear move turns the tool (deg/s) and its angular acceleration (deg/s²)
TURN_SPEED = 90.0
TURN_ACCELERATION = 360.0


class Arm(Protocol):
    """What a profile reads of a robot (a :class:`~dhsim_tui.core.model.robot.Robot`)."""

    @property
    def joints(self) -> Sequence: ...

    @property
    def units(self) -> str: ...


@dataclass(frozen=True)
class Trapezoid:
    """Position along a distance ``distance`` against time: accelerate at
    ``acceleration`` for ``ramp`` seconds up to ``peak``, cruise, decelerate
    the same way; ``duration`` in all. A zero distance takes no time."""

    distance: float
    peak: float
    acceleration: float
    ramp: float
    duration: float

    def position(self, t: np.ndarray | float) -> np.ndarray:
        """The distance covered at times ``t`` (clamped to 0..duration): exactly
        0 before the start and exactly ``distance`` from the end on."""
        t = np.clip(np.asarray(t, dtype=float), 0.0, self.duration)
        a, ramp, duration = self.acceleration, self.ramp, self.duration
        rising = 0.5 * a * t * t
        cruising = 0.5 * a * ramp * ramp + self.peak * (t - ramp)
        left = duration - t
        falling = self.distance - 0.5 * a * left * left
        out = np.where(t < ramp, rising, np.where(t <= duration - ramp, cruising, falling))
        return np.where(t >= duration, self.distance, out)


def trapezoid(distance: float, top: float, acceleration: float) -> Trapezoid:
    """The fastest trapezoid over ``distance`` (>= 0) with speed at most ``top``
    and acceleration at most ``acceleration`` (both > 0)."""
    if distance <= 0.0 or not math.isfinite(distance):
        return Trapezoid(0.0, 0.0, acceleration, 0.0, 0.0)
    if distance * acceleration <= top * top:  # a triangle: the top speed is never reached
        ramp = math.sqrt(distance / acceleration)
        return Trapezoid(distance, acceleration * ramp, acceleration, ramp, 2.0 * ramp)
    ramp = top / acceleration
    return Trapezoid(distance, top, acceleration, ramp, distance / top + ramp)


def joint_limits(robot: Arm, percent: float | None) -> tuple[np.ndarray, np.ndarray]:
    """Each joint's top speed at ``percent`` (None: the default) and its top
    acceleration, in deg or robot units per second (per second squared)."""
    share = (JOINT_SPEED_PERCENT if percent is None else percent) / 100.0
    speeds = np.array([top_speed(j, robot.units) * share for j in robot.joints])
    accelerations = np.array([top_acceleration(j, robot.units) for j in robot.joints])
    return speeds, accelerations


def joint_profile(
    robot: Arm, start: Sequence[float], goal: Sequence[float], percent: float | None
) -> Trapezoid:
    """The profile of ``s`` for a joint move from ``start`` to ``goal``: joint
    i moves ``s · |goal_i - start_i|``, so its speed is ``ṡ`` times its
    distance; ``ṡ`` and ``s̈`` are the largest every joint allows."""
    distance = np.abs(np.asarray(goal, dtype=float) - np.asarray(start, dtype=float))
    speeds, accelerations = joint_limits(robot, percent)
    moving = distance > 0.0
    if not moving.any():
        return trapezoid(0.0, 1.0, 1.0)
    with np.errstate(over="ignore"):  # a denormal distance: no time at all (inf)
        top = float(np.min(speeds[moving] / distance[moving]))
        acceleration = float(np.min(accelerations[moving] / distance[moving]))
    return trapezoid(1.0, top, acceleration)


def linear_profile(robot: Arm, length: float, turn_deg: float, speed: float) -> Trapezoid:
    """The profile of ``s`` for a linear move of ``length`` (robot units) and a
    turn of ``turn_deg`` at tool ``speed`` (robot units a second)."""
    acceleration = mm_to_unit(LINEAR_ACCELERATION_MM, robot.units)
    tops, accelerations = [], []
    if length > 0.0:
        tops.append(speed / length)
        accelerations.append(acceleration / length)
    if turn_deg > 0.0:
        tops.append(TURN_SPEED / turn_deg)
        accelerations.append(TURN_ACCELERATION / turn_deg)
    if not tops:
        return trapezoid(0.0, 1.0, 1.0)
    return trapezoid(1.0, min(tops), min(accelerations))


def blend(start: np.ndarray, goal: np.ndarray, s: np.ndarray) -> np.ndarray:
    """``start + s · (goal - start)`` for each ``s`` (rows), exactly ``start``
    at s = 0 and exactly ``goal`` at s = 1 (each end counted from its own
    side, so no rounding puts a joint past a target on its limit)."""
    start = np.asarray(start, dtype=float)
    goal = np.asarray(goal, dtype=float)
    s = np.asarray(s, dtype=float)[:, None]
    change = goal - start
    return np.where(s < 0.5, start + s * change, goal - (1.0 - s) * change)


def line_poses(first: np.ndarray, last: np.ndarray, turn: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Poses along the line from ``first`` to ``last`` at path fractions ``s``:
    the point in a straight line, the rotation ``turn`` (a world rotation
    vector, rad: ``last = exp(turn) · first``) scaled by ``s`` (Rodrigues);
    exactly ``last`` at s = 1."""
    s = np.asarray(s, dtype=float)
    count = len(s)
    poses = np.zeros((count, 4, 4))
    poses[:, 3, 3] = 1.0
    poses[:, :3, 3] = blend(first[:3, 3], last[:3, 3], s)
    angle = float(np.linalg.norm(turn))
    if angle > 0.0:
        axis = turn / angle
        k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
        theta = s * angle
        turns = (
            np.eye(3)[None]
            + np.sin(theta)[:, None, None] * k[None]
            + (1.0 - np.cos(theta))[:, None, None] * (k @ k)[None]
        )
        poses[:, :3, :3] = turns @ first[:3, :3]
    else:
        poses[:, :3, :3] = first[:3, :3]
    poses[s >= 1.0, :3, :3] = last[:3, :3]
    return poses

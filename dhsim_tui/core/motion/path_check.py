"""The path check: what would go wrong on the real arm, found in a
:class:`~dhsim_tui.core.motion.trajectory.Trajectory` before it moves.

Every sample is checked; a run of samples with the same problem in the same
step is one :class:`Problem`, with the step, the time of its first and last
sample and the joint or frame it concerns:

- **limit**: a joint at or past one of its limits (within
  :data:`LIMIT_TOLERANCE`);
- **speed**: a joint faster than its top speed (``vmax``, or the default
  when the robot file gives none, and the detail says so; whatever the
  move's percentage), by finite differences between consecutive samples,
  beyond a relative :data:`SPEED_TOLERANCE`;
- **reach**: a linear move whose tool leaves the reachable space (IK finds
  no solution from the sample before); the arm stops there;
- **jump**: a linear move that can't go on without a joint jumping (another
  IK branch); the arm stops there;
- **singular**: in a linear move, the manipulability below
  :data:`~dhsim_tui.core.analysis.jacobian.SINGULAR_THRESHOLD`, the pose
  panel's red (a joint move or a wait passes a singular pose without harm:
  the joints are interpolated, nothing is divided by the Jacobian);
- **floor**: a frame's origin (frames 0 to n, and the tool point when the
  tool is not frame n) below the floor, the views' floor: world z =
  -``base_height`` (a pedestal of that height under frame 0's origin).

A problem's ``detail`` follows its kind (``dhsim run`` prints ``speed: Th1
at 271.18 deg/s, ...``); its :attr:`Problem.message` stands alone (the
simulator's status line). Both name the joint or frame once.

Start and end poses outside the limits never get here: they are load errors
(:func:`~dhsim_tui.core.model.program.check_programs`).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, replace

import numpy as np

from dhsim_tui.core.analysis.jacobian import SINGULAR_THRESHOLD
from dhsim_tui.core.analysis.workspace import length_scale
from dhsim_tui.core.ik.reasons import amount, length
from dhsim_tui.core.model.program import top_speed
from dhsim_tui.core.model.robot import Robot, Tool
from dhsim_tui.core.model.validation import fmt
from dhsim_tui.core.motion.trajectory import JUMP, REACH, Trajectory

LIMIT, SPEED, SINGULAR, FLOOR = "limit", "speed", "singular", "floor"
#: the kinds of problem, in the order a sample's are listed
KINDS = (REACH, JUMP, LIMIT, SPEED, SINGULAR, FLOOR)
#: a joint this close to a limit (deg or robot units) is on it
LIMIT_TOLERANCE = 1e-9
#: a joint's speed may exceed its top speed by this share (rounding) before it counts
SPEED_TOLERANCE = 1e-6
#: a frame this far below the floor (a share of the reach) is under it
FLOOR_TOLERANCE = 1e-6


@dataclass(frozen=True)
class Problem:
    """One problem: its ``kind`` (one of :data:`KINDS`), the ``step`` (1-based)
    it is in, the first and last sample's times (s), what it concerns (a joint
    label such as ``Th3``, ``frame 2``, ``tool``, ``arm``) and what happens
    (``detail``, read after the kind: it names the subject itself)."""

    kind: str
    step: int
    time: float
    until: float
    subject: str
    detail: str

    @property
    def message(self) -> str:
        """The problem in one line without its kind before it: ``Th1 at
        271.18 deg/s, over its top speed 180 deg/s``, ``singular in a linear
        move, manipulability 0.0012 (below 0.001)``; the subject named once."""
        if self.kind == SINGULAR:  # the only detail that doesn't say what it is
            return f"{self.kind} {self.detail}"
        return self.detail

    def as_dict(self) -> dict:
        return {
            "kind": self.kind,
            "step": self.step,
            "time": self.time,
            "until": self.until,
            "subject": self.subject,
            "detail": self.detail,
        }


def check_path(trajectory: Trajectory) -> tuple[Problem, ...]:
    """Every problem of ``trajectory``, by time (then by kind)."""
    with np.errstate(all="ignore"):
        problems = [
            *_failures(trajectory),
            *_limits(trajectory),
            *_speeds(trajectory),
            *_singular(trajectory),
            *_floor(trajectory),
        ]
    return tuple(sorted(problems, key=lambda p: (p.time, p.step, KINDS.index(p.kind))))


def runs(mask: np.ndarray, step: np.ndarray) -> list[tuple[int, int]]:
    """(first, last) sample index of each run of True in ``mask`` that stays
    in one step."""
    picked = np.flatnonzero(mask)
    if not len(picked):
        return []
    breaks = np.flatnonzero((np.diff(picked) != 1) | (np.diff(step[picked]) != 0)) + 1
    firsts = np.concatenate([[0], breaks])
    lasts = np.concatenate([breaks, [len(picked)]]) - 1
    return [(int(picked[a]), int(picked[b])) for a, b in zip(firsts, lasts, strict=True)]


def _problem(trajectory: Trajectory, kind: str, run: tuple[int, int], subject: str, detail: str):
    first, last = run
    time = trajectory.time
    return Problem(
        kind, int(trajectory.step[first]), float(time[first]), float(time[last]), subject, detail
    )


def _unit(robot: Robot, index: int) -> str:
    return robot.joints[index].unit(robot.units)


def _failures(trajectory: Trajectory) -> list[Problem]:
    robot = trajectory.robot
    out = []
    for failure in trajectory.failures:
        until = trajectory.spans[failure.step - 1].end
        if failure.kind == REACH:
            detail = f"the tool leaves the reachable space ({failure.reason}); the arm stops there"
            subject = "tool"
        else:
            index = failure.joint if failure.joint is not None else 0
            subject = robot.labels[index]
            detail = (
                f"the tool can't go on without {subject} jumping {failure.reason} "
                f"{_unit(robot, index)} (another IK branch); the arm stops there"
            )
        out.append(Problem(failure.kind, failure.step, failure.time, until, subject, detail))
    return out


def _limits(trajectory: Trajectory) -> list[Problem]:
    robot, q = trajectory.robot, trajectory.q
    out = []
    for index, joint in enumerate(robot.joints):
        values = q[:, index]
        for side, limit, mask in (
            ("lower", joint.min, values <= joint.min + LIMIT_TOLERANCE),
            ("upper", joint.max, values >= joint.max - LIMIT_TOLERANCE),
        ):
            for run in runs(mask, trajectory.step):
                seen = values[run[0] : run[1] + 1]
                past = seen.min() < joint.min if side == "lower" else seen.max() > joint.max
                where = "past" if past else "at"
                detail = (
                    f"{robot.labels[index]} {where} its {side} limit "
                    f"{fmt(limit)} {_unit(robot, index)}"
                )
                out.append(_problem(trajectory, LIMIT, run, robot.labels[index], detail))
    return out


def joint_speeds(trajectory: Trajectory, index: int) -> np.ndarray:
    """Joint ``index``'s speed (deg or robot units per second) at each sample
    from the sample before, by finite differences (N-1 values: sample 1 on).
    One joint at a time, so a long run of a many-jointed arm never holds
    every joint's differences at once."""
    return np.abs(np.diff(trajectory.q[:, index])) / np.diff(trajectory.time)


def _speeds(trajectory: Trajectory) -> list[Problem]:
    robot = trajectory.robot
    if len(trajectory.time) < 2:
        return []
    out = []
    for index, joint in enumerate(robot.joints):
        speeds = joint_speeds(trajectory, index)
        top = top_speed(joint, robot.units)
        over = np.concatenate([[False], speeds > top * (1.0 + SPEED_TOLERANCE)])
        for run in runs(over, trajectory.step):
            peak = float(speeds[run[0] - 1 : run[1]].max())
            unit = _unit(robot, index)
            given = "its top speed" if joint.vmax is not None else "the default top speed"
            detail = f"{robot.labels[index]} at {_over(peak, top)} {unit}/s, over {given} "
            detail += f"{fmt(top)} {unit}/s" + ("" if joint.vmax is not None else " (no vmax)")
            out.append(_problem(trajectory, SPEED, run, robot.labels[index], detail))
    return out


def _over(value: float, top: float) -> str:
    """``value`` with the decimals that show it above ``top`` (90.004, not 90)."""
    for decimals in range(2, 10):
        text = amount(value, decimals)
        if float(text) > top:
            return text
    return amount(value, 10)


def _singular(trajectory: Trajectory) -> list[Problem]:
    linear = trajectory.move == "linear"
    if not linear.any():
        return []
    mu = trajectory.mu
    out = []
    for run in runs(linear & (mu < SINGULAR_THRESHOLD), trajectory.step):
        lowest = float(mu[run[0] : run[1] + 1].min())
        # read after the kind: "singular: in a linear move, ..."; message: "singular in a ..."
        detail = f"in a linear move, manipulability {lowest:.2g} (below {SINGULAR_THRESHOLD:g})"
        out.append(_problem(trajectory, SINGULAR, run, "arm", detail))
    return out


#: samples whose frames are computed at a time by :func:`frame_heights`
HEIGHTS_AT_ONCE = 16384


def frame_heights(trajectory: Trajectory) -> Iterator[tuple[str, np.ndarray]]:
    """Each frame's name (``frame 0`` ... ``frame n``, then ``tool`` when the
    tool is not frame n) and its world z at every sample, one frame at a
    time: frame k by batch FK of the arm cut after joint k, a chunk of
    samples at a time (never an (N, 4, 4) array per frame)."""
    robot, q = trajectory.robot, trajectory.q
    bare = replace(robot, tool=Tool(), poses=(), programs=())
    yield "frame 0", np.full(len(q), robot.kinematics.base[2, 3])
    for k in range(1, robot.dof + 1):
        arm = bare if k == robot.dof else replace(bare, joints=robot.joints[:k])
        z = np.empty(len(q))
        for first in range(0, len(q), HEIGHTS_AT_ONCE):
            part = q[first : first + HEIGHTS_AT_ONCE, :k]
            z[first : first + len(part)] = arm.kinematics.batch(part)[:, 2, 3]
        yield f"frame {k}", z
    if not robot.tool.is_identity:
        yield "tool", trajectory.pose[:, 2, 3]


def floor_height(robot: Robot) -> float:
    """The floor's world z, as the views draw it (scene.wireframe)."""
    return -robot.base_height


def _floor(trajectory: Trajectory) -> list[Problem]:
    robot = trajectory.robot
    floor = floor_height(robot)
    lowest = floor - FLOOR_TOLERANCE * length_scale(robot)
    out = []
    for name, heights in frame_heights(trajectory):
        for run in runs(heights < lowest, trajectory.step):
            depth = float(floor - heights[run[0] : run[1] + 1].min())
            detail = f"{name} {length(robot, depth)} below the floor"
            out.append(_problem(trajectory, FLOOR, run, name, detail))
    return out

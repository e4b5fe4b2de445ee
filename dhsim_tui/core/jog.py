"""Joint stepping: step sizes and moves that stop at a joint's limit.

UI-free so the control screen, the CLI and the tests share one rule: a step
never wraps and never passes a limit; it stops on the limit and says so.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dhsim_tui.core import ik_reasons
from dhsim_tui.core.ik import POSITION, IKResult, rotation_error, solve
from dhsim_tui.core.jacobian import controllable_rows, jacobian, length_scale, normalised
from dhsim_tui.core.model import Robot, mm_to_unit
from dhsim_tui.core.orientation import rotx, roty, rotz

#: step sizes offered by ``[`` and ``]``, smallest first
REVOLUTE_STEPS_DEG = (0.1, 1.0, 5.0, 15.0, 45.0)
PRISMATIC_STEPS_MM = (0.1, 1.0, 10.0, 50.0, 100.0)
DEFAULT_STEP_LEVEL = 1
#: joint values are kept to this many decimals so repeated 0.1 steps stay exact
DECIMALS = 9


def step_size(robot: Robot, index: int, level: int) -> float:
    """The step of joint ``index`` at ladder ``level`` (deg, or the robot's unit)."""
    level = max(0, min(level, len(REVOLUTE_STEPS_DEG) - 1))
    if robot.joints[index].is_revolute:
        return REVOLUTE_STEPS_DEG[level]
    return mm_to_unit(PRISMATIC_STEPS_MM[level], robot.units)


@dataclass(frozen=True)
class Move:
    """The outcome of a step: the new joint vector and whether a limit stopped it."""

    q: tuple[float, ...]
    moved: bool
    limit: str | None = None  # "min" or "max" when the joint is on a limit after the step

    @property
    def blocked(self) -> bool:
        return self.limit is not None and not self.moved


def set_joint(robot: Robot, q: tuple[float, ...], index: int, value: float) -> Move:
    """Set one joint, clamped into its limits."""
    joint = robot.joints[index]
    clamped = min(max(round(value, DECIMALS), joint.min), joint.max)  # round, then clamp
    limit = None
    if value <= joint.min:
        limit = "min"
    elif value >= joint.max:
        limit = "max"
    new = (*q[:index], clamped, *q[index + 1 :])
    return Move(new, clamped != q[index], limit)


def step_joint(robot: Robot, q: tuple[float, ...], index: int, delta: float) -> Move:
    """Move one joint by ``delta``, stopping on its limit."""
    return set_joint(robot, q, index, q[index] + delta)


#: Cartesian rows: world X, Y, Z (robot unit), then turns about the tool's own x, y, z (deg)
CARTESIAN_ROWS = ("X", "Y", "Z", "Rx", "Ry", "Rz")
#: a Cartesian step that would move any revolute joint further than this is a branch flip
MAX_JOINT_JUMP_DEG = 30.0


def cartesian_step_size(robot: Robot, row: int, level: int) -> float:
    level = max(0, min(level, len(REVOLUTE_STEPS_DEG) - 1))
    if row < 3:
        return mm_to_unit(PRISMATIC_STEPS_MM[level], robot.units)
    return REVOLUTE_STEPS_DEG[level]


def cartesian_target(robot: Robot, q: tuple[float, ...], row: int, delta: float):
    """The current tool pose moved ``delta`` along world X/Y/Z or turned about
    the tool's own x/y/z axis."""
    return move_pose(robot.kinematics.pose(q), row, delta)


def move_pose(pose, row: int, delta: float):
    """A copy of ``pose`` moved along world X/Y/Z (rows 0-2) or turned about
    its own x/y/z axis (rows 3-5, degrees)."""
    pose = pose.copy()
    if row < 3:
        pose[row, 3] += delta
    else:
        pose[:3, :3] = pose[:3, :3] @ (rotx, roty, rotz)[row - 3](delta)
    return pose


@dataclass(frozen=True)
class CartesianMove:
    q: tuple[float, ...]
    moved: bool
    reason: str = ""


def cartesian_move(robot: Robot, q: tuple[float, ...], target) -> CartesianMove:
    """Follow ``target`` from ``q`` by inverse kinematics, continuously: no
    restarts, so the arm never jumps to another branch; what can't be reached
    moves nothing and says why: which part (position or orientation) and
    what stops it (a joint's limit, a singularity, the reach)."""
    with np.errstate(all="ignore"):  # degenerate arms: guarded, never printed
        return _cartesian_move(robot, tuple(q), np.asarray(target, dtype=float))


def _cartesian_move(robot: Robot, q: tuple[float, ...], target: np.ndarray) -> CartesianMove:
    rows = controllable_rows(robot)
    # fewer joints than directions it can move in (a planar arm): it positions the tool
    position_only = robot.dof < int(rows.sum())
    current = robot.kinematics.pose(q)
    change = np.concatenate(
        [
            (target[:3, 3] - current[:3, 3]) / length_scale(robot),
            rotation_error(target[:3, :3], current[:3, :3]),
        ]
    )
    turning = bool(np.abs(change[:3]).max() < 1e-12)
    if position_only:
        rows = rows.copy()
        rows[3:] = True  # orientation is let go, so any turn there is "not possible"
        if turning and np.abs(change[3:]).max() > 1e-12:
            return CartesianMove(q, False, "this arm only positions its tool; it can't turn it")
    if np.abs(change[~rows]).max(initial=0.0) > 1e-9:
        return CartesianMove(q, False, "the arm has no joint that moves the tool that way")
    key = (robot, q, target.tobytes())
    if _last_refusal[0] == key:  # the same step again (a held key): the same answer, at once
        return _last_refusal[1]
    result = solve(robot, target, q, max_iter=40, position_only=position_only)
    if not result.success:
        move = CartesianMove(q, False, _why(robot, result, turning))
        _last_refusal[:] = [key, move]
        return move
    jumps = [
        (abs(a - b), i)
        for i, (j, a, b) in enumerate(zip(robot.joints, result.q, q, strict=True))
        if j.is_revolute
    ]
    if jumps and max(jumps)[0] > MAX_JOINT_JUMP_DEG:
        if singular_towards(robot, q, change, position_only):
            return CartesianMove(q, False, ik_reasons.why_not_moved(robot, ik_reasons.SINGULAR, ()))
        jump, index = max(jumps)
        turn = ik_reasons.amount(jump, 1)
        return CartesianMove(
            q,
            False,
            f"that step swings {robot.labels[index]} {turn} deg at once; take a smaller one",
        )
    new_q = tuple(round(v, DECIMALS) for v in result.q)
    return CartesianMove(new_q, new_q != q)


#: the last refused step and its answer (a held key repeats it many times a second)
_last_refusal: list = [None, None]


def _why(robot: Robot, result: IKResult, turning: bool) -> str:
    """A refused step's reason, short enough for a status line: the part that
    can't follow (position, or the orientation that should stay or turn) and
    what stops it."""
    cause, limited = result.cause, result.limited
    if cause == ik_reasons.STOPPED:
        return "no solution found"
    if result.failed == POSITION or cause == ik_reasons.SINGULAR:
        if cause == ik_reasons.OUT_OF_REACH:
            distance = ik_reasons.length(robot, result.position_error)
            return f"out of reach (closest found {distance} away)"
        return ik_reasons.why_not_moved(robot, cause, limited)
    # ORIENTATION: the position can be reached, but not with this orientation
    if turning:
        return ik_reasons.why_not_turned(robot, cause, limited)
    if cause == ik_reasons.LIMIT:
        return f"the tool can't keep its orientation there: {ik_reasons.at_limits(robot, limited)}"
    return "the tool can't keep its orientation there"


def singular_towards(robot: Robot, q, change: np.ndarray, position_only: bool) -> bool:
    """Whether the arm at ``q`` is singular along ``change`` (a dimensionless
    6-vector): the motion asked for lies along a direction it has lost here."""
    rows = controllable_rows(robot).copy()
    if position_only:
        rows[3:] = False
    jac = normalised(robot, jacobian(robot, q))
    rank = min(robot.dof, int(rows.sum()))
    return ik_reasons.lost_along(jac[rows], change[rows], rank)

"""Joint stepping: step sizes and moves that stop at a joint's limit.

UI-free so the control screen, the CLI and the tests share one rule: a step
never wraps and never passes a limit; it stops on the limit and says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.analysis.jacobian import controllable_rows, jacobian, normalised
from dhsim_tui.core.analysis.workspace import length_scale, reach
from dhsim_tui.core.ik import reasons as ik_reasons
from dhsim_tui.core.ik.nearest import inverse
from dhsim_tui.core.ik.numerical import POSITION, IKResult
from dhsim_tui.core.ik.rotation import rotation_error
from dhsim_tui.core.model.orientation import rotx, roty, rotz
from dhsim_tui.core.model.robot import Robot, mm_to_unit

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


def snapped(robot: Robot, index: int, value: float, level: int) -> float:
    """``value`` for joint ``index`` rounded to a whole number of steps at
    ladder ``level`` (a slider picked with the mouse), within its limits."""
    joint = robot.joints[index]
    step = step_size(robot, index, level)
    if not math.isfinite(value):
        value = joint.home
    rounded = round(value / step) * step
    return min(max(round(rounded, DECIMALS), joint.min), joint.max)


def step_joint(robot: Robot, q: tuple[float, ...], index: int, delta: float) -> Move:
    """Move one joint by ``delta``, stopping on its limit."""
    return set_joint(robot, q, index, q[index] + delta)


#: Cartesian rows: X, Y, Z (robot unit), then turns about x, y, z (deg), in the
#: jogging frame: the world's axes or the tool's own (FRAMES)
CARTESIAN_ROWS = ("X", "Y", "Z", "Rx", "Ry", "Rz")
#: the jogging frames: WORLD moves along and turns about the world's X, Y, Z
#: (turns about axes through the tool point, so the tool stays where it is);
#: TOOL moves along and turns about the tool's own x, y, z (z: the approach)
WORLD, TOOL = "world", "tool"
FRAMES = (WORLD, TOOL)
#: a Cartesian step that would move any revolute joint further than this is a branch flip
MAX_JOINT_JUMP_DEG = 30.0


def row_name(row: int, frame: str = WORLD) -> str:
    """A row as the panel and messages name it: ``X`` ``Y`` ``Z`` ``Rx`` ``Ry``
    ``Rz``; the tool's own axes in lower case (``x`` ``y`` ``z``) in TOOL."""
    name = CARTESIAN_ROWS[row]
    return name.lower() if frame == TOOL and row < 3 else name


def cartesian_step_size(robot: Robot, row: int, level: int) -> float:
    level = max(0, min(level, len(REVOLUTE_STEPS_DEG) - 1))
    if row < 3:
        return mm_to_unit(PRISMATIC_STEPS_MM[level], robot.units)
    return REVOLUTE_STEPS_DEG[level]


def cartesian_target(
    robot: Robot, q: tuple[float, ...], row: int, delta: float, frame: str = WORLD
):
    """The current tool pose moved ``delta`` along x/y/z or turned about x/y/z
    of ``frame`` (see :func:`move_pose`)."""
    return move_pose(robot.kinematics.pose(q), row, delta, frame)


def move_pose(pose, row: int, delta: float, frame: str = WORLD):
    """A copy of ``pose`` moved ``delta`` along x/y/z (rows 0-2, robot unit)
    or turned ``delta`` degrees about x/y/z (rows 3-5) of ``frame``: WORLD,
    the world's axes (a turn about a world axis through the tool point: the
    tool point stays); TOOL, the pose's own axes (z is the approach vector)."""
    if frame not in FRAMES:
        raise ValueError(f"frame must be one of {FRAMES}, not {frame!r}")
    pose = np.array(pose, dtype=float)  # a copy
    if row < 3:
        direction = pose[:3, row] if frame == TOOL else np.eye(3)[row]
        pose[:3, 3] += delta * direction
    else:
        turn = (rotx, roty, rotz)[row - 3](delta)
        pose[:3, :3] = pose[:3, :3] @ turn if frame == TOOL else turn @ pose[:3, :3]
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
    result = inverse(
        robot,
        target,
        q,
        max_iter=40,
        position_only=position_only,
        max_change=[MAX_JOINT_JUMP_DEG if j.is_revolute else math.inf for j in robot.joints],
    )
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


# -- IK branches: the arm's other solutions for the same tool pose (b) ------------------
#: a solution this close to the arm's joints (on every joint: radians, or a
#: fraction of the reach) is the configuration the arm is in
SAME_BRANCH = 1e-3


def branch_index(robot: Robot, solutions, q: tuple[float, ...]) -> int:
    """Which of ``solutions`` (each with ``.q``) the arm at ``q`` is in: the
    nearest, if it is within :data:`SAME_BRANCH` on every joint; -1 if none."""
    scales = [
        np.pi / 180.0 if joint.is_revolute else 1.0 / max(reach(robot), 1e-12)
        for joint in robot.joints
    ]
    best, index = SAME_BRANCH, -1
    for i, solution in enumerate(solutions):
        gaps = (abs(a - b) * k for a, b, k in zip(solution.q, q, scales, strict=True))
        gap = max(gaps, default=0.0)
        if gap <= best:
            best, index = gap, i
    return index


def branch_caption(found, index: int, labels: tuple[str, ...] = ()) -> str:
    """The caption of solution ``index`` of ``found`` (an ``ik_all.Solutions``),
    such as "branch 3/8: shoulder left, elbow down, wrist flip"; it says when it
    is the only one, or one of a family (a redundant arm has infinitely many). Two
    solutions with the same words differ by whole turns of some joint: the
    later one names them (``Th6 -360°``), given the joints' ``labels``."""
    solutions = found.solutions
    config = solutions[index].config if 0 <= index < len(solutions) else ""
    if config and labels:
        config = ", ".join([config, *_turns(solutions, index, labels)])
    if len(solutions) == 1 and not found.family:
        return "the only solution for this pose" + (f": {config}" if config else "")
    where = f"branch {index + 1}/{len(solutions)}"
    if found.family:
        where += " (one of a family)"
    return where + (f": {config}" if config else "")


def _turns(solutions, index: int, labels: tuple[str, ...]) -> list[str]:
    """The whole turns solution ``index`` is away from the first solution with
    the same configuration words (none when it is that first one)."""
    mine = solutions[index]
    first = next(s for s in solutions if s.config == mine.config)
    turns = []
    for label, a, b in zip(labels, mine.q, first.q, strict=False):
        whole = round((a - b) / 360.0)
        if whole and abs(a - b - 360.0 * whole) < 1.0:
            turns.append(f"{label} {360 * whole:+d}°")
    return turns


def branch_goal(q: tuple[float, ...]) -> tuple[float, ...]:
    """A solution's joints as the screen keeps them (rounded like every move)."""
    return tuple(round(float(v), DECIMALS) for v in q)

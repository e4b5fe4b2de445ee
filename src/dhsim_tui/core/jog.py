"""Joint stepping: step sizes and moves that stop at a joint's limit.

UI-free so the control screen, the CLI and the tests share one rule: a step
never wraps and never passes a limit; it stops on the limit and says so.
"""

from __future__ import annotations

from dataclasses import dataclass

from dhsim_tui.core.model import Robot, mm_to_unit

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
    clamped = round(min(max(value, joint.min), joint.max), DECIMALS)
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

"""The simulator's typed values, each a question in a ValueEntry dialog: a
joint's exact value, a Cartesian target and the name of a pose to save.

Each is a plain flow: ``await`` it from a worker (``@work``), as
:mod:`.fields` does for the editor; it returns the answer, or None when the
dialog was cancelled. Checking the answer is the core's.
"""

from __future__ import annotations

from textual.app import App

from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics import EndEffector
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.validation import fmt
from dhsim_tui.core.motion.jog import TOOL, WORLD, row_name
from dhsim_tui.tui.screens.dialogs import short_path
from dhsim_tui.tui.screens.value_entry import ValueEntry

#: a path in a status message longer than this is shortened in the middle
PATH_WIDTH = 60


def shorten_path_in(message: str, path: object) -> str:
    """``message`` with ``path`` (as it quotes it) shortened in the middle, so a
    long path can't push the reason off the screen."""
    if path is None:
        return message
    for quoted in dict.fromkeys((str(path), printable(str(path)))):
        if len(quoted) > PATH_WIDTH and quoted in message:
            return message.replace(quoted, short_path(quoted, PATH_WIDTH))
    return message


async def ask_joint_value(app: App, robot: Robot, index: int, value: float) -> float | None:
    """Joint ``index``'s exact value, within its limits (now ``value``)."""
    joint = robot.joints[index]
    label = joint.label(index + 1)
    unit = joint.unit(robot.units)

    def check(text: str) -> float:
        number = editing.parse_number(text, label)
        if not joint.min <= number <= joint.max:
            raise DhsimError(
                f"{fmt(number)} is outside {label}'s limits "
                f"{fmt(joint.min)}..{fmt(joint.max)} {unit}"
            )
        return number

    hint = f"{fmt(joint.min)} .. {fmt(joint.max)} {unit} · enter sets · escape cancels"
    return await app.push_screen_wait(ValueEntry(f"{label} ({unit})", fmt(value), hint, check))


async def ask_cartesian_step(
    app: App, robot: Robot, row: int, frame: str, pose: EndEffector
) -> float | None:
    """How far to move the tool along (or turn it about) ``row`` in
    ``frame``: asked as the world target of a WORLD position row, as a
    distance or an angle otherwise; the answer is the step from ``pose``."""
    name = row_name(row, frame)
    unit = robot.units
    absolute = row < 3 and frame == WORLD
    if absolute:
        title, value = f"{name} target ({unit})", fmt(round(pose.xyz[row], 4))
        hint = "where the tool should go, world coordinates"
    elif row < 3:
        title, value = f"move along {name} ({unit})", "0"
        hint = f"how far, along the tool's own {name[-1]} axis"
    else:
        title, value = f"{name} turn (deg)", "0"
        hint = (
            "turn the tool about its own axis"
            if frame == TOOL
            else "turn the tool about this world axis, through the tool point"
        )
    target = await app.push_screen_wait(
        ValueEntry(title, value, hint, lambda text: editing.parse_number(text, name))
    )
    if target is None:
        return None
    return target - pose.xyz[row] if absolute else target


async def ask_pose_name(app: App, robot: Robot, q: tuple[float, ...]) -> tuple[Robot, str] | None:
    """A name for the joints ``q`` as a pose: the robot with it, and the name."""

    def check(text: str) -> tuple[Robot, str]:
        return editing.set_pose(robot, text, q), text.strip()

    return await app.push_screen_wait(
        ValueEntry(
            "save pose as",
            f"pose{len(robot.poses) + 1}",
            "a name; an existing pose of that name is replaced",
            check,
        )
    )

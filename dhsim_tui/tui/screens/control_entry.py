"""The control screen's typed values: a joint's exact value, a Cartesian
target and the name of a pose to save (each in a ValueEntry dialog)."""

from __future__ import annotations

from textual import work

from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
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


class ValueFlows:
    """Mixed into the control screen, which has ``q``, ``pose``, ``robot``,
    ``cartesian``, ``frame``, ``say``, ``_move_to``, ``_jog``, ``_redraw`` and ``_interrupt``."""

    def action_enter_value(self) -> None:
        self._interrupt()  # now, not when the dialog's worker gets to run
        self._ask_value()

    @work(exclusive=True, group="modal")
    async def _ask_value(self) -> None:
        if self.cartesian:
            await self._enter_cartesian()
            return
        index = self.selected
        joint = self.robot.joints[index]
        label = joint.label(index + 1)
        unit = joint.unit(self.robot.units)

        def check(text: str) -> float:
            value = editing.parse_number(text, label)
            if not joint.min <= value <= joint.max:
                raise DhsimError(
                    f"{fmt(value)} is outside {label}'s limits "
                    f"{fmt(joint.min)}..{fmt(joint.max)} {unit}"
                )
            return value

        hint = f"{fmt(joint.min)} .. {fmt(joint.max)} {unit} · enter sets · escape cancels"
        value = await self.app.push_screen_wait(
            ValueEntry(f"{label} ({unit})", fmt(self.q[index]), hint, check)
        )
        if value is not None:
            self._move_to(index, value)

    async def _enter_cartesian(self) -> None:
        self._redraw()  # self.pose must be the pose of the current q
        row = self.cartesian_row
        name = row_name(row, self.frame)
        unit = self.robot.units
        if row < 3 and self.frame == WORLD:
            title, value = f"{name} target ({unit})", fmt(round(self.pose.xyz[row], 4))
            hint = "where the tool should go, world coordinates"
        elif row < 3:
            title, value = f"move along {name} ({unit})", "0"
            hint = f"how far, along the tool's own {name[-1]} axis"
        else:
            title, value = f"{name} turn (deg)", "0"
            hint = (
                "turn the tool about its own axis"
                if self.frame == TOOL
                else "turn the tool about this world axis, through the tool point"
            )
        target = await self.app.push_screen_wait(
            ValueEntry(title, value, hint, lambda text: editing.parse_number(text, name))
        )
        if target is not None:
            self._redraw()
            absolute = row < 3 and self.frame == WORLD
            self._jog(row, target - self.pose.xyz[row] if absolute else target)

    @work(exclusive=True, group="modal")
    async def action_save_pose(self) -> None:
        """Keep the current joints as a named pose, in the robot and its file."""
        q = self.q

        def check(text: str) -> tuple[Robot, str]:
            return editing.set_pose(self.robot, text, q), text.strip()

        answer = await self.app.push_screen_wait(
            ValueEntry(
                "save pose as",
                f"pose{len(self.robot.poses) + 1}",
                "a name; an existing pose of that name is replaced",
                check,
            )
        )
        if answer is None:
            return
        robot, name = answer
        self.robot = robot
        try:
            saved_to = self.app.keep_robot(robot)  # type: ignore[attr-defined]
        except DhsimError as exc:
            reason = shorten_path_in(str(exc), self.app.robot_path)  # type: ignore[attr-defined]
            self.say(f"not saved: {reason} (pose {name} is kept in memory)", error=True)
        else:
            where = (
                f"saved in {short_path(saved_to, PATH_WIDTH)}"
                if saved_to
                else "kept until you quit (e, ctrl+s saves)"
            )
            self.say(f"pose {name} {where}")
        self.refresh_bindings()

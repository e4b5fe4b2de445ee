"""Cartesian jogging for the control screen (``c``, ``f``, and the arrows in
Cartesian mode): move the tool along or about the world's or its own axes,
the joints following by inverse kinematics.
"""

from __future__ import annotations

from dhsim_tui.core.motion.jog import (
    CARTESIAN_ROWS,
    TOOL,
    WORLD,
    cartesian_move,
    cartesian_step_size,
    move_pose,
    row_name,
)
from dhsim_tui.tui.widgets.cartesian_panel import TITLES as CARTESIAN_TITLES
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel


class CartesianJogging:
    """Mixed into the control screen, which has ``q``, ``robot``, ``cartesian``,
    ``cartesian_row``, ``step_level``, ``frame``, ``_commanded``,
    ``_cartesian_panel``, ``_interrupt``, ``_update_step_caption``,
    ``_show_now``, ``say`` and ``refresh_bindings``."""

    def action_row(self, delta: int) -> None:
        self._pick_row((self.cartesian_row + delta) % len(CARTESIAN_ROWS))

    def _pick_row(self, row: int) -> None:
        self.cartesian_row = row
        self._update_step_caption()
        self._show_now()

    def on_cartesian_panel_row_picked(self, message: CartesianPanel.RowPicked) -> None:
        """A click on a Cartesian row selects it."""
        self._pick_row(message.row)

    def on_cartesian_panel_wheeled(self, message: CartesianPanel.Wheeled) -> None:
        """The wheel over a Cartesian row moves the tool along it."""
        self._pick_row(message.row)
        self.action_jog(message.steps)

    def action_jog(self, multiple: int) -> None:
        self._interrupt()
        row = self.cartesian_row
        self._jog(row, multiple * cartesian_step_size(self.robot, row, self.step_level))

    def _jog(self, row: int, delta: float) -> None:
        """Move the tool; the joints follow by inverse kinematics from where they
        are. Steps add up on the commanded pose, not on the reached one, so a
        run of steps stays on its line instead of collecting solver residue."""
        base = (
            self._commanded if self._commanded is not None else self.robot.kinematics.pose(self.q)
        )
        target = move_pose(base, row, delta, self.frame)
        move = cartesian_move(self.robot, self.q, target)
        if not move.moved:
            self.say(f"{row_name(row, self.frame)}: {move.reason or 'no change'}", error=True)
            return
        self.say("")
        self.q = move.q
        self._commanded = target

    def action_cartesian(self, _in_cartesian: int = 0) -> None:
        self.cartesian = not self.cartesian
        self.say(
            f"Cartesian jogging, {self.frame.upper()} frame (f): ↑↓ axis, ←→ move the tool"
            if self.cartesian
            else "joint jogging"
        )

    def action_frame(self, frame: str = "") -> None:
        """``f``: Cartesian jogging along and about the world's axes, or the
        tool's own (``frame``: the one to switch to; either, when not given)."""
        self.frame = frame if frame in (WORLD, TOOL) else (TOOL if self.frame == WORLD else WORLD)
        self._cartesian_panel.border_title = CARTESIAN_TITLES[self.frame]
        self._show_now()
        self.refresh_bindings()
        self.say(
            "TOOL frame: along and about the tool's own x, y, z (z: the approach)"
            if self.frame == TOOL
            else "WORLD frame: along and about the world's X, Y, Z (turns about the tool point)"
        )

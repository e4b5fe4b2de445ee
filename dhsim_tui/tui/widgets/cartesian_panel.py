"""The Cartesian panel: the tool's pose, one row per direction it can be jogged.

The title names the jogging frame (``f`` switches it). In the WORLD frame the
rows move the tool along the world's X, Y, Z and turn it about the world's
axes through the tool point; each shows a current value, as a teach pendant
does: the tool's world X, Y, Z and its orientation as roll, pitch and yaw. In
the TOOL frame the rows move along and turn about the tool's own x, y, z: the
position rows show which way each tool axis points in the world (z is the
approach vector), the turn rows roll, pitch and yaw.

Few bytes per key press (issue 9): one styled run per row, and a new pose
repaints only the rows that changed, each up to its last changed column.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from rich.text import Text
from textual import events
from textual.message import Message

from dhsim_tui.core.model.robot import LENGTH_DECIMALS
from dhsim_tui.core.motion.jog import CARTESIAN_ROWS, TOOL, WORLD
from dhsim_tui.tui.widgets.joint_panel import ascii_mode
from dhsim_tui.tui.widgets.pose_panel import TextPanel, refresh_changed_lines

#: the panel's title in each jogging frame (f switches)
TITLES = {WORLD: "Cartesian: WORLD frame (f)", TOOL: "Cartesian: TOOL frame (f)"}
TITLE = TITLES[WORLD]
#: the angle shown on each turn row
ANGLES = {"Rx": "roll", "Ry": "pitch", "Rz": "yaw"}


def cartesian_text(
    xyz: tuple[float, float, float],
    rpy: tuple[float, float, float],
    selected: int,
    units: str,
    ascii: bool = False,
    frame: str = WORLD,
    axes: Sequence[Sequence[float]] | None = None,
) -> Text:
    """Six rows, the selected one marked ``▶`` (ASCII ``>``); fixed columns so
    values don't jitter. ``axes``: the tool's x, y, z axes in world
    coordinates (the rotation's columns), shown on the TOOL frame's rows."""
    text = Text()
    places = LENGTH_DECIMALS[units]
    pointer, degree = (">", "deg") if ascii else ("▶", "°")
    tool = frame == TOOL and axes is not None
    for i, name in enumerate(CARTESIAN_ROWS):
        marker = pointer if i == selected else " "
        style = "bold reverse" if i == selected else ""
        if i < 3 and tool:
            x, y, z = (round(float(v), 2) + 0.0 for v in axes[i])
            line = f"{marker} {name.lower():<3}tool {name.lower()} = ({x:5.2f},{y:5.2f},{z:5.2f})"
        elif i < 3:
            value = f"{round(xyz[i], places) + 0.0:11.{places}f}"
            line = f"{marker} {name:<3}{'world':<12}{value} {units}"
        else:
            axis = f"tool {name[1]}" if frame == TOOL else f"world {name[1].upper()}"
            value = f"{round(rpy[i - 3], 2) + 0.0:10.2f}"
            line = f"{marker} {name:<3}{axis:<8}{ANGLES[name]:<5}{value}{degree}"
        text.append(line, style=style)
        if i < len(CARTESIAN_ROWS) - 1:
            text.append("\n")
    return text


class CartesianPanel(TextPanel):
    """Shows what the screen hands it: the tool's pose, the frame and the
    selected row."""

    DEFAULT_CSS = "CartesianPanel { height: 8; }"
    ALLOW_SELECT = False

    _frame: str | None = None

    @dataclass
    class RowPicked(Message):
        """A click on a row: select it."""

        row: int

    @dataclass
    class Wheeled(Message):
        """The wheel over a row: move the tool that many steps along it."""

        row: int
        steps: int

    def _row_at(self, y: int) -> int | None:
        return y if 0 <= y < len(CARTESIAN_ROWS) else None

    def on_click(self, event: events.Click) -> None:
        row = self._row_at(event.y)
        if row is not None:
            self.post_message(self.RowPicked(row))

    def on_mouse_scroll_up(self, event: events.MouseScrollUp) -> None:
        self._wheel(event, 1)

    def on_mouse_scroll_down(self, event: events.MouseScrollDown) -> None:
        self._wheel(event, -1)

    def _wheel(self, event: events.MouseEvent, steps: int) -> None:
        event.stop()
        row = self._row_at(event.y)
        if row is not None:
            self.post_message(self.Wheeled(row, steps))

    def show(
        self,
        xyz: tuple[float, float, float],
        rpy: tuple[float, float, float],
        selected: int,
        units: str,
        frame: str = WORLD,
        axes: Sequence[Sequence[float]] | None = None,
    ) -> None:
        if frame != self._frame:  # a border title repaints the whole panel
            self._frame = frame
            self.border_title = TITLES[frame]
        text = cartesian_text(xyz, rpy, selected, units, ascii_mode(self), frame, axes)
        refresh_changed_lines(self, self._text, text)
        self._text = text

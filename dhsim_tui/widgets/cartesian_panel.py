"""The Cartesian panel: X, Y, Z of the tool in the world and turns about its axes.

Every row shows a current value, as a teach pendant does: the position rows
the tool's world X, Y, Z; the turn rows (which turn the tool about its own
x, y, z axis) the tool's orientation as roll, pitch and yaw.

Few bytes per key press (issue 9): one styled run per row, and a new pose
repaints only the rows that changed, each up to its last changed column.
"""

from __future__ import annotations

from rich.text import Text

from dhsim_tui.core.jog import CARTESIAN_ROWS
from dhsim_tui.core.model import LENGTH_DECIMALS
from dhsim_tui.widgets.joint_panel import ascii_mode
from dhsim_tui.widgets.pose_panel import TextPanel, refresh_changed_lines

TITLE = "Cartesian: move the tool"
#: what each turn row turns about, and the angle shown on it
TURNS = {"Rx": ("tool x", "roll"), "Ry": ("tool y", "pitch"), "Rz": ("tool z", "yaw")}


def cartesian_text(
    xyz: tuple[float, float, float],
    rpy: tuple[float, float, float],
    selected: int,
    units: str,
    ascii: bool = False,
) -> Text:
    """Six rows, the selected one marked ``▶`` (ASCII ``>``); fixed columns so
    values don't jitter."""
    text = Text()
    places = LENGTH_DECIMALS[units]
    pointer, degree = (">", "deg") if ascii else ("▶", "°")
    for i, name in enumerate(CARTESIAN_ROWS):
        marker = pointer if i == selected else " "
        style = "bold reverse" if i == selected else ""
        if i < 3:
            value = f"{round(xyz[i], places) + 0.0:11.{places}f}"
            line = f"{marker} {name:<3}{'world':<12}{value} {units}"
        else:
            axis, angle = TURNS[name]
            value = f"{round(rpy[i - 3], 2) + 0.0:11.2f}"
            line = f"{marker} {name:<3}{axis:<7}{angle:<5}{value}{degree}"
        text.append(line, style=style)
        if i < len(CARTESIAN_ROWS) - 1:
            text.append("\n")
    return text


class CartesianPanel(TextPanel):
    """Shows what the screen hands it: the tool's pose and the selected row."""

    DEFAULT_CSS = "CartesianPanel { height: 8; }"

    def show(
        self,
        xyz: tuple[float, float, float],
        rpy: tuple[float, float, float],
        selected: int,
        units: str,
    ) -> None:
        text = cartesian_text(xyz, rpy, selected, units, ascii_mode(self))
        refresh_changed_lines(self, self._text, text)
        self._text = text

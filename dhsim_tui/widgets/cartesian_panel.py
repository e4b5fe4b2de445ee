"""The Cartesian panel: X, Y, Z of the tool in the world and turns about its axes.

Every row shows a current value, as a teach pendant does: the position rows
the tool's world X, Y, Z; the turn rows (which turn the tool about its own
x, y, z axis) the tool's orientation as roll, pitch and yaw.
"""

from __future__ import annotations

from rich.text import Text
from textual.widgets import Static

from dhsim_tui.core.jog import CARTESIAN_ROWS
from dhsim_tui.core.model import LENGTH_DECIMALS

TITLE = "Cartesian: move the tool"
#: what each turn row turns about, and the angle shown on it
TURNS = {"Rx": ("tool x", "roll"), "Ry": ("tool y", "pitch"), "Rz": ("tool z", "yaw")}


def cartesian_text(
    xyz: tuple[float, float, float],
    rpy: tuple[float, float, float],
    selected: int,
    units: str,
) -> Text:
    """Six rows, the selected one marked ``▶``; fixed columns so values don't jitter."""
    text = Text()
    places = LENGTH_DECIMALS[units]
    for i, name in enumerate(CARTESIAN_ROWS):
        marker = "▶" if i == selected else " "
        style = "bold reverse" if i == selected else ""
        if i < 3:
            value = f"{round(xyz[i], places) + 0.0:11.{places}f}"
            line = f"{marker} {name:<3}{'world':<12}{value} {units}"
        else:
            axis, angle = TURNS[name]
            value = f"{round(rpy[i - 3], 2) + 0.0:11.2f}"
            line = f"{marker} {name:<3}{axis:<7}{angle:<5}{value}°"
        text.append(line, style=style)
        if i < len(CARTESIAN_ROWS) - 1:
            text.append("\n")
    return text


class CartesianPanel(Static):
    """Shows what the screen hands it: the tool's pose and the selected row."""

    DEFAULT_CSS = "CartesianPanel { height: 8; }"

    def show(
        self,
        xyz: tuple[float, float, float],
        rpy: tuple[float, float, float],
        selected: int,
        units: str,
    ) -> None:
        self.update(cartesian_text(xyz, rpy, selected, units), layout=False)

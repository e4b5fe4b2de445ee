"""The Cartesian panel: X, Y, Z of the tool in the world and turns about its axes."""

from __future__ import annotations

from rich.text import Text
from textual.widgets import Static

from dhsim_tui.core.jog import CARTESIAN_ROWS
from dhsim_tui.core.model import LENGTH_DECIMALS

ROW_TEXT = {"Rx": "turn about tool x", "Ry": "turn about tool y", "Rz": "turn about tool z"}


def cartesian_text(xyz: tuple[float, float, float], selected: int, units: str) -> Text:
    text = Text()
    for i, name in enumerate(CARTESIAN_ROWS):
        marker = "▶" if i == selected else " "
        style = "bold reverse" if i == selected else ""
        if i < 3:
            places = LENGTH_DECIMALS[units]
            line = f"{marker} {name:<3}{round(xyz[i], places) + 0.0:11.{places}f} {units}"
        else:
            line = f"{marker} {name:<3} {ROW_TEXT[name]}"
        text.append(line, style=style)
        if i < len(CARTESIAN_ROWS) - 1:
            text.append("\n")
    return text


class CartesianPanel(Static):
    """Shows what the screen hands it: the tool position and the selected row."""

    DEFAULT_CSS = "CartesianPanel { height: 8; }"

    def show(self, xyz: tuple[float, float, float], selected: int, units: str) -> None:
        self.update(cartesian_text(xyz, selected, units), layout=False)

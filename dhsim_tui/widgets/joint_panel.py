"""The joints panel: one row per joint with its value and a slider bar in text."""

from __future__ import annotations

from rich.text import Text
from textual.containers import VerticalScroll
from textual.widgets import Static

from dhsim_tui.core.model import LENGTH_DECIMALS, Joint


def format_value(joint: Joint, value: float, units: str) -> str:
    """A joint value with its unit, fixed decimals so it doesn't jitter."""
    if joint.is_revolute:
        return f"{round(value, 2) + 0.0:9.2f}°  "
    decimals = LENGTH_DECIMALS[units]
    return f"{round(value, decimals) + 0.0:9.{decimals}f} {units:<2}"


def slider(joint: Joint, value: float, width: int) -> Text:
    """``├───┊──●────┤``: the range, home (┊) and value (●); ◀/▶ on a limit."""
    width = max(width, 5)
    inner = width - 2
    span = joint.max - joint.min

    def cell(v: float) -> int:
        return min(inner - 1, max(0, round((v - joint.min) / span * (inner - 1))))

    chars = ["─"] * inner
    styles = ["dim"] * inner
    home = cell(joint.home)
    chars[home], styles[home] = "┊", "dim"
    at = cell(value)
    if value <= joint.min:
        chars[at], styles[at] = "◀", "bold red"
    elif value >= joint.max:
        chars[at], styles[at] = "▶", "bold red"
    else:
        chars[at], styles[at] = "●", "bold"
    text = Text("├", style="dim")
    for ch, style in zip(chars, styles, strict=True):
        text.append(ch, style=style)
    text.append("┤", style="dim")
    return text


class JointRow(Static):
    """One joint: label, bar, value. Repaints only when its own value changes."""

    DEFAULT_CSS = """
    JointRow { height: 1; }
    JointRow.-selected { background: $accent 30%; text-style: bold; }
    """

    def __init__(self, number: int, joint: Joint, units: str, value: float) -> None:
        super().__init__()
        self.number = number
        self.joint = joint
        self.units = units
        self.value = value

    def set_value(self, value: float) -> None:
        if value != self.value:
            self.value = value
            self.refresh()

    def render(self) -> Text:
        label = self.joint.label(self.number)
        value_text = format_value(self.joint, self.value, self.units)
        bar_width = self.size.width - len(value_text) - 8
        at_limit = not self.joint.min < self.value < self.joint.max
        marker = "▶" if self.has_class("-selected") else " "
        text = Text(f"{marker} {label:<4} ")
        text.append_text(slider(self.joint, self.value, bar_width))
        text.append(value_text, style="bold red" if at_limit else "")
        return text


class JointPanel(VerticalScroll, can_focus=False):
    """The rows, scrolled to keep the selected joint in view."""

    DEFAULT_CSS = """
    JointPanel { height: auto; max-height: 100%; }
    """

    def rows(self) -> list[JointRow]:
        if not hasattr(self, "_rows"):
            self._rows = list(self.query(JointRow))
        return self._rows

    def select(self, index: int) -> None:
        for i, row in enumerate(self.rows()):
            row.set_class(i == index, "-selected")
            if i == index:
                row.refresh()
                self.scroll_to_widget(row, animate=False)
            else:
                row.refresh()

    def show(self, q: tuple[float, ...]) -> None:
        for row, value in zip(self.rows(), q, strict=True):
            row.set_value(value)

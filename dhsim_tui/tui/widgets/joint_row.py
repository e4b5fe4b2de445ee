"""One joint's row of the joints panel: its value and a slider bar in text.

Few bytes per key press (``bench/bytes.py`` counts them): a row is built as
a handful of styled runs (label, the bar up to the value, the value marker,
the rest of the bar, the value), never one span per glyph; Textual writes
each span as its own colour code and reset. A step repaints only its own
row, and only up to the last column that changed.
"""

from __future__ import annotations

from dataclasses import dataclass

from rich.cells import cell_len
from rich.text import Text
from textual import events
from textual.geometry import Region
from textual.message import Message
from textual.widgets import Static

from dhsim_tui.core.model.robot import LENGTH_DECIMALS, Joint
from dhsim_tui.terminal import charset as terminal

#: columns before the bar: the marker, a space, the label in four, a space
BAR_START = 7
#: the bar's glyphs: ends, track, home, value, value on its min / max limit
BAR_UNICODE = ("├", "┤", "─", "┊", "●", "◀", "▶")
BAR_ASCII = ("|", "|", "-", ":", "#", "<", ">")


def ascii_mode(widget: Static) -> bool:
    """Whether the app draws in 7-bit ASCII (``app.ascii_mode``, set by the app)."""
    try:
        app = widget.app
    except Exception:  # no app yet (a widget made outside one)
        return False
    return terminal.ascii_mode(app)


def format_value(joint: Joint, value: float, units: str, ascii: bool = False) -> str:
    """A joint value with its unit, fixed decimals so it doesn't jitter."""
    if joint.is_revolute:
        return f"{round(value, 2) + 0.0:9.2f}" + ("deg" if ascii else "°  ")
    decimals = LENGTH_DECIMALS[units]
    return f"{round(value, decimals) + 0.0:9.{decimals}f} {units:<2}"


def slider(joint: Joint, value: float, width: int, ascii: bool = False) -> Text:
    """``├───┊──●────┤``: the range, home (┊) and value (●); ◀/▶ on a limit.
    In ASCII ``|---:--#----|`` and ``<``/``>``. One span per run of equal style."""
    left, right, track, home_glyph, dot, at_min, at_max = BAR_ASCII if ascii else BAR_UNICODE
    width = max(width, 5)
    inner = width - 2
    span = joint.max - joint.min

    def cell(v: float) -> int:
        return min(inner - 1, max(0, round((v - joint.min) / span * (inner - 1))))

    chars = [track] * inner
    chars[cell(joint.home)] = home_glyph
    at = cell(value)
    if value <= joint.min:
        chars[at], marker_style = at_min, "bold red"
    elif value >= joint.max:
        chars[at], marker_style = at_max, "bold red"
    else:
        chars[at], marker_style = dot, "bold"
    text = Text()
    text.append(left + "".join(chars[:at]), style="dim")
    text.append(chars[at], style=marker_style)
    text.append("".join(chars[at + 1 :]) + right, style="dim")
    return text


def changed_extent(old: Text | None, new: Text) -> int | None:
    """How many leading cells of a one-line ``new`` must be repainted to turn
    ``old`` into it: up to the last character that differs (text or style);
    None when nothing changed."""
    if old is None:
        return cell_len(new.plain)
    a, b = old.plain, new.plain
    if old.spans != new.spans or len(a) != len(b):
        return max(cell_len(a), cell_len(b))
    if a == b:
        return None
    last = max(i for i, (x, y) in enumerate(zip(a, b, strict=True)) if x != y)
    return max(cell_len(a[: last + 1]), cell_len(b[: last + 1]))


def bar_value(joint: Joint, column: int, width: int) -> float:
    """The joint value at ``column`` of a ``width``-cell bar (its ends are
    the limits; the inverse of where :func:`slider` puts the marker)."""
    inner = max(width, 5) - 2
    cell = min(inner - 1, max(0, column - 1))
    return joint.min + (joint.max - joint.min) * cell / max(inner - 1, 1)


class JointRow(Static):
    """One joint: label, bar, value. Repaints only when its own value changes,
    and then only the columns up to the last one that changed.

    The mouse, as on the seed's sliders: a click selects the joint, a click
    or drag on the bar asks for the value under the pointer, the wheel asks
    for a step; the screen decides (it rounds to the step, keeps the limits).
    """

    DEFAULT_CSS = """
    JointRow { height: 1; }
    JointRow.-selected { background: $accent 30%; text-style: bold; }
    """
    ALLOW_SELECT = False  # a drag moves the joint, not a text selection

    @dataclass
    class Picked(Message):
        """A click on the row (``value`` None) or on its bar, or a drag along
        the bar (``value``: the joint value under the pointer)."""

        row: JointRow
        value: float | None = None

        def can_replace(self, message: Message) -> bool:
            # a drag's newest position is the one that counts
            return (
                isinstance(message, JointRow.Picked)
                and message.row is self.row
                and message.value is not None
                and self.value is not None
            )

    @dataclass
    class Wheeled(Message):
        """The wheel over the row: ``steps`` steps up (> 0) or down."""

        row: JointRow
        steps: int

    def __init__(self, number: int, joint: Joint, units: str, value: float) -> None:
        super().__init__()
        self.number = number
        self.joint = joint
        self.units = units
        self.value = value
        self._shown: tuple[tuple[int, bool, bool], Text] | None = None
        self._dragging = False

    @property
    def index(self) -> int:
        """The joint's place in the robot (0-based)."""
        return self.number - 1

    def _bar_width(self) -> int:
        ascii = ascii_mode(self)
        return self.size.width - len(format_value(self.joint, self.value, self.units, ascii)) - 8

    def _value_at(self, x: int) -> float | None:
        """The value under column ``x``, or None off the bar."""
        width = max(self._bar_width(), 5)
        if BAR_START <= x < BAR_START + width:
            return bar_value(self.joint, x - BAR_START, width)
        return None

    def on_mouse_down(self, event: events.MouseDown) -> None:
        if event.button != 1:
            return
        value = self._value_at(event.x)
        self.post_message(self.Picked(self, value))
        if value is not None:
            self._dragging = True
            self.capture_mouse()

    def on_mouse_move(self, event: events.MouseMove) -> None:
        if self._dragging and self.app.mouse_captured is self:
            width = max(self._bar_width(), 5)
            column = min(max(event.x, BAR_START), BAR_START + width - 1)
            self.post_message(self.Picked(self, bar_value(self.joint, column - BAR_START, width)))

    def on_mouse_up(self, event: events.MouseUp) -> None:
        self._dragging = False
        self.release_mouse()

    def on_mouse_scroll_up(self, event: events.MouseScrollUp) -> None:
        event.stop()
        self.post_message(self.Wheeled(self, 1))

    def on_mouse_scroll_down(self, event: events.MouseScrollDown) -> None:
        event.stop()
        self.post_message(self.Wheeled(self, -1))

    def set_value(self, value: float) -> None:
        if value == self.value:
            return
        self.value = value
        before = self._shown
        if before is None or not self.is_mounted:
            self.refresh()
            return
        key, old = before
        new = self.render()
        if key != self._key():
            self.refresh()
            return
        extent = changed_extent(old, new)
        if extent is not None:
            self.refresh(Region(0, 0, min(extent, self.size.width), 1))

    def _key(self) -> tuple[int, bool, bool]:
        return (self.size.width, self.has_class("-selected"), ascii_mode(self))

    def render(self) -> Text:
        ascii = ascii_mode(self)
        label = self.joint.label(self.number)
        value_text = format_value(self.joint, self.value, self.units, ascii)
        bar_width = self._bar_width()
        at_limit = not self.joint.min < self.value < self.joint.max
        marker = (">" if ascii else "▶") if self.has_class("-selected") else " "
        text = Text(f"{marker} {label:<4} ")
        text.append_text(slider(self.joint, self.value, bar_width, ascii))
        text.append(value_text, style="bold red" if at_limit else "")
        self._shown = (self._key(), text)
        return text

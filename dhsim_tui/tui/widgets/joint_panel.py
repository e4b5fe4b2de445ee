"""The joints panel: one row per joint (:mod:`joint_row`), and joint jogging's keys.

It takes focus: while it has it, the arrows select and step joints, ``[ ]``
change the step and enter asks for a joint's exact value. The panel keeps
which joint is selected; what a key or the mouse asks of the arm it posts as
a message, and the screen answers by asking the core (it holds the robot and
the joint values, and hands them back with :meth:`JointPanel.show`).
"""

from __future__ import annotations

from dataclasses import dataclass

from textual import events
from textual.binding import Binding
from textual.containers import VerticalScroll
from textual.message import Message
from textual.reactive import reactive

from dhsim_tui.tui.keys import Keys
from dhsim_tui.tui.widgets.joint_row import JointRow, ascii_mode
from dhsim_tui.tui.widgets.stepping import (
    STEP_SIZE_BINDINGS,
    StepSizeRequested,
    arrow_bindings,
)

__all__ = ["JointPanel", "JointRow", "ascii_mode"]

SELECT = Keys("joint", help="select a joint")
STEP = Keys("step (shift ×10)", help="step the selected joint")
BIG_STEP = Keys(legend=False, help="ten steps at once")
ENTER = Keys("exact value", help="type the selected joint's exact value")

BINDINGS = [
    *arrow_bindings("joint", "select", "step", "Joint", "Step", (SELECT, STEP, BIG_STEP)),
    *STEP_SIZE_BINDINGS,
    Binding("enter", "ask_value", "Set", key_display="⏎", show=False, id="joint.enter",
            tooltip="Type the exact value of the selected joint", group=ENTER),
]  # fmt: skip


class JointPanel(VerticalScroll, can_focus=True, inherit_bindings=False):
    """The rows, scrolled to keep the selected joint in view."""

    DEFAULT_CSS = """
    JointPanel { height: auto; max-height: 100%; }
    """
    BINDINGS = BINDINGS

    selected: reactive[int] = reactive(0, init=False)

    @dataclass
    class Selected(Message):
        """Another joint was selected (a key or a click)."""

        index: int

    @dataclass
    class StepRequested(Message):
        """Step joint ``index`` by ``steps`` steps (negative: down). Presses
        that queue up in one direction add up into one request."""

        index: int
        steps: int

        def can_replace(self, message: Message) -> bool:
            if (
                isinstance(message, JointPanel.StepRequested)
                and message.index == self.index
                and (message.steps > 0) == (self.steps > 0)
            ):
                message.steps += self.steps  # this one is dropped: the later one carries it
                return True
            return False

    @dataclass
    class ValueRequested(Message):
        """Set joint ``index`` to ``value`` (a click or drag on its bar); a
        drag's newest position is the one that counts."""

        index: int
        value: float

        def can_replace(self, message: Message) -> bool:
            return isinstance(message, JointPanel.ValueRequested) and message.index == self.index

    @dataclass
    class ValueAsked(Message):
        """Enter: ask for joint ``index``'s exact value."""

        index: int

    def rows(self) -> list[JointRow]:
        if not hasattr(self, "_rows"):
            self._rows = list(self.query(JointRow))
        return self._rows

    def on_mount(self) -> None:
        self._mark(self.selected)

    # -- what the screen hands it ----------------------------------------------
    def show(self, q: tuple[float, ...]) -> None:
        for row, value in zip(self.rows(), q, strict=True):
            row.set_value(value)

    # -- keys --------------------------------------------------------------------
    def action_select(self, delta: int) -> None:
        if self.rows():
            self.selected = (self.selected + delta) % len(self.rows())

    def action_step(self, steps: int) -> None:
        self.post_message(self.StepRequested(self.selected, steps))

    def action_step_size(self, delta: int) -> None:
        self.post_message(StepSizeRequested(delta))

    def action_ask_value(self) -> None:
        self.post_message(self.ValueAsked(self.selected))

    def watch_selected(self, index: int) -> None:
        self._mark(index)
        self.post_message(self.Selected(index))

    def _mark(self, index: int) -> None:
        """The selected row marked ▶ (a changed class repaints that row only),
        the mark shown only while the panel jogs (is its screen's focus)."""
        jogging = self.is_attached and self.screen.focused is self
        for i, row in enumerate(self.rows()):
            row.set_class(i == index and jogging, "-selected")
            if i == index:
                self.scroll_to_widget(row, animate=False)

    def _on_hide(self, event: events.Hide) -> None:
        """Hidden (a maximised view, a terminal too small), it keeps the focus:
        its keys go on working, and come back with it (Textual's own would
        hand the focus on)."""
        event.prevent_default()

    def on_focus(self) -> None:
        self._mark(self.selected)

    def on_blur(self) -> None:
        self._mark(self.selected)

    # -- the mouse: the rows say where, the panel asks -----------------------------
    def on_joint_row_picked(self, message: JointRow.Picked) -> None:
        """A click selects the joint (and joint jogging); on its bar, or
        dragged along it, asks for the value under the pointer."""
        message.stop()
        self.focus()
        self.selected = message.row.index
        if message.value is not None:
            self.post_message(self.ValueRequested(message.row.index, message.value))

    def on_joint_row_wheeled(self, message: JointRow.Wheeled) -> None:
        """The wheel over a joint selects and steps it."""
        message.stop()
        self.focus()
        self.selected = message.row.index
        self.post_message(self.StepRequested(message.row.index, message.steps))

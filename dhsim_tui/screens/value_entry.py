"""A modal that asks for one number and only accepts a valid one."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.markup import escape
from textual.screen import ModalScreen
from textual.widgets import Input, Label

from dhsim_tui.core.errors import DhsimError


class ValueEntry(ModalScreen[Any]):
    """Type a value, ``enter`` to accept, ``escape`` to cancel (returns None).

    ``check`` turns the text into a value (a number, a name, a robot...) or
    raises DhsimError with the reason, which is shown under the input; the
    typed text is kept so it can be fixed, and nothing changes until a valid
    value is accepted.
    """

    BINDINGS = [
        Binding(
            "escape",
            "cancel",
            "Cancel",
            id="entry.cancel",
            tooltip="Close without changing anything",
        )
    ]
    DEFAULT_CSS = """
    ValueEntry { align: center middle; }
    ValueEntry > Vertical {
        width: 52; height: auto; border: round $accent; padding: 0 1;
        background: $surface;
    }
    ValueEntry Label { width: 100%; }
    ValueEntry #error { color: $error; }
    ValueEntry #hint { color: $text-muted; }
    """

    def __init__(self, title: str, value: str, hint: str, check: Callable[[str], Any]) -> None:
        super().__init__()
        self._title = title
        self._value = value
        self._hint = hint
        self._check = check

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = escape(self._title)
            yield Input(self._value, id="value", select_on_focus=True)
            yield Label(Text(self._hint), id="hint")
            yield Label("", id="error")

    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        try:
            value = self._check(event.value)
        except DhsimError as exc:
            self.query_one("#error", Label).update(Text(str(exc)))  # echoes user text
            return
        self.dismiss(value)

    def on_input_changed(self, event: Input.Changed) -> None:
        self.query_one("#error", Label).update("")

    def action_cancel(self) -> None:
        self.dismiss(None)

"""A modal that asks for one number and only accepts a valid one."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from rich.text import Text
from textual import events
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.markup import escape
from textual.widgets import Input, Label

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal.charset import shown
from dhsim_tui.tui.screens.modal import Dialog

#: the Input's own keys (ctrl+u, backspace, enter...) and what they do
_INPUT_ACTIONS = {binding.key: binding.action for binding in Binding.make_bindings(Input.BINDINGS)}


class OrderedInput(Input):
    """An Input that applies every key in the order it came.

    Textual lets a key bound on the Input (ctrl+u, backspace, enter) bubble
    up to the app before its binding runs, while a printable key is inserted
    at once: in a burst, "ctrl+u - 1 4" could clear the field after "-14"
    was typed. Here the Input runs its own bindings as the key arrives.
    """

    _typed = False  # a key reached it (its Focus event may come later)

    def _on_focus(self, event: events.Focus) -> None:
        """Select the text on focus (to type over it) only if nothing was
        typed yet: in a burst the Focus event can arrive after the first
        keys, and selecting then would let the next key replace them."""
        if self._typed:
            event.prevent_default()
            self._restart_blink()

    async def _on_key(self, event: events.Key) -> None:
        self._typed = True
        action = _INPUT_ACTIONS.get(event.key)
        if action is not None:
            event.stop()
            event.prevent_default()
            await self.run_action(action)


#: the longest title shown in the border (the box is 52 wide)
TITLE_LIMIT = 44


class ValueEntry(Dialog[Any]):
    """Type a value, ``enter`` to accept, ``escape`` to cancel (returns None).

    ``check`` turns the text into a value (a number, a name, a robot...) or
    raises DhsimError with the reason, which is shown under the input; the
    typed text is kept so it can be fixed, and nothing changes until a valid
    value is accepted.

    Type-ahead: the input has the focus from the moment the dialog exists, so
    keys typed while it is still being drawn go to it, in order, instead of
    to a screen with nothing focused (where they were lost or reordered).
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
        width: 52; max-width: 100%; height: auto; border: round $accent; padding: 0 1;
        background: $surface;
    }
    ValueEntry Label { width: 100%; }
    ValueEntry #error { color: $error; }
    ValueEntry #hint { color: $text-muted; }
    ValueEntry #live { color: $text; }
    """

    def __init__(
        self,
        title: str,
        value: str,
        hint: str,
        check: Callable[[str], Any],
        live: Callable[[str], str] | None = None,
    ) -> None:
        """``live``, when given, turns the text as it is typed into a line
        shown under the input (what the value would make of the robot: the
        home joint value an offset gives); "" shows nothing."""
        super().__init__()
        self._title = title
        self._hint = hint
        self._check = check
        self._live = live
        self._input = OrderedInput(value, id="value", select_on_focus=True)
        self.set_focus(self._input, scroll_visible=False)

    def compose(self) -> ComposeResult:
        title = shown(printable(self._title))
        with Vertical() as box:
            if len(title) <= TITLE_LIMIT:
                box.border_title = escape(title)
            else:  # too long for the border: shown whole, wrapped, above the input
                yield Label(Text(title), id="title")
            yield self._input
            if self._live is not None:
                yield Label(self._live_text(self._input.value), id="live")
            yield Label(Text(shown(printable(self._hint))), id="hint")
            yield Label("", id="error")

    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        try:
            value = self._check(event.value)
        except DhsimError as exc:
            error = shown(printable(str(exc)))  # echoes user text
            self.query_one("#error", Label).update(Text(error))
            return
        self.dismiss(value)

    def on_input_changed(self, event: Input.Changed) -> None:
        self.query_one("#error", Label).update("")
        if self._live is not None:
            self.query_one("#live", Label).update(self._live_text(event.value))

    def _live_text(self, text: str) -> Text:
        assert self._live is not None
        try:
            line = self._live(text)
        except DhsimError:
            line = ""  # not a value yet: enter says why
        return Text(shown(printable(line)))

    def action_cancel(self) -> None:
        self.dismiss(None)

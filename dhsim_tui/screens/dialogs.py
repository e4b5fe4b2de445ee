"""Small modal questions: yes/no, one of several, and the unsaved-changes guard."""

from __future__ import annotations

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.markup import escape
from textual.screen import ModalScreen
from textual.widgets import Label, OptionList
from textual.widgets.option_list import Option

DIALOG_CSS = """
    {name} {{ align: center middle; }}
    {name} > Vertical {{
        width: 60; max-width: 100%; height: auto; max-height: 100%;
        border: round $accent; background: $surface; padding: 0 1;
    }}
    {name} OptionList {{ height: auto; max-height: 16; border: none; padding: 0; }}
    {name} .hint {{ color: $text-muted; }}
"""


class Confirm(ModalScreen[bool]):
    """A yes/no question: ``y`` or ``enter`` for yes, ``n`` or ``escape`` for no."""

    BINDINGS = [
        Binding("y,enter", "answer(True)", "Yes", id="confirm.yes", tooltip="Yes"),
        Binding("n,escape", "answer(False)", "No", id="confirm.no", tooltip="No"),
    ]
    DEFAULT_CSS = DIALOG_CSS.format(name="Confirm")

    def __init__(self, question: str, title: str = "Are you sure?") -> None:
        super().__init__()
        self._question = question
        self._title = title

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = escape(self._title)
            yield Label(Text(self._question))
            yield Label("y yes · n no", classes="hint")

    def action_answer(self, yes: bool) -> None:
        self.dismiss(yes)


class Choice(ModalScreen[str | None]):
    """Pick one of ``choices`` with the arrows and ``enter``; ``escape`` cancels."""

    BINDINGS = [Binding("escape", "cancel", "Cancel", id="choice.cancel", tooltip="Cancel")]
    DEFAULT_CSS = DIALOG_CSS.format(name="Choice")

    def __init__(
        self, title: str, choices: list[tuple[str, str]], current: str | None = None, hint: str = ""
    ) -> None:
        """``choices`` are (value, what the user reads)."""
        super().__init__()
        self._title = title
        self._choices = choices
        self._current = current
        self._hint = hint

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = escape(self._title)
            options = OptionList(*(Option(Text(text), id=value) for value, text in self._choices))
            yield options
            yield Label(self._hint or "↑↓ choose · enter picks · escape cancels", classes="hint")

    def on_mount(self) -> None:
        options = self.query_one(OptionList)
        values = [value for value, _ in self._choices]
        if self._current in values:
            options.highlighted = values.index(self._current)
        options.focus()

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        event.stop()
        self.dismiss(event.option.id)

    def action_cancel(self) -> None:
        self.dismiss(None)


class SaveGuard(ModalScreen[str]):
    """Unsaved changes: ``s`` save, ``d`` discard, ``escape`` stay."""

    BINDINGS = [
        Binding("s", "answer('save')", "Save", id="guard.save", tooltip="Save, then go on"),
        Binding(
            "d",
            "answer('discard')",
            "Discard",
            id="guard.discard",
            tooltip="Throw the changes away, then go on",
        ),
        Binding(
            "escape,c", "answer('stay')", "Stay", id="guard.stay", tooltip="Go back to the editor"
        ),
    ]
    DEFAULT_CSS = DIALOG_CSS.format(name="SaveGuard")

    def __init__(self, name: str, doing: str) -> None:
        super().__init__()
        self._name = name
        self._doing = doing

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = "Unsaved changes"
            yield Label(
                Text(f"{self._name} has changes that are not saved. Save before {self._doing}?")
            )
            yield Label("s save · d discard · escape stay", classes="hint")

    def action_answer(self, answer: str) -> None:
        self.dismiss(answer)

"""The help screen: every key of the screen that opened it."""

from __future__ import annotations

from rich.table import Table
from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import VerticalScroll
from textual.markup import escape
from textual.widgets import Static

from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal.charset import shown
from dhsim_tui.tui.screens.modal import Dialog


class HelpScreen(Dialog[None]):
    """Lists (keys, what they do); any of escape, ``?`` or ``q`` closes it."""

    BINDINGS = [
        Binding(
            "escape,question_mark,q",
            "close",
            "Close",
            id="help.close",
            tooltip="Back to the simulator",
        ),
    ]
    DEFAULT_CSS = """
    HelpScreen { align: center middle; }
    HelpScreen > VerticalScroll {
        width: 70; max-width: 100%; height: auto; max-height: 100%;
        border: round $accent; background: $surface; padding: 0 1;
    }
    """

    def __init__(self, title: str, rows: list[tuple[str, str]], notes: str = "") -> None:
        super().__init__()
        self._title = title
        self._rows = rows
        self._notes = notes

    def compose(self) -> ComposeResult:
        table = Table.grid(padding=(0, 2))
        table.add_column(style="bold")
        table.add_column()
        for keys, text in self._rows:  # pose names: escaped; ASCII in ASCII mode
            table.add_row(Text(shown(printable(keys))), Text(shown(printable(text))))
        with VerticalScroll() as box:
            box.border_title = escape(shown(printable(self._title)))
            box.border_subtitle = "escape closes"
            yield Static(table)
            if self._notes:  # written here, not read
                yield Static(Text(shown(self._notes)), classes="notes")

    def action_close(self) -> None:
        self.dismiss(None)

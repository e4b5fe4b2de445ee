"""What is behind the first question of ``dhsim new`` and ``dhsim edit``:
a plain screen, not a simulator of a robot that is not the one being made
(``dhsim new`` showed a one-joint arm behind "number of joints")."""

from __future__ import annotations

from textual.app import ComposeResult
from textual.screen import Screen
from textual.widgets import Static


class StartScreen(Screen[None]):
    """An empty screen with a line saying what is being opened; the app
    replaces it with the simulator when the editor is left."""

    DEFAULT_CSS = """
    StartScreen { align: center middle; }
    StartScreen Static { width: auto; color: $text-muted; }
    """

    def __init__(self, what: str) -> None:
        super().__init__()
        self._what = what

    def compose(self) -> ComposeResult:
        yield Static(self._what, markup=False)

"""The program's plot (``t`` on the program panel): the joints and the tool
speed against time, with a cursor at the time played, drawn with plotext
(:mod:`dhsim_tui.render.program_plot`); escape, ``t`` or ``q`` closes it."""

from __future__ import annotations

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.widgets import Static

from dhsim_tui.render.program_plot import plot_text
from dhsim_tui.tui.screens.modal import Dialog
from dhsim_tui.tui.widgets.view_style import look_of


class ProgramPlot(Dialog[None]):
    """A playback's trajectory and problems, at the time played."""

    BINDINGS = [
        Binding("escape,t,q", "close", "Close", id="plot.close", tooltip="Back to the simulator"),
    ]
    DEFAULT_CSS = """
    ProgramPlot { align: center middle; }
    ProgramPlot > Vertical {
        width: 100%; height: 100%; border: round $accent; background: $surface;
    }
    """

    def __init__(self, title: str, trajectory, problems, cursor: float) -> None:
        super().__init__()
        self._title = title
        self._trajectory = trajectory
        self._problems = problems
        self._cursor = cursor

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = self._title
            box.border_subtitle = "escape closes"
            yield Static(id="plot")

    def on_mount(self) -> None:
        look = look_of(self.app)
        width, height = self.app.size
        text = plot_text(
            self._trajectory,
            self._problems,
            max(width - 2, 40),  # the box's inside
            max(height - 2, 16),
            colour=not look.mono,
            ascii=look.ascii,
            cursor=self._cursor,
        )
        self.query_one("#plot", Static).update(Text.from_ansi(text))

    def action_close(self) -> None:
        self.dismiss(None)

"""The three views of the arm (and a legend), as one panel both screens use."""

from __future__ import annotations

from textual.app import ComposeResult
from textual.containers import Container
from textual.widgets import Static

from dhsim_tui.scene import VIEWS, Wireframe, project
from dhsim_tui.widgets.arm_view import ArmView, PlotextArmView

#: at and above this size a screen shows all three views at once
WIDE_SIZE = (120, 36)


def is_wide(width: int, height: int) -> bool:
    return width >= WIDE_SIZE[0] and height >= WIDE_SIZE[1]


LEGEND = (
    "[b]Frames[/]  [bold ansi_bright_red]━━[/] x   [bold ansi_bright_green]━━[/] y   "
    "[bold ansi_bright_blue]━━[/] z   [bold ansi_bright_magenta]◆[/] tool\n"
    "links ━━   pedestal [ansi_yellow]━━[/]   floor [ansi_bright_black]┄┄[/]\n\n"
)


class ViewsPanel(Container):
    """Top, front and side views. Narrow: the selected one; wide (the screen
    has class ``-wide``): all three in a grid with the legend."""

    def __init__(self, renderer: str = "braille", keys: str = "", *, id: str | None = None):
        super().__init__(id=id, classes="views-panel")
        self.renderer = renderer
        self.keys = keys
        self.selected = 1

    def compose(self) -> ComposeResult:
        view_class = PlotextArmView if self.renderer == "plotext" else ArmView
        for view in VIEWS:
            yield view_class(view, id=f"view-{view.key}")
        yield Static(LEGEND + self.keys, classes="legend")

    def on_mount(self) -> None:
        self._views = [self.query_one(f"#view-{view.key}") for view in VIEWS]
        self.select(self.selected)

    @property
    def views(self) -> list[ArmView | PlotextArmView]:
        return self._views

    def show(self, wire: Wireframe) -> None:
        """Project the wireframe into every view (hidden ones are cheap)."""
        for view, widget in zip(VIEWS, self._views, strict=True):
            widget.show(project(wire, view))

    def select(self, index: int) -> None:
        self.selected = index % len(VIEWS)
        for i, widget in enumerate(self._views):
            widget.set_class(i == self.selected, "-selected")

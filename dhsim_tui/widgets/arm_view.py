"""One orthographic view of the arm: a braille canvas (default) or plotext."""

from __future__ import annotations

from rich.segment import Segment
from rich.style import Style
from rich.text import Text
from textual.app import RenderResult
from textual.geometry import Region
from textual.strip import Strip
from textual.widget import Widget
from textual_plotext import PlotextPlot

from dhsim_tui.scene import View, ViewScene, equal_scale_limits
from dhsim_tui.scene.raster import Raster, rasterize

#: terminal colours of the scene's colour names (ANSI, so every terminal has them)
STYLES = {
    "red": Style(color="bright_red"),
    "green": Style(color="bright_green"),
    "blue": Style(color="bright_blue"),
    "yellow": Style(color="yellow"),
    "gray": Style(color="bright_black"),
    "default": Style(),
    "magenta": Style(color="bright_magenta", bold=True),
}
#: the same colours in plotext's names
PLOTEXT_COLOURS = {
    "red": "red+",
    "green": "green+",
    "blue": "blue+",
    "yellow": "orange",
    "gray": "gray",
    "default": "default",
    "magenta": "magenta+",
}

VIEW_CSS = """
    {name} {{
        border: round $panel-lighten-2;
        border-title-color: $text-muted;
    }}
    {name}.-selected {{ border: round $accent; border-title-color: $accent; }}
"""


class ArmView(Widget):
    """A view of the wireframe, same scale on both axes, as braille dots.

    The raster is recomputed only when the scene or the widget's size
    changes, and each row is painted from it as one strip.
    """

    DEFAULT_CSS = VIEW_CSS.format(name="ArmView")

    def __init__(self, view: View, *, id: str | None = None) -> None:
        super().__init__(id=id, classes="view")
        self.view = view
        self.border_title = view.caption
        self._scene: ViewScene | None = None
        self._raster: Raster | None = None
        self._strips: dict[int, Strip] = {}
        self._base_style = Style()

    @property
    def scene(self) -> ViewScene | None:
        return self._scene

    @property
    def raster(self) -> Raster | None:
        """What is on screen now (for tests and screenshots)."""
        return self._raster

    def show(self, scene: ViewScene) -> None:
        """Draw this scene, repainting only the rows that differ from the last one."""
        self._scene = scene
        old = self._raster
        width, height = self.size
        if old is None or old.colours.shape != (height, width) or not self.is_mounted:
            self._raster = None
            self._show_scale()
            self.refresh()
            return
        new = rasterize(scene, width, height)
        if new.xlim != old.xlim or new.ylim != old.ylim:
            self._show_scale()
        if new.palette != old.palette:
            changed = list(range(height))
        else:
            recoloured = (new.colours != old.colours).any(axis=1)
            changed = [y for y in range(height) if recoloured[y] or new.lines[y] != old.lines[y]]
        self._raster = new
        for y in changed:
            self._strips.pop(y, None)
            self.refresh(Region(0, y, width, 1))

    def _current(self) -> Raster | None:
        width, height = self.size
        if self._scene is None or width < 2 or height < 2:
            return None
        if self._raster is None or self._raster.colours.shape != (height, width):
            self._raster = rasterize(self._scene, width, height)
            self._strips = {}
            self._base_style = self.rich_style
        return self._raster

    def _show_scale(self) -> None:
        """The length of one terminal column, in the robot's unit, under the view."""
        width, height = self.size
        if self._scene is None or width < 2 or height < 2:
            return
        xlim, _ = equal_scale_limits(self._scene.bounds, width, height)
        per_col = 2 * (xlim[1] - xlim[0]) / (2 * width - 1)
        scale = f"1 col = {per_col:.3g} {self._scene.units}".rstrip()
        if self.border_subtitle != scale:
            self.border_subtitle = scale

    def on_resize(self) -> None:
        self._show_scale()

    def render_line(self, y: int) -> Strip:
        raster = self._current()
        if raster is None or y >= len(raster.lines):
            return Strip.blank(self.size.width)
        strip = self._strips.get(y)
        if strip is None:
            strip = self._strips[y] = self._paint(raster, y)
        return strip

    def _paint(self, raster: Raster, y: int) -> Strip:
        base = self._base_style
        line, colours = raster.lines[y], raster.colours[y].tolist()
        segments: list[Segment] = []
        start = 0
        for x in range(1, len(line) + 1):
            if x == len(line) or colours[x] != colours[start]:
                colour = colours[start]
                style = base if colour < 0 else base + STYLES[raster.palette[colour]]
                segments.append(Segment(line[start:x], style))
                start = x
        return Strip(segments, len(line))


class PlotextArmView(PlotextPlot):
    """The same view drawn by plotext (``dhsim --renderer plotext``).

    Kept for comparison: plotext rebuilds its whole canvas on every change,
    10-15 ms a view here, which is why the braille canvas is the default.
    """

    DEFAULT_CSS = VIEW_CSS.format(name="PlotextArmView")

    def __init__(self, view: View, *, id: str | None = None) -> None:
        super().__init__(id=id, classes="view")
        self.view = view
        self.border_title = view.caption
        self._scene: ViewScene | None = None
        self._cache: tuple[tuple, Text] | None = None
        self.plt.frame(False)
        self.plt.xticks([])
        self.plt.yticks([])

    @property
    def scene(self) -> ViewScene | None:
        return self._scene

    def show(self, scene: ViewScene) -> None:
        self._scene = scene
        self.refresh()

    def render(self) -> RenderResult:
        scene = self._scene
        width, height = self.size
        if scene is None or width < 2 or height < 2:
            return ""
        key = (id(scene), width, height, self.app.theme)
        if self._cache is not None and self._cache[0] == key:
            return self._cache[1]
        xlim, ylim = equal_scale_limits(scene.bounds, width, height)
        plt = self.plt
        plt.clear_data()
        plt.xlim(*xlim)
        plt.ylim(*ylim)
        for line in scene.lines:
            plt.plot(line.xs, line.ys, marker="braille", color=PLOTEXT_COLOURS[line.colour])
        plt.scatter(
            [scene.end_effector[0]],
            [scene.end_effector[1]],
            marker="◆",
            color=PLOTEXT_COLOURS["magenta"],
        )
        text = super().render()
        assert isinstance(text, Text)
        self._cache = (key, text)
        return text

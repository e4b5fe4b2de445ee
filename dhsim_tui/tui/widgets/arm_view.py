"""One view of the arm: a picture (plotext's, or bare braille) painted row by
row, repainting only the cells that changed since the last frame."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from rich.segment import Segment
from rich.style import Style
from rich.text import Text
from textual import events
from textual.geometry import Region
from textual.message import Message
from textual.strip import Strip
from textual.widget import Widget

from dhsim_tui.render.cloud import CloudLayer
from dhsim_tui.render.picture import NO_ROLE, Framing, Look, Picture
from dhsim_tui.render.plotext_picture import PlotextPainter, bare_picture
from dhsim_tui.scene import View, ViewScene
from dhsim_tui.scene.cloud import ViewCloud
from dhsim_tui.tui.widgets.view_style import look_of, role_styles

RENDERERS = ("plotext", "braille")


def caption(view: View, ascii: bool = False) -> str:
    """The view's name, the world axes its picture runs along, and its key."""
    if view.is_3d:
        return f"{view.title}  ({view.number})"
    right, up = view.axis_names
    arrows = ("> ", "^") if ascii else ("→ ", "↑")
    return f"{view.title}  {right}{arrows[0]}{up}{arrows[1]}  ({view.number})"


class ArmView(Widget):
    """A view of the wireframe, the same scale on both axes.

    ``show`` takes the scene and where to look; the picture is rebuilt at
    once when the view is on screen (else when it next is), and only the
    changed run of each row is refreshed, so a joint step repaints a few
    cells rather than the whole view.
    """

    DEFAULT_CSS = """
    ArmView {
        border: round $panel-lighten-2;
        border-title-color: $text-muted;
        border-subtitle-color: $text-muted;
    }
    ArmView.-selected { border: round $accent; border-title-color: $accent; }
    """
    #: a drag orbits the 3-D view: no text selection in the pictures
    ALLOW_SELECT = False

    @dataclass
    class Pressed(Message):
        """A click on the view: select it (``double``: and maximise it)."""

        view: ArmView
        double: bool = False

    @dataclass
    class Wheel(Message):
        """The mouse wheel over the view: zoom in (steps > 0) or out."""

        view: ArmView
        steps: int

    @dataclass
    class Dragged(Message):
        """The mouse moved this far (cells) with the button held down."""

        view: ArmView
        dx: int
        dy: int

        def can_replace(self, message: Message) -> bool:
            return False  # every part of a drag counts: they add up

    def __init__(self, view: View, renderer: str = "plotext", *, id: str | None = None) -> None:
        super().__init__(id=id, classes="view")
        self.view = view
        self.renderer = renderer
        self._painter = PlotextPainter() if renderer == "plotext" else None
        self._scene: ViewScene | None = None
        self._framing: Framing | None = None
        self._cloud: ViewCloud | None = None  # the workspace, drawn behind the arm
        self._cloud_layer = CloudLayer()
        self._picture: Picture | None = None
        self._stale = True  # the picture does not show the latest scene
        self._strips: dict[int, Strip] = {}
        self._styles: list[Style] | None = None
        self._base_style = Style()
        self._drag_from: tuple[int, int] | None = None

    # -- what the rest of the app sees ---------------------------------------
    @property
    def scene(self) -> ViewScene | None:
        return self._scene

    @property
    def picture(self) -> Picture | None:
        """What is on screen now (tests and screenshots)."""
        return self._picture

    @property
    def look(self) -> Look:
        return look_of(self.app)

    def on_mount(self) -> None:
        self.border_title = caption(self.view, self.look.ascii)

    @property
    def cloud(self) -> ViewCloud | None:
        return self._cloud

    def show(self, scene: ViewScene, framing: Framing, cloud: ViewCloud | None = None) -> None:
        """Draw this scene, over ``cloud`` if given (the workspace, faint,
        behind everything); repaint only the cells that differ from the last."""
        self._scene, self._framing, self._cloud = scene, framing, cloud
        self._stale = True
        if self.is_mounted and self.display and self._picture is not None:
            self._redraw()

    def restyle(self) -> None:
        """The theme or colour mode changed: repaint every row."""
        self._styles = None
        self._strips.clear()
        self.refresh()

    # -- drawing --------------------------------------------------------------
    def _draw(self) -> Picture | None:
        width, height = self.size
        if self._scene is None or self._framing is None or width < 2 or height < 2:
            return None
        look = self.look
        if self._painter is None:
            picture = bare_picture(self._scene, width, height, self._framing, look)
        else:
            picture = self._painter.draw(self._scene, width, height, self._framing, look)
        return self._cloud_layer.under(picture, self._cloud, look)

    def _redraw(self) -> None:
        old = self._picture
        new = self._draw()
        self._stale = False
        if new is None or old is None or new.size != old.size:
            self._picture = new
            self._strips.clear()
            self.refresh()
            return
        self._picture = new
        changed_roles = new.roles != old.roles
        width = new.size[0]
        for y, (before, after) in enumerate(zip(old.lines, new.lines, strict=True)):
            row_roles = changed_roles[y]
            if before == after and not row_roles.any():
                continue
            differs = np.frombuffer(before.encode("utf-32-le"), np.uint32) != np.frombuffer(
                after.encode("utf-32-le"), np.uint32
            )
            columns = np.flatnonzero(differs | row_roles)
            self._strips.pop(y, None)
            start, end = int(columns[0]), int(columns[-1]) + 1
            self.refresh(Region(start, y, min(end, width) - start, 1))

    def _current(self) -> Picture | None:
        width, height = self.size
        if self._stale or self._picture is None or self._picture.size != (width, height):
            self._picture = self._draw()
            self._stale = False
            self._strips.clear()
        return self._picture

    def on_resize(self) -> None:
        self._stale = True
        self._strips.clear()

    def render_line(self, y: int) -> Strip:
        picture = self._current()
        width = self.size.width
        if picture is None or y >= len(picture.lines):
            return Strip.blank(width)
        strip = self._strips.get(y)
        if strip is None:
            strip = self._strips[y] = self._paint(picture, y)
        return strip

    def _paint(self, picture: Picture, y: int) -> Strip:
        """One row as runs of equal style: one segment per run, not per glyph."""
        if self._styles is None:
            app = self.app
            self._base_style = self.rich_style
            self._styles = [
                self._base_style + style
                for style in role_styles(
                    app.console.color_system,
                    ansi_theme=app.current_theme.ansi,
                    mono=self.look.mono,
                )
            ]
        styles, base = self._styles, self._base_style
        line, roles = picture.lines[y], picture.roles[y].tolist()
        segments: list[Segment] = []
        start = 0
        for x in range(1, len(line) + 1):
            if x == len(line) or roles[x] != roles[start]:
                role = roles[start]
                segments.append(Segment(line[start:x], base if role == NO_ROLE else styles[role]))
                start = x
        return Strip(segments, len(line))

    # -- the mouse -----------------------------------------------------------
    def on_click(self, event: events.Click) -> None:
        event.stop()
        self.post_message(self.Pressed(self, double=event.chain == 2))

    def on_mouse_scroll_up(self, event: events.MouseScrollUp) -> None:
        event.stop()
        self.post_message(self.Wheel(self, 1))

    def on_mouse_scroll_down(self, event: events.MouseScrollDown) -> None:
        event.stop()
        self.post_message(self.Wheel(self, -1))

    def on_mouse_down(self, event: events.MouseDown) -> None:
        if event.button == 1:
            self._drag_from = (event.screen_x, event.screen_y)
            self.capture_mouse()

    def on_mouse_move(self, event: events.MouseMove) -> None:
        start = self._drag_from
        if start is None or self.app.mouse_captured is not self:
            return
        dx, dy = event.screen_x - start[0], event.screen_y - start[1]
        if dx or dy:
            self._drag_from = (event.screen_x, event.screen_y)
            self.post_message(self.Dragged(self, dx, dy))

    def on_mouse_up(self, event: events.MouseUp) -> None:
        self._drag_from = None
        self.release_mouse()

    def describe(self) -> Text:
        """The picture as plain text (for tests)."""
        return Text("\n".join(self._picture.lines) if self._picture else "")

"""The four views of the arm (top, front, side, 3-D) and a one-line legend.

Narrow terminals show the selected view; from 120×36 all four share a 2×2
grid, and ``maximise`` gives the selected one the whole panel. The three
orthographic views share one scale (100 mm is as many columns in each),
the seed's work area by default; ``zoom`` narrows it about the arm.
``set_cloud`` lays a cloud of points (the workspace) faintly behind the arm
in every view; it is projected once per cloud and orbit, and rasterised once
per zoom and size, so a joint step costs what it did without it.
"""

from __future__ import annotations

import numpy as np
from rich.style import Style
from rich.text import Text
from textual.app import ComposeResult
from textual.containers import Container
from textual.widgets import Static

from dhsim_tui.render.picture import CELL_ROLES, Framing
from dhsim_tui.scene import VIEWS, Wireframe, project
from dhsim_tui.scene.cloud import ViewCloud, project_cloud, projection_key
from dhsim_tui.scene.oblique import Orbit, project_oblique, view_point
from dhsim_tui.scene.projection import ORTHO_VIEWS, View, ViewScene, per_dot_needed
from dhsim_tui.terminal import ascii_mode
from dhsim_tui.widgets.arm_view import ArmView
from dhsim_tui.widgets.view_style import look_of, role_styles

#: at and above this size a screen shows all four views at once
WIDE_SIZE = (120, 36)
#: zoom factors: each + or - multiplies or divides by ZOOM_STEP, within these
ZOOM_STEP = 1.5
ZOOM_RANGE = (1 / 4, 64.0)
#: room the axes take in a plotext view: y labels and axis, x axis and labels
AXES_ROOM = (7, 2)


def is_wide(width: int, height: int) -> bool:
    return width >= WIDE_SIZE[0] and height >= WIDE_SIZE[1]


#: the legend's entry for the workspace cloud: ASCII, mono, colour
CLOUD_LEGEND = ("   . workspace", "   · workspace", "⢕", " workspace")


def legend(ascii: bool, mono: bool, styles: dict[str, Style], cloud: bool = False) -> Text:
    """One line, never wrapped: what each mark means, in the views' own styles
    (and the workspace cloud's, when it is shown)."""
    text = _legend(ascii, mono, styles)
    if cloud:
        if ascii or mono:
            text.append(CLOUD_LEGEND[0 if ascii else 1])
        else:
            text.append("   ")
            text.append(CLOUD_LEGEND[2], styles["cloud"])
            text.append(CLOUD_LEGEND[3])
    return text


def _legend(ascii: bool, mono: bool, styles: dict[str, Style]) -> Text:
    if ascii:
        return Text("axes x y z   @ tool   # links   : pedestal   _ floor")
    if mono:
        return Text("axes: letters x y z at their tips   ◆ tool   ━ links   ┄ floor")
    return Text.assemble(
        ("axes ", "bold"),
        ("━", styles["x"]),
        " x  ",
        ("━", styles["y"]),
        " y  ",
        ("━", styles["z"]),
        " z   ",
        ("◆", styles["tool"]),
        " tool   ━ links   ",
        ("━", styles["pedestal"]),
        " pedestal   ",
        ("┄", styles["floor"]),
        " floor",
    )


class ViewsPanel(Container):
    """Top, front, side and 3-D views of the same wireframe."""

    DEFAULT_CSS = """
    ViewsPanel .legend { height: 1; padding: 0 1; color: $text-muted; }
    """

    def __init__(self, renderer: str = "plotext", *, id: str | None = None):
        super().__init__(id=id, classes="views-panel")
        self.renderer = renderer
        self.selected = 1
        self.zoom = 1.0
        self.orbit = Orbit()
        self.maximised = False
        self._zoom_centre: np.ndarray | None = None  # world point zoomed about
        self._wire: Wireframe | None = None
        self._legend_width = 0
        self._cloud: np.ndarray | None = None  # world points (n, 3), or none shown
        self._cloud_version = 0  # a new number for every set_cloud
        self._view_clouds: dict[str, ViewCloud] = {}  # per view key, as projected

    def compose(self) -> ComposeResult:
        with Container(classes="views-grid"):
            for view in VIEWS:
                yield ArmView(view, self.renderer, id=f"view-{view.key}")
        yield Static("", classes="legend")

    def on_mount(self) -> None:
        self._views = list(self.query(ArmView))
        self._show_legend()
        self.select(self.selected)
        self.watch(self.app, "theme", self._restyle, init=False)

    def _show_legend(self) -> None:
        app, look = self.app, look_of(self.app)
        styles = role_styles(app.console.color_system, ansi_theme=app.current_theme.ansi)
        text = legend(
            look.ascii,
            look.mono,
            dict(zip(CELL_ROLES, styles, strict=True)),
            cloud=self._cloud is not None,
        )
        self._legend_width = text.cell_len
        self.query_one(".legend", Static).update(text)
        self._fit_legend()

    def _fit_legend(self) -> None:
        """The legend is one line or nothing: never wrapped, never cut."""
        self.set_class(self.size.width < self._legend_width + 2, "-cramped")

    def _restyle(self) -> None:
        """A new theme: the views and legend take its colours (ANSI or not)."""
        self._show_legend()
        for widget in self._views:
            widget.restyle()

    @property
    def views(self) -> list[ArmView]:
        return self._views

    @property
    def selected_view(self) -> View:
        return VIEWS[self.selected]

    # -- what is drawn ------------------------------------------------------
    def show(self, wire: Wireframe) -> None:
        """Project the wireframe into every view at one scale."""
        self._wire = wire
        scenes = [project(wire, view) for view in ORTHO_VIEWS]
        scenes.append(project_oblique(wire, self.orbit))
        framings = self._framings(scenes)
        for widget, scene, framing in zip(self._views, scenes, framings, strict=True):
            widget.show(scene, framing, self._view_cloud(widget.view, wire))
        self._show_zoom()

    # -- the workspace cloud ------------------------------------------------
    @property
    def cloud(self) -> np.ndarray | None:
        """The points shown behind the arm (world, robot units), or None."""
        return self._cloud

    def set_cloud(self, points: np.ndarray | None) -> None:
        """Show ``points`` (n, 3: world positions in the robot's unit, e.g.
        ``core.workspace.sample_positions``) faintly behind the arm in every
        view, with a legend entry; ``None`` takes them away again."""
        if points is None:
            cloud = None
        else:
            cloud = np.asarray(points, dtype=float).reshape(-1, 3)
            cloud = cloud[np.isfinite(cloud).all(axis=1)]
        if cloud is None and self._cloud is None:
            return
        self._cloud = cloud
        self._cloud_version += 1
        self._view_clouds.clear()
        if self.is_mounted:
            self._show_legend()
        self._redraw()

    def _view_cloud(self, view: View, wire: Wireframe) -> ViewCloud | None:
        """The cloud in this view's picture plane, projected again only when
        the cloud, the orbit (3-D) or the work area changed."""
        if self._cloud is None:
            return None
        cached = self._view_clouds.get(view.key)
        key = projection_key(view, wire.area, self.orbit, self._cloud_version)
        if cached is None or cached.key != key:
            cached = project_cloud(self._cloud, view, wire.area, self.orbit, self._cloud_version)
            self._view_clouds[view.key] = cached
        return cached

    def _canvas(self) -> tuple[int, int]:
        """The plot area of a view (all views are the same size)."""
        widget = self._views[self.selected]
        width, height = widget.size
        if width < 2 or height < 2:
            width, height = 40, 18
        if self.renderer == "plotext":
            width, height = width - AXES_ROOM[0], height - AXES_ROOM[1]
        return max(width, 2), max(height, 2)

    def _framings(self, scenes: list[ViewScene]) -> list[Framing]:
        cols, rows = self._canvas()
        ortho = max(per_dot_needed(s.bounds, cols, rows) for s in scenes[:3]) / self.zoom
        iso = per_dot_needed(scenes[3].bounds, cols, rows) / self.zoom
        framings = []
        for scene in scenes:
            view = scene.view
            if self._zoom_centre is not None and self._wire is not None:
                centre = view_point(self._wire, view, self.orbit, self._zoom_centre)
            else:
                b = scene.bounds
                centre = ((b[0] + b[1]) / 2, (b[2] + b[3]) / 2)
            framings.append(Framing(centre, iso if view.is_3d else ortho))
        return framings

    def _redraw(self) -> None:
        if self._wire is not None:
            self.show(self._wire)

    def _show_zoom(self) -> None:
        for widget in self._views:
            scene = widget.scene
            parts = []
            if widget.view.is_3d:
                parts.append(self.orbit.ascii_label if ascii_mode(self.app) else self.orbit.label)
                if scene is not None and scene.grid_step:
                    parts.append(f"grid {scene.grid_step:g} {scene.units}".rstrip())
            if self.zoom != 1.0:
                parts.append(f"zoom {self.zoom:.3g}x")
            subtitle = "  ".join(parts)
            if widget.border_subtitle != subtitle:
                widget.border_subtitle = subtitle

    # -- keys ---------------------------------------------------------------
    def select(self, index: int) -> None:
        self.selected = index % len(VIEWS)
        for i, widget in enumerate(self._views):
            widget.set_class(i == self.selected, "-selected")

    def toggle_maximise(self) -> bool:
        """The selected view alone, over the whole screen (the screen's
        ``-max`` class hides everything else); again: back."""
        self.maximised = not self.maximised
        self.screen.set_class(self.maximised, "-max")
        return self.maximised

    def zoom_by(self, steps: int) -> None:
        """Zoom in (steps > 0) or out about the arm as it is now."""
        if self._wire is None:
            return
        if self._zoom_centre is None:
            points = np.vstack([self._wire.links, self._wire.origins])
            self._zoom_centre = (points.min(axis=0) + points.max(axis=0)) / 2
        self.zoom = float(np.clip(self.zoom * ZOOM_STEP**steps, *ZOOM_RANGE))
        self._redraw()

    def reset_zoom(self) -> None:
        """Back to the seed's work area: reach + 30 on every side, floor at -h."""
        self.zoom = 1.0
        self._zoom_centre = None
        self._redraw()

    def orbit_by(self, d_azimuth: float, d_elevation: float) -> None:
        self.orbit = self.orbit.turned(d_azimuth, d_elevation)
        self._redraw()

    def on_resize(self) -> None:
        self._fit_legend()
        self.call_after_refresh(self._redraw)

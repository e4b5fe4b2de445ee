"""The four views of the arm (top, front, side, 3-D) and a one-line legend.

Narrow terminals show the selected view; from 120×36 all four share a 2×2
grid, and ``maximise`` gives the selected one the whole panel. The panel
owns what the views show and how: which is selected, maximised, the zoom,
the 3-D orbit, which frames' axes are drawn and whether the views are fitted
to the arm (as they open, and ``F``) or show the work area (``0``, ``F``).
Its views post what the mouse does (a click selects, a double click
maximises, the wheel zooms, a drag orbits the 3-D view) and the panel acts
on it; what the screen must know comes back as messages.

Framing: the views open fitted, each framed on the arm as it stands (and on
the program's path while one is drawn), with a small margin, and keep that
framing while the arm moves inside it: a student sees the robot before
pressing a key. The work area (``0``, or ``F`` again): the three
orthographic views share one scale (100 mm is as many columns in each) and
show the seed's work area, and the 3-D view the floor and every point the
arm can reach. ``zoom`` narrows either about the arm.
``set_cloud`` lays a cloud of points (the workspace) faintly behind the arm
in every view; it is projected once per cloud and orbit, and rasterised once
per zoom and size, so a joint step costs what it did without it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from textual.app import ComposeResult
from textual.containers import Container
from textual.message import Message
from textual.reactive import reactive
from textual.widgets import Static

from dhsim_tui.render.picture import CELL_ROLES, Framing
from dhsim_tui.scene import VIEWS, Wireframe, project
from dhsim_tui.scene.cloud import ViewCloud, project_cloud, projection_key
from dhsim_tui.scene.kept_framing import KeptFramings
from dhsim_tui.scene.oblique import Orbit, project_oblique
from dhsim_tui.scene.projection import ORTHO_VIEWS, View, ViewScene
from dhsim_tui.scene.wireframe import FRAME_MODES
from dhsim_tui.terminal.charset import ascii_mode
from dhsim_tui.tui.widgets.arm_view import ArmView
from dhsim_tui.tui.widgets.legend import FRAMES_SHORT, legend_line
from dhsim_tui.tui.widgets.view_keys import BINDINGS
from dhsim_tui.tui.widgets.view_style import look_of, role_styles

#: at and above this size a screen shows all four views at once
WIDE_SIZE = (120, 36)
#: zoom factors: each + or - multiplies or divides by ZOOM_STEP, within these
ZOOM_STEP = 1.5
ZOOM_RANGE = (1 / 4, 64.0)
#: room the axes take in a plotext view: y labels and axis, x axis and labels
AXES_ROOM = (7, 2)
#: degrees the 3-D view turns per cell dragged (a row is two columns tall)
DRAG_DEGREES = (3.0, 6.0)


def is_wide(width: int, height: int) -> bool:
    return width >= WIDE_SIZE[0] and height >= WIDE_SIZE[1]


def _path_key(wire: Wireframe) -> tuple | None:
    """What tells one program's path drawn from another (the control screen
    makes a new array of it for every frame): its length and ends."""
    trail = wire.trail
    if trail is None or len(trail) < 2:
        return None
    return (len(trail), *trail[0].tolist(), *trail[-1].tolist())


class ViewsPanel(Container):
    """Top, front, side and 3-D views of the same wireframe."""

    DEFAULT_CSS = """
    ViewsPanel .legend { height: 1; padding: 0 1; color: $text-muted; }
    """
    BINDINGS = BINDINGS

    @dataclass
    class Maximised(Message):
        """The selected view took the whole screen (or gave it back)."""

        panel: ViewsPanel
        maximised: bool

    @dataclass
    class Selected(Message):
        """Another view was selected (a key or a click)."""

        panel: ViewsPanel
        index: int

    selected: reactive[int] = reactive(1, init=False)
    maximised: reactive[bool] = reactive(False, init=False)
    #: which frames' axes are drawn: FRAME_MODES
    frames: reactive[str] = reactive("all", init=False)
    #: every view fitted to the arm (as the views open; F toggles), or the
    #: work area (0)
    fit: reactive[bool] = reactive(True, init=False)

    def __init__(self, renderer: str = "plotext", *, id: str | None = None):
        super().__init__(id=id, classes="views-panel")
        self.renderer = renderer
        self.zoom = 1.0
        self.orbit = Orbit()
        self._zoom_centre: np.ndarray | None = None  # world point zoomed about
        self._kept = KeptFramings(len(VIEWS))  # framings that hold still while the arm moves
        self._wire: Wireframe | None = None
        self._legend_key: tuple | None = None
        self._cloud: np.ndarray | None = None  # world points (n, 3), or none shown
        self._cloud_version = 0  # a new number for every set_cloud
        self._path_key: tuple | None = None  # the program's path last shown
        self._view_clouds: dict[str, ViewCloud] = {}  # per view key, as projected

    def compose(self) -> ComposeResult:
        with Container(classes="views-grid"):
            for view in VIEWS:
                yield ArmView(view, self.renderer, id=f"view-{view.key}")
        yield Static("", classes="legend")

    def on_mount(self) -> None:
        self._views = list(self.query(ArmView))
        self._show_legend()
        self._mark_selected()
        # the theme's signal, not ``self.watch(self.app, "theme", ...)``: in
        # Textual 8.2.8 a watcher on the app outlives the panel and keeps it,
        # and its whole screen, alive (docs/upstream/textual-footer-leak.md)
        self.app.theme_changed_signal.subscribe(self, self._theme_changed)

    def on_unmount(self) -> None:
        self.app.theme_changed_signal.unsubscribe(self)

    def _theme_changed(self, _theme: object) -> None:
        self._restyle()

    # -- the legend ----------------------------------------------------------
    def _show_legend(self) -> None:
        """The legend for the robot, frames and cloud shown, packed into the
        panel's width; hidden when not even the links fit."""
        wire = self._wire
        joint_types = wire.joint_types if wire is not None else ()
        pedestal = wire is not None and wire.pedestal is not None
        width = max(self.size.width - 2, 0)
        look = look_of(self.app)
        trail = wire is not None and wire.trail is not None
        key = (
            trail,
            look,
            self.app.theme,
            width,
            self.frames,
            self._cloud is not None,
            joint_types,
            pedestal,
        )
        if key == self._legend_key:
            return
        self._legend_key = key
        app = self.app
        styles = role_styles(app.console.color_system, ansi_theme=app.current_theme.ansi)
        text, cramped = legend_line(
            look,
            dict(zip(CELL_ROLES, styles, strict=True)),
            joint_types,
            pedestal,
            self.frames,
            self._cloud is not None,
            width,
            trail,
        )
        self.set_class(cramped, "-cramped")
        self.query_one(".legend", Static).update(text)

    def _restyle(self) -> None:
        """A new theme: the views and legend take its colours (ANSI or not)."""
        self._legend_key = None
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
        """Project the wireframe into every view."""
        new_robot = self._wire is None or (
            self._wire.joint_types,
            self._wire.pedestal is None,
            self._wire.trail is None,
        ) != (wire.joint_types, wire.pedestal is None, wire.trail is None)
        self._wire = wire
        path_key = _path_key(wire)
        if path_key != self._path_key:  # a path drawn, gone or another: fit it afresh
            self._path_key = path_key
            self._kept.forget()
        scenes = [project(wire, view, self.frames) for view in ORTHO_VIEWS]
        scenes.append(project_oblique(wire, self.orbit, self.frames))
        framings = self._framings(scenes)
        for widget, scene, framing in zip(self._views, scenes, framings, strict=True):
            widget.show(scene, framing, self._view_cloud(widget.view, wire))
        self._show_captions()
        if new_robot and self.is_mounted:
            self._show_legend()

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

    # -- framing -----------------------------------------------------------
    def _canvas(self, view: View) -> tuple[int, int]:
        """The plot area of a view (all views are the same size): the 3-D
        view has no tick axes, the others lose their room."""
        widget = self._views[self.selected]
        width, height = widget.size
        if width < 2 or height < 2:
            width, height = 40, 18
        if self.renderer == "plotext" and not view.is_3d:
            width, height = width - AXES_ROOM[0], height - AXES_ROOM[1]
        return max(width, 2), max(height, 2)

    def _framings(self, scenes: list[ViewScene]) -> list[Framing]:
        canvases = [self._canvas(scene.view) for scene in scenes]
        return self._kept.framings(
            scenes,
            canvases,
            fit=self.fit,
            zoom=self.zoom,
            wire=self._wire,
            orbit=self.orbit,
            zoom_centre=self._zoom_centre,
        )

    def _redraw(self) -> None:
        if self._wire is not None:
            self.show(self._wire)

    def _show_captions(self) -> None:
        ascii = ascii_mode(self.app)
        for widget in self._views:
            scene = widget.scene
            parts = []
            if widget.view.is_3d:
                parts.append(self.orbit.ascii_label if ascii else self.orbit.label)
                if scene is not None and scene.grid_step and not self.fit:
                    parts.append(f"grid {scene.grid_step:g} {scene.units}".rstrip())
            if self.fit:
                parts.append("fit (F)")
            if self.zoom != 1.0:
                parts.append(f"zoom {self.zoom:.3g}x")
            if self.frames != "all":
                parts.append(f"frames: {FRAMES_SHORT[self.frames]}")
            subtitle = "  ".join(parts)
            if widget.border_subtitle != subtitle:
                widget.border_subtitle = subtitle

    # -- what keys and the mouse do ------------------------------------------
    def action_next_view(self) -> None:
        self.select_next()

    def action_view(self, index: int) -> None:
        self.select(index)

    def action_maximise(self) -> None:
        self.toggle_maximise()

    def action_zoom(self, steps: int) -> None:
        """In (steps > 0) or out about the arm; 0: the whole work area."""
        if steps == 0:
            self.reset_zoom()
        else:
            self.zoom_by(steps)

    def action_fit(self) -> None:
        self.toggle_fit()

    def action_frames(self) -> None:
        self.cycle_frames()

    def action_orbit(self, azimuth: int, elevation: int) -> None:
        """Turn the 3-D view (and select it, if it is not on screen)."""
        iso = self._views[len(VIEWS) - 1]
        if not iso.display or not iso.size.area:
            self.select(len(VIEWS) - 1)
        self.orbit_by(azimuth * Orbit.STEP, elevation * Orbit.STEP)

    def select(self, index: int) -> None:
        self.selected = index % len(VIEWS)

    def select_next(self) -> None:
        self.select(self.selected + 1)

    def watch_selected(self, index: int) -> None:
        self._mark_selected()
        self.post_message(self.Selected(self, index))

    def _mark_selected(self) -> None:
        if not hasattr(self, "_views"):
            return
        for i, widget in enumerate(self._views):
            widget.set_class(i == self.selected, "-selected")

    def toggle_maximise(self) -> bool:
        """The selected view alone, over the whole screen; again: back."""
        self.maximised = not self.maximised
        return self.maximised

    def watch_maximised(self, maximised: bool) -> None:
        self.set_class(maximised, "-max")
        self.post_message(self.Maximised(self, maximised))

    def zoom_by(self, steps: int) -> None:
        """Zoom in (steps > 0) or out about the arm as it is now (fitted:
        about the middle of the fit)."""
        if self._wire is None:
            return
        if self._zoom_centre is None:
            points = np.vstack([self._wire.links, self._wire.origins])
            self._zoom_centre = (points.min(axis=0) + points.max(axis=0)) / 2
        self.zoom = float(np.clip(self.zoom * ZOOM_STEP**steps, *ZOOM_RANGE))
        self._redraw()

    def reset_zoom(self) -> None:
        """Back to the seed's work area: reach + 30 on every side, floor at -h
        (and out of F)."""
        self.zoom = 1.0
        self._zoom_centre = None
        if self.fit:
            self.fit = False  # the watcher redraws
        else:
            self._redraw()

    def toggle_fit(self) -> bool:
        """F: every view fitted to the arm as it stands (how they open);
        again: the work area."""
        self.fit = not self.fit
        return self.fit

    def watch_fit(self) -> None:
        self._kept.forget()
        self.zoom = 1.0
        self._zoom_centre = None
        self._redraw()

    def cycle_frames(self) -> str:
        """x: every frame's axes -> frame 0's and the last's -> none -> every."""
        self.frames = FRAME_MODES[(FRAME_MODES.index(self.frames) + 1) % len(FRAME_MODES)]
        return self.frames

    def watch_frames(self) -> None:
        self._kept.forget()  # what F frames includes the axes drawn
        self._redraw()
        if self.is_mounted:
            self._show_legend()

    def orbit_by(self, d_azimuth: float, d_elevation: float) -> None:
        self.orbit = self.orbit.turned(d_azimuth, d_elevation)
        self._kept.forget_fit(len(VIEWS) - 1)  # F keeps the 3-D view filled as it turns
        self._redraw()

    def on_arm_view_pressed(self, message: ArmView.Pressed) -> None:
        message.stop()
        self.select(self._views.index(message.view))
        if message.double:
            self.toggle_maximise()

    def on_arm_view_wheel(self, message: ArmView.Wheel) -> None:
        message.stop()
        self.zoom_by(message.steps)

    def on_arm_view_dragged(self, message: ArmView.Dragged) -> None:
        message.stop()
        if message.view.view.is_3d:
            # grab the scene: dragging right turns it right, down tips it towards you
            self.orbit_by(-DRAG_DEGREES[0] * message.dx, DRAG_DEGREES[1] * message.dy)

    def on_resize(self) -> None:
        self._show_legend()
        self.call_after_refresh(self._redraw)

"""Framings that hold still: the views' framing kept while the arm stays in it.

The 3-D view is framed on its floor and the arm, and keeps that framing
while the arm stays in it and the canvas and elevation hold (turning the
view never moves it). Fitted (``F``), each view is framed on the arm as it
stands and keeps that framing until the arm leaves it or the canvas
changes. :class:`KeptFramings` holds those framings for a views panel;
everything it computes is :mod:`.framing`'s.
"""

from __future__ import annotations

from collections.abc import Sequence

from dhsim_tui.scene.figure import least_size
from dhsim_tui.scene.framing import Framing, fit_bounds, fitted, work_area_framings
from dhsim_tui.scene.oblique import Orbit, view_point
from dhsim_tui.scene.projection import ViewScene, holds
from dhsim_tui.scene.wireframe import Wireframe

Canvas = tuple[int, int]


class KeptFramings:
    """The framings of a set of views (the 3-D view last), at zoom 1."""

    def __init__(self, count: int) -> None:
        self.count = count
        self.forget()

    def forget(self) -> None:
        """Frame every view afresh (the frames drawn changed, or F)."""
        self._fits: list[Framing | None] = [None] * self.count
        self._fit_canvas: tuple[Canvas, ...] | None = None
        self._iso: Framing | None = None
        self._iso_key: tuple | None = None

    def forget_fit(self, index: int) -> None:
        """Fit view ``index`` afresh (the 3-D view turned: F keeps it filled)."""
        self._fits[index] = None

    def framings(
        self,
        scenes: Sequence[ViewScene],
        canvases: Sequence[Canvas],
        *,
        fit: bool,
        zoom: float,
        wire: Wireframe | None,
        orbit: Orbit,
        zoom_centre=None,
    ) -> list[Framing]:
        """Each view's framing: fitted to the arm (``fit``) or the work area,
        zoomed ``zoom`` times (about ``zoom_centre``, a world point, if given)."""
        if fit:
            return [f.zoomed(zoom) for f in self._fitted(scenes, tuple(canvases), wire)]
        framings = work_area_framings(scenes, list(canvases))
        framings[-1] = self._iso_framing(scenes[-1], canvases[-1], framings[-1], orbit)
        if zoom_centre is None or wire is None:
            return [framing.zoomed(zoom) for framing in framings]
        return [
            framing.zoomed(zoom, view_point(wire, scene.view, orbit, zoom_centre))
            for framing, scene in zip(framings, scenes, strict=True)
        ]

    def _iso_framing(
        self, scene: ViewScene, canvas: Canvas, fresh: Framing, orbit: Orbit
    ) -> Framing:
        cols, rows = canvas
        key = (cols, rows, orbit.elevation)
        kept = self._iso
        if (
            kept is None
            or key != self._iso_key
            or not holds(fit_bounds(scene), kept.centre, kept.per_dot, cols, rows)
        ):
            kept, self._iso, self._iso_key = fresh, fresh, key
        return kept

    def _fitted(
        self, scenes: Sequence[ViewScene], canvases: tuple[Canvas, ...], wire: Wireframe | None
    ) -> list[Framing]:
        if canvases != self._fit_canvas:
            self._fits = [None] * self.count
            self._fit_canvas = canvases
        least = least_size(wire) if wire is not None else 1.0
        framings = []
        for index, (scene, (cols, rows)) in enumerate(zip(scenes, canvases, strict=True)):
            base = self._fits[index]
            if base is None or not holds(fit_bounds(scene), base.centre, base.per_dot, cols, rows):
                base = self._fits[index] = fitted(scene, cols, rows, least)
            framings.append(base)
        return framings

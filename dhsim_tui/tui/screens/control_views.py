"""The view keys of the control screen: select a view (``tab``, ``1``-``4``),
maximise it (``z``), zoom (``+ - 0``), fit the arm (``F``), choose the frames
drawn (``x``) and orbit the 3-D view (``a d w s``). The views panel holds
all of that; these only hand it the keys.
"""

from __future__ import annotations

from dhsim_tui.scene import VIEWS
from dhsim_tui.scene.oblique import Orbit


class ViewControls:
    """Mixed into the control screen, which has ``_views`` (the views panel)."""

    @property
    def view_index(self) -> int:
        """The selected view (the views panel's)."""
        return self._views.selected

    def action_next_view(self) -> None:
        self._views.select_next()

    def action_view(self, index: int) -> None:
        self._views.select(index)

    def action_maximise(self) -> None:
        self._views.toggle_maximise()

    def action_zoom(self, steps: int) -> None:
        if steps == 0:
            self._views.reset_zoom()
        else:
            self._views.zoom_by(steps)

    def action_fit(self) -> None:
        self._views.toggle_fit()

    def action_frames(self) -> None:
        self._views.cycle_frames()

    def action_orbit(self, azimuth: int, elevation: int) -> None:
        """Turn the 3-D view (and show it, if it is hidden)."""
        iso = self._views.views[len(VIEWS) - 1]
        if not iso.display or not iso.size.area:
            self._views.select(len(VIEWS) - 1)
        self._views.orbit_by(azimuth * Orbit.STEP, elevation * Orbit.STEP)

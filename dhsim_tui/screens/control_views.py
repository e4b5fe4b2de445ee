"""The view keys of the control screen: select a view (``tab``, ``1``-``4``),
maximise it (``z``), zoom (``+ - 0``) and orbit the 3-D view (``a d w s``).
"""

from __future__ import annotations

from dhsim_tui.scene import VIEWS
from dhsim_tui.scene.oblique import Orbit


class ViewControls:
    """Mixed into the control screen, which has ``view_index`` and ``_views``
    (the views panel)."""

    def action_next_view(self) -> None:
        self.view_index = (self.view_index + 1) % len(VIEWS)

    def action_view(self, index: int) -> None:
        self.view_index = index

    def action_maximise(self) -> None:
        self._views.toggle_maximise()

    def action_zoom(self, steps: int) -> None:
        if steps == 0:
            self._views.reset_zoom()
        else:
            self._views.zoom_by(steps)

    def action_orbit(self, azimuth: int, elevation: int) -> None:
        """Turn the 3-D view (and show it, if it is hidden)."""
        if not self._views.views[3].display or not self._views.views[3].size.area:
            self.view_index = 3
        self._views.orbit_by(azimuth * Orbit.STEP, elevation * Orbit.STEP)

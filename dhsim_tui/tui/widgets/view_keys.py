"""The views panel's keys: select a view (``tab``, ``1``-``4``), maximise it
(``z``), zoom (``+ - 0``), the arm fitted or the work area (``F``; the
views open fitted), choose the frames drawn
(``x``) and orbit the 3-D view (``a d w s``). They call the panel's own
``action_*``; a screen hands them on (the panel takes no focus), see
:func:`dhsim_tui.tui.keys.forwarded`."""

from __future__ import annotations

from textual.binding import Binding

from dhsim_tui.tui.keys import Keys

SELECT = Keys("view", help="select the top, front, side or 3-D view")
MAXIMISE = Keys("maximise view", help="maximise the selected view (again: back)")
ZOOM = Keys("zoom", help="zoom in / out about the arm; 0: the whole work area")
FIT = Keys(
    "fit the arm", help="fit every view to the arm as it stands (again, or 0: the work area)"
)
FRAMES = Keys("frames drawn", help="frame axes drawn: every frame → base and tool only → none")
ORBIT = Keys("orbit 3-D", help="orbit the 3-D view: azimuth, elevation (15° a press)")

#: the views' keys: the panel's own (the control screen hands them on, see
#: keys.forwarded: the panel takes no focus)
BINDINGS = [
    Binding("tab", "next_view", "View", show=False, id="view.next", tooltip="Select the next view",
            group=SELECT),
    Binding("1", "view(0)", "Top", show=False, id="view.top", tooltip="Top view", group=SELECT),
    Binding("2", "view(1)", "Front", show=False, id="view.front", tooltip="Front view",
            group=SELECT),
    Binding("3", "view(2)", "Side", show=False, id="view.side", tooltip="Side view", group=SELECT),
    Binding("4", "view(3)", "3-D", show=False, id="view.iso", tooltip="3-D view (a d w s: orbit)",
            group=SELECT),
    Binding("z", "maximise", "Maximise", show=False, id="view.maximise",
            tooltip="The selected view over the whole screen; again: back", group=MAXIMISE),
    Binding("plus,equals_sign", "zoom(1)", "Zoom in", show=False, id="view.zoom_in",
            tooltip="Zoom in about the arm", group=ZOOM),
    Binding("minus", "zoom(-1)", "Zoom out", show=False, id="view.zoom_out",
            tooltip="Zoom out", group=ZOOM),
    Binding("0", "zoom(0)", "Whole area", show=False, id="view.zoom_reset",
            tooltip="Back to the whole work area (reach + 30, floor at -base height)", group=ZOOM),
    Binding("F", "fit", "Fit", show=False, id="view.fit",
            tooltip="Fit every view to the arm as it stands; again: the whole work area",
            group=FIT),
    Binding("a", "orbit(-1, 0)", "Orbit", show=False, id="view.orbit_left",
            tooltip="Turn the 3-D view: azimuth down", group=ORBIT),
    Binding("d", "orbit(1, 0)", "Orbit", show=False, id="view.orbit_right",
            tooltip="Turn the 3-D view: azimuth up", group=ORBIT),
    Binding("w", "orbit(0, 1)", "Orbit", show=False, id="view.orbit_up",
            tooltip="Turn the 3-D view: look from higher", group=ORBIT),
    Binding("s", "orbit(0, -1)", "Orbit", show=False, id="view.orbit_down",
            tooltip="Turn the 3-D view: look from lower", group=ORBIT),
    Binding("x", "frames", "Frames", show=False, id="view.frames",
            tooltip="Frame axes drawn: every frame, base and tool only, none", group=FRAMES),
]  # fmt: skip

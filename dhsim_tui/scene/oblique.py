"""The 3-D view: an orthographic projection of the wireframe seen from any
direction, orbiting with keys, over a grid on the floor.

Angles follow MATLAB's ``view(az, el)``, as in the seed's figures:

* ``azimuth`` turns the viewpoint about world +z, counter-clockwise seen from
  above, measured from the -y axis: ``view(0, 0)`` looks along +y and is the
  front view (X right, Z up);
* ``elevation`` is the viewpoint's angle above the floor plane: ``view(az, 90)``
  looks straight down and is the top view turned by ``az``.

The default, ``view(45, 35.26...)``, is isometric: the viewer sits on the
(+x, -y, +z) diagonal, so +x points to the lower right, +y to the upper right
(away from the viewer) and +z up, all three shortened alike (by sqrt(2/3)).

Picture coordinates are measured from the centre of the work area, so that
the region to keep visible (``ViewScene.bounds``) is the same from every
direction and the scale never jumps while orbiting.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from dhsim_tui.core.analysis.workspace import WorkArea
from dhsim_tui.scene.projection import (
    ISO,
    Polyline,
    View,
    ViewScene,
    path_extent,
    wire_lines,
)
from dhsim_tui.scene.wireframe import Wireframe

#: the isometric elevation, atan(1 / sqrt 2) = 35.26...°
ISOMETRIC_ELEVATION = math.degrees(math.atan(1 / math.sqrt(2)))
#: nice grid spacings are these times a power of ten
NICE = (1.0, 2.0, 5.0)
#: lines per side of the floor to aim for, the outline's two edges included (5 or 7 result)
GRID_LINES = 6


@dataclass(frozen=True)
class Orbit:
    """Where the 3-D view looks from, in degrees (MATLAB's ``view(az, el)``)."""

    azimuth: float = 45.0
    elevation: float = ISOMETRIC_ELEVATION
    #: how far one key press turns the view, in degrees
    STEP: ClassVar[float] = 15.0

    def turned(self, d_azimuth: float = 0.0, d_elevation: float = 0.0) -> Orbit:
        """Turned by the given angles: azimuth wrapped into (-180, 180],
        elevation clamped to [-90, 90] (non-finite turns are ignored)."""
        d_az = d_azimuth if math.isfinite(d_azimuth) else 0.0
        d_el = d_elevation if math.isfinite(d_elevation) else 0.0
        azimuth = 180.0 - (180.0 - (self.azimuth + d_az)) % 360.0
        elevation = min(90.0, max(-90.0, self.elevation + d_el))
        return replace(self, azimuth=azimuth, elevation=elevation)

    def _whole(self) -> tuple[int, int]:
        return round(self.azimuth), round(self.elevation)

    @property
    def label(self) -> str:
        """``"az 45° el 35°"``: whole degrees, for a caption."""
        return "az {}° el {}°".format(*self._whole())

    @property
    def ascii_label(self) -> str:
        """``"az 45 deg el 35 deg"``, for terminals without the degree sign."""
        return "az {} deg el {} deg".format(*self._whole())


def camera(orbit: Orbit) -> tuple[np.ndarray, np.ndarray]:
    """Unit world vectors along the picture's right and up directions.

    ``right x up`` points at the viewer; ``right`` stays in the floor plane
    and ``up`` has z = cos(elevation) >= 0, so neither degenerates at the poles.
    """
    az, el = math.radians(orbit.azimuth), math.radians(orbit.elevation)
    right = np.array([math.cos(az), math.sin(az), 0.0])
    up = np.array([-math.sin(el) * math.sin(az), math.sin(el) * math.cos(az), math.cos(el)])
    return right, up


def grid_step(lo: float, hi: float) -> float:
    """A 1, 2 or 5 × 10^k spacing giving GRID_LINES lines or close across [lo, hi]
    (counting the two edges). On a square centred on frame 0, as the work area
    is, the count is 2 ceil(half / step) + 1, and one of the nice steps in
    [width / 6, width / 2) (a span of 3 > 2.5) always makes it 5 or 7."""
    width = hi - lo
    if not (math.isfinite(width) and width > 0):
        return 1.0
    power = math.floor(math.log10(width / GRID_LINES))
    steps = [m * 10.0**k for k in (power - 1, power, power + 1) for m in NICE]
    return min(steps, key=lambda step: abs(len(grid_ticks(lo, hi, step)) + 2 - GRID_LINES))


def grid_ticks(lo: float, hi: float, step: float) -> np.ndarray:
    """The multiples of ``step`` strictly inside (lo, hi) (the edges are the outline)."""
    margin = 1e-9 * (hi - lo)
    first, last = math.ceil((lo + margin) / step), math.floor((hi - margin) / step)
    return step * np.arange(first, last + 1, dtype=float)


def floor_points(wire: Wireframe, step: float) -> tuple[np.ndarray, np.ndarray]:
    """The floor in 3-D: the grid lines, one (m, 3) polyline with NaN pen
    lifts, and the closed outline of the work area's x/y square (5, 3)."""
    a, z = wire.area, wire.floor_z
    strokes = [((x, a.ymin, z), (x, a.ymax, z)) for x in grid_ticks(a.xmin, a.xmax, step)]
    strokes += [((a.xmin, y, z), (a.xmax, y, z)) for y in grid_ticks(a.ymin, a.ymax, step)]
    grid = [point for stroke in strokes for point in (*stroke, (math.nan,) * 3)][:-1]
    corners = ((a.xmin, a.ymin), (a.xmax, a.ymin), (a.xmax, a.ymax), (a.xmin, a.ymax))
    outline = [(x, y, z) for x, y in (*corners, corners[0])]
    return np.asarray(grid, dtype=float).reshape(-1, 3), np.asarray(outline, dtype=float)


def _tuples(xy: tuple[np.ndarray, np.ndarray]) -> tuple[tuple[float, ...], tuple[float, ...]]:
    return tuple(xy[0].tolist()), tuple(xy[1].tolist())


def _box(area: WorkArea) -> tuple[np.ndarray, np.ndarray]:
    return (
        np.array([area.xmin, area.ymin, area.zmin]),
        np.array([area.xmax, area.ymax, area.zmax]),
    )


def picture_coordinates(area: WorkArea, orbit: Orbit):
    """World points (m, 3) -> the 3-D picture's (xs, ys): along the camera's
    right and up, measured from the centre of the work area."""
    lows, highs = _box(area)
    centre = (lows + highs) / 2
    right, up = camera(orbit)

    def to_2d(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        shifted = np.asarray(points, dtype=float) - centre
        return shifted @ right, shifted @ up

    return to_2d


def view_point(wire: Wireframe, view: View, orbit: Orbit, point: np.ndarray) -> tuple[float, float]:
    """Where a world point lands in a view's picture (what zooming centres on)."""
    if view.is_3d:
        xs, ys = picture_coordinates(wire.area, orbit)(np.asarray(point, dtype=float)[None, :])
        return float(xs[0]), float(ys[0])
    return float(point[view.right]), float(point[view.up])


#: room left above and below the drawing, a fraction of its height
PICTURE_MARGIN = 0.03


def picture_bounds(
    wire: Wireframe, orbit: Orbit, arm: np.ndarray | None = None
) -> tuple[float, float, float, float]:
    """What the 3-D view frames: the floor of the work area as far up, down
    and across as it could show from ``orbit``'s elevation at *any*
    azimuth (its square turned to its widest, the diagonal ``hypot(hx, hy)``
    across and ``|sin el|`` of that deep), and the arm (``arm``: its world
    points, default the links and frame origins) as it shows from ``orbit``;
    with a small margin above and below.

    The seed's box up to reach + 30 above frame 0 is not framed: most of it
    is empty whatever the pose, which made the 3-D view mostly floor. The
    views panel keeps this framing while the arm stays within it, turning
    included, and frames again when it leaves (``ViewsPanel``).
    """
    area = wire.area
    lows, highs = _box(area)
    centre = (lows + highs) / 2
    hx, hy = (highs[0] - lows[0]) / 2, (highs[1] - lows[1]) / 2
    el = math.radians(orbit.elevation)
    depth, rise = abs(math.sin(el)), math.cos(el)
    across = math.hypot(hx, hy)
    floor = (wire.floor_z - centre[2]) * rise
    top, bottom = floor + depth * across, floor - depth * across
    points = np.vstack([wire.links, wire.origins]) if arm is None else arm
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    points = points[np.isfinite(points).all(axis=1)]
    if len(points):
        xs, ys = picture_coordinates(area, orbit)(points)
        top, bottom = max(top, float(ys.max())), min(bottom, float(ys.min()))
        across = max(across, float(np.abs(xs).max()))
    pad = PICTURE_MARGIN * (top - bottom)
    return (-across, across, bottom - pad, top + pad)


def project_oblique(wire: Wireframe, orbit: Orbit = Orbit(), frames: str = "all") -> ViewScene:
    """The 3-D view of the wireframe from ``orbit``, over the floor grid and
    the links' shadow, with the axes of the frames ``frames`` shows.

    ``bounds`` (:func:`picture_bounds`) depend on the floor, the arm and
    the elevation: turning the view about the vertical never moves them.
    """
    to_2d = picture_coordinates(wire.area, orbit)
    half = (_box(wire.area)[1] - _box(wire.area)[0]) / 2
    wider = wire.area.limits("x" if half[0] >= half[1] else "y")
    step = grid_step(*wider)  # one spacing both ways, from the wider side
    grid, outline = floor_points(wire, step)
    role = "floor_hit" if wire.below_floor else "floor"  # something went through it
    floor = [Polyline(*_tuples(to_2d(grid)), "grid"), Polyline(*_tuples(to_2d(outline)), role)]
    if wire.shadow is not None:
        floor.append(Polyline(*_tuples(to_2d(wire.shadow)), "shadow"))
    if wire.trail is not None and len(wire.trail) > 1:
        floor.append(Polyline(*_tuples(to_2d(wire.trail)), "trail"))
    lines, tips, ee, arm, marks, fit = wire_lines(wire, to_2d, floor, frames)
    return ViewScene(
        view=ISO,
        lines=lines,
        end_effector=ee,
        bounds=picture_bounds(wire, orbit, _arm_points(wire, frames)),
        units=wire.units,
        tips=tips,
        arm_bounds=arm,
        grid_step=step,
        marks=marks,
        fit_bounds=fit,
        path_bounds=path_extent(wire, to_2d),
    )


def _arm_points(wire: Wireframe, frames: str) -> np.ndarray:
    """The arm as drawn: links, pedestal, tool and the axes of the frames shown."""
    shown = wire.shown_frames(frames)
    parts = [wire.links, wire.end_effector[None, :], wire.axes[shown].reshape(-1, 3)]
    if wire.pedestal is not None:
        parts.append(wire.pedestal)
    return np.vstack(parts)

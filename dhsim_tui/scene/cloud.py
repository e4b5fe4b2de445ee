"""A cloud of world points (the workspace) in each view's picture plane, and
its braille dots at given limits. numpy only, no UI.

The cloud is drawn behind the arm. Projecting it is cheap but not free (20,000
points), and rasterising it costs about as much as the arm; neither depends on
the joints, so the views do both once per cloud, orbit, zoom and size, and on
a joint step only lay the cached cells under the arm (``render.cloud``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from dhsim_tui.core.analysis.workspace import WorkArea
from dhsim_tui.scene.oblique import Orbit, picture_coordinates
from dhsim_tui.scene.projection import VIEWS, View
from dhsim_tui.scene.raster import BRAILLE_BITS

#: the 3-D view's starting orbit
ISOMETRIC = Orbit()


@dataclass(frozen=True, eq=False)
class ViewCloud:
    """A point cloud in one view's picture coordinates (the plane the view's
    limits are given in). ``key`` tells two projections apart: equal keys,
    the same points in the same place."""

    xs: np.ndarray
    ys: np.ndarray
    key: tuple = field(default=())

    def __len__(self) -> int:
        return len(self.xs)


def projection_key(view: View, area: WorkArea, orbit: Orbit, key: object = None) -> tuple:
    """What a view's projection of the cloud ``key`` depends on: the 3-D
    view's on the orbit and the work area (its picture is centred on it)."""
    return (key, view.key, orbit, area) if view.is_3d else (key, view.key)


def project_cloud(
    points: np.ndarray, view: View, area: WorkArea, orbit: Orbit = ISOMETRIC, key: object = None
) -> ViewCloud:
    """The world points (n, 3) as the view shows them: the orthographic views
    take two world axes, the 3-D view looks from ``orbit`` (its picture is
    measured from the centre of the work area, as ``project_oblique``'s)."""
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    tag = projection_key(view, area, orbit, key)
    if view.is_3d:
        xs, ys = picture_coordinates(area, orbit)(pts)
        return ViewCloud(xs, ys, tag)
    return ViewCloud(
        np.ascontiguousarray(pts[:, view.right]), np.ascontiguousarray(pts[:, view.up]), tag
    )


def project_clouds(
    points: np.ndarray, area: WorkArea, orbit: Orbit = ISOMETRIC, key: object = None
) -> tuple[ViewCloud, ...]:
    """The cloud in every view, in the order of ``VIEWS``."""
    return tuple(project_cloud(points, view, area, orbit, key) for view in VIEWS)


def cloud_dots(
    cloud: ViewCloud,
    cols: int,
    rows: int,
    xlim: tuple[float, float],
    ylim: tuple[float, float],
) -> np.ndarray:
    """The braille dots (4·rows, 2·cols) the cloud's points fall on, with the
    same mapping from picture coordinates to dots as ``scene.raster``."""
    nx, ny = 2 * cols, 4 * rows
    dots = np.zeros((max(ny, 0), max(nx, 0)), dtype=bool)
    if cols < 1 or rows < 1 or len(cloud) == 0 or not (xlim[1] > xlim[0] and ylim[1] > ylim[0]):
        return dots
    sx = (nx - 1) / (xlim[1] - xlim[0])
    sy = (ny - 1) / (ylim[1] - ylim[0])
    with np.errstate(invalid="ignore", over="ignore"):
        px = np.rint((cloud.xs - xlim[0]) * sx)
        py = np.rint((ylim[1] - cloud.ys) * sy)
        inside = (px >= 0) & (px < nx) & (py >= 0) & (py < ny)  # False for NaN
    dots[py[inside].astype(np.int64), px[inside].astype(np.int64)] = True
    return dots


def braille_bits(dots: np.ndarray) -> np.ndarray:
    """Each cell's braille bits (rows, cols) from its 4×2 dots (0: no dot)."""
    ny, nx = dots.shape
    rows, cols = ny // 4, nx // 2
    cells = dots[: 4 * rows, : 2 * cols].reshape(rows, 4, cols, 2).astype(np.int32)
    return np.einsum("rycx,yx->rc", cells, BRAILLE_BITS)


def thinned(dots: np.ndarray) -> np.ndarray:
    """Every other dot, as on a chessboard: a filled region reads as a light
    shade (⢕⡪) rather than solid blocks, its edges kept to a dot or two."""
    ny, nx = dots.shape
    board = (np.add.outer(np.arange(ny), np.arange(nx)) % 2) == 0
    return dots & board

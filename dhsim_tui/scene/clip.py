"""Segments cut to a rectangle (Liang–Barsky, vectorised): what a picture
draws of a link that runs far off it. The braille raster samples only the
part that shows; plotext's ASCII lines never walk off the picture.
"""

from __future__ import annotations

import numpy as np


def clip_segments(
    x0: np.ndarray,
    x1: np.ndarray,
    y0: np.ndarray,
    y1: np.ndarray,
    xlim: tuple[float, float],
    ylim: tuple[float, float],
) -> tuple[np.ndarray, ...]:
    """The segments (x0, y0)-(x1, y1) cut to ``xlim`` × ``ylim``: the cut end
    points (an end inside keeps its exact value) and which segments show at
    all. A segment with an end not finite (a pen lift), or whose arithmetic
    overflows, does not show."""
    shows = np.isfinite(x0) & np.isfinite(x1) & np.isfinite(y0) & np.isfinite(y1)
    t0, t1 = np.zeros_like(x0), np.ones_like(x0)
    with np.errstate(all="ignore"):
        dx, dy = x1 - x0, y1 - y0
        for p, q in (
            (-dx, x0 - xlim[0]),
            (dx, xlim[1] - x0),
            (-dy, y0 - ylim[0]),
            (dy, ylim[1] - y0),
        ):
            shows &= (p != 0) | (q >= 0)  # parallel to this edge and outside it
            t = q / p
            t0 = np.where(p < 0, np.maximum(t0, t), t0)
            t1 = np.where(p > 0, np.minimum(t1, t), t1)
        shows &= (t0 <= t1) & np.isfinite(dx) & np.isfinite(dy)  # False for a NaN too
        cut0, cut1 = t0 > 0.0, t1 < 1.0
        # an end inside keeps its exact value; every end is then held to the
        # rectangle: for far ends the arithmetic loses digits (-1e54 + 1e54
        # is 0, and t may round to 1 for an end that lies outside)
        x0, x1 = np.where(cut0, x0 + t0 * dx, x0), np.where(cut1, x0 + t1 * dx, x1)
        y0, y1 = np.where(cut0, y0 + t0 * dy, y0), np.where(cut1, y0 + t1 * dy, y1)
        return (
            np.clip(x0, *xlim),
            np.clip(x1, *xlim),
            np.clip(y0, *ylim),
            np.clip(y1, *ylim),
            shows,
        )

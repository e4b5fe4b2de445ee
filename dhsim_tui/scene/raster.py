"""Braille rasterisation of a view: each terminal cell holds 2×4 dots.

This is the fast path for drawing the views (about a millisecond a view,
against 10-15 ms for a plotext build of the same size; see bench/latency.py).
The output is plain data — one string and one colour row per terminal row —
so any widget can paint it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dhsim_tui.scene.clip import clip_segments
from dhsim_tui.scene.projection import Mark, ViewScene, equal_scale_limits

#: bit of each dot in a braille cell, indexed [dot row][dot column]
BRAILLE_BITS = np.array([[0x01, 0x08], [0x02, 0x10], [0x04, 0x20], [0x40, 0x80]], dtype=np.int32)
#: the role of the end-effector mark
MARKER = "tool"
MARKER_CHAR = "◆"


@dataclass(frozen=True)
class Raster:
    """Rows of characters and, per cell, an index into ``palette`` (-1: empty)."""

    lines: tuple[str, ...]
    colours: np.ndarray  # (rows, cols) int16
    palette: tuple[str, ...]
    xlim: tuple[float, float]
    ylim: tuple[float, float]

    @property
    def units_per_dot(self) -> tuple[float, float]:
        rows, cols = self.colours.shape
        return (
            (self.xlim[1] - self.xlim[0]) / max(2 * cols - 1, 1),
            (self.ylim[1] - self.ylim[0]) / max(4 * rows - 1, 1),
        )


#: pixel coordinates are clamped to this before clipping, so that a point
#: astronomically far off (a fuzzed file) cannot overflow the arithmetic
_FAR = 1e12


def _sample_segments(px: np.ndarray, py: np.ndarray, nx: int, ny: int) -> tuple[np.ndarray, ...]:
    """Dot coordinates along every segment of a polyline within the picture
    (``nx`` by ``ny`` dots), at least one per dot step, the index of each
    dot's segment start point and how many dots along its segment it is;
    segments touching a NaN or infinite point are skipped (the pen is lifted)."""
    # a NaN or infinite end lifts the pen
    finite = np.isfinite(px) & np.isfinite(py)
    shows = finite[:-1] & finite[1:]
    x0, x1, y0, y1 = px[:-1], px[1:], py[:-1], py[1:]
    fx, fy = px[finite], py[finite]
    if fx.size and (fx.min() < -1 or fx.max() > nx or fy.min() < -1 or fy.max() > ny):
        # some of it runs off the picture: cut to it and a dot's margin round
        # it, far ends pulled in first so that the arithmetic cannot overflow
        x0, x1, y0, y1, cut = clip_segments(
            *(np.clip(v, -_FAR, _FAR) for v in (x0, x1, y0, y1)),
            (-1.0, float(nx)),
            (-1.0, float(ny)),
        )
        shows &= cut
    first = np.nonzero(shows)[0]
    x0, x1, y0, y1 = x0[shows], x1[shows], y0[shows], y1[shows]
    if x0.size == 0:
        empty = np.empty(0, np.int64)
        return empty, empty, empty, empty
    span = np.maximum(np.abs(x1 - x0), np.abs(y1 - y0))
    counts = np.minimum(span, 4096).astype(np.int64) + 2
    seg = np.repeat(np.arange(counts.size), counts)
    starts = np.cumsum(counts) - counts
    along = np.arange(seg.size) - starts[seg]
    t = along / (counts[seg] - 1)
    xs = np.rint(x0[seg] + (x1 - x0)[seg] * t).astype(np.int64)
    ys = np.rint(y0[seg] + (y1 - y0)[seg] * t).astype(np.int64)
    return xs, ys, first[seg], along


#: how each role's lines are drawn: the arm (links, pedestal) in solid
#: quadrant blocks, a pen one cell wide across and half a cell deep (the same
#: length on screen: a cell is twice as tall as wide), which reads as a bar
#: where braille dots read as a dotted line; the faint things behind it every
#: k-th dot; the rest (frame axes, shadow) one braille dot
HEAVY = frozenset({"link", "pedestal"})
DOTTED = {"grid": 4, "floor": 2}
#: the glyph of each mark: a revolute joint, a prismatic one, the tool
MARK_GLYPHS = {"revolute": "●", "prismatic": "■", MARKER: MARKER_CHAR}
#: quadrant blocks by their bits: upper left 1, upper right 2, lower left 4, lower right 8
QUADRANTS = " ▘▝▀▖▌▞▛▗▚▐▜▄▙▟█"
_QUAD_BITS = np.array([[1, 2], [4, 8]], dtype=np.int32)


def _dot_runs(scene: ViewScene, xlim, ylim, nx: int, ny: int):
    """Every line's dots as (xs, ys, line index, heavy): braille dots, or for
    the heavy roles quadrant pixels (x in dots, y in half cells), pen included."""
    sx = (nx - 1) / (xlim[1] - xlim[0])
    sy = (ny - 1) / (ylim[1] - ylim[0])
    xs_all: list[float] = []
    ys_all: list[float] = []
    owner: list[int] = []
    for number, line in enumerate(scene.lines):
        xs_all.extend(line.xs)
        ys_all.extend(line.ys)
        xs_all.append(np.nan)
        ys_all.append(np.nan)
        owner.extend([number] * (len(line.xs) + 1))
    with np.errstate(over="ignore", invalid="ignore"):  # a point too far off: inf, pen lifted
        px = (np.array(xs_all, dtype=float) - xlim[0]) * sx
        py = (ylim[1] - np.array(ys_all, dtype=float)) * sy
    xs, ys, segment, along = _sample_segments(px, py, nx, ny)
    line_of = np.array(owner, dtype=np.int64)[segment] if segment.size else segment
    roles = [line.role for line in scene.lines]
    every = np.array([DOTTED.get(role, 1) for role in roles] + [1], dtype=np.int64)
    keep = (along % every[line_of]) == 0 if line_of.size else np.ones(0, bool)
    xs, ys, line_of = xs[keep], ys[keep], line_of[keep]
    heavy_role = np.array([role in HEAVY for role in roles] + [False], dtype=bool)
    heavy = heavy_role[line_of] if line_of.size else np.zeros(0, bool)
    if heavy.any():
        hx, hy, hl = xs[heavy], ys[heavy] // 2, line_of[heavy]
        xs = np.concatenate([xs[~heavy], hx, hx + 1])
        ys = np.concatenate([ys[~heavy], hy, hy])
        line_of = np.concatenate([line_of[~heavy], hl, hl])
        heavy = np.concatenate([np.zeros(int((~heavy).sum()), bool), np.ones(2 * hx.size, bool)])
    return xs, ys, line_of, heavy


def rasterize(
    scene: ViewScene,
    cols: int,
    rows: int,
    limits: tuple[tuple[float, float], tuple[float, float]] | None = None,
) -> Raster:
    """Draw the scene's polylines, in order, at the same scale on both axes:
    ``limits`` (x and y) if given, else the scene's bounds fitted to the size.

    Each cell belongs to the last line drawn in it and shows that line alone
    (so a link over a frame axis is a clean block of the link's colour): its
    braille dots, or the quadrant blocks of a heavy line. The joints and the
    tool are drawn over everything, each as its glyph.
    """
    xlim, ylim = limits if limits is not None else equal_scale_limits(scene.bounds, cols, rows)
    nx, ny = 2 * cols, 4 * rows
    roles = tuple(dict.fromkeys(line.role for line in scene.lines))
    marks = scene.marks or _tool_mark(scene)
    palette = (*roles, *dict.fromkeys(MARK_GLYPHS))
    xs, ys, line_of, heavy = _dot_runs(scene, xlim, ylim, nx, ny)
    tall = np.where(heavy, ny // 2, ny)  # heavy pixels are half a cell tall
    inside = (xs >= 0) & (xs < nx) & (ys >= 0) & (ys < tall)
    xs, ys, line_of, heavy = xs[inside], ys[inside], line_of[inside], heavy[inside]
    cell = np.where(heavy, ys // 2, ys // 4) * cols + xs // 2
    top = np.full(rows * cols, -1, dtype=np.int64)  # the last line drawn in each cell owns it
    np.maximum.at(top, cell, line_of)
    mine = line_of == top[cell]
    dots = np.zeros((ny, nx), dtype=bool)
    dots[ys[mine & ~heavy], xs[mine & ~heavy]] = True
    quads = np.zeros((ny // 2, nx), dtype=bool)
    quads[ys[mine & heavy], xs[mine & heavy]] = True
    # each cell's 4×2 dots weighted by their braille bits, its 2×2 quadrants by theirs
    bits = np.einsum("rycx,yx->rc", dots.reshape(rows, 4, cols, 2).astype(np.int32), BRAILLE_BITS)
    quad = np.einsum("rycx,yx->rc", quads.reshape(rows, 2, cols, 2).astype(np.int32), _QUAD_BITS)
    colour_of_line = np.array([palette.index(line.role) for line in scene.lines] + [-1])
    colours = colour_of_line[top].reshape(rows, cols).astype(np.int16)
    chars = np.where(bits > 0, bits + 0x2800, 0x20)
    quad_chars = np.array([ord(c) for c in QUADRANTS])[quad]
    chars = np.where(quad > 0, quad_chars, chars)
    grid = [list(map(chr, row)) for row in chars.tolist()]
    sx = (nx - 1) / (xlim[1] - xlim[0])
    sy = (ny - 1) / (ylim[1] - ylim[0])
    for mark in marks:
        mx, my = (mark.x - xlim[0]) * sx, (ylim[1] - mark.y) * sy
        if np.isfinite(mx) and np.isfinite(my) and 0 <= round(mx) < nx and 0 <= round(my) < ny:
            x, y = round(mx) // 2, round(my) // 4
            if mark.role != MARKER and colours[y, x] == palette.index(MARKER):
                continue  # the tool's cell stays the tool's
            grid[y][x] = MARK_GLYPHS[mark.role]
            colours[y, x] = palette.index(mark.role)
    lines = ["".join(row) for row in grid]
    return Raster(tuple(lines), colours, palette, xlim, ylim)


def _tool_mark(scene: ViewScene) -> tuple[Mark, ...]:
    """A scene made without marks still shows its tool."""
    return (Mark(*scene.end_effector, MARKER),)

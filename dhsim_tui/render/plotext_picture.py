"""A view's picture built by plotext: axes with numbered ticks in the robot's
unit, and the wireframe placed on plotext's canvas.

plotext 5 draws a braille line in about 4 ms a view (its per-dot work is pure
Python) and drops the dots of one line where two lines share a cell. So the
dots are put together by ``scene.raster`` (numpy, 0.15 ms) and plotext gets
each occupied cell as one point of a scatter, with the finished braille glyph
as its marker; plotext lays out the axes, ticks and labels and places every
cell (about 2 ms a view). In 7-bit ASCII plotext draws the lines itself, one
ASCII marker per role (``x``, ``y``, ``z`` for the axes, ``#`` for links).

Only plotext's documented figure methods are used, on a figure of our own:
``plotext._figure._figure_class`` (the class behind ``plotext.plot``;
textual-plotext uses it too) and its ``_limit_size`` (what ``plotext.limit_size``
does for the global figure) are the private names, so plotext is pinned
exactly and ``tests/scene/test_render.py`` fails if they change. No NaN or inf ever reaches
plotext: pen lifts become ``None`` (plotext 5's own gap marker) and every
number is checked finite.
"""

from __future__ import annotations

import math
import re

import numpy as np
from plotext._figure import _figure_class

from dhsim_tui.render.picture import (
    CELL_ROLES,
    NO_ROLE,
    ROLE_INDEX,
    Framing,
    Look,
    Picture,
    blank,
)
from dhsim_tui.render.ticks import (
    on_dots,
    regular_scale,
    tick_label,
    tick_values,
    x_step,
    y_step,
)
from dhsim_tui.scene.clip import clip_segments
from dhsim_tui.scene.projection import Mark, ViewScene, limits_at
from dhsim_tui.scene.raster import MARKER, rasterize

#: plotext's markers for each role in 7-bit ASCII
ASCII_MARKS = {
    "grid": ".",
    "floor": "_",
    "floor_hit": "!",
    "shadow": ",",
    "trail": ":",
    "pedestal": "H",
    "link": "#",
    "x": "x",
    "y": "y",
    "z": "z",
    "revolute": "O",
    "prismatic": "=",
    "tool": "@",
}
_MARK_ROLE = {mark: ROLE_INDEX[role] for role, mark in ASCII_MARKS.items()}
#: plotext's frame glyphs in 7-bit ASCII
_ASCII_FRAME = str.maketrans("─│┤┬└┼┌┐┘├┴", "-|+++++++++")
_SGR = re.compile(r"\x1b\[[0-9;]*m")
#: where the ticks' values fall within their cells: on the first of its two
#: dot columns, on the second of its four dot rows (from the top: the middle
#: of the cell, where plotext's tick marks point)
TICK_DOT = (0, 1)
#: a vertical axis has at least this many labels where its rows allow
LABELS_AT_LEAST = 3
#: the smallest picture that still gets axes (columns, rows)
MIN_SIZE = (30, 8)
_AXES = ROLE_INDEX["axes"]


def _finite(values) -> list[float | None]:
    """Plain floats for plotext, ``None`` for a pen lift; never NaN or inf."""
    return [float(v) if math.isfinite(v) else None for v in values]


def _clip(xs: np.ndarray, ys: np.ndarray, xlim, ylim) -> tuple[list, list]:
    """The polyline's segments cut to the limits, as points with ``None``
    between strokes: plotext then never walks a line that runs far off the
    picture, and gets no NaN."""
    xs, ys = np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)
    x0, x1, y0, y1, shows = clip_segments(xs[:-1], xs[1:], ys[:-1], ys[1:], xlim, ylim)
    out_x: list[float | None] = []
    out_y: list[float | None] = []
    for a, b, c, d in zip(
        x0[shows].tolist(), x1[shows].tolist(), y0[shows].tolist(), y1[shows].tolist(), strict=True
    ):
        if out_x:
            out_x.append(None)
            out_y.append(None)
        out_x += [a, b]
        out_y += [c, d]
    return out_x, out_y


class PlotextPainter:
    """One view's plotext figure, kept between frames.

    plotext lays out the axes, ticks and labels; that frame is rebuilt only
    when the size, limits or ticks change (resize, zoom). On a joint step
    only the wireframe moves: its braille cells are put on the last frame's
    canvas, where plotext would place them (``tests/scene/test_render.py`` checks
    that against plotext's own scatter of the same glyphs). In ASCII plotext
    draws the lines itself, on every frame.
    """

    def __init__(self) -> None:
        self.figure = _figure_class()
        self.figure.theme("clear")  # no colours: roles are styled by the widget
        # plotext caps a figure at the size of the terminal it sees (80x24
        # when headless); the view's size is the widget's, not the terminal's
        self.figure._limit_size(False, False)
        self.builds = 0  # how many times plotext built a picture (tests)
        self._frame_key: tuple | None = None
        self._frame: tuple[list[str], np.ndarray] | None = None

    def draw(self, scene: ViewScene, cols: int, rows: int, framing: Framing, look: Look) -> Picture:
        if cols < MIN_SIZE[0] or rows < MIN_SIZE[1]:
            return bare_picture(scene, cols, rows, framing, look)
        with_ticks = not scene.view.is_3d  # the 3-D view's scale is in its caption
        canvas_rows = rows - 2 if with_ticks else rows
        if with_ticks:  # a regular scale: a tick every k rows, on its value's row
            most = canvas_rows // LABELS_AT_LEAST  # rows apart, to leave that many labels
            per_dot, vertical, _ = regular_scale(framing.per_dot, most)
            cx, cy = framing.centre
            cy = -on_dots(-cy, per_dot, 4 * canvas_rows, TICK_DOT[1], 4)
            framing = Framing((cx, cy), per_dot)
        else:
            vertical = y_step(4 * framing.per_dot)
        # the y labels' width sets the canvas width: find the y ticks first
        _, ylim = limits_at(framing.centre, framing.per_dot, 2, canvas_rows)
        per_col = 2 * framing.per_dot
        # y labels two rows apart at least; x labels a space apart, as fine
        # as that allows (the same step on both axes where it can be)
        # (two spaces: plotext moves a label a column to make room, and then
        # leaves out its neighbour and its tick where only one was left)
        across = x_step(self._x_span(framing, cols), per_col, least=vertical, gap=2)
        y_ticks = tick_values(ylim, vertical) if with_ticks else []
        y_labels = [tick_label(v, vertical) for v in y_ticks]
        label_width = max((len(label) for label in y_labels), default=0)
        left = label_width + 1 if with_ticks else 0
        canvas_cols = cols - left
        if with_ticks:
            cx = on_dots(framing.centre[0], framing.per_dot, 2 * canvas_cols, TICK_DOT[0], 2)
            framing = Framing((cx, framing.centre[1]), framing.per_dot)
        xlim, ylim = limits_at(framing.centre, framing.per_dot, canvas_cols, canvas_rows)
        x_ticks = tick_values(xlim, across) if with_ticks else []
        if with_ticks:  # a label too near the edge plotext moves in, over its neighbour's
            x_ticks = _centred_fit(x_ticks, across, left, cols, xlim[0], framing.per_dot)
        x_labels = [tick_label(v, across) for v in x_ticks]
        canvas = (left, 0, canvas_cols, canvas_rows)
        if not all(map(math.isfinite, (*xlim, *ylim, *x_ticks, *y_ticks))):
            return bare_picture(scene, cols, rows, framing, look)
        middles = (
            cell_middles(xlim, framing.per_dot, 2),
            cell_middles(ylim, framing.per_dot, 4),
        )
        layout = (cols, rows, *middles, tuple(x_ticks), tuple(y_ticks), with_ticks)
        if look.ascii:  # plotext draws the lines too, with ASCII markers
            self._layout(layout, x_labels, y_labels)
            self._ascii_lines(scene, xlim, ylim)
            lines, roles = self._build(cols, rows, canvas, ascii_marks=True)
            lines = [line.translate(_ASCII_FRAME) for line in lines]
            return Picture(tuple(lines), roles, xlim, ylim, canvas)
        if layout != self._frame_key or self._frame is None:
            self._layout(layout, x_labels, y_labels)
            self._frame = self._build(cols, rows, canvas, ascii_marks=False)
            self._frame_key = layout
        frame_lines, frame_roles = self._frame
        chars, cell_roles = braille_cells(scene, canvas_cols, canvas_rows, xlim, ylim, look)
        lines = [
            frame_lines[y][:left] + "".join(chars[y]) if y < canvas_rows else frame_lines[y]
            for y in range(rows)
        ]
        roles = frame_roles.copy()
        roles[:canvas_rows, left:] = cell_roles
        return Picture(tuple(lines), roles, xlim, ylim, canvas)

    def _layout(self, layout: tuple, x_labels: list[str], y_labels: list[str]) -> None:
        cols, rows, xlim, ylim, x_ticks, y_ticks, with_ticks = layout
        fig = self.figure
        fig.clear_data()
        fig.xaxes(with_ticks, False)
        fig.yaxes(with_ticks, False)
        fig.plot_size(cols, rows)
        fig.xlim(*xlim)  # the middles of the first and last cells (cell_middles)
        fig.ylim(*ylim)
        fig.xticks(list(x_ticks), x_labels)
        fig.yticks(list(y_ticks), y_labels)
        # plotext draws ticks only for axes that hold data: one blank point
        fig.scatter([(xlim[0] + xlim[1]) / 2], [(ylim[0] + ylim[1]) / 2], marker=" ")

    def _build(self, cols: int, rows: int, canvas, *, ascii_marks: bool):
        """plotext's picture as rows of text, and each cell's role: the
        frame, ticks and labels are "axes"; in ASCII the marker names the
        role of a canvas cell."""
        text = _SGR.sub("", self.figure.build())
        self.builds += 1
        lines = [line.ljust(cols)[:cols] for line in text.split("\n")[:rows]]
        lines += [" " * cols] * (rows - len(lines))
        left, _, _, canvas_rows = canvas
        roles = np.full((rows, cols), NO_ROLE, dtype=np.int8)
        for y, line in enumerate(lines):
            for x, ch in enumerate(line):
                if ch == " ":
                    continue
                if y < canvas_rows and x >= left:
                    roles[y, x] = _MARK_ROLE.get(ch, NO_ROLE) if ascii_marks else NO_ROLE
                else:
                    roles[y, x] = _AXES
        return lines, roles

    @staticmethod
    def _x_span(framing: Framing, cols: int) -> tuple[float, float]:
        half = framing.per_dot * cols  # at most the whole width, 2 dots a column
        return (framing.centre[0] - half, framing.centre[0] + half)

    def _ascii_lines(self, scene: ViewScene, xlim, ylim) -> None:
        """plotext draws each role's lines with its ASCII marker."""
        by_role: dict[str, tuple[list, list]] = {}
        for line in scene.lines:
            xs, ys = _clip(np.asarray(line.xs), np.asarray(line.ys), xlim, ylim)
            if xs:
                px, py = by_role.setdefault(line.role, ([], []))
                if px:
                    px.append(None)
                    py.append(None)
                px += xs
                py += ys
        for role, (xs, ys) in by_role.items():
            self.figure.plot(xs, ys, marker=ASCII_MARKS[role])
        # the joints, then the tool over them; only marks on the picture:
        # plotext turns a point far off it into inf
        for mark in scene.marks or (Mark(*scene.end_effector, MARKER),):
            if xlim[0] <= mark.x <= xlim[1] and ylim[0] <= mark.y <= ylim[1]:
                self.figure.scatter([mark.x], [mark.y], marker=ASCII_MARKS[mark.role])
        return None


def _centred_fit(ticks: list[float], step: float, left: int, cols: int, x0: float, per_dot):
    """The x ticks whose labels fit centred under their columns (a column
    ``left`` + the cell of the value's dot), within the picture's width and
    short of its last column: plotext moves a label in from there, over its
    neighbour's, and then leaves one of them out with its tick."""
    kept = []
    for value in ticks:
        width = len(tick_label(value, step))
        col = left + round((value - x0) / per_dot) // 2 if per_dot > 0 else left
        start = col - width // 2
        if start >= 0 and start + width <= cols - 1:
            kept.append(value)
    return kept


def cell_middles(lim: tuple[float, float], per_dot: float, dots: int) -> tuple[float, float]:
    """The limits of a picture's axis (its outermost dots, ``per_dot``
    apart), moved in to the middles of its first and last cells of
    ``dots`` dots: plotext's limits. plotext places a value in the cell
    whose middle is nearest it, which is then the cell the braille raster
    draws it in."""
    half = (dots - 1) / 2 * per_dot
    return lim[0] + half, lim[1] - half


def braille_cells(scene: ViewScene, cols: int, rows: int, xlim, ylim, look: Look):
    """The wireframe's cells on a cols × rows canvas: braille glyphs (numpy
    puts the dots together) and each cell's role; without colour, letters
    name the axes at their tips."""
    raster = rasterize(scene, cols, rows, (xlim, ylim))
    chars = [list(line) for line in raster.lines]
    role_of = np.array([ROLE_INDEX[r] for r in raster.palette] + [NO_ROLE], dtype=np.int8)
    roles = role_of[raster.colours]  # colours == -1 picks NO_ROLE
    if look.mono:
        _label_tips(scene, chars, roles, xlim, ylim)
    return chars, roles


def _label_tips(scene: ViewScene, chars, roles: np.ndarray, xlim, ylim) -> None:
    """Without colour, a letter at the end of a frame axis names it: in the
    tip's own cell when the axis shows there (not under a link, joint or the
    tool), and never beside the same letter, so two frames' tips side by
    side never run together as ``xx``."""
    rows, cols = roles.shape
    sx = (2 * cols - 1) / (xlim[1] - xlim[0])
    sy = (4 * rows - 1) / (ylim[1] - ylim[0])
    taken: dict[tuple[int, int], str] = {}
    for tip in scene.tips:
        if not (math.isfinite(tip.x) and math.isfinite(tip.y)):
            continue
        x = round((tip.x - xlim[0]) * sx) // 2
        y = round((ylim[1] - tip.y) * sy) // 4
        if not (0 <= x < cols and 0 <= y < rows) or roles[y, x] != ROLE_INDEX[tip.role]:
            continue
        if (y, x) in taken or any(
            taken.get((y + dy, x + dx)) == tip.role for dy in (-1, 0, 1) for dx in (-1, 0, 1)
        ):
            continue
        chars[y][x] = tip.role
        taken[(y, x)] = tip.role


def bare_picture(scene: ViewScene, cols: int, rows: int, framing: Framing, look: Look) -> Picture:
    """The wireframe alone, every cell for the arm (no axes): the braille
    renderer, and views too small for axes."""
    if cols < 2 or rows < 2:
        return blank(max(cols, 0), max(rows, 0))
    xlim, ylim = limits_at(framing.centre, framing.per_dot, cols, rows)
    raster = rasterize(scene, cols, rows, (xlim, ylim))
    role_of = np.array([ROLE_INDEX[r] for r in raster.palette] + [NO_ROLE], dtype=np.int8)
    roles = role_of[raster.colours]
    chars = [list(line) for line in raster.lines]
    if look.mono or look.ascii:
        _label_tips(scene, chars, roles, xlim, ylim)
    if look.ascii:
        for y in range(rows):
            for x in range(cols):
                if roles[y, x] != NO_ROLE and ord(chars[y][x]) > 127:
                    chars[y][x] = ASCII_MARKS[CELL_ROLES[roles[y, x]]]
    lines = tuple("".join(row) for row in chars)
    return Picture(lines, roles, xlim, ylim, (0, 0, cols, rows))

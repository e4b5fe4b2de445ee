"""The views as an SVG drawing for a report: vector lines, not terminal cells.

Each view is a panel with its caption, a frame and numbered ticks in the
robot's unit (the same 1, 2, 5 × 10^k steps as on screen), and the scene
drawn in the order the screen draws it: the floor and its grid, the links'
shadow, the frame axes, the pedestal and the links over them, then the
joints (``●`` revolute, ``■`` prismatic) and the tool (``◆``). The page is
white, the links a strong orange, the axes red, green and blue. Nothing is
drawn with a font but the words and numbers, so the picture looks the same
in any viewer, a browser or LaTeX (through Inkscape or ``rsvg-convert``).

Plain text, no UI: the same picture at any size.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from html import escape

import numpy as np

from dhsim_tui.render.ticks import nice_step, tick_label, tick_values
from dhsim_tui.scene.clip import clip_segments
from dhsim_tui.scene.framing import Framing
from dhsim_tui.scene.projection import ViewScene, limits_at

#: how each line role is stroked: colour, width (px), dashes
STROKES: dict[str, tuple[str, float, str]] = {
    "grid": ("#d4d4d4", 0.8, "2 4"),
    "floor": ("#9a9a9a", 1.2, "5 3"),
    "floor_hit": ("#c000c0", 2.0, "5 3"),
    "shadow": ("#cfcfcf", 3.0, ""),
    "trail": ("#2f8f8f", 1.2, "3 2"),
    "x": ("#d62728", 1.6, ""),
    "y": ("#2ca02c", 1.6, ""),
    "z": ("#1f77b4", 1.6, ""),
    "pedestal": ("#8c8c8c", 7.0, ""),
    "link": ("#ff7f0e", 7.0, ""),
}
TOOL_COLOUR = "#c800c8"
JOINT_FILL, JOINT_EDGE = "#ffffff", "#202020"
FRAME_COLOUR, LABEL_COLOUR = "#a0a0a0", "#404040"
FONT = "DejaVu Sans, Helvetica, Arial, sans-serif"
#: room round a panel's plot: left (y labels), right, top (caption), bottom (x labels)
MARGINS = (52, 10, 24, 26)
MARGINS_3D = (10, 10, 24, 10)
#: the smallest gap between ticks, in pixels
TICK_GAP = 56


@dataclass(frozen=True)
class Panel:
    """One view placed on the page: where, how big, and what it shows."""

    scene: ViewScene
    caption: str
    x: float
    y: float
    width: float
    height: float

    @property
    def plot(self) -> tuple[float, float, float, float]:
        """The plot area: left, top, width, height (pixels)."""
        left, right, top, bottom = MARGINS_3D if self.scene.view.is_3d else MARGINS
        return (
            self.x + left,
            self.y + top,
            max(self.width - left - right, 8.0),
            max(self.height - top - bottom, 8.0),
        )

    @property
    def canvas(self) -> tuple[int, int]:
        """The plot area as braille cells (2 × 4 dots a cell, a dot a pixel),
        for the framings the screen uses."""
        _, _, width, height = self.plot
        return max(int(width) // 2, 1), max(int(height) // 4, 1)


def _n(value: float) -> str:
    return f"{value:.2f}".rstrip("0").rstrip(".")


class _Page:
    def __init__(self, width: float, height: float) -> None:
        self.width, self.height = width, height
        self.parts: list[str] = []
        self._clips = 0

    def add(self, text: str) -> None:
        self.parts.append(text)

    def clip(self, left: float, top: float, width: float, height: float) -> str:
        self._clips += 1
        name = f"plot{self._clips}"
        self.add(
            f'<clipPath id="{name}"><rect x="{_n(left)}" y="{_n(top)}" '
            f'width="{_n(width)}" height="{_n(height)}"/></clipPath>'
        )
        return name

    def text(self, x: float, y: float, words: str, *, size: float = 11, anchor: str = "start",
             colour: str = LABEL_COLOUR, weight: str = "normal") -> None:  # fmt: skip
        self.add(
            f'<text x="{_n(x)}" y="{_n(y)}" font-size="{_n(size)}" text-anchor="{anchor}" '
            f'fill="{colour}" font-weight="{weight}" xml:space="preserve">{escape(words)}</text>'
        )

    def svg(self) -> str:
        head = (
            '<svg xmlns="http://www.w3.org/2000/svg" '
            f'width="{_n(self.width)}" height="{_n(self.height)}" '
            f'viewBox="0 0 {_n(self.width)} {_n(self.height)}" font-family="{FONT}">\n'
            f'<rect width="100%" height="100%" fill="#ffffff"/>\n'
        )
        return head + "\n".join(self.parts) + "\n</svg>\n"


def _polylines(xs, ys, to_px) -> list[list[tuple[float, float]]]:
    """The points split where the pen lifts (NaN), as pixel coordinates."""
    strokes: list[list[tuple[float, float]]] = [[]]
    for x, y in zip(xs, ys, strict=True):
        if math.isfinite(x) and math.isfinite(y):
            strokes[-1].append(to_px(x, y))
        elif strokes[-1]:
            strokes.append([])
    return [stroke for stroke in strokes if len(stroke) > 1]


def _draw_panel(page: _Page, panel: Panel, framing: Framing) -> None:
    scene = panel.scene
    left, top, width, height = panel.plot
    cols, rows = panel.canvas
    xlim, ylim = limits_at(framing.centre, framing.per_dot, cols, rows)
    scale = min(width / (xlim[1] - xlim[0]), height / (ylim[1] - ylim[0]))
    mid_x, mid_y = left + width / 2, top + height / 2
    cx, cy = (xlim[0] + xlim[1]) / 2, (ylim[0] + ylim[1]) / 2
    # what the plot shows, at one scale on both axes
    span_x, span_y = width / scale, height / scale
    xlim, ylim = (cx - span_x / 2, cx + span_x / 2), (cy - span_y / 2, cy + span_y / 2)

    def to_px(x: float, y: float) -> tuple[float, float]:
        return (mid_x + (x - cx) * scale, mid_y - (y - cy) * scale)

    page.text(panel.x + 4, panel.y + 16, panel.caption, size=12, weight="bold")
    page.add(
        f'<rect x="{_n(left)}" y="{_n(top)}" width="{_n(width)}" height="{_n(height)}" '
        f'fill="none" stroke="{FRAME_COLOUR}" stroke-width="0.8"/>'
    )
    if not scene.view.is_3d:
        _ticks(page, panel, xlim, ylim, to_px, scale)
    clip = page.clip(left, top, width, height)
    page.add(f'<g clip-path="url(#{clip})" stroke-linecap="round" stroke-linejoin="round">')
    # cut to a little more than the plot first: a link far off it is no path of miles
    margin = 20 / scale
    box_x, box_y = (xlim[0] - margin, xlim[1] + margin), (ylim[0] - margin, ylim[1] + margin)
    for line in scene.lines:
        colour, stroke, dashes = STROKES.get(line.role, ("#808080", 1.0, ""))
        xs, ys = np.asarray(line.xs, float), np.asarray(line.ys, float)
        if xs.size < 2:
            continue
        x0, x1, y0, y1, shows = clip_segments(xs[:-1], xs[1:], ys[:-1], ys[1:], box_x, box_y)
        dash = f' stroke-dasharray="{dashes}"' if dashes else ""
        for a, b, c, d in zip(x0[shows], x1[shows], y0[shows], y1[shows], strict=True):
            (p, q), (r, s) = to_px(a, c), to_px(b, d)
            page.add(
                f'<line x1="{_n(p)}" y1="{_n(q)}" x2="{_n(r)}" y2="{_n(s)}" '
                f'stroke="{colour}" stroke-width="{_n(stroke)}"{dash}/>'
            )
    for mark in scene.marks:
        if math.isfinite(mark.x) and math.isfinite(mark.y):
            page.add(_mark(mark.role, *to_px(mark.x, mark.y)))
    page.add("</g>")


def _mark(role: str, x: float, y: float) -> str:
    """A joint (circle: revolute, square: prismatic) or the tool (diamond) at (x, y)."""
    if role == "tool":
        corners = ((x, y - 7), (x + 7, y), (x, y + 7), (x - 7, y))
        points = " ".join(f"{_n(a)},{_n(b)}" for a, b in corners)
        return f'<polygon points="{points}" fill="{TOOL_COLOUR}" stroke="#ffffff"/>'
    edge = f'fill="{JOINT_FILL}" stroke="{JOINT_EDGE}" stroke-width="1.6"'
    if role == "prismatic":
        return f'<rect x="{_n(x - 5)}" y="{_n(y - 5)}" width="10" height="10" {edge}/>'
    return f'<circle cx="{_n(x)}" cy="{_n(y)}" r="5" {edge}/>'


def _ticks(page: _Page, panel: Panel, xlim, ylim, to_px, scale: float) -> None:
    left, top, width, height = panel.plot
    step = nice_step(TICK_GAP / scale)
    unit = panel.scene.units
    for value in tick_values(xlim, step):
        px, _ = to_px(value, 0.0)
        page.add(
            f'<line x1="{_n(px)}" y1="{_n(top + height)}" x2="{_n(px)}" '
            f'y2="{_n(top + height + 4)}" stroke="{FRAME_COLOUR}"/>'
        )
        page.text(px, top + height + 16, tick_label(value, step), size=10, anchor="middle")
    for value in tick_values(ylim, step):
        _, py = to_px(0.0, value)
        page.add(
            f'<line x1="{_n(left - 4)}" y1="{_n(py)}" x2="{_n(left)}" y2="{_n(py)}" '
            f'stroke="{FRAME_COLOUR}"/>'
        )
        page.text(left - 6, py + 3.5, tick_label(value, step), size=10, anchor="end")
    if unit:
        page.text(left + width, top - 6, unit, size=10, anchor="end")


def _legend(page: _Page, x: float, y: float, kinds: set[str]) -> None:
    """What each mark means, in one row."""
    items: list[tuple[str, str]] = [("link", "links")]
    items += [
        (kind, kind if len(kinds) > 1 else "joint")
        for kind in ("revolute", "prismatic")
        if kind in kinds
    ]
    items += [("tool", "tool"), ("x", "x"), ("y", "y"), ("z", "z"), ("floor", "floor")]
    for role, words in items:
        if role in STROKES:
            colour, stroke, dashes = STROKES[role]
            dash = f' stroke-dasharray="{dashes}"' if dashes else ""
            page.add(
                f'<line x1="{_n(x)}" y1="{_n(y - 4)}" x2="{_n(x + 18)}" y2="{_n(y - 4)}" '
                f'stroke="{colour}" stroke-width="{_n(min(stroke, 5))}"{dash}/>'
            )
        else:
            page.add(_mark(role, x + 9, y - 4))
        page.text(x + 22, y, words, size=11)
        x += 34 + 7 * len(words)


def svg_figure(
    panels: Sequence[Panel],
    framings: Sequence[Framing],
    size: tuple[int, int],
    title: str,
    joint_kinds: set[str],
) -> str:
    """The page: a title line, the panels, a legend under them."""
    width, height = size
    page = _Page(width, height)
    page.text(8, 16, title, size=13, weight="bold")
    for panel, framing in zip(panels, framings, strict=True):
        _draw_panel(page, panel, framing)
    _legend(page, 12, height - 10, joint_kinds)
    return page.svg()


#: the page's own rows: the title above the panels, the legend under them
TITLE_ROOM, LEGEND_ROOM = 24, 26


def layout(
    scenes: Sequence[ViewScene], captions: Sequence[str], size: tuple[int, int]
) -> list[Panel]:
    """One panel over the page, or four in a 2 × 2 grid."""
    width, height = size
    inner = height - TITLE_ROOM - LEGEND_ROOM
    if len(scenes) == 1:
        return [Panel(scenes[0], captions[0], 0, TITLE_ROOM, width, inner)]
    half_w, half_h = width / 2, inner / 2
    return [
        Panel(scene, caption, (i % 2) * half_w, TITLE_ROOM + (i // 2) * half_h, half_w, half_h)
        for i, (scene, caption) in enumerate(zip(scenes, captions, strict=True))
    ]

"""Partial screen updates that start where the change starts.

Textual 8.2.8 writes a partial update (``ChopsUpdate.render_segments``) from
the left edge of each widget the changed span touches, cropping only on the
right ("TODO: crop to x extents" in its own console renderer). A view whose
arm moved near its right side resent the whole row from the view's left
border. This renderer skips the whole segments that end before the span and
starts at the first one that reaches it, as Textual's ``__rich_console__``
already does; a segment is never cut, so no wide character is split.

``install()`` replaces the method on the class (Textual is pinned exactly;
``tests/tui/test_bytes.py`` checks the screen comes out the same, cell for cell).
"""

from __future__ import annotations

from rich.console import Console
from rich.control import Control
from textual import _compositor
from textual.strip import Strip


def _from(strip: Strip, x: int, x1: int) -> tuple[int, Strip]:
    """The strip (drawn from column ``x``) without its segments that end at or
    before column ``x1``, and the column where what is left starts."""
    if x >= x1:
        return x, strip
    segments = list(strip)
    for index, segment in enumerate(segments):
        width = segment.cell_length
        if x + width > x1:
            rest = segments[index:]
            return x, Strip(rest, sum(s.cell_length for s in rest))
        x += width
    return x, Strip([], 0)


def render_segments(self: _compositor.ChopsUpdate, console: Console) -> str:
    """``ChopsUpdate.render_segments``, cropped on the left as well."""
    sequences: list[str] = []
    append = sequences.append
    move_to = Control.move_to
    chops = self.chops
    chop_ends = self.chop_ends
    last_y = self.spans[-1][0]
    for y, x1, x2 in self.spans:
        line = chops[y]
        ends = chop_ends[y]
        for end, (x, strip) in zip(ends, line.items(), strict=False):
            if strip is None or x > x2 or end <= x1:
                continue
            if end > x2:
                strip = strip.crop(0, x2 - x)
            x, strip = _from(strip, x, x1)
            if not strip.cell_length:
                continue
            append(move_to(x, y).segment.text)
            append(strip.render(console))
        if y != last_y:
            append("\n")
    return "".join(sequences)


#: Textual's own method, kept for the test that compares the two
ORIGINAL = _compositor.ChopsUpdate.render_segments


def install() -> None:
    _compositor.ChopsUpdate.render_segments = render_segments  # type: ignore[method-assign]

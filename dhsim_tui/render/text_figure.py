"""The views as plain text, as the simulator draws them: ``dhsim draw`` to a
``.txt`` file or to standard output (coloured when that is a terminal).

Each view is its plotext picture (ticks, braille, the links in blocks)
under a caption line; four views sit in a 2 × 2 grid with a column between.
No UI: the colours are plain SGR codes, one per role.
"""

from __future__ import annotations

from collections.abc import Sequence

from dhsim_tui.render.picture import CELL_ROLES, NO_ROLE, Look, Picture
from dhsim_tui.render.plotext_picture import PlotextPainter
from dhsim_tui.scene.framing import Framing
from dhsim_tui.scene.projection import ViewScene

#: the room the tick axes take in a plotext view (y labels, x axis and labels)
AXES_ROOM = (7, 2)
#: each role's colour in 256 colours (as the simulator's ``widgets.view_style``)
SGR = {
    "x": "38;5;167",
    "y": "38;5;71",
    "z": "38;5;69",
    "link": "38;5;208",
    "pedestal": "38;5;244",
    "tool": "1;38;5;207",
    "revolute": "1",
    "prismatic": "1",
    "floor": "38;5;242",
    "floor_hit": "1;38;5;220",
    "grid": "38;5;239",
    "shadow": "38;5;240",
    "trail": "38;5;73",
    "axes": "38;5;247",
    "cloud": "38;5;238",
}


def canvas(scene: ViewScene, cols: int, rows: int) -> tuple[int, int]:
    """The plot area of a ``cols`` × ``rows`` picture: the 3-D view has no tick axes."""
    if scene.view.is_3d:
        return cols, rows
    return max(cols - AXES_ROOM[0], 2), max(rows - AXES_ROOM[1], 2)


def _coloured(picture: Picture) -> list[str]:
    lines = []
    for line, roles in zip(picture.lines, picture.roles.tolist(), strict=True):
        out, start = [], 0
        for x in range(1, len(line) + 1):
            if x == len(line) or roles[x] != roles[start]:
                run = line[start:x]
                role = roles[start]
                code = SGR.get(CELL_ROLES[role]) if role != NO_ROLE else None
                out.append(f"\x1b[{code}m{run}\x1b[0m" if code else run)
                start = x
        lines.append("".join(out))
    return lines


def text_figure(
    scenes: Sequence[ViewScene],
    captions: Sequence[str],
    framings: Sequence[Framing],
    size: tuple[int, int],
    *,
    ascii: bool = False,
    colour: bool = False,
) -> str:
    """The views drawn in a ``size`` (columns, rows) block of text; each
    picture is one row shorter than its share, for its caption."""
    width, height = size
    look = Look(ascii=ascii, mono=not colour)
    if len(scenes) == 1:
        cells = [(width, height - 1)]
    else:
        cells = [((width - 1) // 2, (height - 1) // 2 - 1)] * len(scenes)
    blocks = []
    for scene, caption, framing, (cols, rows) in zip(
        scenes, captions, framings, cells, strict=True
    ):
        picture = PlotextPainter().draw(scene, cols, rows, framing, look)
        body = _coloured(picture) if colour else list(picture.lines)
        plain = list(picture.lines)
        blocks.append((caption[:cols].ljust(cols), body, plain, cols))
    if len(blocks) == 1:
        caption, body, _, _ = blocks[0]
        return "\n".join(line.rstrip() for line in [caption, *body]) + "\n"
    out: list[str] = []
    for pair in (blocks[:2], blocks[2:4]):
        out.append(" ".join(block[0] for block in pair).rstrip())
        for y in range(len(pair[0][1])):
            row = []
            for _caption, body, plain, cols in pair:
                pad = cols - len(plain[y])
                row.append(body[y] + " " * max(pad, 0))
            out.append(" ".join(row).rstrip())
    return "\n".join(out) + "\n"

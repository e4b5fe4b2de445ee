"""The workspace cloud under a view's picture: faint cells wherever the
picture's canvas is empty, so the arm, the floor and the axes always win.

The cloud's cells depend on the cloud, the view's limits and size and the
look, never on the joints: :class:`CloudLayer` makes them once and keeps them,
and each frame only lays them into the empty cells (a few numpy operations
on the canvas, a small fraction of a millisecond).

What a cloud cell shows: with colour, the cloud's braille dots thinned to a
chessboard (a light shade, its edges to a dot); without colour (NO_COLOR) a
middle dot ``·``, plainly not part of the arm's braille, in every cell of
its edge and every other cell inside (a light pattern); in 7-bit ASCII the
same with ``.``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from dhsim_tui.render.picture import NO_ROLE, ROLE_INDEX, Look, Picture
from dhsim_tui.scene.cloud import ViewCloud, braille_bits, cloud_dots, thinned

CLOUD_ROLE = ROLE_INDEX["cloud"]
#: the cloud's mark without colour, and in 7-bit ASCII
MONO_MARK = "·"
ASCII_MARK = "."


def cloud_glyphs(cloud: ViewCloud, cols: int, rows: int, xlim, ylim, look: Look) -> np.ndarray:
    """(rows, cols) code points of the cloud's cells, 0 where it has none."""
    dots = cloud_dots(cloud, cols, rows, xlim, ylim)
    if dots.size == 0:
        return np.zeros((max(rows, 0), max(cols, 0)), dtype=np.uint32)
    bits = braille_bits(dots)
    if look.ascii or look.mono:
        mark = ord(ASCII_MARK if look.ascii else MONO_MARK)
        return np.where(sparse_cells(bits > 0), mark, 0).astype(np.uint32)
    light = braille_bits(thinned(dots))
    # a cell whose dots all fall off the chessboard keeps its own
    shown = np.where(light > 0, light, bits)
    return np.where(shown > 0, shown + 0x2800, 0).astype(np.uint32)


def sparse_cells(occupied: np.ndarray) -> np.ndarray:
    """The cells to mark without colour: the cloud's edge (a cell with an
    empty neighbour, or at the picture's edge) all, its inside every other
    cell as on a chessboard, so a filled region is a light pattern."""
    rows, cols = occupied.shape
    padded = np.pad(occupied, 1, constant_values=False)
    inside = occupied & padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:]
    board = (np.add.outer(np.arange(rows), np.arange(cols)) % 2) == 0
    return occupied & (~inside | board)


def with_cloud(picture: Picture, glyphs: np.ndarray) -> Picture:
    """The picture with the cloud's glyphs in every canvas cell that is empty
    (a space with no role): the arm and everything else stay on top."""
    left, top, cols, rows = picture.canvas
    if glyphs.shape != (rows, cols) or not glyphs.any():
        return picture
    width = picture.size[0]
    text = "".join(picture.lines[top : top + rows])
    codes = np.frombuffer(text.encode("utf-32-le"), dtype=np.uint32).reshape(rows, width).copy()
    canvas = codes[:, left : left + cols]
    roles = picture.roles.copy()
    canvas_roles = roles[top : top + rows, left : left + cols]
    free = (glyphs != 0) & (canvas_roles == NO_ROLE) & (canvas == 0x20)
    if not free.any():
        return picture
    canvas[free] = glyphs[free]
    canvas_roles[free] = CLOUD_ROLE
    changed = np.flatnonzero(free.any(axis=1))
    lines = list(picture.lines)
    for y in changed.tolist():
        lines[top + y] = codes[y].tobytes().decode("utf-32-le")
    return replace(picture, lines=tuple(lines), roles=roles)


class CloudLayer:
    """One view's cloud cells, made once per cloud, limits, size and look."""

    def __init__(self) -> None:
        self._key: tuple | None = None
        self._cloud: ViewCloud | None = None
        self._glyphs: np.ndarray | None = None
        self.builds = 0  # how many times the cells were made (tests)

    def glyphs(self, cloud: ViewCloud, picture: Picture, look: Look) -> np.ndarray:
        _, _, cols, rows = picture.canvas
        key = (cloud.key, cols, rows, picture.xlim, picture.ylim, look)
        if cloud is not self._cloud or key != self._key or self._glyphs is None:
            self._glyphs = cloud_glyphs(cloud, cols, rows, picture.xlim, picture.ylim, look)
            self._key, self._cloud = key, cloud
            self.builds += 1
        return self._glyphs

    def under(self, picture: Picture, cloud: ViewCloud | None, look: Look) -> Picture:
        """The picture with the cloud behind it (unchanged without a cloud)."""
        if cloud is None:
            return picture
        return with_cloud(picture, self.glyphs(cloud, picture, look))

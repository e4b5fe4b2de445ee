"""What a view shows, as plain data: one string per terminal row and, per
cell, the scene role that drew it. Widgets turn roles into styles."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dhsim_tui.scene.framing import Framing
from dhsim_tui.scene.projection import ROLES

__all__ = ["CELL_ROLES", "NO_ROLE", "ROLE_INDEX", "Framing", "Look", "Picture", "blank"]

#: every role a cell can have: the scene's, then the plot's frame and ticks,
#: then the workspace cloud drawn behind everything (``render.cloud``)
CELL_ROLES: tuple[str, ...] = (*ROLES, "axes", "cloud")
ROLE_INDEX = {role: i for i, role in enumerate(CELL_ROLES)}
#: the index of an empty (or unstyled) cell
NO_ROLE = -1


@dataclass(frozen=True)
class Look:
    """How a terminal wants the view drawn."""

    ascii: bool = False
    #: no colour to tell things apart: letters name the axes at their tips
    mono: bool = False


@dataclass(frozen=True)
class Picture:
    """Rows of characters (one cell each) and a role index per cell."""

    lines: tuple[str, ...]
    roles: np.ndarray  # (rows, cols) int8, NO_ROLE for none
    xlim: tuple[float, float]
    ylim: tuple[float, float]
    #: where the plot area starts (column, row) and its size (cols, rows)
    canvas: tuple[int, int, int, int]

    @property
    def size(self) -> tuple[int, int]:
        rows, cols = self.roles.shape
        return cols, rows

    def text(self) -> str:
        return "\n".join(self.lines)


def blank(cols: int, rows: int) -> Picture:
    return Picture(
        tuple(" " * cols for _ in range(rows)),
        np.full((rows, cols), NO_ROLE, dtype=np.int8),
        (0.0, 1.0),
        (0.0, 1.0),
        (0, 0, cols, rows),
    )

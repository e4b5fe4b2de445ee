"""A command of the palette (ctrl+p): its name, a line of help, what it runs.
Each screen offers its own (``palette_commands()``); the palette adds the
app's."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

#: the views' names, in the order of the keys 1 2 3 4
VIEW_NAMES = ("top", "front", "side", "3-D")


@dataclass(frozen=True)
class PaletteCommand:
    """One line of the palette: its name, a line of help, what it runs."""

    title: str
    help: str
    run: Callable[[], Any]

"""The screen as an SVG, in the colours the terminal really has.

Textual's ``export_screenshot`` records the screen in full colour whatever
the terminal: a 16-colour screenshot came out byte for byte like a
truecolor one. Here each recorded colour is first brought down to the
terminal's depth (16 or 256 colours, as the terminal would show it), so a
picture of ``TERM=xterm`` looks like ``TERM=xterm``. Used by the simulator's
"Save picture" (``i``; :func:`write_picture` names the file) and by
``screenshots/generate.py``.
"""

from __future__ import annotations

import io
import re
import time
from pathlib import Path

from rich.color import ColorSystem
from rich.console import Console
from rich.segment import Segment
from rich.style import Style

from dhsim_tui.core.files.atomicfile import write_file
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.text import printable


def _downgraded(style: Style | None, system: ColorSystem) -> Style | None:
    if style is None:
        return None
    color = style.color.downgrade(system) if style.color is not None else None
    bgcolor = style.bgcolor.downgrade(system) if style.bgcolor is not None else None
    if color is style.color and bgcolor is style.bgcolor:
        return style
    return style + Style.from_color(color, bgcolor)


def export_svg(app, title: str | None = None) -> str:
    """What ``app`` shows now, as an SVG, in its terminal's colours."""
    width, height = app.size
    console = Console(
        width=width,
        height=height,
        file=io.StringIO(),
        force_terminal=True,
        color_system="truecolor",
        record=True,
        legacy_windows=False,
        safe_box=False,
    )
    # as Textual's own export_screenshot draws the screen
    screen_render = app.screen._compositor.render_update(
        full=True, screen_stack=app._background_screens
    )
    console.print(screen_render)
    system = app.console._color_system
    if system in (ColorSystem.STANDARD, ColorSystem.EIGHT_BIT):
        console._record_buffer[:] = [
            Segment(text, _downgraded(style, system), control)
            for text, style, control in console._record_buffer
        ]
    return console.export_svg(title=title or app.title)


def write_picture(app, robot_name: str) -> Path:
    """What ``app`` shows now, as an SVG in the working folder
    (``dhsim-<robot>-<date>-<time>.svg``, never over another file); the
    file's path. DhsimError when it cannot be written."""
    name = re.sub(r"[^A-Za-z0-9_-]+", "_", robot_name).strip("_")[:40] or "robot"
    stem = f"dhsim-{name}-{time.strftime('%Y%m%d-%H%M%S')}"
    data = export_svg(app, title=f"dhsim: {printable(robot_name)}").encode()
    for number in range(1, 100):
        path = Path(f"{stem}.svg" if number == 1 else f"{stem}-{number}.svg")
        if not path.exists():
            write_file(path, data)
            return path
    raise DhsimError(f"{stem}.svg and 98 more exist already")

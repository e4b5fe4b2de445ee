"""What the terminal can show: UTF-8, or only 7-bit ASCII.

A C locale, a Linux console (``TERM=linux``, whose fonts lack most of the
glyphs) or ``--ascii``: then every byte dhsim writes is ASCII (which one the
terminal has: :mod:`locale_env`). The screens write ASCII at the source where
it reads better (``deg``, ``...``, ``up/down``; :func:`shown`), borders are
``+ - |`` (the ``-ascii`` CSS class on the app), and the driver passes
everything it writes through :func:`~dhsim_tui.terminal.ascii_table.to_ascii`,
a translation that keeps every character's cell width, so a glyph nobody
thought of becomes ``?`` instead of a byte the terminal garbles.

This module imports neither Textual nor Rich at import time.
"""

from __future__ import annotations

from dhsim_tui.terminal.ascii_table import to_ascii


def ascii_mode(app: object | None = None) -> bool:
    """Whether ``app`` (default: the running Textual app, if any) draws in ASCII."""
    if app is None:
        try:
            from textual._context import active_app
        except ImportError:  # pragma: no cover - Textual is a dependency
            return False
        try:
            app = active_app.get()
        except LookupError:  # no app running (a test, the command line)
            return False
    return bool(getattr(app, "ascii_mode", False))


# -- at the source: words rather than look-alikes -----------------------------------
#: longer first: a pair of arrows before a single arrow
_PROSE = (
    ("↑ ↓", "up/down"),
    ("↑↓", "up/down"),
    ("← →", "left/right"),
    ("←→", "left/right"),
    ("⇄", "<->"),
    ("↔", "<->"),
    ("→", "->"),
    ("←", "<-"),
    ("↑", "up"),
    ("↓", "down"),
    (" · ", " | "),
    ("…", "..."),
    (" — ", " - "),
    ("—", "-"),
    ("–", "-"),
    ("°", " deg"),
    ("μ", "mu"),
    ("µ", "mu"),
    ("⏎", "enter"),
    ("≤", "<="),
    ("≥", ">="),
    ("±", "+/-"),
    ("⚠", "!"),
    ("×", "x"),
)


def ascii_text(text: str) -> str:
    """Text to read (a message, a hint, a title) in ASCII: words where a
    glyph stood (``↑↓`` -> ``up/down``, ``…`` -> ``...``, ``°`` -> `` deg``,
    `` · `` -> `` | ``), then :func:`to_ascii` for the rest. Not width-true:
    for text that is laid out afterwards, not for a fixed grid."""
    if text.isascii():
        return text
    for glyph, words in _PROSE:
        if glyph in text:
            text = text.replace(glyph, words)
    return to_ascii(text)


def shown(text: str, app: object | None = None) -> str:
    """``text`` as the screen shows it: as it is, or in ASCII (:func:`ascii_text`)
    when ``app`` (default: the running app) is in ASCII mode."""
    return ascii_text(text) if ascii_mode(app) else text


#: the footer's key names in ASCII (Textual's defaults and dhsim's own)
#: (a pair of arrows fits the 80-column footer only as three characters)
_KEY_WORDS = (
    ("^↑↓", "^up/dn"),
    ("↑↓", "^/v"),
    ("←→", "</>"),
    ("↑", "up"),
    ("↓", "down"),
    ("←", "left"),
    ("→", "right"),
    ("⏎", "enter"),
    ("⌫", "bksp"),
    ("⇥", "tab"),
)


def ascii_key(display: str) -> str:
    """A key as the footer shows it, in ASCII: ``↑↓`` -> ``^/v``, ``←→`` -> ``</>``,
    ``⏎`` -> ``enter``, ``^↑↓`` -> ``^up/dn``."""
    if display.isascii():
        return display
    for glyph, words in _KEY_WORDS:
        display = display.replace(glyph, words)
    return to_ascii(display)


# -- scrollbars -------------------------------------------------------------------
def install_ascii_scrollbars() -> None:
    """Scrollbars drawn without the partial-block glyphs at the thumb's ends
    while the running app is in ASCII mode (a thumb of whole cells, in colour).

    Textual picks the renderer from ``ScrollBar.renderer``; the one put there
    asks the running app each time, so other apps in the process (tests) are
    drawn as before. Installing twice changes nothing."""
    from textual.scrollbar import ScrollBar

    if not getattr(ScrollBar.renderer, "_dhsim_ascii_aware", False):
        ScrollBar.renderer = _mode_aware_renderer(ScrollBar.renderer)


def _mode_aware_renderer(base: type) -> type:
    class AsciiScrollBarRender(base):
        """No partial blocks: the thumb's ends round to whole cells."""

        VERTICAL_BARS = [" "] * len(base.VERTICAL_BARS)
        HORIZONTAL_BARS = [" "] * len(base.HORIZONTAL_BARS)

    class ModeAwareScrollBarRender(base):
        _dhsim_ascii_aware = True

        @classmethod
        def render_bar(cls, *args, **kwargs):
            if ascii_mode():
                return AsciiScrollBarRender.render_bar(*args, **kwargs)
            return base.render_bar(*args, **kwargs)

    return ModeAwareScrollBarRender

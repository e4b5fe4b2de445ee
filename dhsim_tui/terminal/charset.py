"""What the terminal can show: UTF-8, or only 7-bit ASCII.

A C locale, a Linux console (``TERM=linux``, whose fonts lack most of the
glyphs) or ``--ascii``: then every byte dhsim writes is ASCII. The screens
write ASCII at the source where it reads better (``deg``, ``...``,
``up/down``; :func:`shown`), borders are ``+ - |`` (the ``-ascii`` CSS class
on the app), and the driver passes everything it writes through
:func:`to_ascii`, a translation that keeps every character's cell width, so a
glyph nobody thought of becomes ``?`` instead of a byte the terminal garbles.

The locale must be read from the environment the process was started with:
CPython (PEP 538) sets ``LC_CTYPE=C.UTF-8`` in ``os.environ`` at start-up when
the locale is C, so ``os.environ`` says UTF-8 exactly when the terminal is not.
:func:`original_environ` undoes that from ``/proc/self/environ``, which the
kernel keeps as it was at exec.

This module is imported by the command line before Textual is: it imports
neither Textual nor Rich at import time.
"""

from __future__ import annotations

import os
import re
import unicodedata
from collections.abc import Mapping

#: the variables that name the character set, strongest first (POSIX)
LOCALE_VARIABLES = ("LC_ALL", "LC_CTYPE", "LANG")
#: what PEP 538 writes into LC_CTYPE when it coerces the C locale
COERCED_CTYPES = frozenset({"C.UTF-8", "C.utf8", "UTF-8"})
#: where Linux keeps the environment a process was started with
PROC_ENVIRON = "/proc/self/environ"


# -- which one ------------------------------------------------------------------
def _read_proc_environ(path: str) -> dict[str, str] | None:
    try:
        with open(path, "rb") as file:
            raw = file.read()
    except OSError:  # not Linux, no /proc, or not readable
        return None
    environ: dict[str, str] = {}
    for entry in raw.split(b"\0"):
        name, sep, value = entry.partition(b"=")
        if sep and name:
            environ[os.fsdecode(name)] = os.fsdecode(value)
    return environ


def original_environ(
    environ: Mapping[str, str] | None = None, proc_environ: str = PROC_ENVIRON
) -> dict[str, str]:
    """``environ`` (default: ``os.environ``) with ``LC_CTYPE`` as the process
    was started with, when Python's locale coercion (PEP 538) changed it.

    Only that change is undone: the variables as the program sees them are
    kept otherwise (a test may set them). Where ``/proc`` cannot be read
    (not Linux), ``environ`` as it is.
    """
    current = dict(os.environ if environ is None else environ)
    ctype = current.get("LC_CTYPE")
    if ctype not in COERCED_CTYPES:
        return current
    started = _read_proc_environ(proc_environ)
    if started is None or started.get("LC_CTYPE") == ctype:
        return current
    if "LC_CTYPE" in started:
        current["LC_CTYPE"] = started["LC_CTYPE"]
    else:
        del current["LC_CTYPE"]
    return current


def is_utf8_locale(name: str) -> bool:
    """``en_US.UTF-8``, ``C.utf8``, ``UTF-8``... (any case); not ``C``,
    ``POSIX``, ``en_US`` (Latin-1) or ``de_DE.ISO-8859-15``."""
    lowered = name.lower()
    return "utf-8" in lowered or "utf8" in lowered


def wants_ascii(environ: Mapping[str, str], *, force: bool | None = None) -> bool:
    """True when the screen must be 7-bit ASCII.

    ``force`` (``--ascii`` True, ``--unicode`` False) decides if given.
    Otherwise: ``TERM=linux`` (the Linux console) is ASCII; else the first
    non-empty of LC_ALL, LC_CTYPE, LANG decides: UTF-8 or not. None of them
    set is the C locale: ASCII.
    """
    if force is not None:
        return force
    if environ.get("TERM", "") == "linux":
        return True
    for variable in LOCALE_VARIABLES:
        value = environ.get(variable, "")
        if value:
            return not is_utf8_locale(value)
    return True


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


# -- the last safety net: char for char, same width ---------------------------------
#: single characters with an obvious ASCII look-alike of the same width
_LOOKALIKES = {
    # punctuation and symbols
    "…": "~",
    "·": ".",
    "•": "*",
    "∙": ".",
    "‧": ".",
    "°": "o",
    "º": "o",
    "μ": "u",
    "µ": "u",
    "×": "x",
    "÷": "/",
    "±": "+",
    "−": "-",
    "‐": "-",
    "‑": "-",
    "‒": "-",
    "–": "-",
    "—": "-",
    "―": "-",
    "‘": "'",
    "’": "'",
    "‚": ",",
    "‛": "'",
    "“": '"',
    "”": '"',
    "„": '"',
    "‹": "<",
    "›": ">",
    "«": "<",
    "»": ">",
    "≤": "<",
    "≥": ">",
    "≠": "#",
    "≈": "~",
    "∞": "8",
    "¦": "|",
    "§": "S",
    "¶": "P",
    "©": "c",
    "®": "r",
    "¬": "-",
    "\u00a0": " ",  # no-break space
    "\u2007": " ",
    "\u2009": " ",
    "\u202f": " ",
    "\u3000": "  ",  # ideographic space (wide)
    # markers
    "●": "*",
    "○": "o",
    "◉": "*",
    "◎": "o",
    "◆": "@",
    "◇": "o",
    "◈": "@",
    "■": "#",
    "□": "o",
    "▪": "#",
    "▫": "o",
    "★": "*",
    "☆": "*",
    "✓": "v",
    "✔": "v",
    "✗": "x",
    "✘": "x",
    "⚠": "!",
    "⏎": "<",
    "↵": "<",
    "⌫": "<",
    "⇥": ">",
    "⇤": "<",
    "⌃": "^",
    "⎋": "e",
    # triangles
    "▲": "^",
    "△": "^",
    "▴": "^",
    "▵": "^",
    "▶": ">",
    "▷": ">",
    "▸": ">",
    "▹": ">",
    "►": ">",
    "▻": ">",
    "▼": "v",
    "▽": "v",
    "▾": "v",
    "▿": "v",
    "◀": "<",
    "◁": "<",
    "◂": "<",
    "◃": "<",
    "◄": "<",
    "◅": "<",
    # block elements (half blocks, partial bars, shades, quadrants)
    "▀": "-",
    "▔": "-",
    "▁": "_",
    "▂": "_",
    "▃": "_",
    "▄": "=",
    "▅": "=",
    "▆": "=",
    "▇": "#",
    "█": "#",
    "▉": "#",
    "▊": "|",
    "▋": "|",
    "▌": "|",
    "▍": "|",
    "▎": "|",
    "▏": "|",
    "▐": "|",
    "▕": "|",
    "░": ".",
    "▒": ":",
    "▓": "#",
    "▖": ".",
    "▗": ".",
    "▘": "'",
    "▝": "'",
    "▚": ":",
    "▞": ":",
    "▙": "#",
    "▛": "#",
    "▜": "#",
    "▟": "#",
}


def _box_drawing(name: str) -> str:
    """U+2500..257F from its name: a line, a corner or crossing, a diagonal."""
    if "DIAGONAL" in name:
        if "CROSS" in name:
            return "X"
        return "/" if "UPPER RIGHT TO LOWER LEFT" in name else "\\"
    words = set(name.split())
    ways = words & {"UP", "DOWN", "LEFT", "RIGHT"}
    if "HORIZONTAL" in words:
        ways |= {"LEFT", "RIGHT"}
    if "VERTICAL" in words:
        ways |= {"UP", "DOWN"}
    if ways <= {"LEFT", "RIGHT"}:
        return "-"
    if ways <= {"UP", "DOWN"}:
        return "|"
    return "+"


def _braille(code: int) -> str:
    """A braille cell (2x4 dots) by how many dots it has."""
    dots = (code - 0x2800).bit_count()
    if dots == 0:
        return " "
    if dots <= 2:
        return "."
    if dots <= 4:
        return ":"
    return "*"


def _arrow(name: str) -> str:
    """An arrow (U+2190..21FF, U+27F0..27FF, U+2900..297F) by where it points."""
    left = "LEFTWARDS" in name or "LEFT " in name
    right = "RIGHTWARDS" in name or " RIGHT" in name
    up = "UPWARDS" in name or "UP " in name
    down = "DOWNWARDS" in name or " DOWN" in name
    if "NORTH EAST" in name or "SOUTH WEST" in name:
        return "/"
    if "NORTH WEST" in name or "SOUTH EAST" in name:
        return "\\"
    if left and right:
        return "="
    if up and down:
        return "|"
    if left:
        return "<"
    if right:
        return ">"
    if up:
        return "^"
    if down:
        return "v"
    return "?"


def _ascii_char(char: str, width: int) -> str:
    """An ASCII stand-in for ``char`` exactly ``width`` cells wide."""
    if width <= 0:
        return ""  # combining marks, zero-width and format characters, C1 controls
    if char in _LOOKALIKES and len(_LOOKALIKES[char]) == width:
        return _LOOKALIKES[char]
    code = ord(char)
    name = unicodedata.name(char, "")
    if width == 1:
        if 0x2500 <= code <= 0x257F:
            return _box_drawing(name)
        if 0x2800 <= code <= 0x28FF:
            return _braille(code)
        if "ARROW" in name:
            return _arrow(name)
        if "SPACE" in name and unicodedata.category(char) == "Zs":
            return " "
    # an accented letter, a superscript digit, a fullwidth form: its plain letters
    plain = "".join(
        c for c in unicodedata.normalize("NFKD", char) if c.isascii() and c.isprintable()
    )
    if len(plain) == width:
        return plain
    return "?" * width


class _AsciiTable(dict):
    """``str.translate`` table: ASCII stays, anything else is worked out on
    first sight and kept (each character costs one look-up after that)."""

    def __missing__(self, code: int) -> str:
        from rich.cells import get_character_cell_size

        char = chr(code)
        if code < 0x80:
            value = char
        else:
            try:
                width = get_character_cell_size(char)
            except (TypeError, ValueError):  # pragma: no cover - any str char has a size
                width = 1
            value = _ascii_char(char, width)
        self[code] = value
        return value


_TABLE = _AsciiTable()


#: a run of characters outside ASCII, with the printable one before it (``#`` + VS16)
_NON_ASCII_RUN = re.compile(r"[\x20-\x7e]?[^\x00-\x7f]+")


def _fit_run(match: re.Match[str]) -> str:
    """A run with a joiner or an emoji selector: Rich measures it as a whole
    (``⚠`` + VS16 is two cells), so its ASCII is padded or cut to that."""
    from rich.cells import cell_len

    run = match.group()
    out = run.translate(_TABLE)
    width = cell_len(run)
    return out[:width] if len(out) >= width else out + "?" * (width - len(out))


def to_ascii(text: str) -> str:
    """``text`` in 7-bit ASCII, character for character and cell for cell:
    ``╭─┤`` -> ``+-+``, ``●`` -> ``*``, ``◆`` -> ``@``, braille by its dots,
    a wide (CJK) character -> ``??``, a combining mark -> nothing, anything
    else -> ``?``. ASCII (control characters, escape sequences) passes as it
    is. Same width as Rich, and so Textual, measures: a drawn line stays in
    place."""
    if text.isascii():
        return text
    if "\u200d" in text or "\ufe0f" in text:  # widths that depend on the neighbours
        return _NON_ASCII_RUN.sub(_fit_run, text)
    return text.translate(_TABLE)


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

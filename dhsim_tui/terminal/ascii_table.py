"""The last safety net of ASCII mode: :func:`to_ascii` turns any text into 7-bit
ASCII, character for character and cell for cell, and the driver passes
everything it writes through it while the app is in ASCII mode
(:mod:`charset`). Each character gets an ASCII stand-in exactly as wide as
Rich, and so Textual, measures it: a look-alike from a table (``●`` -> ``*``),
box drawing as ``+ - |``, braille by its dots, an arrow by where it points, an
accented letter as its plain letter, anything else ``?`` (``??`` when wide);
a drawn line stays in place, and a glyph nobody thought of never becomes a
byte the terminal garbles. Rich is imported when the first character outside
ASCII is met, not at import time.
"""

from __future__ import annotations

import re
import unicodedata

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

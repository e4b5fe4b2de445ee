"""Text from files made safe to show: no character that steers a terminal.

A robot file is somebody else's text. Its name, pose names or a mistyped key
may hold an escape sequence (``ESC [ 2 J`` clears the screen), a C1 control
or a bidirectional override (U+202E turns the rest of a line around). Names
that hold one are refused on load (:func:`control_character`); every message
that quotes file content passes it through :func:`printable` first, and
text that may be long (a name, a key) through :func:`shortened`.
"""

from __future__ import annotations

import unicodedata

#: format characters that reorder or hide text (bidi controls, zero-width marks)
_INVISIBLE = frozenset(
    "\u200b\u200c\u200d\u200e\u200f\u202a\u202b\u202c\u202d\u202e"
    "\u2060\u2066\u2067\u2068\u2069\u2028\u2029\ufeff"
)


def is_control(char: str) -> bool:
    """C0, DEL, C1, bidi overrides and isolates, line/paragraph separators,
    zero-width characters, lone surrogates."""
    code = ord(char)
    if code < 0x20 or 0x7F <= code < 0xA0 or char in _INVISIBLE:
        return True
    return unicodedata.category(char) in ("Cc", "Cs")


def control_character(text: str) -> str | None:
    """The first control character in ``text``, escaped (``\\x1b``), or None."""
    for char in text:
        if is_control(char):
            return _escape(char)
    return None


def _escape(char: str) -> str:
    code = ord(char)
    if code <= 0xFF:
        return f"\\x{code:02x}"
    if code <= 0xFFFF:
        return f"\\u{code:04x}"
    return f"\\U{code:08x}"


def printable(text: str) -> str:
    """``text`` with every control character written as an escape
    (``\\x1b``, ``\\u202e``) and every backslash kept as it is."""
    if not any(is_control(c) for c in text):
        return text
    return "".join(_escape(c) if is_control(c) else c for c in text)


#: what stands for the middle of a shortened text
ELLIPSIS = " … "
#: the most characters of a file's text a message or a summary quotes
SHOWN_CHARS = 200


def shortened(text: str, limit: int = SHOWN_CHARS) -> str:
    """``text`` if it has at most ``limit`` characters, else its start and its
    end with `` … `` between, ``limit`` characters in all: a name or a key
    from a file is quoted whole when it is sane and never floods a line.
    (Pass the result through :func:`printable` before it is shown.)"""
    if len(text) <= limit:
        return text
    room = max(limit - len(ELLIPSIS), 2)
    head = (room + 1) // 2
    return f"{text[:head]}{ELLIPSIS}{text[len(text) - (room - head) :]}"


def counted(count: int, word: str, plural: str | None = None) -> str:
    """``1 joint``, ``6 joints``, ``0 joints``: a number and its noun in agreement."""
    return f"{count} {word if count == 1 else plural or word + 's'}"

"""Text from files made safe to show: no character that steers or hides.

A robot file is somebody else's text. Its name, pose names or a mistyped key
may hold an escape sequence (``ESC [ 2 J`` clears the screen), a C1 control,
a bidirectional control (U+202E turns the rest of a line around, U+061C is
an invisible right-to-left mark) or an invisible character (a tag character
U+E0041, an interlinear annotation mark U+FFF9). :func:`printable` is the one
escaper: every message, title or line that quotes file content or a user's
argument passes through it (text that may be long through :func:`shortened`
first), and it writes each such character as a visible escape: ``\\x1b``,
``\\u061c``, ``\\U000e0041``. Which characters it escapes is
:func:`is_control`: the Unicode categories of :data:`ESCAPED_CATEGORIES`
(Cc, Cf, Co, Cs, Zl, Zp) and the bidirectional controls by name
(:data:`BIDI_CONTROLS`, all Cf today). Letters, marks, digits, punctuation,
symbols and spaces of every script pass unchanged (``Braço``, ``机器人``,
``🤖``, variation selectors); so do unassigned code points (Cn), which steer
nothing.

Names are checked against a part of the same rule (:func:`control_character`,
:func:`steers`): a robot, pose or program name may not hold a character that
steers a terminal or the direction of text, or hides inside a name: a
control (Cc), a lone surrogate (Cs), a line or paragraph separator (Zl, Zp),
a bidi control, a zero-width character or the byte order mark
(:data:`ZERO_WIDTH`). The other format and private-use characters (a soft
hyphen, a tag character, an interlinear annotation mark, an icon font's
glyph) are allowed in a name, as they always were, and shown escaped
wherever the name is shown, by :func:`printable` like the rest.

The zero-width joiner U+200D is a format character: an emoji sequence joined
with it (``👨\\u200d👩``) is shown with the joiner escaped and refused in a
name, as it always was: a joiner can hide between any two characters, and
terminals disagree on how wide a joined sequence is.
"""

from __future__ import annotations

import unicodedata

#: the Unicode general categories :func:`printable` escapes: controls (C0,
#: DEL, C1), format characters (bidi marks, zero-width characters, tag
#: characters, interlinear annotation marks, the soft hyphen), private use,
#: lone surrogates, the line and paragraph separators
ESCAPED_CATEGORIES = frozenset({"Cc", "Cf", "Co", "Cs", "Zl", "Zp"})
#: the bidirectional controls (Unicode's Bidi_Control property): the Arabic
#: letter mark, the left-to-right and right-to-left marks, the embeddings and
#: overrides, the isolates. All are Cf; named so that none ever passes.
BIDI_CONTROLS = frozenset(
    "\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069"
)
#: zero-width characters that hide inside a name: space, non-joiner, joiner,
#: word joiner, byte order mark (all Cf)
ZERO_WIDTH = frozenset("\u200b\u200c\u200d\u2060\ufeff")
#: the categories a name may not hold at all (with the two sets above)
_STEERING_CATEGORIES = frozenset({"Cc", "Cs", "Zl", "Zp"})
#: str.isprintable() is False for every character either rule catches (it
#: is False for the categories C* and Z* but the space): a text it calls
#: printable needs no look at each character
_FAST = not any(char.isprintable() for char in BIDI_CONTROLS | ZERO_WIDTH)


def is_control(char: str) -> bool:
    """Whether :func:`printable` escapes ``char``: a character of
    :data:`ESCAPED_CATEGORIES` or a bidi control."""
    if char in BIDI_CONTROLS:
        return True
    return not char.isprintable() and unicodedata.category(char) in ESCAPED_CATEGORIES


def steers(char: str) -> bool:
    """Whether a name may not hold ``char``: a control, a lone surrogate, a
    line or paragraph separator, a bidi control, a zero-width character."""
    if char in BIDI_CONTROLS or char in ZERO_WIDTH:
        return True
    return not char.isprintable() and unicodedata.category(char) in _STEERING_CATEGORIES


def control_character(text: str) -> str | None:
    """The first character of ``text`` a name may not hold (:func:`steers`),
    escaped as :func:`printable` writes it (``\\x1b``, ``\\u061c``), or None."""
    if _FAST and text.isprintable():
        return None
    for char in text:
        if steers(char):
            return escaped(char)
    return None


def escaped(char: str) -> str:
    """One character as a visible escape: ``\\x1b``, ``\\u202e``, ``\\U000e0041``."""
    code = ord(char)
    if code <= 0xFF:
        return f"\\x{code:02x}"
    if code <= 0xFFFF:
        return f"\\u{code:04x}"
    return f"\\U{code:08x}"


def printable(text: str, also: str = "") -> str:
    """``text`` with every character that :func:`is_control` (and every one
    in ``also``) written as an escape (``\\x1b``, ``\\u202e``), every
    backslash kept as it is. The one escaper of dhsim: the command line,
    the simulator and the exports show text through it."""
    if _FAST and text.isprintable() and not (also and any(c in text for c in also)):
        return text
    if not any(is_control(c) or c in also for c in text):
        return text
    return "".join(escaped(c) if is_control(c) or c in also else c for c in text)


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

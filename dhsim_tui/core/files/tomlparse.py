"""TOML text parsed with care (:func:`parse_toml`): one UTF-8 byte order mark
taken off, and the text scanned first for what would make Python's TOML
parser slow or greedy (:func:`_hostile`: a key path of more than
:data:`MAX_KEY_PARTS` dotted parts, a line of more than
:data:`MAX_LINE_CHARS` characters), so a hostile file is refused at once,
naming the line. Every failure is a :class:`RobotFileError`.
"""

from __future__ import annotations

import re
import sys
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10: the same parser, as a package
    import tomli as tomllib

from dhsim_tui.core.files.atomicfile import file_error as _error
from dhsim_tui.core.model.text import shortened

#: a key path (``a.b.c = 1``, ``[a.b]``, ``[[a.b]]``, ``{ a.b = 1 }``) of more
#: parts than this is refused before parsing: dhsim's files need at most 3
#: (``poses."a b" = ...`` under a header); Python's parser takes time and
#: memory growing with the square of the parts (20,000: 7 s and 1.6 GB)
MAX_KEY_PARTS = 16
#: a line longer than this is refused before parsing: the longest a robot
#: file needs is a pose of 32 values or a name (at most 1,000 characters)
MAX_LINE_CHARS = 10_000

#: one part of a key: a bare word or a quoted string on one line. No nested
#: repetition (Python 3.10 has no possessive quantifiers): inside a repeat,
#: each alternative matches one character of a class of its own, so a failed
#: match backs off in linear time, never exponential.
_KEY_PART = r"""(?:[A-Za-z0-9_-]+|"(?:[^"\\\n]|\\.)*"|'[^'\n]*')"""
#: what the scan passes over whole: comments and strings (dots in them are no keys)
_SKIPPED = (
    r"#[^\n]*"
    r'|"""(?:[^"\\]|\\[\s\S]|"(?!""))*"{3,5}'
    r"|'''(?:[^']|'(?!''))*'{3,5}"
    r'|"(?:[^"\\\n]|\\.)*"'
    r"|'[^'\n]*'"
)
#: a run of more than MAX_KEY_PARTS dotted parts, a comment or string passed
#: over, or a quote that opens no string (the parser stops there: so does the scan).
#: Values have runs of at most 2 (``1.5``, ``07:32:00.25``); only keys have more.
_SCAN = re.compile(
    rf"(?P<deep>(?<![A-Za-z0-9_.-]){_KEY_PART}(?:[ \t]*\.[ \t]*{_KEY_PART}){{{MAX_KEY_PARTS}}})"
    rf"|{_SKIPPED}|(?P<stop>[\"'])"
)


def _hostile(text: str) -> str | None:
    """What in ``text`` would make the TOML parser slow or greedy, naming the
    line (None: nothing). Linear in the text: strings and comments are passed
    over once, and a run of dotted parts is tried from its first part only
    (from each part only when spaces stand around the dots: at most
    MAX_KEY_PARTS tries of a part)."""
    for match in _SCAN.finditer(text):
        if match.lastgroup == "stop":
            break
        if match.lastgroup == "deep":
            line = text.count("\n", 0, match.start()) + 1
            return (
                f"line {line}: a key path of more than {MAX_KEY_PARTS} dotted parts "
                f"({shortened(match.group(), 40)}); a robot file's keys have 1 to 3"
            )
    for number, line in enumerate(text.split("\n"), start=1):
        if len(line) > MAX_LINE_CHARS:
            return (
                f"line {number} is {len(line)} characters long; "
                f"a robot file's lines have at most {MAX_LINE_CHARS}"
            )
    return None


def parse_toml(text: str, source: str = "<robot>") -> dict[str, Any]:
    """The TOML document in ``text`` (one byte order mark may start it),
    refused before parsing when it holds what would make the parser hang
    (:func:`_hostile`); every failure is a RobotFileError starting with ``source``."""
    text = text.removeprefix("\ufeff")  # a byte order mark, as some editors write
    if text.startswith("\ufeff"):
        raise _error(f"{source}: starts with two byte order marks; a file may have one")
    problem = _hostile(text)
    if problem is not None:
        raise _error(f"{source}: {problem}")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise _error(f"{source}: not valid TOML: {exc}") from None
    except RecursionError:  # tomllib recurses into nested arrays and inline tables
        raise _error(f"{source}: not valid TOML: nested too deeply") from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise _error(f"{source}: not valid TOML: {exc}") from None

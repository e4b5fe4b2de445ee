"""TOML text parsed with care (:func:`parse_toml`): one UTF-8 byte order mark
taken off, and the text scanned first for what would make Python's TOML
parser slow or greedy (:func:`_hostile`), so a hostile file is refused at
once, naming the line:

* a key path of more than :data:`MAX_KEY_PARTS` dotted parts;
* a line of more than :data:`MAX_LINE_CHARS` characters;
* a multi-line string of more than :data:`MAX_STRING_CHARS` characters;
* more than :data:`MAX_TABLE_HEADERS` table headers, :data:`MAX_POSES`
  poses, :data:`MAX_PROGRAMS` programs, :data:`MAX_KEYS` keys in all (each
  part of a dotted key or a table header counted) or :data:`MAX_VALUES`
  values in lists and inline tables (counted by their commas).

Every limit is far above what a robot needs: a robot file has a few table
headers (``[tool]``, ``[poses]``, ``[programs]``, one ``[[joints]]`` a
joint, at most 32), names of at most 1,000 characters, and a few hundred
keys besides its poses and its programs' steps. Within the 1 MB a robot
file may have, the parser alone took 3 s and 400 MB on 26,000 table headers
of 16 parts, and 40,000 poses took seconds to check; what passes the scan
is parsed and checked in well under a second and 150 MB. The
scan runs in linear time and bounded memory: no pattern repeats a group
more than :data:`MAX_LINE_CHARS` or :data:`MAX_STRING_CHARS` times (Python's
``re`` keeps a little state for each repetition of a group: an 800 KB
multi-line string cost the old scan 90 MB). Every failure is a
:class:`RobotFileError`.
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
#: a multi-line string longer than this is refused: a robot file's strings
#: are names (at most 1,000 characters), a program's move or a pose's name
MAX_STRING_CHARS = 10_000
#: table headers (``[t]``, ``[[t]]``): a robot file has at most 35; each
#: costs the parser a table or two for each of its parts
MAX_TABLE_HEADERS = 1_000
#: poses (keys of ``[poses]``, or ``poses.NAME = ...``): a robot has tens;
#: each is checked against the joints, and each program step that names one
#: looks it up
MAX_POSES = 1_000
#: programs (keys of ``[programs]``, ``programs.NAME = ...``, ``[[programs.NAME]]``)
MAX_PROGRAMS = 1_000
#: keys in all, each part of a dotted key or table header counted (``a.b = 1``
#: is 2): the poses, a few hundred for the robot itself, the rest for the
#: programs' steps (each step 1 to 3 keys)
MAX_KEYS = 10_000
#: values in lists and inline tables, counted by the commas between them
#: (outside strings and comments): the poses' joint values (at most 32 a
#: pose), the steps of the programs and their joint values; each costs the
#: parser and the checks some microseconds
MAX_VALUES = 60_000

#: a basic string on one line, its characters counted: a bounded repeat, so
#: the scan's state stays small however long the line is
_BASIC = rf'"(?:[^"\\\n]|\\.){{0,{MAX_LINE_CHARS}}}"'
#: one part of a key: a bare word or a quoted string on one line. No nested
#: repetition (Python 3.10 has no possessive quantifiers): inside a repeat,
#: each alternative matches one character of a class of its own, so a failed
#: match backs off in linear time, never exponential.
_KEY_PART = rf"""(?:[A-Za-z0-9_-]+|{_BASIC}|'[^'\n]*')"""
_DOT = r"[ \t]*\.[ \t]*"
#: a key path of 1 to MAX_KEY_PARTS parts
_PATH = rf"{_KEY_PART}(?:{_DOT}{_KEY_PART}){{0,{MAX_KEY_PARTS - 1}}}"
#: where no key starts: inside a word or just after a dot
_NOT_IN_WORD = r"(?<![A-Za-z0-9_.-])"
_LINE_START = r"(?:(?<=\n)|\A)[ \t]*"
#: what the scan passes over whole: comments and strings (dots in them are no
#: keys), multi-line strings of at most MAX_STRING_CHARS characters (a longer
#: one, or one never closed, is ``long``)
_SKIPPED = (
    r"#[^\n]*"
    rf'|"""(?:[^"\\]|\\[\s\S]|"(?!"")){{0,{MAX_STRING_CHARS}}}"{{3,5}}'
    rf"|'''(?:[^']|'(?!'')){{0,{MAX_STRING_CHARS}}}'{{3,5}}"
    r"""|(?P<long>""\"|''')"""
    rf"|{_BASIC}"
    r"|'[^'\n]*'"
)
#: a run of more than MAX_KEY_PARTS dotted parts; a table header; a key at
#: the start of a line (``statement``: a key of the table above it) or
#: elsewhere (``key``: in an inline table); a comment or string passed over;
#: or a quote that opens no string (the parser stops there: so does the
#: scan). Values have runs of at most 2 parts (``1.5``, ``07:32:00.25``) and
#: no ``=`` after them.
_SCAN = re.compile(
    rf"(?P<deep>{_NOT_IN_WORD}{_KEY_PART}(?:{_DOT}{_KEY_PART}){{{MAX_KEY_PARTS}}})"
    rf"|(?P<header>{_LINE_START}\[\[?[ \t]*(?P<table>{_PATH})[ \t]*\])"
    rf"|(?P<statement>{_LINE_START}(?P<name>{_PATH})[ \t]*=)"
    rf"|(?P<key>{_NOT_IN_WORD}(?P<inline>{_PATH})[ \t]*=)"
    rf"|{_SKIPPED}|(?P<stop>[\"'])"
)
_PART = re.compile(_KEY_PART)
#: a line of more than MAX_LINE_CHARS characters, tried from the start of
#: each line only (from every character, a search would take quadratic time)
_LONG_LINE = re.compile(rf"(?<![^\n])[^\n]{{{MAX_LINE_CHARS + 1}}}")


def _parts(path: str) -> tuple[str, ...]:
    """A key path's parts as names (``"poses"`` is ``poses``; a quoted part
    with escapes stays quoted: no table of dhsim's has such a name)."""
    parts = []
    for part in _PART.findall(path):
        if part[:1] == "'" or (part[:1] == '"' and "\\" not in part):
            part = part[1:-1]
        parts.append(part)
    return tuple(parts)


class _Counts:
    """What the scan has met so far; each method returns the first count
    past its limit (None: none)."""

    def __init__(self) -> None:
        self.table: tuple[str, ...] = ()
        self.headers = 0
        self.keys = 0
        self.poses = 0
        self.programs: set[str] = set()
        self.commas = 0

    def values(self, text: str, start: int, end: int) -> tuple[int, str] | None:
        """The commas of ``text[start:end]`` (no string, no comment there)
        counted: where the first one past the limit is, and why (None: none)."""
        found = text.count(",", start, end)
        if self.commas + found <= MAX_VALUES:
            self.commas += found
            return None
        at = start - 1
        for _ in range(MAX_VALUES - self.commas + 1):
            at = text.index(",", at + 1)
        return at, (
            f"more than {MAX_VALUES:,} values in lists and inline tables (counted by "
            "their commas); a robot file has far fewer"
        )

    def header(self, path: tuple[str, ...]) -> str | None:
        self.headers += 1
        if self.headers > MAX_TABLE_HEADERS:
            return (
                f"more than {MAX_TABLE_HEADERS:,} table headers; a robot file has a few "
                "([tool], [poses], [programs], one [[joints]] a joint)"
            )
        self.table = path
        return self.key(path, path)

    def key(self, parts: tuple[str, ...], path: tuple[str, ...]) -> str | None:
        """A key of ``parts`` whose whole path is ``path`` (``()``: not known)."""
        self.keys += len(parts)
        if self.keys > MAX_KEYS:
            return (
                f"more than {MAX_KEYS:,} keys (each part of a dotted key or table "
                "header counted); a robot file has far fewer"
            )
        if len(path) == 2 and path[0] == "poses":
            self.poses += 1
            if self.poses > MAX_POSES:
                return f"more than {MAX_POSES:,} poses; a robot file has at most {MAX_POSES:,}"
        if len(path) >= 2 and path[0] == "programs":
            self.programs.add(path[1])
            if len(self.programs) > MAX_PROGRAMS:
                return (
                    f"more than {MAX_PROGRAMS:,} programs; "
                    f"a robot file has at most {MAX_PROGRAMS:,}"
                )
        return None


def _hostile(text: str) -> str | None:
    """What in ``text`` would make the TOML parser slow or greedy, naming the
    line (None: nothing). Linear in the text: strings and comments are passed
    over once, and a run of dotted parts is tried from its first part only
    (from each part only when spaces stand around the dots: at most
    MAX_KEY_PARTS tries of a part)."""
    counts = _Counts()
    passed = 0  # the end of the last match: what lies between holds values only
    for match in _SCAN.finditer(text):
        kind = match.lastgroup
        problem = None
        if kind == "stop":
            passed = len(text)  # the parser stops at the quote: nothing after it counts
            break
        too_many = counts.values(text, passed, match.start())
        if too_many is not None:
            return _at(text, *too_many)
        passed = match.end()
        if kind == "deep":
            problem = (
                f"a key path of more than {MAX_KEY_PARTS} dotted parts "
                f"({shortened(match.group(), 40)}); a robot file's keys have 1 to 3"
            )
        elif kind == "long":
            if len(text) - match.end() <= MAX_STRING_CHARS:
                passed = len(text)  # a short string never closed: the parser says so
                break
            problem = (
                f"a multi-line string of more than {MAX_STRING_CHARS:,} characters; "
                "a robot file's strings are names of at most 1,000"
            )
        elif kind == "header":
            problem = counts.header(_parts(match["table"]))
        elif kind == "statement":
            parts = _parts(match["name"])
            problem = counts.key(parts, counts.table + parts)
        elif kind == "key":
            problem = counts.key(_parts(match["inline"]), ())
        if problem is not None:
            return _at(text, match.start(), problem)
    too_many = counts.values(text, passed, len(text))
    if too_many is not None:
        return _at(text, *too_many)
    long_line = _LONG_LINE.search(text)
    if long_line is not None:
        start = long_line.start()
        end = text.find("\n", start)
        length = (len(text) if end < 0 else end) - start
        return (
            f"line {text.count(chr(10), 0, start) + 1} is {length} characters long; "
            f"a robot file's lines have at most {MAX_LINE_CHARS}"
        )
    return None


def _at(text: str, index: int, problem: str) -> str:
    """``problem`` with the line of ``text[index]``: ``line 12: ...``."""
    return f"line {text.count(chr(10), 0, index) + 1}: {problem}"


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

"""TOML values for :mod:`dhsim_tui.core.files.tomledit`: comparing a file's
value with the one it should hold, editing an array of numbers in place, and
writing an array of inline tables one table a line (a program's steps)::

    demo = [
      { move = "joint", to = "qr" },
      { wait = 0.5 },
    ]

:func:`rows_text` writes such an array as text (``dumps`` uses it for a
fresh file); :func:`rows_item` is the same array as a tomlkit item, for a
file updated in place.
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping, Sequence
from typing import Any

import tomlkit
from tomlkit.items import Array, Comment, InlineTable, Item, Table, Whitespace

#: how far a row of an array of inline tables is indented
ROW_INDENT = "  "
#: the items of a container's body that are not values: comments and blank lines
GAP_TYPES = (Comment, Whitespace)


# -- comparing -----------------------------------------------------------------


def plain(value: Any) -> Any:
    """A tomlkit item as plain Python (numbers as float, for comparing)."""
    if hasattr(value, "unwrap"):
        value = value.unwrap()
    if isinstance(value, bool | str):
        return value
    if isinstance(value, int | float):
        return float(value)
    if isinstance(value, Mapping):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [plain(v) for v in value]
    return value


def same(old: Any, new: Any) -> bool:
    """Does the file's ``old`` value read back as ``new``? (7 is 7.0; "7" is not)"""
    old = plain(old)
    if isinstance(new, float):
        return isinstance(old, float) and old == new
    if isinstance(new, Mapping):
        return (
            isinstance(old, Mapping)
            and list(old) == list(new)
            and all(same(old[k], v) for k, v in new.items())
        )
    if isinstance(new, list | tuple):
        return (
            isinstance(old, list)
            and len(old) == len(new)
            and all(same(o, n) for o, n in zip(old, new, strict=True))
        )
    return type(old) is type(new) and old == new


def frozen(value: Any) -> Any:
    """``value`` hashable: lists as tuples, tables as tuples of pairs."""
    if isinstance(value, Mapping):
        return tuple((k, frozen(v)) for k, v in value.items())
    if isinstance(value, list | tuple):
        return tuple(frozen(v) for v in value)
    return value


def is_rows(value: Any) -> bool:
    """A non-empty list of tables (``[[joints]]``, a program's steps)."""
    return (
        isinstance(value, list | tuple)
        and bool(value)
        and all(isinstance(v, Mapping) for v in value)
    )


# -- arrays of numbers ----------------------------------------------------------


def sync_array(array: Array, new: list) -> None:
    """Edit ``array`` element by element into ``new``, keeping unchanged
    elements (and the array's layout) as written."""
    old = [plain(v) for v in array]
    if not all(isinstance(v, float | str) for v in old):
        raise ValueError("an array of something other than numbers")
    if len(old) == len(new):  # a changed value (or two swapped) stays in its place
        for k, value in enumerate(new):
            if not same(array[k], value):
                array[k] = value
        return
    matcher = difflib.SequenceMatcher(None, old, new, autojunk=False)
    for tag, i1, i2, j1, j2 in reversed(matcher.get_opcodes()):
        if tag == "equal":
            continue
        common = min(i2 - i1, j2 - j1)
        for k in range(common):
            if not same(array[i1 + k], new[j1 + k]):
                array[i1 + k] = new[j1 + k]
        for k in reversed(range(i1 + common, i2)):
            del array[k]
        for k in range(j1 + common, j2):
            _insert(array, i1 + (k - j1), new[k])


def _insert(array: Array, index: int, value: Any) -> None:
    """Insert keeping the array's spacing (tomlkit writes ``[new,old]`` at 0)."""
    if index == 0 and len(array):
        first = array[0]
        array.insert(1, first)
        array[0] = value
    else:
        array.insert(index, value)


# -- rows of an array of tables ------------------------------------------------------


def match_rows(old: list[tuple], new: list[tuple]) -> list[int | None]:
    """For each new row, the old row it reuses (or None for a fresh one):
    unchanged runs first, then moved rows, then changed rows in place. When
    as many rows stay unchanged in their places as that keeps, and it would
    make a fresh row, every row stays in its place instead: of two equal
    rows, the one edited is changed where it is (not dropped and written anew)."""
    plan: list[int | None] = [None] * len(new)
    used: set[int] = set()
    opcodes = difflib.SequenceMatcher(None, old, new, autojunk=False).get_opcodes()
    for tag, i1, i2, j1, _j2 in opcodes:
        if tag == "equal":
            for k in range(i2 - i1):
                plan[j1 + k] = i1 + k
                used.add(i1 + k)
    for j, key in enumerate(new):
        if plan[j] is None:
            for i, old_key in enumerate(old):
                if i not in used and old_key == key:
                    plan[j] = i
                    used.add(i)
                    break
    for tag, i1, i2, j1, j2 in opcodes:
        if tag == "replace":
            free_old = [i for i in range(i1, i2) if i not in used]
            free_new = [j for j in range(j1, j2) if plan[j] is None]
            for i, j in zip(free_old, free_new, strict=False):
                plan[j] = i
                used.add(i)
    if len(old) == len(new) and None in plan:
        unchanged = sum(1 for j, i in enumerate(plan) if i is not None and old[i] == new[j])
        if sum(a == b for a, b in zip(old, new, strict=True)) >= unchanged:
            return list(range(len(new)))
    return plan


def pop_gap(row: Table) -> list:
    """Take the comments and blank lines that end ``row`` (they sit above the
    next row's header, or above what follows the array)."""
    body = row.value.body
    gap = []
    while body and body[-1][0] is None and isinstance(body[-1][1], GAP_TYPES):
        gap.insert(0, body.pop())
    return gap


def place_gaps(tables: list, plan: list[int | None], gaps: list[list], count: int) -> None:
    """Row i's heading is gaps[i - 1], written before its header; the last gap
    stays at the end. A deleted row's heading moves to the next surviving row."""
    heading: dict[int, list] = {i: gaps[i - 1] for i in range(1, count)}
    carried: list = []
    kept = set(plan)
    for i in range(count):
        if i not in kept:
            carried += heading.pop(i, [])
        elif carried:
            heading[i] = carried + heading.get(i, [])
            carried = []
    for j, table in enumerate(tables):
        own = heading.get(plan[j], []) if plan[j] is not None else []
        if j > 0 and not own:
            own = [(None, Whitespace("\n"))]
        text = "".join(item.as_string() for _, item in own)
        table.trivia.indent = text + table.trivia.indent
    final = carried + (gaps[count - 1] if count else [])
    tables[-1].value.body.extend(final)


# -- arrays of inline tables, one a line ------------------------------------------


def key_text(key: str) -> str:
    """A key as TOML writes it: bare when it can be, else quoted and escaped."""
    return tomlkit.key(key).as_string()


def inline_text(row: Mapping[str, Any]) -> str:
    """``{ move = "joint", to = [0.0, 45.0], speed = 50.0 }``."""
    if not row:
        return "{}"
    parts = [f"{key_text(k)} = {tomlkit.item(_list(v)).as_string()}" for k, v in row.items()]
    return "{ " + ", ".join(parts) + " }"


def _list(value: Any) -> Any:
    return list(value) if isinstance(value, tuple) else value


def rows_text(rows: Sequence[Mapping[str, Any]]) -> str:
    """An array of inline tables, one a line (``[]`` when there are none)."""
    if not rows:
        return "[]"
    return "[\n" + "".join(f"{ROW_INDENT}{inline_text(row)},\n" for row in rows) + "]"


def rows_item(rows: Sequence[Mapping[str, Any]]) -> Item:
    """:func:`rows_text` as a tomlkit item, to put in a document."""
    return tomlkit.parse(f"x = {rows_text(rows)}\n")["x"]


def inline_item(row: Mapping[str, Any]) -> InlineTable:
    """:func:`inline_text` as a tomlkit item."""
    return tomlkit.parse(f"x = {inline_text(row)}\n")["x"]


def section_text(name: str, table: Mapping[str, Sequence[Mapping[str, Any]]]) -> str:
    """A ``[name]`` table whose every value is an array of inline tables."""
    lines = [f"[{key_text(name)}]\n"]
    lines += [f"{key_text(key)} = {rows_text(rows)}\n" for key, rows in table.items()]
    return "".join(lines)

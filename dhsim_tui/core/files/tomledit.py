"""Update a TOML document in place, keeping the user's words (tomlkit).

:func:`update_text` takes the text of an existing file and the plain data it
should hold from now on, and changes only what differs: comments, blank lines,
key order, quoting and the spelling of unchanged numbers all survive. A value
that changes rewrites one line; a new key or pose adds one line next to its
neighbours; rows of an array of tables (``[[joints]]``) are matched to the new
rows so that inserting, deleting or moving one touches only that row.

The result is not trusted: :mod:`dhsim_tui.core.files.robotfile` parses it again and
falls back to a fresh document if it does not read back exactly.
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping, Sequence
from typing import Any

import tomlkit
from tomlkit.items import AoT, Array, Comment, InlineTable, Item, Table, Whitespace

#: the items of a container's body that are not values: comments and blank lines
_GAP_TYPES = (Comment, Whitespace)


def update_text(
    text: str,
    data: Mapping[str, Any],
    defaults: Mapping[str, Any],
    current: Mapping[str, Any] | None = None,
    ordered: tuple[str, ...] = (),
) -> str:
    """``text`` changed to hold ``data``.

    ``defaults`` holds, in the shape of ``data``, the value of every key a
    file may leave out (a list of them for an array of tables, one per new
    row); such a key that the file leaves out stays out while its value is the
    default. ``current`` is what ``text`` holds, completed with its defaults;
    it lets rows be matched by their values. ``ordered`` names the tables
    whose key order means something (the rest keep the file's order). Any
    tomlkit error propagates.
    """
    doc = tomlkit.parse(text)
    _sync_table(doc, data, defaults, current or {}, top=ordered)
    return doc.as_string()


# -- comparing ---------------------------------------------------------------


def _plain(value: Any) -> Any:
    """A tomlkit item as plain Python (numbers as float, for comparing)."""
    if hasattr(value, "unwrap"):
        value = value.unwrap()
    if isinstance(value, bool | str):
        return value
    if isinstance(value, int | float):
        return float(value)
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    return value


def _same(old: Any, new: Any) -> bool:
    """Does the file's ``old`` value read back as ``new``? (7 is 7.0; "7" is not)"""
    old = _plain(old)
    if isinstance(new, float):
        return isinstance(old, float) and old == new
    return type(old) is type(new) and old == new


# -- tables ------------------------------------------------------------------


def _sync_table(
    table: Any,
    new: Mapping[str, Any],
    defaults: Any,
    current: Any,
    top: tuple[str, ...] | None = None,
    keep_order: bool = False,
) -> None:
    """``top`` is given for the document itself: the names of its ordered tables."""
    defaults = defaults if isinstance(defaults, Mapping) else {}
    current = current if isinstance(current, Mapping) else {}
    for key in [k for k in table if k not in new]:
        del table[key]
    if keep_order:
        _reorder(table, new)
    for key, value in new.items():
        if key in table:
            ordered = top is not None and key in top
            _sync_value(table, key, value, defaults.get(key), current.get(key), ordered)
        elif key in defaults and _plain(defaults[key]) == _plain(value):
            continue  # left out of the file and still the default
        elif top is not None and isinstance(value, Mapping):
            skip = defaults.get(key) if isinstance(defaults.get(key), Mapping) else {}
            kept = {k: v for k, v in value.items() if k not in skip or _plain(skip[k]) != v}
            _add_section(table, key, kept, list(new))
        else:
            _add_key(table, key, value, list(new))


def _reorder(table: Any, new: Mapping[str, Any]) -> None:
    """Move the keys that are out of ``new``'s order (each with its trailing
    comment) next to their new neighbours; the others and the comments stay."""
    kept = [k for k in table if k in new]
    wanted = [k for k in new if k in kept]
    if kept == wanted:
        return
    stay: set[str] = set()
    for block in difflib.SequenceMatcher(None, kept, wanted, autojunk=False).get_matching_blocks():
        stay.update(kept[block.a : block.a + block.size])
    move = [k for k in kept if k not in stay]
    for count in range(1, len(move) + 1):  # rather the last ones (a pose added again)
        tail = set(wanted[-count:])
        if [k for k in kept if k not in tail] == [k for k in wanted if k not in tail]:
            move = wanted[-count:]
            break
    container = table.value if isinstance(table, Table | InlineTable) else table
    moving = {k: container.item(k) for k in move}
    for key in moving:
        del table[key]
    for key in wanted:
        if key in moving:
            _add_key(table, key, moving[key], list(new))


def _sync_value(
    table: Any, key: str, value: Any, default: Any, current: Any, ordered: bool = False
) -> None:
    old = table[key]
    if isinstance(value, Mapping):
        if isinstance(old, Table | InlineTable):
            _sync_table(old, value, default, current, keep_order=ordered)
        else:
            table[key] = dict(value)
    elif _is_rows(value):
        if isinstance(old, AoT | Array) and all(isinstance(r, Table | InlineTable) for r in old):
            _sync_rows(old, value, default, current)
        else:
            table[key] = [dict(v) for v in value]
    elif isinstance(value, list | tuple):
        if isinstance(old, Array):
            _sync_array(old, list(value))
        else:
            table[key] = list(value)
    elif not _same(old, value):
        table[key] = value


def _is_rows(value: Any) -> bool:
    return (
        isinstance(value, list | tuple)
        and bool(value)
        and all(isinstance(v, Mapping) for v in value)
    )


def _add_key(table: Any, key: str, value: Any, order: list[str]) -> None:
    """Add ``key`` after the nearest key that comes before it in ``order``
    (or before the first key after it), so the file keeps the schema's order."""
    if isinstance(table, InlineTable):
        table[key] = value
        return
    container = table.value if isinstance(table, Table) else table
    plain = {
        str(k.key): i
        for i, (k, item) in enumerate(container.body)
        if k is not None and not isinstance(item, Table | AoT)
    }
    position = order.index(key)
    before = [k for k in order[:position] if k in plain]
    after = [k for k in order[position + 1 :] if k in plain]
    if before:
        container._insert_after(before[-1], key, value)
    elif after:
        container._insert_at(plain[after[0]], key, value)
    else:
        container.append(key, value)


def _add_section(doc: Any, key: str, value: Mapping[str, Any], order: list[str]) -> None:
    """A new ``[table]``: before the first table or array of tables that
    comes after it in ``order`` (and before the comments heading it), else at
    the end."""
    section = tomlkit.table()
    for name, item in value.items():
        section[name] = list(item) if isinstance(item, tuple) else item
    later = set(order[order.index(key) + 1 :])
    body = doc.body
    for index, (k, item) in enumerate(body):
        if k is not None and str(k.key) in later and isinstance(item, Table | AoT):
            while (
                index > 0
                and body[index - 1][0] is None
                and isinstance(body[index - 1][1], _GAP_TYPES)
            ):
                index -= 1
            section.trivia.indent = "\n"
            if index > 0 and isinstance(body[index - 1][1], Table):
                # the comments that end the table before head the next one: keep them there
                section.value.body.extend(_pop_gap(body[index - 1][1]))
            doc._insert_at(index, key, section)
            return
    doc.append(key, section)


# -- arrays of numbers ----------------------------------------------------------


def _sync_array(array: Array, new: list) -> None:
    """Edit ``array`` element by element into ``new``, keeping unchanged
    elements (and the array's layout) as written."""
    old = [_plain(v) for v in array]
    if not all(isinstance(v, float | str) for v in old):
        raise ValueError("an array of something other than numbers")
    if len(old) == len(new):  # a changed value (or two swapped) stays in its place
        for k, value in enumerate(new):
            if not _same(array[k], value):
                array[k] = value
        return
    matcher = difflib.SequenceMatcher(None, old, new, autojunk=False)
    for tag, i1, i2, j1, j2 in reversed(matcher.get_opcodes()):
        if tag == "equal":
            continue
        common = min(i2 - i1, j2 - j1)
        for k in range(common):
            if not _same(array[i1 + k], new[j1 + k]):
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


# -- arrays of tables ([[joints]] or an inline array of tables) -------------------


def _row_key(row: Any, keys: Sequence[str]) -> tuple:
    plain = _plain(row)
    return tuple((k, plain.get(k, None)) for k in keys)


def _match(old: list[tuple], new: list[tuple]) -> list[int | None]:
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


def _sync_rows(rows: AoT | Array, new: Sequence[Mapping], defaults: Any, current: Any) -> None:
    keys = list(new[0])
    old_rows = list(rows)
    if isinstance(current, list) and len(current) == len(old_rows):
        old_keys = [_row_key(row, keys) for row in current]
    else:
        old_keys = [_row_key(row, keys) for row in old_rows]
    plan = _match(old_keys, [_row_key(row, keys) for row in new])
    given = defaults if isinstance(defaults, list) else []
    row_defaults = [d if isinstance(d, Mapping) else {} for d in given[: len(new)]]
    row_defaults += [{}] * (len(new) - len(row_defaults))
    if plan != list(range(len(old_rows))):
        # a fresh row is written like the old ones: a key none of them
        # writes is left out while it has its default (no "offset = 0.0")
        written = {str(key) for row in old_rows for key in row}
        fresh = [
            {k: v for k, v in row.items() if k in written or not _is_default(k, v, default)}
            for row, default in zip(new, row_defaults, strict=True)
        ]
        _rearrange(rows, old_rows, plan, fresh)
    for j, i in enumerate(plan):
        if i is not None:
            _sync_table(old_rows[i], new[j], row_defaults[j], None)


def _is_default(key: str, value: Any, defaults: Mapping[str, Any]) -> bool:
    return key in defaults and _plain(defaults[key]) == _plain(value)


def _fresh_row(rows: AoT | Array, values: Mapping[str, Any]) -> Item:
    row = tomlkit.table() if isinstance(rows, AoT) else tomlkit.inline_table()
    for key, value in values.items():
        row[key] = value
    if isinstance(row, InlineTable) and len(rows):  # spaced like its neighbours: { a = 1 }
        style = rows[0].as_string()
        items = [item for key, item in row.value.body if key is not None]
        if style.startswith("{ ") and items:
            items[0].trivia.indent = " "
        if style.endswith(" }") and items:
            items[-1].trivia.trail = " "
    return row


def _rearrange(rows: AoT | Array, old_rows: list, plan: list[int | None], new) -> None:
    """Put the rows in ``plan``'s order: drop the unused ones, move the
    reused ones, insert fresh ones. In ``[[joints]]`` the comments and blank
    lines above a row's header belong to that row and travel with it."""
    is_aot = isinstance(rows, AoT)
    gaps: list[list] = []
    if is_aot:
        gaps = [_pop_gap(row) for row in old_rows]
    kept = set(plan)
    for i in reversed(range(len(old_rows))):
        if i not in kept:
            del rows[i]
    order = [i for i in range(len(old_rows)) if i in kept]
    for j, i in enumerate(plan):
        if i is None:
            rows.insert(j, _fresh_row(rows, new[j]))
            order.insert(j, None)
        elif order[j] != i:
            k = order.index(i)
            row = rows[k]
            del rows[k]
            rows.insert(j, row)
            order.insert(j, order.pop(k))
    if is_aot:
        _place_gaps(list(rows), plan, gaps, len(old_rows))


def _pop_gap(row: Table) -> list:
    """Take the comments and blank lines that end ``row`` (they sit above the
    next row's header, or above what follows the array)."""
    body = row.value.body
    gap = []
    while body and body[-1][0] is None and isinstance(body[-1][1], _GAP_TYPES):
        gap.insert(0, body.pop())
    return gap


def _place_gaps(tables: list, plan: list[int | None], gaps: list[list], count: int) -> None:
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

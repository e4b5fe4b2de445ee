"""Update a TOML document in place, keeping the user's words (tomlkit).

:func:`update_text` takes the text of an existing file and the plain data it
should hold from now on, and changes only what differs: comments, blank lines,
key order, quoting and the spelling of unchanged numbers all survive. A value
that changes rewrites one line; a new key or pose adds one line next to its
neighbours; rows of an array of tables (``[[joints]]``, a program's steps)
are matched to the new rows so that inserting, deleting or moving one touches
only that row. An array of tables inside a table (a program under
``[programs]``) is written as inline tables, one a line
(:mod:`dhsim_tui.core.files.tomlitems`); at the top it is ``[[name]]`` tables.

The result is not trusted: :mod:`dhsim_tui.core.files.robotfile` parses it again and
falls back to a fresh document if it does not read back exactly.
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping, Sequence
from typing import Any

import tomlkit
from tomlkit.items import AoT, Array, InlineTable, Item, Table
from tomlkit.toml_document import TOMLDocument

from dhsim_tui.core.files.tomlitems import (
    GAP_TYPES,
    frozen,
    is_rows,
    match_rows,
    place_gaps,
    plain,
    pop_gap,
    rows_item,
    same,
    sync_array,
)


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
        _drop(table, key)
    if keep_order:
        _reorder(table, new)
    for key, value in new.items():
        if key in table:
            ordered = top is not None and key in top
            _sync_value(table, key, value, defaults.get(key), current.get(key), ordered)
        elif key in defaults and plain(defaults[key]) == plain(value):
            continue  # left out of the file and still the default
        elif top is not None and isinstance(value, Mapping):
            skip = defaults.get(key) if isinstance(defaults.get(key), Mapping) else {}
            kept = {k: v for k, v in value.items() if k not in skip or plain(skip[k]) != v}
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
    elif is_rows(value):
        rows = isinstance(old, AoT | Array) and len(old) > 0
        if rows and all(isinstance(r, Table | InlineTable) for r in old):
            _sync_rows(old, value, default, current)
        else:
            table[key] = _new_value(table, value)
    elif isinstance(value, list | tuple) and not value and isinstance(old, AoT | Array):
        if len(old):  # no rows left (a program without steps): an empty array
            _drop(table, key, tomlkit.array())
    elif isinstance(value, list | tuple):
        if isinstance(old, Array):
            sync_array(old, list(value))
        else:
            table[key] = list(value)
    elif not same(old, value):
        table[key] = value


def _new_value(table: Any, value: Any) -> Any:
    """``value`` as it is written into ``table``: an array of tables below the
    top as inline tables, one a line (a program's steps), unless its
    neighbours are ``[[programs.name]]`` tables; the rest as tomlkit makes it
    (``[[joints]]`` at the top)."""
    if is_rows(value) and not isinstance(table, TOMLDocument):
        if isinstance(table, Table) and any(isinstance(v, AoT) for _, v in table.value.body):
            return [dict(row) for row in value]
        return rows_item(value)
    if isinstance(value, tuple):
        return list(value)
    return value


def _add_key(table: Any, key: str, value: Any, order: list[str]) -> None:
    """Add ``key`` after the nearest key that comes before it in ``order``
    (or before the first key after it), so the file keeps the schema's order."""
    if not isinstance(value, Item):
        value = _new_value(table, value)
    if isinstance(table, InlineTable):
        table[key] = value
        return
    container = table.value if isinstance(table, Table) else table
    if not isinstance(value, Item) and is_rows(value):  # [[programs.name]] after its kind
        _append_rows(container, key, value)
        return
    placed = {
        str(k.key): i
        for i, (k, item) in enumerate(container.body)
        if k is not None and not isinstance(item, Table | AoT)
    }
    position = order.index(key)
    before = [k for k in order[:position] if k in placed]
    after = [k for k in order[position + 1 :] if k in placed]
    if before:
        container._insert_after(before[-1], key, value)
    elif after:
        container._insert_at(placed[after[0]], key, value)
    else:
        container.append(key, value)


def _append_rows(container: Any, key: str, rows: list) -> None:
    """A new array of tables after the last one in ``container``; it takes
    over the comments that ended that one (they head what follows)."""
    last = next((v for _, v in reversed(container.body) if isinstance(v, AoT) and len(v)), None)
    gap = pop_gap(last[-1]) if last is not None else []
    container.append(key, rows)
    container.item(key)[-1].value.body.extend(gap)


def _drop(table: Any, key: str, value: Any = None) -> None:
    """Delete ``key`` (or set it to ``value``). The comments that end an
    array of tables head what follows it: they stay, before the next table
    or at the end of ``table``."""
    item = table[key]
    rows = isinstance(item, AoT) and len(item) > 0 and not isinstance(table, InlineTable)
    gap = pop_gap(item[-1]) if rows else []
    container = table.value if isinstance(table, Table) else table
    names = [str(k.key) for k, _ in container.body if k is not None] if gap else [key]
    later = names[names.index(key) + 1 :]
    if value is None:
        del table[key]
    else:
        table[key] = value
    if not gap:
        return
    for name in later:
        following = container.item(name)
        first = following[0] if isinstance(following, AoT) and len(following) else following
        if isinstance(first, Table):
            first.trivia.indent = "".join(v.as_string() for _, v in gap) + first.trivia.indent
            return
    container.body.extend(gap)


def _add_section(doc: Any, key: str, value: Mapping[str, Any], order: list[str]) -> None:
    """A new ``[table]``: before the first table or array of tables that
    comes after it in ``order`` (and before the comments heading it), else at
    the end."""
    section = tomlkit.table()
    for name, item in value.items():
        section[name] = _new_value(section, item)
    later = set(order[order.index(key) + 1 :])
    body = doc.body
    for index, (k, item) in enumerate(body):
        if k is not None and str(k.key) in later and isinstance(item, Table | AoT):
            while (
                index > 0
                and body[index - 1][0] is None
                and isinstance(body[index - 1][1], GAP_TYPES)
            ):
                index -= 1
            section.trivia.indent = "\n"
            if index > 0 and isinstance(body[index - 1][1], Table):
                # the comments that end the table before head the next one: keep them there
                section.value.body.extend(pop_gap(body[index - 1][1]))
            doc._insert_at(index, key, section)
            return
    doc.append(key, section)


# -- arrays of tables ([[joints]] or an inline array of tables) -------------------


def _row_key(row: Any, keys: Sequence[str]) -> tuple:
    values = plain(row)
    return tuple((k, frozen(values.get(k, None))) for k in keys)


def _sync_rows(rows: AoT | Array, new: Sequence[Mapping], defaults: Any, current: Any) -> None:
    keys = list(dict.fromkeys(key for row in new for key in row))  # rows may differ in keys
    old_rows = list(rows)
    if isinstance(current, list) and len(current) == len(old_rows):
        old_keys = [_row_key(row, keys) for row in current]
    else:
        old_keys = [_row_key(row, keys) for row in old_rows]
    plan = match_rows(old_keys, [_row_key(row, keys) for row in new])
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
        if i is None:
            continue
        row = old_rows[i]
        if isinstance(row, InlineTable) and _reshaped(row, new[j], row_defaults[j]):
            # keys come or go: the row written anew (tomlkit would space it oddly)
            kept = {
                k: v
                for k, v in new[j].items()
                if k in row or not _is_default(k, v, row_defaults[j])
            }
            rows[j] = _fresh_row(rows, kept)
        else:
            _sync_table(row, new[j], row_defaults[j], None)


def _reshaped(row: InlineTable, new: Mapping[str, Any], defaults: Mapping[str, Any]) -> bool:
    """Would syncing ``row`` to ``new`` add or remove a key?"""
    gone = any(key not in new for key in row)
    return gone or any(k not in row and not _is_default(k, v, defaults) for k, v in new.items())


def _is_default(key: str, value: Any, defaults: Mapping[str, Any]) -> bool:
    return key in defaults and plain(defaults[key]) == plain(value)


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
        gaps = [pop_gap(row) for row in old_rows]
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
        place_gaps(list(rows), plan, gaps, len(old_rows))

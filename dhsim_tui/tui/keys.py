"""Keys, written once: the bindings make the footer, the key legend and the help.

A binding that belongs in the legend and the help has a :class:`Keys` group:
its ``description`` is the legend's words, its ``help`` the help's line; the
bindings of one group share a row (``↑ ↓ joint``). A binding without a group
is in the help alone, with its tooltip. Textual's footer shows a group's
bindings under its words only when more than one of them is shown, and no
group here shows more than one: the footer reads each binding's own label.

A widget that owns keys but cannot take focus (the views panel) has them
handed on by its screen with :func:`forwarded`: the same keys, ids, labels and
tooltips, calling the widget's ``action_*`` through the screen's
``action_forward``.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace

from textual.binding import Binding

from dhsim_tui.terminal.charset import ascii_text


@dataclass(frozen=True)
class Keys(Binding.Group):
    """A row of the legend and of the help: ``description`` (the legend's
    words) and ``help`` (the help's; the first binding's tooltip if empty).
    ``legend=False`` keeps the row out of the legend (help only)."""

    help: str = ""
    legend: bool = True


#: the arrows' glyphs (in ASCII they keep their names)
ARROWS = {"up": "↑", "down": "↓", "left": "←", "right": "→"}
#: how other keys are named in the legend and the help (Textual's key names)
KEY_NAMES = {
    "plus": "+",
    "comma": ",",
    "full_stop": ".",
    "space": "space",
    "minus": "-",
    "question_mark": "?",
    "left_square_bracket": "[",
    "right_square_bracket": "]",
    "enter": "enter",
}
#: keys that only stand in for another on some keyboards: not named
ALIASES = frozenset({"equals_sign"})
#: what the mouse does, the legend's last row
MOUSE_ROW = ("mouse", "click, wheel")


def key_name(key: str, ascii: bool = False) -> str:
    """``shift+left`` -> ``shift+←`` (ASCII: as it is); ``plus`` -> ``+``."""
    *modifiers, name = key.split("+")
    name = KEY_NAMES.get(name, name if ascii else ARROWS.get(name, name))
    return "+".join([*modifiers, name])


def binding_keys(binding: Binding, every: bool, ascii: bool = False) -> list[str]:
    """The names of a binding's keys: the first (``every`` False) or all of them."""
    keys = [k.strip() for k in binding.key.split(",") if k.strip() not in ALIASES]
    return [key_name(k, ascii) for k in (keys if every else keys[:1])]


def _joined(names: list[str], legend: bool) -> str:
    """``1 2 3 4`` -> ``1-4`` (legend); a shared modifier once: ``shift+← →``."""
    names = list(dict.fromkeys(names))
    prefixes = {n.rsplit("+", 1)[0] for n in names if "+" in n}
    if len(names) > 1 and len(prefixes) == 1 and all("+" in n for n in names):
        prefix = prefixes.pop()
        names = [names[0], *(n[len(prefix) + 1 :] for n in names[1:])]
    text = " ".join(names)
    if legend:
        text = re.sub(r"\b1 2 3 4\b", "1-4", text)
    return text


def _rows(bindings: Iterable[Binding]) -> list[tuple[Keys | None, list[Binding]]]:
    """The bindings by row: a group's together (where its first one stands),
    each ungrouped one alone."""
    rows: list[tuple[Keys | None, list[Binding]]] = []
    index: dict[Keys, int] = {}
    for binding in bindings:
        group = binding.group if isinstance(binding.group, Keys) else None
        if group is None:
            rows.append((None, [binding]))
        elif group in index:
            rows[index[group]][1].append(binding)
        else:
            index[group] = len(rows)
            rows.append((group, [binding]))
    return rows


def legend_rows(bindings: Iterable[Binding], ascii: bool = False) -> list[tuple[str, str]]:
    """(keys, words) for the key legend: one row per group, the mouse last."""
    rows = []
    for group, members in _rows(bindings):
        if group is None or not group.legend or not group.description:
            continue
        names = [name for b in members for name in binding_keys(b, False, ascii)]
        keys = _joined(names, legend=True)
        rows.append(("⏎" if keys == "enter" and not ascii else keys, group.description))
    rows.append(MOUSE_ROW)
    if ascii:
        rows = [(keys, ascii_text(words)) for keys, words in rows]
    return rows


def help_rows(
    bindings: Iterable[Binding], more: Mapping[str, str] | None = None
) -> list[tuple[str, str]]:
    """(keys, what they do) for the help: every row, ``more[id]`` added to the
    words of the row whose first binding has that id (a pose list, say)."""
    rows = []
    more = more or {}
    for group, members in _rows(bindings):
        names = [name for b in members for name in binding_keys(b, every=True)]
        words = (group.help if group is not None else "") or members[0].tooltip
        rows.append((_joined(names, legend=False), words + more.get(members[0].id or "", "")))
    return rows


def forwarded(bindings: Iterable[Binding], target: str) -> list[Binding]:
    """``bindings`` of the widget ``#target``, as its screen's: each calls the
    screen's ``forward(target, action, parameters)``."""
    out = []
    for binding in bindings:
        name, _, rest = binding.action.partition("(")
        parameters = ast.literal_eval(f"({rest[:-1]},)") if rest else ()
        # one tuple: Textual passes an action only as many values as it names
        out.append(replace(binding, action=f"forward({target!r}, {name!r}, {parameters!r})"))
    return out

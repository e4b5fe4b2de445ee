"""Fewer bytes to the terminal: drop the colour codes that change nothing.

Textual renders every segment of a line as its full SGR ("select graphic
rendition") sequence, the text and a reset (``Strip.render``), so two
neighbouring segments of the same colour are written as
``ESC[38;5;239;48;5;233m│ESC[0mESC[38;5;239;48;5;233m─ESC[0m``. Most of a
frame's bytes are such codes (``bench/bytes.py`` counts them by kind).

:func:`compact` keeps track of the attributes in force on the terminal and
of the ones the data asks for, and writes an SGR sequence only when
something is about to be drawn with attributes that differ, and then only
the difference (``ESC[1m`` to turn on bold) or a reset and the new
attributes, whichever is shorter. What the terminal shows is the same, cell
for cell. The rules that keep it so:

* SGR sequences are held back until text is printed. Cursor moves
  (``CUP``, ``CUU``..., carriage return, backspace, tab) never look at the
  attributes and pass straight through.
* Any other control sequence (erase in line or display uses the current
  background, insert/delete lines, scrolling, mode changes) is preceded by
  the attributes asked for so far, so it sees exactly what it saw before.
  After a sequence that may change the attributes on its own (restore
  cursor ``ESC 8`` or ``CSI u``, ``?1049l``, resets, anything not known to
  leave them alone) nothing is assumed any more.
* A line feed may scroll the screen, which fills the new line with the
  current background (and, on the Linux console, reverse and blink): the
  background, reverse and blink asked for are set before it.
* At the start, the attributes in force are unknown: SGR sequences pass
  unchanged until a reset makes them known. An SGR sequence this module does
  not model (colon sub-parameters, underline colours, fonts) passes unchanged
  too, and makes them unknown again.
* At the end of the data, the attributes asked for are set (a pending reset
  is written), so the next write starts from what Textual expects.

It is a pure function of one write, meant for
:meth:`~dhsim_tui.terminal.signals.DhsimDriver.write` to call on everything it writes
(``super().write(compact(data))``): a step's update takes about 0.2 ms, a
full 160x48 frame a few ms.
"""

from __future__ import annotations

import re
from functools import lru_cache

#: attributes: (the codes that are on, foreground, background); colours are
#: their SGR parameters ("31", "38;5;239", "38;2;1;2;3"), None the default
State = tuple[frozenset[int], str | None, str | None]
DEFAULT: State = (frozenset(), None, None)

#: attribute code -> the code that turns it off (bold and dim share 22, etc.)
_ON_OFF = {1: 22, 2: 22, 3: 23, 4: 24, 21: 24, 5: 25, 6: 25, 7: 27, 8: 28, 9: 29}
_ON_OFF.update({51: 54, 52: 54, 53: 55})
_OFF_CLEARS: dict[int, frozenset[int]] = {}
for _on, _off in _ON_OFF.items():
    _OFF_CLEARS[_off] = _OFF_CLEARS.get(_off, frozenset()) | {_on}
#: what a line scrolled in by a line feed shows besides the background:
#: reverse and blink (the Linux console's erase character has them)
_SCROLL_ATTRIBUTES = frozenset({5, 6, 7})

#: one token, as the groups of a match (findall): a run of SGR sequences with
#: plain parameters (the common case: a reset and the next colour), printable
#: text, another CSI sequence (whole, parameters, intermediates, final), an
#: OSC string, another escape or DCS/SOS/PM/APC string, one control character
_TOKEN = re.compile(
    r"((?:\x1b\[[0-9;]*m)+)"
    r"|([^\x00-\x1f\x7f-\x9f]+)"
    r"|(\x1b\[([0-?]*)([ -/]*)([@-~]))"
    r"|(\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)?)"
    r"|(\x1b[PX^_][^\x1b]*(?:\x1b\\)?|\x1b[ -/]*[0-~]?)"
    r"|([\x00-\x1f\x7f-\x9f])"
)
Token = tuple[str, str, str, str, str, str, str, str, str]
#: CSI finals that only move the cursor (CUU CUD CUF CUB CNL CPL CHA CUP VPA HPA HPR VPR HVP)
_MOVES = frozenset("ABCDEFGHd`aef")
#: CSI finals (no private marker) that leave the attributes alone: insert and
#: erase, scrolling, set/reset mode, margins, reports, repeat, window ops
_KEEPS = frozenset("@JKLMPSTXZbchlnrt")
#: private modes whose reset restores a saved cursor, attributes included
_RESTORING_MODES = frozenset({"47", "1047", "1048", "1049"})


class _Opaque(Exception):
    """An SGR sequence this module does not model."""


def _apply_known(state: State | None, params: list[str]) -> State | None:
    """The attributes after these SGR parameters; None while unknown (before
    the first reset, when ``state`` is None). Raises ``_Opaque``."""
    attrs = set(state[0]) if state is not None else set()
    fg, bg = (state[1], state[2]) if state is not None else (None, None)
    known = state is not None
    i = 0
    while i < len(params):
        p = params[i] or "0"
        if not p.isdigit():
            raise _Opaque
        code = int(p)
        if code == 0:
            attrs, fg, bg, known = set(), None, None, True
        elif code in _ON_OFF:
            attrs.add(code)
        elif code in _OFF_CLEARS:
            attrs -= _OFF_CLEARS[code]
        elif 30 <= code <= 37 or 90 <= code <= 97:
            fg = str(code)
        elif code == 39:
            fg = None
        elif 40 <= code <= 47 or 100 <= code <= 107:
            bg = str(code)
        elif code == 49:
            bg = None
        elif code in (38, 48):
            kind = params[i + 1] if i + 1 < len(params) else ""
            if kind == "5" and i + 2 < len(params):
                values = params[i + 2 : i + 3]
            elif kind == "2" and i + 4 < len(params):
                values = params[i + 2 : i + 5]
            else:
                raise _Opaque
            if not all(v.isdigit() and int(v) <= 255 for v in values):
                raise _Opaque
            colour = ";".join([str(code), kind, *(str(int(v)) for v in values)])
            i += 1 + len(values)
            if code == 38:
                fg = colour
            else:
                bg = colour
        else:
            raise _Opaque
        i += 1
    return (frozenset(attrs), fg, bg) if known else None


@lru_cache(maxsize=4096)
def _apply(state: State | None, params: str) -> State | _Opaque | None:
    """The attributes after ``ESC[{params}m`` (None: still unknown; an
    ``_Opaque`` instance: not modelled)."""
    try:
        return _apply_known(state, params.split(";"))
    except _Opaque as opaque:
        return opaque


def _full(state: State) -> list[str]:
    attrs, fg, bg = state
    codes = [str(code) for code in sorted(attrs)]
    if fg is not None:
        codes.append(fg)
    if bg is not None:
        codes.append(bg)
    return codes


@lru_cache(maxsize=4096)
def _transition(current: State | None, target: State) -> str:
    """The shortest SGR sequence that turns ``current`` into ``target``."""
    if current == target:
        return ""
    reset = ";".join(["0", *_full(target)]) if target != DEFAULT else "0"
    if current is None:
        return f"\x1b[{reset}m"
    attrs, fg, bg = current
    new_attrs, new_fg, new_bg = target
    codes: list[str] = []
    removed = attrs - new_attrs
    offs = sorted({_ON_OFF[code] for code in removed})
    codes.extend(str(off) for off in offs)
    cleared = set().union(*(_OFF_CLEARS[off] for off in offs)) if offs else set()
    # what an off code cleared that should stay on, and what is new
    codes.extend(str(code) for code in sorted(new_attrs - (attrs - cleared)))
    if fg != new_fg:
        codes.append(new_fg if new_fg is not None else "39")
    if bg != new_bg:
        codes.append(new_bg if new_bg is not None else "49")
    diff = ";".join(codes)
    return f"\x1b[{diff if len(diff) < len(reset) else reset}m"


def _scroll_safe(base: State, target: State) -> State:
    """``base`` with what a line scrolled in by a line feed shows taken from
    ``target``: the background, reverse and blink, and the foreground when
    reverse is on."""
    attrs, fg, _ = base
    new_attrs, new_fg, new_bg = target
    attrs = (attrs - _SCROLL_ATTRIBUTES) | (new_attrs & _SCROLL_ATTRIBUTES)
    if 7 in new_attrs:
        fg = new_fg
    return attrs, fg, new_bg


@lru_cache(maxsize=4096)
def _apply_run(state: State, run: str) -> State | None:
    """The attributes after a run of plain SGR sequences, from a known state
    (None: the run needs a closer look, one sequence at a time)."""
    new: State | _Opaque | None = state
    for sequence in run[2:-1].split("m\x1b["):
        new = _apply(new, sequence)
        if new is None or isinstance(new, _Opaque):
            return None
    return new


def _is_move(token: Token) -> bool:
    """A cursor move: CR, backspace, tab, or one of the CSI moves."""
    if token[8]:
        return token[8] in "\r\b\t"
    return (
        bool(token[2])
        and token[5] in _MOVES
        and not token[4]
        and token[3][:1] not in ("<", "=", ">", "?")
    )


def _next_target(tokens: list[Token], start: int, target: State) -> State | None:
    """The attributes asked for when something is next drawn after
    ``tokens[start]`` (skipping cursor moves and SGR sequences); None if
    they will not be known."""
    for token in tokens[start + 1 :]:
        if token[0]:
            new = _apply_run(target, token[0])
            if new is None:
                return None
            target = new
        elif not _is_move(token):
            break
    return target


def _before_line_feed(current: State, target: State, tokens: list[Token], at: int) -> State:
    """What to set before a line feed (which may scroll, see the module):
    whichever state with the right scroll attributes makes this and the next
    SGR sequence shortest in all."""
    after = _next_target(tokens, at, target)
    candidates = [target, _scroll_safe(current, target)]
    if after is not None:
        candidates.append(_scroll_safe(after, target))

    def cost(state: State) -> int:
        now = len(_transition(current, state))
        return now + (len(_transition(state, after)) if after is not None else 0)

    return min(candidates, key=cost)


def compact(data: str) -> str:
    """``data`` (what Textual writes to the terminal) with the SGR sequences
    that change nothing left out; the terminal shows the same. See the module."""
    if "\x1b[" not in data:
        return data
    out: list[str] = []
    append = out.append
    current: State | None = None  # in force on the terminal (None: unknown)
    target: State | None = None  # asked for by the data so far
    tokens: list[Token] = _TOKEN.findall(data)

    for index, token in enumerate(tokens):
        run, text, csi, params, inter, final, osc, other, ctrl = token
        if text:
            if current != target:
                append(_transition(current, target))  # type: ignore[arg-type]
                current = target
            append(text)
            continue
        if run:
            new = _apply_run(target, run) if target is not None else None
            if new is not None:
                target = new
                continue
            # unknown attributes, or a sequence not modelled: one at a time
            for sequence in run[2:-1].split("m\x1b["):
                state = _apply(target, sequence)
                if isinstance(state, _Opaque):
                    if current != target:
                        append(_transition(current, target))  # type: ignore[arg-type]
                    append(f"\x1b[{sequence}m")
                    current = target = None
                elif state is None:  # unknown and still unknown: as it was
                    append(f"\x1b[{sequence}m")
                else:
                    target = state
            continue
        if csi:
            private = params[:1] in ("<", "=", ">", "?")
            if final in _MOVES and not inter and not private:
                append(csi)
                continue
            if current != target:
                append(_transition(current, target))  # type: ignore[arg-type]
                current = target
            append(csi)
            if private and final in "hl" and params[:1] == "?":
                # ?1049l and the like restore a saved cursor, attributes and all
                keeps = final == "h" or not (_RESTORING_MODES & set(params[1:].split(";")))
            elif private:
                keeps = final in "nc"  # reports
            else:
                # SGR with sub-parameters (4:3) is not modelled either
                keeps = final in _KEEPS and not inter
            if not keeps:
                current = target = None
            continue
        if ctrl:
            if ctrl in "\r\b\t\x00\x07\x7f\x0e\x0f":  # moves, nothing, charset shifts
                append(ctrl)
                continue
            if ctrl in "\n\x0b\x0c":  # may scroll: the new line's background
                if current is None and target is not None:
                    append(_transition(current, target))
                    current = target
                elif current is not None and current != target:
                    state = _before_line_feed(current, target, tokens, index)  # type: ignore[arg-type]
                    append(_transition(current, state))
                    current = state
                append(ctrl)
                continue
            # another C0 or a C1 control: as if it were any other sequence
            if current != target:
                append(_transition(current, target))  # type: ignore[arg-type]
            append(ctrl)
            current = target = None
            continue
        # OSC (titles, hyperlinks): attributes stay; other escapes and strings
        # (save/restore cursor, resets, charsets, DCS): assume nothing after
        if current != target:
            append(_transition(current, target))  # type: ignore[arg-type]
            current = target
        append(osc or other)
        if not osc:
            current = target = None
    if current != target:
        append(_transition(current, target))  # type: ignore[arg-type]
    return "".join(out)

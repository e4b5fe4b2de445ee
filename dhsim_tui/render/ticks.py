"""Numbered ticks: 1, 2 or 5 × 10^k steps in the robot's unit, at every scale
(a robot in metres gets 0.5 m or 0.2 m ticks, one in millimetres 100 mm)."""

from __future__ import annotations

import math


def nice_step(least: float) -> float:
    """The smallest 1, 2 or 5 × 10^k that is at least ``least``."""
    if not least > 0 or not math.isfinite(least):
        return 1.0
    power = 10.0 ** math.floor(math.log10(least))
    for factor in (1.0, 2.0, 5.0, 10.0):
        if factor * power >= least * (1 - 1e-12):
            return factor * power
    return 10.0 * power


def tick_values(lim: tuple[float, float], step: float) -> list[float]:
    first = math.ceil(lim[0] / step - 1e-9)
    last = math.floor(lim[1] / step + 1e-9)
    return [k * step for k in range(first, last + 1)]


def tick_label(value: float, step: float) -> str:
    decimals = max(0, -math.floor(math.log10(step) + 1e-12))
    text = f"{value:.{decimals}f}"
    return "0" if float(text) == 0 else text


def y_step(per_row: float) -> float:
    """The step of a vertical axis: labels at least two rows apart."""
    return nice_step(2 * per_row)


def x_step(lim: tuple[float, float], per_col: float, least: float = 0.0, gap: int = 1) -> float:
    """The finest 1, 2, 5 × 10^k step (and at least ``least``) whose labels,
    centred on their ticks along a horizontal axis of limits ``lim`` with
    ``per_col`` robot units to a column, keep ``gap`` spaces between them."""
    step = nice_step(max(2 * per_col, least))
    for _ in range(64):  # a few decades at most
        labels = [tick_label(v, step) for v in (lim[0], lim[1], *tick_values(lim, step)[:3])]
        if step >= (max(map(len, labels)) + gap) * per_col * (1 - 1e-9):
            break
        step = nice_step(step * 1.000001)
    return step


#: the fewest and the most rows between the labels of a vertical axis in a
#: regular scale (:func:`regular_scale`): two at least, as ``y_step``
ROWS_APART = (2, 8)


def regular_scale(per_dot: float, most_rows: int = ROWS_APART[1]) -> tuple[float, float, int]:
    """The smallest length per braille dot, at least ``per_dot``, at which a
    1, 2 or 5 × 10^k step is a whole number of rows (a row is 4 dots, a
    column 2), from 2 to ``most_rows`` rows: (that length, the step, the
    rows between labels). Of equal lengths, the finer step.

    At that scale every tick of a vertical axis is the same number of rows
    from the next, and every tick of a horizontal one whose step is a 1, 2
    or 5 × 10^k multiple of it the same number of columns: the spacing is
    regular. The picture shows more than at ``per_dot``: at most 1.25
    times (as if zoomed out by that) up to 8 rows apart, 1.33 up to 6, 1.5
    up to 5."""
    most = max(ROWS_APART[0], min(most_rows, ROWS_APART[1]))
    if not per_dot > 0 or not math.isfinite(per_dot):
        return 1.0, 4.0 * ROWS_APART[0], ROWS_APART[0]
    best = (math.inf, 1.0, ROWS_APART[0])
    for rows in range(ROWS_APART[0], most + 1):
        step = nice_step(4 * rows * per_dot)
        length = step / (4 * rows)
        if length < best[0] * (1 - 1e-9):
            best = (length, step, rows)
    return best


def on_dots(centre: float, per_dot: float, dots: int, first: int, every: int) -> float:
    """``centre`` moved by at most ``every / 2`` dots so that, in a picture
    ``dots`` dots across centred on it at ``per_dot`` (its dots run from
    ``centre - per_dot * (dots - 1) / 2`` up, as ``limits_at`` lays them),
    every multiple of ``every * per_dot`` falls on a whole dot, ``first``
    dots past a multiple of ``every`` counted from the low end.

    A tick's value on a whole dot is drawn in the cell its tick is placed
    in (the ticks of :func:`regular_scale` are such multiples). For a
    vertical axis counted from the top, pass and take back ``-centre``."""
    if not per_dot > 0 or not math.isfinite(centre / per_dot):
        return centre
    low = centre / per_dot - (dots - 1) / 2  # the picture's first dot, in dots from 0
    # a multiple sits at dot (n * every - low): make -low ≡ first (mod every)
    low = -first - every * round((-low - first) / every)
    return (low + (dots - 1) / 2) * per_dot

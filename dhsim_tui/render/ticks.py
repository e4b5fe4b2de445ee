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


def x_step(lim: tuple[float, float], per_col: float, least: float = 0.0) -> float:
    """The finest 1, 2, 5 × 10^k step (and at least ``least``) whose labels,
    centred on their ticks along a horizontal axis of limits ``lim`` with
    ``per_col`` robot units to a column, keep a space between them."""
    step = nice_step(max(2 * per_col, least))
    for _ in range(64):  # a few decades at most
        labels = [tick_label(v, step) for v in (lim[0], lim[1], *tick_values(lim, step)[:3])]
        if step >= (max(map(len, labels)) + 1) * per_col * (1 - 1e-9):
            break
        step = nice_step(step * 1.000001)
    return step

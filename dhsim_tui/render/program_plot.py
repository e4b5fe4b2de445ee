"""A program's joints and tool speed against time, drawn with plotext as
text (on a figure of our own, as :mod:`dhsim_tui.render.plotext_picture`
does: plotext is pinned): ``dhsim run --plot`` prints it, the simulator's
program panel shows it (``t``) with a cursor at the time played.

A legend line, then two plots, one above the other, sharing the time axis:

- the joint values, one line per joint (revolute in degrees, prismatic in
  the robot's unit); each joint has its own mark (``1`` ... ``9``, ``A``
  ...), so it is told apart without colour too: in colour a fine (braille)
  line in the joint's colour carries its mark every few columns, without
  colour the line is drawn in its mark. The limits near the curves are
  faint dotted lines in the joint's colour;
- the tool point's speed (robot units a second, by finite differences);
  each problem is an ``x`` on it at its first sample.

The legend is a line of its own above the curves, never on them. Step
boundaries are faint dotted vertical lines in both plots, the upper plot's
time axis numbers the step that starts at each (as many as fit); the lower
one has the time. Every other axis has round 1-2-5 ticks
(:mod:`dhsim_tui.render.ticks`). In colour the marks are coloured (told apart
in 16 colours too); without (a pipe, a file, NO_COLOR) they are plain, and in 7-bit ASCII
every mark and the frame are ASCII too: the caller says which (``colour``,
``ascii``).
"""

from __future__ import annotations

import re

import numpy as np
from plotext._figure import _figure_class
from plotext._utility import colorize

from dhsim_tui.render.ticks import nice_step, tick_label, tick_values, x_step

#: the joints' colours, in turn (256-colour indices, exact in truecolor):
#: cyan, magenta, olive, teal, purple, silver. Each comes out as its own of
#: the 16 colours (14, 13, 3, 6, 5, 7), none of them red, green, blue or
#: bright yellow, the frame axes' and the links' (tui.colour moves those in
#: 16 colours); the 16 themselves are not used: the themes map bright and
#: plain ones to one colour
COLOURS = (51, 201, 142, 30, 127, 250)
#: each joint's mark, in turn (no I or O: they read as 1 and 0)
MARKS = "123456789ABCDEFGHJKLMNPQRSTUVWXYZ"
#: the step boundaries' colour: gray, faint
FAINT = 8
_SGR = re.compile(r"\x1b\[[0-9;]*m")
_ASCII_FRAME = str.maketrans("─│┤┬└┼┌┐┘├┴┊·", "-|+++++++++:.")
#: the most points a line gets (plotext's time grows with them)
MAX_POINTS = 2000
#: columns between two of a joint's marks on its line (colour)
MARK_EVERY = 12
#: columns between two time labels, at least (a glance reads 0 1 2, not 0 0.5 1.0 1.5)
TIME_LABEL_COLUMNS = 8
#: the fewest rows the two plots get (the legend gives way)
MIN_PLOTS_ROWS = 14
#: columns between two dots of a limit
DOT_EVERY = 4


def _thin(count: int) -> np.ndarray:
    """At most MAX_POINTS sample indices, the first and the last kept."""
    if count <= MAX_POINTS:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, MAX_POINTS).round().astype(int))


def mark_of(index: int) -> str:
    return MARKS[index % len(MARKS)]


def colour_of(index: int) -> int:
    return COLOURS[index % len(COLOURS)]


def axis_range(low: float, high: float, rows: int) -> tuple[float, float, float]:
    """A vertical axis around ``low..high`` over ``rows`` rows: its limits (a
    little wider: the curves never run on the frame) and its 1-2-5 tick step
    (labels about two rows apart, closer when that leaves fewer than two)."""
    if not high > low:
        low, high = low - 1.0, high + 1.0
    pad = 0.03 * (high - low)
    low, high = low - pad, high + pad
    step = nice_step(2.0 * (high - low) / max(rows, 2))
    for _ in range(4):  # a scale needs two numbers: finer steps (two or three do)
        if len(tick_values((low, high), step)) >= 2:
            break
        step = nice_step(step * 0.3996)  # the next finer: 500 -> 200 -> 100 -> 50
    return low, high, step


def shown_limits(robot, q: np.ndarray) -> list[tuple[int, float]]:
    """(joint, limit) of the limits a joint comes near: within a quarter of
    the curves' span (at least 10 units) of that joint's values. The others
    would squash the curves and say nothing."""
    near = max(0.25 * float(np.max(q) - np.min(q)), 10.0)
    return [
        (index, limit)
        for index, joint in enumerate(robot.joints)
        for limit in (joint.min, joint.max)
        if float(np.min(np.abs(q[:, index] - limit))) <= near
    ]


def legend_lines(robot, width: int, *, colour: bool) -> list[str]:
    """The joints' legend, above the plots: the units, each joint's mark and
    label; wrapped to ``width``."""
    units = "deg" if all(j.is_revolute for j in robot.joints) else f"deg, {robot.units}"
    items = [f"joints ({units}) against time:"]
    for index, label in enumerate(robot.labels):
        mark = mark_of(index)
        items.append((colorize(mark, colour_of(index)) if colour else mark) + f" {label}")
    lines, line, used = [], "", 0
    for item in items:
        size = len(_SGR.sub("", item))
        if line and used + 2 + size > width:
            lines.append(line)
            line, used = "", 0
        line, used = (f"{line}  {item}", used + 2 + size) if line else (item, size)
    return [*lines, line]


def _step_ticks(shown, duration: float, columns: int) -> tuple[list[float], list[str]]:
    """The step starts and their numbers, as many as fit without touching."""
    ticks, labels, free = [], [], -1.0
    for span in shown:
        label = str(span.number)
        column = span.start / duration * columns
        if column - len(label) / 2 >= free:
            ticks.append(span.start)
            labels.append(label)
            free = column + len(label) / 2 + 1
    return ticks, labels


def plot_text(
    trajectory,
    problems,
    width: int,
    height: int,
    *,
    colour: bool,
    ascii: bool,
    cursor: float | None = None,
) -> str:
    """The legend and the two plots as text ``width`` columns by ``height``
    rows; ``cursor``: a time marked by a vertical line in both (the time
    played)."""
    robot = trajectory.robot
    width, height = max(width, 40), max(height, 16)
    picked = _thin(len(trajectory.time))
    time = trajectory.time[picked].tolist()
    duration = max(trajectory.duration, float(trajectory.time[-1]), 1e-9)
    shown = [span for span in trajectory.spans if span.duration > 0]
    q = trajectory.q[picked]
    speed = trajectory.tool_speed
    legend = legend_lines(robot, width, colour=colour)
    room = max(height - MIN_PLOTS_ROWS, 1)
    if len(legend) > room:  # many joints on a small screen: the plots first
        legend = [*legend[: room - 1], "..." if ascii else "…"]

    limits = shown_limits(robot, q)
    values = [float(np.min(q)), float(np.max(q)), *(limit for _, limit in limits)]
    rows = max((height - len(legend)) // 2 - 4, 3)  # a plot's canvas: its half less its frame
    bottom, top, step = axis_range(min(values), max(values), rows)
    y_ticks = tick_values((bottom, top), step)
    fastest = float(np.max(speed)) if len(speed) else 0.0
    _, s_top, s_step = axis_range(0.0, fastest if fastest > 0 else 1.0, rows)
    s_ticks = tick_values((0.0, s_top), s_step)
    # both plots' tick labels as wide: their canvases, and the step lines, line up
    label_width = max(
        *(len(tick_label(v, step)) for v in y_ticks),
        *(len(tick_label(v, s_step)) for v in s_ticks),
    )
    columns = max(width - label_width - 3, 10)

    figure = _figure_class()  # our own figure: plotext's global one keeps state between plots
    figure._limit_size(False, False)  # the size asked for, not the terminal plotext sees
    figure.plot_size(width, height - len(legend))
    figure.subplots(2, 1)
    faint = FAINT if colour else None
    bar, dot = (":", ".") if ascii else ("┊", "·")

    def boundaries(plot, low: float, high: float) -> None:
        heights = np.linspace(low, high, rows * 2 + 1).tolist()
        for span in shown[1:]:
            plot.scatter([span.start] * len(heights), heights, marker=bar, color=faint)
        if cursor is not None:
            plot.vline(cursor, "default" if colour else None)

    joints = figure.subplot(1, 1)
    _look(joints, colour)
    dots = np.linspace(0.0, duration, max(columns // DOT_EVERY, 2)).tolist()
    for index, limit in limits:  # first: the curves are drawn over them
        joints.scatter(
            dots, [limit] * len(dots), marker=dot, color=colour_of(index) if colour else None
        )
    boundaries(joints, bottom, top)
    for index in range(robot.dof):
        tint = colour_of(index) if colour else None
        if colour and not ascii:  # a fine line in its colour ...
            joints.plot(time, q[:, index].tolist(), color=tint, marker="braille")
        else:  # the line drawn in its mark: in ASCII, or told apart without colour
            joints.plot(time, q[:, index].tolist(), marker=mark_of(index), color=tint)
    if colour and not ascii:  # ... its mark on it every few columns, over every line
        every = np.linspace(0.0, duration, max(columns // MARK_EVERY, 2) + 1)
        for index in range(robot.dof):
            at = every[:-1] + (every[1] - every[0]) * (index + 0.5) / robot.dof  # in turn
            joints.scatter(
                at.tolist(),
                np.interp(at, time, q[:, index]).tolist(),
                marker=mark_of(index),
                color=colour_of(index),
            )
    joints.xlim(0.0, duration)
    joints.ylim(bottom, top)
    joints.yticks(y_ticks, [tick_label(v, step).rjust(label_width) for v in y_ticks])
    joints.xticks(*_step_ticks(shown, duration, columns))
    joints.xlabel(f"step  ({bar} starts, {dot * 3} limits)" if limits else f"step  ({bar} starts)")

    speeds = figure.subplot(2, 1)
    _look(speeds, colour)
    boundaries(speeds, 0.0, s_top)
    speeds.plot(
        time,
        speed[picked].tolist(),
        color="default" if colour else None,
        marker="*" if ascii else "braille",
    )
    if problems:
        times = [problem.time for problem in problems]
        at = np.searchsorted(trajectory.time, times).clip(0, len(speed) - 1)
        speeds.scatter(times, speed[at].tolist(), marker="x", color=9 if colour else None)
    speeds.ylim(0.0, s_top)
    speeds.yticks(s_ticks, [tick_label(v, s_step).rjust(label_width) for v in s_ticks])
    t_step = x_step((0.0, duration), duration / columns, TIME_LABEL_COLUMNS * duration / columns)
    t_ticks = tick_values((0.0, duration), t_step)
    speeds.xlim(0.0, duration)
    speeds.xticks(t_ticks, [tick_label(v, t_step) for v in t_ticks])
    speeds.title(f"tool speed ({robot.units}/s)" + ("; x: a problem" if problems else ""))
    speeds.xlabel("time (s)")
    text = "\n".join([*legend, figure.build()])
    if not colour:
        text = _SGR.sub("", text)
    if ascii:
        text = text.translate(_ASCII_FRAME)
    return "\n".join(line.rstrip() for line in text.splitlines())


def _look(plot, colour: bool) -> None:
    if colour:
        plot.canvas_color("default")
        plot.axes_color("default")
        plot.ticks_color("default")
    else:
        plot.theme("clear")

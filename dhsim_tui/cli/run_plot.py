"""``dhsim run --plot``: a program's joints and tool speed against time,
drawn with plotext in the terminal (on a figure of our own, as
:mod:`dhsim_tui.render.plotext_picture` does: plotext is pinned).

Two plots, one above the other, sharing the time axis:

- the joint values, one line per joint (revolute in degrees, prismatic in
  the robot's unit), each joint's limits as horizontal lines in its colour;
- the tool point's speed (robot units a second, by finite differences).

Step boundaries are vertical lines in both, and the step numbers label the
upper plot's time axis; each problem is an ``x`` on the speed line at its
first sample. On a terminal the lines are coloured; otherwise (a pipe, a
file) there is no colour and each joint is drawn with its own digit, and
in 7-bit ASCII (the locale, or TERM=linux) the frame is drawn in ASCII too.
"""

from __future__ import annotations

import os
import re
import sys

import numpy as np
from plotext._figure import _figure_class

from dhsim_tui.terminal.locale_env import original_environ, wants_ascii

#: the joints' colours, in turn (plotext's names)
COLOURS = ("blue+", "green+", "orange+", "magenta+", "cyan+", "yellow+", "red+")
_SGR = re.compile(r"\x1b\[[0-9;]*m")
_ASCII_FRAME = str.maketrans("─│┤┬└┼┌┐┘├┴", "-|+++++++++")
#: the most points a line gets (plotext's time grows with them)
MAX_POINTS = 2000


def _coloured() -> bool:
    try:
        return os.isatty(sys.stdout.fileno()) and "NO_COLOR" not in os.environ
    except (AttributeError, OSError, ValueError):
        return False


def _thin(count: int) -> np.ndarray:
    """At most MAX_POINTS sample indices, the first and the last kept."""
    if count <= MAX_POINTS:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, MAX_POINTS).round().astype(int))


def plot_text(
    trajectory, problems, width: int, height: int, *, colour: bool | None = None, ascii=None
) -> str:
    """The two plots as text ``width`` columns by ``height`` rows."""
    colour = _coloured() if colour is None else colour
    ascii = wants_ascii(original_environ(), force=None) if ascii is None else ascii
    robot = trajectory.robot
    picked = _thin(len(trajectory.time))
    time = trajectory.time[picked].tolist()
    duration = max(trajectory.duration, float(trajectory.time[-1]), 1e-9)
    shown = [span for span in trajectory.spans if span.duration > 0]
    starts = [span.start for span in shown]
    figure = _figure_class()  # our own figure: plotext's global one keeps state between plots
    figure._limit_size(False, False)  # the size asked for, not the terminal plotext sees
    figure.plot_size(max(width, 40), max(height, 16))
    figure.subplots(2, 1)

    joints = figure.subplot(1, 1)
    _look(joints, colour)
    for index, joint in enumerate(robot.joints):
        tint = COLOURS[index % len(COLOURS)] if colour else None
        joints.plot(
            time,
            trajectory.q[picked, index].tolist(),
            label=robot.labels[index],
            color=tint,
            marker="braille" if colour else str((index + 1) % 10),
        )
        for limit in (joint.min, joint.max):
            joints.hline(limit, tint)
    for start in starts:
        joints.vline(start, "gray" if colour else None)
    units = "deg" if all(j.is_revolute for j in robot.joints) else f"deg, {robot.units}"
    joints.title(f"joints ({units}) against time; steps at the ticks, limits as lines")
    joints.xlim(0.0, duration)
    if starts:
        joints.xticks(starts, [str(span.number) for span in shown])

    speeds = figure.subplot(2, 1)
    _look(speeds, colour)
    speed = trajectory.tool_speed
    speeds.plot(
        time,
        speed[picked].tolist(),
        color="white" if colour else None,
        marker="braille" if colour else "*",
    )
    for start in starts:
        speeds.vline(start, "gray" if colour else None)
    if problems:
        times = [problem.time for problem in problems]
        at = np.searchsorted(trajectory.time, times).clip(0, len(speed) - 1)
        speeds.scatter(
            times,
            speed[at].tolist(),
            marker="x",
            color="red" if colour else None,
            label="problem",
        )
    speeds.title(f"tool speed ({robot.units}/s)")
    speeds.xlabel("time (s)")
    speeds.xlim(0.0, duration)
    text = figure.build()
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

"""A program's joints and tool speed against time, drawn with plotext as
text (on a figure of our own, as :mod:`dhsim_tui.render.plotext_picture`
does: plotext is pinned): ``dhsim run --plot`` prints it, the simulator's
program panel shows it (``t``) with a cursor at the time played.

Two plots, one above the other, sharing the time axis:

- the joint values, one line per joint (revolute in degrees, prismatic in
  the robot's unit), each joint's limits as horizontal lines in its colour;
- the tool point's speed (robot units a second, by finite differences).

Step boundaries are vertical lines in both, and the step numbers label the
upper plot's time axis; each problem is an ``x`` on the speed line at its
first sample. In colour the lines are coloured; without (a pipe, a file,
NO_COLOR) each joint is drawn with its own digit, and in 7-bit ASCII the
frame is drawn in ASCII too: the caller says which (``colour``, ``ascii``).
"""

from __future__ import annotations

import re

import numpy as np
from plotext._figure import _figure_class

#: the joints' colours, in turn (plotext's names)
COLOURS = ("blue+", "green+", "orange+", "magenta+", "cyan+", "yellow+", "red+")
_SGR = re.compile(r"\x1b\[[0-9;]*m")
_ASCII_FRAME = str.maketrans("─│┤┬└┼┌┐┘├┴", "-|+++++++++")
#: the most points a line gets (plotext's time grows with them)
MAX_POINTS = 2000


def _thin(count: int) -> np.ndarray:
    """At most MAX_POINTS sample indices, the first and the last kept."""
    if count <= MAX_POINTS:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, MAX_POINTS).round().astype(int))


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
    """The two plots as text ``width`` columns by ``height`` rows; ``cursor``:
    a time marked by a vertical line in both (the time played)."""
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
    if cursor is not None:
        joints.vline(cursor, "white" if colour else None)
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
    if cursor is not None:
        speeds.vline(cursor, "white" if colour else None)
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

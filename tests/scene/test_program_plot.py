"""The program plot (render.program_plot) reads at a glance: the legend is a
line above the curves, never on them; every tick is a round 1-2-5 number;
each joint has its own mark (and, in colour, its own of the 16 colours);
limits are faint dots, not lines; the step starts are numbered on the time
axis; without colour nothing is coloured, in ASCII everything is ASCII."""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import replace

import pytest
from rich.color import Color as RichColor
from rich.color import ColorSystem

from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.model.robot import Joint, Robot
from dhsim_tui.core.motion.path_check import check_path
from dhsim_tui.core.motion.trajectory import sample
from dhsim_tui.render.program_plot import COLOURS, MARKS, axis_range, plot_text
from dhsim_tui.render.ticks import tick_values
from dhsim_tui.tui.colour import sixteen

SGR = re.compile(r"\x1b\[([0-9;]*)m")
SIZES = [(78, 22), (100, 30), (160, 48)]


def played(steps, start=None):
    puma, _ = load_robot("puma560")
    program = Program("p", tuple(steps))
    trajectory = sample(replace(puma, programs=(program,)), program, start=start)
    return trajectory, check_path(trajectory)


@pytest.fixture(scope="module")
def spread():
    """Every joint on a curve of its own; Th1 near its limit (160)."""
    return played(
        [
            Step("joint", (150, 90, -200, 30, -60, -130)),
            Step("wait", seconds=0.5),
            Step("joint", (120, 60, -150, 0, -90, -250)),
        ]
    )


@pytest.fixture(scope="module")
def demo():
    puma, _ = load_robot("puma560")
    trajectory = sample(puma, puma.program("demo"))
    return trajectory, check_path(trajectory)


def frames(text: str) -> list[tuple[int, int]]:
    """(top, bottom) line index of each plot's frame."""
    lines = SGR.sub("", text).splitlines()
    tops = [i for i, line in enumerate(lines) if "┌" in line or re.search(r"^\s*\+-", line)]
    bottoms = [i for i, line in enumerate(lines) if "└" in line or re.search(r"^\s*\+\+-", line)]
    return list(zip(tops, bottoms, strict=True))


def inside(text: str, plot: int) -> list[str]:
    """The canvas rows of plot 0 (joints) or 1 (speed), between the frame's sides."""
    lines = SGR.sub("", text).splitlines()
    top, bottom = frames(text)[plot]
    rows = []
    for line in lines[top + 1 : bottom]:
        left = re.search(r"[┤│+|]", line).start()
        right = max(line.rfind("│"), line.rfind("|"))
        rows.append(line[left + 1 : right])
    return rows


def y_labels(text: str, plot: int) -> list[float]:
    lines = SGR.sub("", text).splitlines()
    top, bottom = frames(text)[plot]
    labels = []
    for line in lines[top + 1 : bottom]:
        found = re.match(r"^\s*(-?[0-9.]+)[┤+]", line)
        if found:
            labels.append(float(found.group(1)))
    return labels


def under(text: str, plot: int) -> str:
    """The tick label line under plot 0 or 1."""
    return SGR.sub("", text).splitlines()[frames(text)[plot][1] + 1]


def round_ticks(values: list[float]) -> bool:
    """Equally spaced by 1, 2 or 5 × 10^k, each a multiple of that step."""
    if len(values) < 2:
        return True
    steps = {round(abs(b - a), 9) for a, b in itertools.pairwise(values)}
    if len(steps) != 1:
        return False
    step = steps.pop()
    mantissa = step / 10 ** math.floor(math.log10(step))
    multiples = all(abs(v / step - round(v / step)) < 1e-6 for v in values)
    return any(abs(mantissa - m) < 1e-9 for m in (1, 2, 5)) and multiples


@pytest.mark.parametrize(("width", "height"), SIZES)
@pytest.mark.parametrize("colour", [True, False])
def test_the_legend_is_a_line_above_the_curves(spread, width, height, colour):
    trajectory, problems = spread
    text = plot_text(trajectory, problems, width, height, colour=colour, ascii=False)
    plain = SGR.sub("", text).splitlines()
    assert plain[0].startswith("joints (deg) against time:")
    for label in trajectory.robot.labels:
        assert label in plain[0]
        for plot in (0, 1):
            assert not any(label in row for row in inside(text, plot))
    assert len(plain) <= height and max(len(line) for line in plain) <= width


@pytest.mark.parametrize(("width", "height"), SIZES)
def test_every_tick_is_a_round_number(demo, spread, width, height):
    for trajectory, problems in (demo, spread):
        text = plot_text(trajectory, problems, width, height, colour=False, ascii=False)
        for plot in (0, 1):
            labels = y_labels(text, plot)
            assert len(labels) >= 2 and round_ticks(sorted(labels)), labels
        times = [float(v) for v in under(text, 1).split()]
        assert times[0] == 0 and len(times) >= 3 and round_ticks(times), times


def test_the_old_unround_ticks_are_gone(demo):
    text = plot_text(*demo, 100, 30, colour=False, ascii=False)
    for unround in ("266.0", "177.3", "88.7", "604.5", "3.9", "5.9"):
        assert unround not in text


@pytest.mark.parametrize("ascii", [False, True])
def test_without_colour_each_joint_has_its_own_mark_on_its_curve(spread, ascii):
    trajectory, problems = spread
    text = plot_text(trajectory, problems, 100, 30, colour=False, ascii=ascii)
    assert "\x1b[" not in text
    canvas = "".join(inside(text, 0))
    for index, label in enumerate(trajectory.robot.labels):
        mark = MARKS[index]
        assert f"{mark} {label}" in text.splitlines()[0]
        assert canvas.count(mark) >= 10, label  # a line drawn in it, not a dot
    if ascii:
        assert text.isascii()


def test_in_colour_each_joint_has_its_own_of_the_16_colours_and_its_mark(spread):
    trajectory, problems = spread
    text = plot_text(trajectory, problems, 100, 30, colour=True, ascii=False)
    codes = set(SGR.findall(text)) - {"0", ""}
    for code in codes:  # 256-colour codes, that a 16-colour terminal gets down to its own
        assert re.fullmatch(r"38;5;[0-9]+", code), code
    legend, body = text.split("\n", 1)
    wanted = [COLOURS[i] for i in range(trajectory.robot.dof)]
    assert len(set(wanted)) == trajectory.robot.dof
    # in 16 colours still six, none that the axes and links keep (tui.colour
    # would move it onto another joint's)
    in_sixteen = [RichColor.from_ansi(c).downgrade(ColorSystem.STANDARD) for c in wanted]
    assert len({c.number for c in in_sixteen}) == len(wanted)  # six of the 16
    assert not {c.number for c in in_sixteen} & {1, 2, 4, 9, 10, 11, 12}
    assert all(sixteen(c) is c for c in in_sixteen)  # tui.colour keeps them
    for index, colour in enumerate(wanted):
        painted = (MARKS[index], f"38;5;{colour}")
        # the mark in the legend and on the curve, in its colour
        assert painted in painted_chars(legend) and painted in painted_chars(body)


def painted_chars(text: str) -> set[tuple[str, str]]:
    """(character, its SGR code) of every character drawn."""
    found, code = set(), ""
    for index, part in enumerate(SGR.split(text)):
        if index % 2:
            code = "" if part in ("0", "") else part
        else:
            found.update((char, code) for char in part)
    return found


@pytest.mark.parametrize("colour", [True, False])
def test_limits_are_faint_dots_not_lines(spread, colour):
    trajectory, problems = spread
    text = plot_text(trajectory, problems, 100, 30, colour=colour, ascii=False)
    rows = inside(text, 0)
    assert not any("─" * 8 in row for row in rows)  # no solid horizontal line
    dotted = [row for row in rows if row.count("·") >= 10]
    assert dotted  # Th1's 160 limit, near its curve: dotted across
    assert "limits" in SGR.sub("", text)


def test_only_the_limits_near_a_curve_are_drawn(demo, spread):
    """The demo keeps every joint far from Th4's and Th6's ±266: the axis does
    not reach them (they would squash the curves)."""
    text = plot_text(*demo, 100, 30, colour=False, ascii=False)
    assert min(y_labels(text, 0)) > -266 and max(y_labels(text, 0)) < 266


@pytest.mark.parametrize(("width", "height"), SIZES)
def test_the_step_starts_are_numbered_on_the_time_axis(demo, width, height):
    trajectory, problems = demo
    text = plot_text(trajectory, problems, width, height, colour=False, ascii=False)
    numbers = under(text, 0).split()
    assert numbers[0] == "1" and numbers == sorted(numbers, key=int)
    if width >= 100:
        assert numbers == [str(span.number) for span in trajectory.spans if span.duration > 0]
    assert "step" in SGR.sub("", text).splitlines()[frames(text)[0][1] + 2]
    # each step start after the first is a dotted vertical line in both plots (the
    # curves drawn over it)
    for plot in (0, 1):
        rows = inside(text, plot)
        assert sum(row.count("┊") >= 3 for row in rows) >= len(rows) // 2


def test_the_two_plots_share_their_columns(demo):
    """Both canvases start at the same column: a step line is one line."""
    text = SGR.sub("", plot_text(*demo, 100, 30, colour=False, ascii=False))
    lines = text.splitlines()
    (top0, _), (top1, _) = frames(text)
    assert lines[top0].index("┌") == lines[top1].index("┌")


def test_problems_are_marked_on_the_speed_line():
    trajectory, problems = played([Step("joint", (160, 0, 0, 0, 0, 0)), Step("wait", seconds=0.1)])
    assert problems
    text = plot_text(trajectory, problems, 100, 30, colour=False, ascii=True)
    assert any("x" in row for row in inside(text, 1))
    assert "x: a problem" in text and text.isascii()


@pytest.mark.parametrize(
    ("low", "high", "rows"), [(-90, 90, 5), (5, 5, 3), (0, 0.003, 20), (-266, 266, 4)]
)
def test_a_scale_has_two_round_numbers_at_least(low, high, rows):
    bottom, top, step = axis_range(low, high, rows)
    assert bottom < low <= high < top
    ticks = tick_values((bottom, top), step)
    assert len(ticks) >= 2 and round_ticks(ticks)


def test_many_joints_wrap_the_legend_above_the_plot():
    arm = Robot("big", tuple(Joint(min=-90, max=90) for _ in range(32)))
    program = Program("p", (Step("joint", tuple(float(i * 5 - 80) for i in range(32))),))
    trajectory = sample(replace(arm, programs=(program,)), program)
    text = plot_text(trajectory, (), 78, 22, colour=False, ascii=False)
    lines = text.splitlines()
    top = frames(text)[0][0]
    legend = " ".join(lines[:top])
    assert all(f"{MARKS[i]} {label}" in legend for i, label in enumerate(arm.labels))
    assert len(lines) <= 22 and max(map(len, lines)) <= 78
    assert len(y_labels(text, 0)) >= 2

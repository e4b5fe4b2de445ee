"""Ticks where their values are drawn (issue 27): every tick of a view's axes
sits on the row (or column) in which the raster draws its value, the ticks
are evenly spaced, and z = 0 is on the floor's row of an arm standing on it."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dhsim_tui.core import bundled_names, load_robot
from dhsim_tui.render.picture import ROLE_INDEX, Framing, Look
from dhsim_tui.render.plotext_picture import PlotextPainter
from dhsim_tui.render.ticks import nice_step, on_dots, regular_scale
from dhsim_tui.scene import build_wireframe, project
from dhsim_tui.scene.figure import least_size
from dhsim_tui.scene.framing import fitted, work_area_framings
from dhsim_tui.scene.projection import FRONT, ORTHO_VIEWS, SIDE, Polyline, ViewScene

#: a view's size at 80x24 (one view) and at 120x36 (a quarter), and maximised
SIZES = [(40, 20), (36, 15), (78, 30)]


def ticks(picture):
    """The y ticks as (row, value) and the x ticks as (column, value), read
    off the picture's text: the tick marks on the axes and their labels."""
    left, _, cols, rows = picture.canvas
    ys = []
    for row in range(rows):
        line = picture.lines[row]
        if line[left - 1] in "┤+" and line[: left - 1].strip():
            ys.append((row, float(line[: left - 1])))
    axis, labels = picture.lines[rows], picture.lines[rows + 1]
    marks = [col for col in range(left, left + cols) if axis[col] in "┬+"]
    values = [float(word) for word in labels.split()]
    assert len(marks) == len(values), (axis, labels)
    return ys, list(zip(marks, values, strict=True))


def drawn_row(picture, value: float) -> int:
    """The row the raster draws ``value`` (on the vertical axis) in."""
    (_, _), (y0, y1) = picture.xlim, picture.ylim
    rows = picture.canvas[3]
    per_dot = (y1 - y0) / (4 * rows - 1)
    return int(np.rint((y1 - value) / per_dot)) // 4


def drawn_col(picture, value: float) -> int:
    left, _, cols, _ = picture.canvas
    x0, x1 = picture.xlim
    per_dot = (x1 - x0) / (2 * cols - 1)
    return left + int(np.rint((value - x0) / per_dot)) // 2


def check(picture) -> None:
    ys, xs = ticks(picture)
    assert len(ys) >= 2 and xs  # long labels far from 0 (1659.4) may leave one
    for row, value in ys:
        assert row == drawn_row(picture, value), (row, value, picture.lines)
    for col, value in xs:
        assert col == drawn_col(picture, value), (col, value, picture.lines)
    # evenly spaced: the same number of rows (columns) from one to the next
    assert len({b[0] - a[0] for a, b in itertools.pairwise(ys)}) == 1, ys
    assert len({b[0] - a[0] for a, b in itertools.pairwise(xs)}) <= 1, xs
    step = ys[0][1] - ys[1][1]
    assert step == pytest.approx(nice_step(step * (1 - 1e-9)))


@pytest.mark.parametrize("name", bundled_names())
@pytest.mark.parametrize("ascii", [False, True])
def test_every_tick_sits_where_its_value_is_drawn(name, ascii):
    """Fitted and over the work area, every bundled robot, every view size."""
    robot, _ = load_robot(name)
    wire = build_wireframe(robot, robot.kinematics.frames(robot.home))
    scenes = [project(wire, view) for view in ORTHO_VIEWS]
    look = Look(ascii=ascii)
    for cols, rows in SIZES:
        canvas = (cols - 7, rows - 2)
        framings = work_area_framings(scenes, [canvas] * 3)
        for scene, whole in zip(scenes, framings, strict=True):
            for framing in (whole, fitted(scene, *canvas, least_size(wire))):
                check(PlotextPainter().draw(scene, cols, rows, framing, look))


@settings(max_examples=60, deadline=None)
@given(
    st.floats(-2000, 2000),
    st.floats(-2000, 2000),
    st.floats(0.05, 80.0),
    st.sampled_from(SIZES),
)
def test_ticks_sit_where_drawn_at_any_centre_and_scale(cx, cy, per_dot, size):
    scene = ViewScene(FRONT, (), (math.nan, math.nan), (-1, 1, -1, 1))
    check(PlotextPainter().draw(scene, *size, Framing((cx, cy), per_dot), Look()))


@pytest.mark.parametrize("name", ["irb140", "ur5", "panda", "stanford"])
@pytest.mark.parametrize("view", [FRONT, SIDE])
def test_z_0_is_on_the_floors_row_at_80x24(name, view):
    """An arm standing on the floor (base height 0): the "0" label is on the
    row where the floor is drawn, fitted (as the views open) and not."""
    robot, _ = load_robot(name)
    wire = build_wireframe(robot, robot.kinematics.frames(robot.home))
    assert wire.floor_z == 0.0
    scene = project(wire, view)
    cols, rows = 40, 20  # the view at 80x24
    canvas = (cols - 7, rows - 2)
    scenes = [project(wire, v) for v in ORTHO_VIEWS]
    whole = work_area_framings(scenes, [canvas] * 3)[ORTHO_VIEWS.index(view)]
    for framing in (fitted(scene, *canvas, least_size(wire)), whole):
        picture = PlotextPainter().draw(scene, cols, rows, framing, Look())
        ys, _ = ticks(picture)
        zero = [row for row, value in ys if value == 0]
        left = picture.canvas[0]
        canvas_roles = picture.roles[:, left:]
        on_floor = np.isin(canvas_roles, [ROLE_INDEX["floor"], ROLE_INDEX["floor_hit"]])
        floor = np.flatnonzero(on_floor.any(axis=1))
        assert zero and floor.size, picture.lines
        assert zero == [int(floor[0])] == [int(floor[-1])], picture.lines


def test_a_line_drawn_at_a_ticks_value_is_on_its_row():
    """A level line at each tick's value is drawn in that tick's row."""
    empty = ViewScene(FRONT, (), (math.nan, math.nan), (-1, 1, -1, 1))
    framing = Framing((13.0, 7.0), 9.7)
    ys, _ = ticks(PlotextPainter().draw(empty, 40, 20, framing, Look()))
    assert len(ys) >= 3
    for row, value in ys:
        line = Polyline((-1000.0, 1000.0), (value, value), "floor")
        scene = ViewScene(FRONT, (line,), (math.nan, math.nan), (-1, 1, -1, 1))
        picture = PlotextPainter().draw(scene, 40, 20, framing, Look())
        rows = np.flatnonzero((picture.roles == ROLE_INDEX["floor"]).any(axis=1))
        assert rows.tolist() == [row]


@pytest.mark.parametrize("per_dot", [0.01, 0.0329, 0.37, 1.0, 7.7, 123.0])
def test_a_regular_scale_is_a_whole_number_of_rows_and_shows_at_most_a_quarter_more(per_dot):
    length, step, rows = regular_scale(per_dot)
    assert per_dot <= length <= 1.25 * per_dot
    assert step == pytest.approx(nice_step(step)) and 2 <= rows <= 8
    assert step / (4 * length) == pytest.approx(rows)
    fewer = regular_scale(per_dot, 4)
    assert fewer[2] <= 4 and per_dot <= fewer[0] <= 1.5 * per_dot


@pytest.mark.parametrize(("centre", "per_dot", "dots", "first", "every"), [
    (3.3, 0.7, 40, 0, 2), (-123.4, 2.5, 72, 1, 4), (0.0, 1.0, 80, 1, 4), (55.0, 0.01, 13, 0, 2),
])  # fmt: skip
def test_on_dots_moves_the_centre_less_than_half_a_cell(centre, per_dot, dots, first, every):
    moved = on_dots(centre, per_dot, dots, first, every)
    assert abs(moved - centre) <= every / 2 * per_dot + 1e-9
    low = moved / per_dot - (dots - 1) / 2  # the first dot's value, in dots
    assert (-low - first) / every == pytest.approx(round((-low - first) / every))

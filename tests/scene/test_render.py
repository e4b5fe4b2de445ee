"""The views' pictures: plotext's frame and ticks, the wireframe's cells placed
where plotext places them, one scale, never a NaN or inf handed to plotext."""

from __future__ import annotations

import itertools
import math
import re

import numpy as np
import plotext
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from plotext._figure import _figure_class

from dhsim_tui.core import load_robot
from dhsim_tui.render.picture import NO_ROLE, ROLE_INDEX, Framing, Look
from dhsim_tui.render.plotext_picture import PlotextPainter, braille_cells
from dhsim_tui.render.ticks import nice_step, tick_label, tick_values
from dhsim_tui.scene import build_wireframe, project
from dhsim_tui.scene.oblique import Orbit, project_oblique
from dhsim_tui.scene.projection import FRONT, SIDE, TOP, Polyline, ViewScene, per_dot_needed

SGR = re.compile(r"\x1b\[[0-9;]*m")


def puma_scene(view=FRONT, q=None):
    robot, _ = load_robot("puma560")
    wire = build_wireframe(robot, robot.kinematics.frames(robot.home if q is None else q))
    return project(wire, view) if not view.is_3d else project_oblique(wire, Orbit())


def framing_for(scene: ViewScene, cols: int, rows: int) -> Framing:
    b = scene.bounds
    return Framing(((b[0] + b[1]) / 2, (b[2] + b[3]) / 2), per_dot_needed(b, cols - 7, rows - 2))


def test_plotext_is_the_pinned_version_with_the_figure_class_we_use():
    """The one private name (``_figure_class``) and the methods called on it:
    this fails if a plotext upgrade moves them (plotext is pinned exactly)."""
    assert plotext.__version__ == "5.3.2"
    for method in ("clear_data", "plot_size", "xlim", "ylim", "xticks", "yticks", "xaxes"):
        assert callable(getattr(_figure_class, method))
    for method in ("yaxes", "theme", "scatter", "plot", "build", "_limit_size"):
        assert callable(getattr(_figure_class, method))


@pytest.mark.parametrize("view", [TOP, FRONT, SIDE])
@pytest.mark.parametrize(("cols", "rows"), [(58, 22), (40, 16), (100, 40)])
def test_the_cells_land_where_plotext_itself_places_them(view, cols, rows):
    """The painter puts the wireframe's glyphs on plotext's cached frame; a
    full plotext build with the same glyphs as a scatter gives the same text."""
    scene = puma_scene(view, q=(10.0, -30.0, 20.0, 40.0, 50.0, 60.0))
    painter = PlotextPainter()
    picture = painter.draw(scene, cols, rows, framing_for(scene, cols, rows), Look())
    _, _, canvas_cols, canvas_rows = picture.canvas
    chars, roles = braille_cells(
        scene, canvas_cols, canvas_rows, picture.xlim, picture.ylim, Look()
    )
    ys, xs = np.nonzero(roles != NO_ROLE)
    (x0, x1), (y0, y1) = picture.xlim, picture.ylim
    fig = painter.figure  # the very figure: its ticks and limits are set
    fig.scatter(
        (x0 + (xs + 0.5) * (x1 - x0) / canvas_cols).tolist(),
        (y1 - (ys + 0.5) * (y1 - y0) / canvas_rows).tolist(),
        marker=[chars[y][x] for y, x in zip(ys.tolist(), xs.tolist(), strict=True)],
    )
    built = SGR.sub("", fig.build()).split("\n")[:rows]
    assert [line.ljust(cols)[:cols] for line in built] == list(picture.lines)
    assert xs.size > 6  # the arm really is on the canvas (links in whole blocks)


def test_ticks_are_numbered_in_the_robots_unit_at_their_place():
    scene = puma_scene(FRONT)
    picture = PlotextPainter().draw(scene, 70, 24, framing_for(scene, 70, 24), Look())
    left, _, canvas_cols, canvas_rows = picture.canvas
    labels = picture.lines[-1]
    (x0, x1) = picture.xlim
    for label in ("-500", "0", "500"):
        assert re.search(rf"(?<![\d-]){label}(?!\d)", labels), labels
    # the "0" label sits under the column where x = 0 is drawn
    zero_col = left + (0 - x0) / (x1 - x0) * canvas_cols
    at = re.search(r"(?<![\d-])0(?![\d])", labels).start()
    assert abs(at - zero_col) <= 1.5
    # the y labels are right-aligned left of the axis, evenly spaced multiples
    # of a 1, 2, 5 x 10^k step (two rows apart at least: finer than x's here)
    y_labels = [line[: left - 1].strip() for line in picture.lines[:canvas_rows]]
    numbers = [float(v) for v in y_labels if v]
    step = numbers[0] - numbers[1]
    assert len(numbers) >= 3 and step == nice_step(step)
    assert all(v % step == 0 for v in numbers)
    assert all(a - b == step for a, b in itertools.pairwise(numbers))


@pytest.mark.parametrize("size", [(40, 14), (60, 22), (100, 30)])
def test_a_robot_in_metres_gets_ticks_finer_than_a_metre(size):
    """A robot in metres was numbered at whole metres only (-2 ... 2)."""
    from dhsim_tui.core.model.editing import set_units

    metres = set_units(load_robot("ur5")[0], "m")
    wire = build_wireframe(metres, metres.kinematics.frames(metres.home))
    scene = project(wire, FRONT)
    cols, rows = size
    picture = PlotextPainter().draw(scene, cols, rows, framing_for(scene, cols, rows), Look())
    left, _, _, canvas_rows = picture.canvas
    y_labels = [line[: left - 1].strip() for line in picture.lines[:canvas_rows]]
    numbers = [float(v) for v in y_labels if v]
    assert abs(numbers[0] - numbers[1]) < 1.0  # 0.5 m or 0.2 m
    x_labels = [float(v) for v in picture.lines[-1].split()]
    x_step = x_labels[1] - x_labels[0]
    assert x_step == pytest.approx(nice_step(x_step)) and x_step <= 1.0


@pytest.mark.parametrize(
    ("least", "step"),
    [(0.3, 0.5), (1.0, 1.0), (1.01, 2.0), (240, 500), (501, 1000), (2e-4, 2e-4), (0, 1.0)],
)
def test_nice_steps(least, step):
    assert nice_step(least) == pytest.approx(step)


def test_tick_values_and_labels():
    assert tick_values((-1234.0, 980.0), 500.0) == [-1000.0, -500.0, 0.0, 500.0]
    assert [tick_label(v, 0.5) for v in (-0.5, 0.0, 0.5)] == ["-0.5", "0", "0.5"]
    assert [tick_label(v, 2e-3) for v in (-2e-3, -0.0)] == ["-0.002", "0"]


def test_every_role_is_styled_and_the_axes_frame_is_its_own_role():
    scene = puma_scene(FRONT)
    picture = PlotextPainter().draw(scene, 60, 22, framing_for(scene, 60, 22), Look())
    assert ROLE_INDEX["axes"] in picture.roles[-1]  # the x axis row
    for role in ("link", "x", "z", "tool", "floor", "pedestal"):  # y points away
        assert ROLE_INDEX[role] in picture.roles, role


def test_mono_names_the_axes_with_letters_and_keeps_the_tool():
    scene = puma_scene(FRONT, q=(10.0, -30.0, 20.0, 40.0, 50.0, 60.0))
    picture = PlotextPainter().draw(scene, 60, 22, framing_for(scene, 60, 22), Look(mono=True))
    left, _, _, rows = picture.canvas
    canvas = [line[left:] for line in picture.lines[:rows]]
    assert {"x", "y", "z"} <= set("".join(canvas)) and "◆" in "".join(canvas)
    # one letter a tip, never a run of the same letter (two frames' tips side by side)
    for row in canvas:
        for a, b in itertools.pairwise(row):
            assert not (a == b and a in "xyz"), row


def test_without_colour_a_letter_names_only_an_axis_that_shows():
    """At home, seen from the front, frame 1's y axis lies under frame 0's z
    axis and the link: it gets no letter, where it would have named z's cell."""
    scene = puma_scene(FRONT)
    picture = PlotextPainter().draw(scene, 60, 22, framing_for(scene, 60, 22), Look(mono=True))
    for y, line in enumerate(picture.lines[: picture.canvas[3]]):
        for x, char in enumerate(line):
            if char in "xyz" and x >= picture.canvas[0]:
                assert picture.roles[y, x] == ROLE_INDEX[char], (y, x, char)


def test_ascii_pictures_are_seven_bit_and_drawn_with_plotext_markers():
    for view in (TOP, FRONT, SIDE):
        scene = puma_scene(view)
        painter = PlotextPainter()
        picture = painter.draw(scene, 60, 22, framing_for(scene, 60, 22), Look(ascii=True))
        text = picture.text()
        assert text.isascii(), {ch for ch in text if ord(ch) > 127}
        assert "@" in text and "#" in text and "z" in text
        assert painter.builds == 1


class _FiniteFigure:
    """Wraps a plotext figure: every number it is given must be finite."""

    def __init__(self, figure, seen: list) -> None:
        self._figure, self._seen = figure, seen

    def __getattr__(self, name):
        method = getattr(self._figure, name)

        def checked(*args, **kwargs):
            for value in _numbers(args):
                assert math.isfinite(value), (name, value)
                self._seen.append(value)
            return method(*args, **kwargs)

        return checked


def _numbers(values):
    for value in values:
        if isinstance(value, (list, tuple)):
            yield from _numbers(value)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            yield float(value)


coordinate = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-2000, max_value=2000),
)


@settings(max_examples=60, deadline=None)
@given(
    points=st.lists(st.tuples(coordinate, coordinate), min_size=2, max_size=12),
    ascii_mode=st.booleans(),
    zoom=st.sampled_from([0.25, 1.0, 7.0, 64.0]),
)
def test_no_nan_or_inf_ever_reaches_plotext(points, ascii_mode, zoom):
    xs, ys = zip(*points, strict=True)
    scene = ViewScene(
        FRONT,
        (Polyline(xs, ys, "link"), Polyline(ys, xs, "x")),
        (xs[0], ys[0]),
        (-1000.0, 1000.0, -500.0, 1200.0),
        "mm",
    )
    painter = PlotextPainter()
    seen: list[float] = []
    painter.figure = _FiniteFigure(painter.figure, seen)
    framing = framing_for(scene, 50, 18)
    picture = painter.draw(
        scene, 50, 18, Framing(framing.centre, framing.per_dot / zoom), Look(ascii=ascii_mode)
    )
    assert seen  # the limits and ticks went through the check
    assert len(picture.lines) == 18 and all(len(line) == 50 for line in picture.lines)


def test_the_frame_is_built_once_while_only_the_arm_moves():
    painter = PlotextPainter()
    scene = puma_scene(FRONT)
    framing = framing_for(scene, 60, 22)
    first = painter.draw(scene, 60, 22, framing, Look())
    moved = painter.draw(puma_scene(FRONT, q=(0, -20, 0, 0, 30, 0)), 60, 22, framing, Look())
    assert painter.builds == 1 and moved.lines != first.lines
    assert moved.lines[-2:] == first.lines[-2:]  # the axis and its labels
    painter.draw(scene, 60, 22, Framing(framing.centre, framing.per_dot / 2), Look())
    assert painter.builds == 2  # zoomed: new ticks, plotext builds again


def test_the_3d_view_has_no_tick_axes_and_orbits():
    robot, _ = load_robot("puma560")
    wire = build_wireframe(robot, robot.kinematics.frames(robot.home))
    painter = PlotextPainter()
    iso = project_oblique(wire, Orbit())
    picture = painter.draw(iso, 60, 22, framing_for(iso, 60, 22), Look())
    assert picture.canvas == (0, 0, 60, 22)
    assert ROLE_INDEX["grid"] in picture.roles and ROLE_INDEX["axes"] not in picture.roles
    turned = project_oblique(wire, Orbit().turned(30, 0))
    assert painter.draw(turned, 60, 22, framing_for(turned, 60, 22), Look()).lines != picture.lines

"""The scene layer: equal scale on both axes, frame axes sized to the arm,
pedestal, floor, and the braille raster."""

from __future__ import annotations

import numpy as np
import pytest

from dhsim_tui.core import Joint, Robot, load_robot, reach
from dhsim_tui.scene import VIEWS, build_wireframe, equal_scale_limits, project
from dhsim_tui.scene.clip import clip_segments
from dhsim_tui.scene.projection import Polyline, ViewScene
from dhsim_tui.scene.raster import rasterize
from dhsim_tui.scene.wireframe import AXIS_FRACTION


@pytest.mark.parametrize(("cols", "rows"), [(40, 10), (80, 24), (30, 30), (57, 21), (2, 2)])
@pytest.mark.parametrize("bounds", [(-1000, 1000, -672, 1064), (0, 1, 0, 50), (-5, 5, -5, 5)])
def test_limits_give_both_axes_the_same_length_per_dot(cols, rows, bounds):
    (x0, x1), (y0, y1) = equal_scale_limits(bounds, cols, rows)
    per_x = (x1 - x0) / (2 * cols - 1)
    per_y = (y1 - y0) / (4 * rows - 1)
    assert per_x == pytest.approx(per_y)
    assert x0 <= bounds[0] and x1 >= bounds[1] and y0 <= bounds[2] and y1 >= bounds[3]


@pytest.mark.parametrize(("cols", "rows"), [(40, 12), (70, 20), (25, 40)])
def test_a_100mm_link_is_as_long_across_as_it_is_up(cols, rows):
    """Draw a horizontal and a vertical 100 mm segment: same number of dots."""
    scene = ViewScene(
        VIEWS[1],
        (Polyline((0.0, 100.0), (0.0, 0.0), "x"), Polyline((300.0, 300.0), (0.0, 100.0), "z")),
        (1e9, 1e9),
        (-400.0, 400.0, -400.0, 400.0),
    )
    raster = rasterize(scene, cols, rows)

    def dots(colour: str) -> tuple[int, int]:
        bits = [
            (r, c, ord(ch) - 0x2800)
            for r, line in enumerate(raster.lines)
            for c, ch in enumerate(line)
            if ch != " "
        ]
        xs, ys = [], []
        for r, c, b in bits:
            if raster.palette[raster.colours[r, c]] != colour:
                continue
            for k, (dy, dx) in enumerate(
                [(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (2, 1), (3, 0), (3, 1)]
            ):
                if b & (1 << k):
                    xs.append(2 * c + dx)
                    ys.append(4 * r + dy)
        return max(xs) - min(xs), max(ys) - min(ys)

    across, flat = dots("x")
    tall_x, up = dots("z")
    assert flat == 0 and tall_x == 0
    assert abs(across - up) <= 1  # one dot of rounding at most


def test_frame_axes_scale_with_the_arm_and_shared_origins_draw_longer():
    puma, _ = load_robot("puma560")
    wire = build_wireframe(puma, puma.kinematics.frames(puma.home))
    lengths = np.linalg.norm(wire.axes - wire.origins[:, None, :], axis=2)
    base = AXIS_FRACTION * reach(puma)
    assert AXIS_FRACTION == 0.06  # short beside the links (issue 16: 12% hid the arm)
    assert lengths[0] == pytest.approx([base] * 3)
    assert lengths[1] == pytest.approx([1.5 * base] * 3)  # frame 1 shares frame 0's origin
    small = Robot("small", (Joint(a=10.0),))
    small_wire = build_wireframe(small, small.kinematics.frames(small.home))
    assert np.linalg.norm(small_wire.axes[0, 0] - small_wire.origins[0]) == pytest.approx(0.6)


def test_pedestal_and_floor():
    scara, _ = load_robot("scara_pedestal")
    wire = build_wireframe(scara, scara.kinematics.frames(scara.home))
    assert wire.floor_z == -250.0
    assert np.allclose(wire.pedestal, [[0, 0, -250], [0, 0, 0]])
    front = project(wire, VIEWS[1])
    assert front.lines[0].role == "floor" and front.lines[0].ys == (-250.0, -250.0)
    roles = [line.role for line in front.lines]
    # the pedestal and the links are drawn over the frame axes, the links last
    assert roles[-2:] == ["pedestal", "link"] and roles.index("x") < roles.index("pedestal")
    assert not any(line.role == "pedestal" for line in project(wire, VIEWS[0]).lines)
    assert wire.warnings == ()


def test_frames_below_the_floor_mark_the_floor_as_hit():
    probe = Robot(
        "probe", (Joint("prismatic", 0.0, 50.0, 0.0, 0.0, -400.0, 400.0),), base_z="-z", base_x="+x"
    )
    wire = build_wireframe(probe, probe.kinematics.frames(probe.home))
    assert wire.below_floor == (1,)
    assert wire.warnings == ("below the floor: frame 1",)
    assert project(wire, VIEWS[1]).lines[0].role == "floor_hit"


@pytest.mark.parametrize("half_length", [15.0, 640.0, 2560.0, 1e9, 1e300])
def test_a_line_far_longer_than_the_picture_is_drawn_solid_where_it_crosses(half_length):
    """At zoom 64 a link runs far off the picture: it was sampled at 4096
    points over its whole length, so the part on the picture came out dotted,
    or blank. Cut to the picture first, it is a solid row of dots."""
    line = Polyline((-half_length, half_length), (0.1, 0.1), "link")
    nan = float("nan")
    scene = ViewScene(view=None, lines=(line,), end_effector=(nan, nan), bounds=(-10, 10, -10, 10))
    raster = rasterize(scene, 40, 10, ((-10.0, 10.0), (-10.0, 10.0)))
    drawn = [row for row in raster.lines if row.strip()]
    assert len(drawn) == 1
    assert all(cell != " " for cell in drawn[0]), drawn[0]  # every column has its dots


def test_a_segment_inside_the_picture_keeps_its_exact_ends():
    nan = float("nan")
    line = Polyline((-3.3, 7.7), (-2.2, 4.4), "link")
    scene = ViewScene(view=None, lines=(line,), end_effector=(nan, nan), bounds=(-10, 10, -10, 10))
    raster = rasterize(scene, 40, 10, ((-10.0, 10.0), (-10.0, 10.0)))
    cols = [i for row in raster.lines for i, cell in enumerate(row) if cell != " "]
    # -3.3 and 7.7 on a 40-cell row from -10 to 10 (two dots a cell): cells 13..35
    assert min(cols) == 13 and max(cols) == 35


def test_cut_segments_lie_in_the_rectangle_even_from_astronomically_far_ends():
    """(-2.2e54, -664) to (1e12, -1.5): t rounds to 1 at the far side and
    x0 + t dx loses every digit; the cut ends still lie on the picture."""
    x0, x1 = np.array([-2.1598715963246474e54, 0.0]), np.array([1e12, 1e300])
    y0, y1 = np.array([-664.3337447860113, -1.5]), np.array([-1.5, 1e300])
    a, b, c, d, shows = clip_segments(x0, x1, y0, y1, (-1200.0, 1200.0), (-500.0, 1200.0))
    assert shows.tolist() == [True, True]
    assert np.abs(np.concatenate([a, b])).max() <= 1200.0
    assert np.concatenate([c, d]).min() >= -500.0 and np.concatenate([c, d]).max() <= 1200.0
    # an end inside keeps its exact value
    inside = clip_segments(*(np.array([v]) for v in (0.1, 0.7, 0.2, 0.3)), (0.0, 1.0), (0.0, 1.0))
    assert [float(v[0]) for v in inside[:4]] == [0.1, 0.7, 0.2, 0.3]

"""The 3-D view: the orbit's angles (MATLAB's view(az, el)), the camera, the
floor grid, orbit-invariant bounds, checked against hand computations and the
orthographic views."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from dhsim_tui.core import Joint, Robot, bundled_names, load_robot
from dhsim_tui.core.analysis.workspace import WorkArea
from dhsim_tui.scene import build_wireframe
from dhsim_tui.scene.oblique import (
    PICTURE_MARGIN,
    Orbit,
    camera,
    grid_step,
    grid_ticks,
    project_oblique,
)
from dhsim_tui.scene.projection import FRONT, ISO, SIDE, TOP, project
from dhsim_tui.scene.wireframe import Wireframe

BUNDLED = bundled_names()
AZIMUTHS = st.floats(-180.0, 180.0, allow_nan=False)
ELEVATIONS = st.floats(-90.0, 90.0, allow_nan=False)
#: orbits a user reaches with the keys, poles included
ORBITS = [Orbit(az, el) for az in range(-165, 181, 15) for el in range(-90, 91, 15)]


def _wire(name: str, q=None) -> tuple[Robot, Wireframe]:
    robot, _ = load_robot(name)
    return robot, build_wireframe(robot, robot.kinematics.frames(robot.home if q is None else q))


def _random_poses(robot: Robot, count: int, seed: int = 9) -> list[np.ndarray]:
    rng = np.random.default_rng(seed)
    return [rng.uniform(robot.lower, robot.upper) for _ in range(count)]


def _box_corners(area: WorkArea) -> np.ndarray:
    xs, ys, zs = area.limits("x"), area.limits("y"), area.limits("z")
    return np.array([(x, y, z) for x in xs for y in ys for z in zs], dtype=float)


def _box_centre(area: WorkArea) -> np.ndarray:
    return _box_corners(area).mean(axis=0)


def _by_role(scene, role: str):
    (line,) = [line for line in scene.lines if line.role == role]
    return np.array(line.xs), np.array(line.ys)


# -- the orbit ---------------------------------------------------------------------------


def test_the_default_orbit_is_isometric_and_labelled_in_whole_degrees():
    orbit = Orbit()
    assert orbit.azimuth == 45.0
    assert math.tan(math.radians(orbit.elevation)) == pytest.approx(1 / math.sqrt(2), abs=1e-12)
    assert orbit.label == "az 45° el 35°"
    assert orbit.ascii_label == "az 45 deg el 35 deg"
    assert Orbit(-0.4, -89.6).label == "az 0° el -90°"
    assert Orbit.STEP == 15.0


@pytest.mark.parametrize(
    ("start", "turn", "expected"),
    [
        ((45.0, 35.0), (15.0, 15.0), (60.0, 50.0)),
        ((170.0, 0.0), (15.0, 0.0), (-175.0, 0.0)),
        ((-170.0, 0.0), (-15.0, 0.0), (175.0, 0.0)),
        ((165.0, 0.0), (15.0, 0.0), (180.0, 0.0)),
        ((-165.0, 0.0), (-15.0, 0.0), (180.0, 0.0)),  # -180 is written +180
        ((0.0, 80.0), (0.0, 15.0), (0.0, 90.0)),
        ((0.0, -80.0), (0.0, -15.0), (0.0, -90.0)),
        ((10.0, 20.0), (720.0, 0.0), (10.0, 20.0)),
        ((10.0, 20.0), (math.nan, math.inf), (10.0, 20.0)),
    ],
)
def test_turned_wraps_the_azimuth_and_clamps_the_elevation(start, turn, expected):
    turned = Orbit(*start).turned(*turn)
    assert (turned.azimuth, turned.elevation) == pytest.approx(expected, abs=1e-9)


@given(AZIMUTHS, ELEVATIONS, st.floats(-1e4, 1e4), st.floats(-1e4, 1e4))
def test_turned_stays_in_range_and_keeps_the_direction(az, el, d_az, d_el):
    turned = Orbit(az, el).turned(d_az, d_el)
    assert -180.0 < turned.azimuth <= 180.0
    assert -90.0 <= turned.elevation <= 90.0
    # the same direction as turning without wrapping, up to rounding
    gap = (turned.azimuth - (az + d_az)) % 360.0
    assert min(gap, 360.0 - gap) < 1e-9 * max(1.0, abs(az + d_az))
    assert turned.elevation == min(90.0, max(-90.0, el + d_el))


# -- the camera --------------------------------------------------------------------------


@given(AZIMUTHS, ELEVATIONS)
def test_the_camera_is_orthonormal_and_faces_matlabs_viewpoint(az, el):
    right, up = camera(Orbit(az, el))
    assert np.linalg.norm(right) == pytest.approx(1.0)
    assert np.linalg.norm(up) == pytest.approx(1.0)
    assert right @ up == pytest.approx(0.0, abs=1e-12)
    assert right[2] == 0.0  # the picture's horizontal stays level
    assert up[2] >= 0.0
    # MATLAB: the viewpoint is at azimuth az from -y (counter-clockwise), el above the floor
    a, e = math.radians(az), math.radians(el)
    viewer = [math.cos(e) * math.sin(a), -math.cos(e) * math.cos(a), math.sin(e)]
    assert np.cross(right, up) == pytest.approx(viewer, abs=1e-12)


def test_a_unit_cube_makes_the_isometric_hexagon_worked_out_by_hand():
    right, up = camera(Orbit())
    corners = np.array([(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    picture = np.column_stack([corners @ right, corners @ up])
    r2, r6 = math.sqrt(2), math.sqrt(6)
    # view(45, 35.26): +x to the lower right, +y to the upper right, +z straight up
    by_hand = {
        (0, 0, 0): (0, 0),
        (1, 0, 0): (1 / r2, -1 / r6),
        (0, 1, 0): (1 / r2, 1 / r6),
        (0, 0, 1): (0, 2 / r6),
        (1, 1, 0): (r2, 0),
        (1, 0, 1): (1 / r2, 1 / r6),  # behind (0, 1, 0): the view runs along (1, -1, 1)
        (0, 1, 1): (1 / r2, 3 / r6),
        (1, 1, 1): (r2, 2 / r6),
    }
    for corner, point in zip(corners, picture, strict=True):
        assert point == pytest.approx(by_hand[tuple(int(c) for c in corner)], abs=1e-12)
    # isometric: the three axes shortened alike, and +x, -y, +z 120 degrees apart
    axes = np.array([[right[k], up[k]] for k in range(3)])
    assert np.linalg.norm(axes, axis=1) == pytest.approx([math.sqrt(2 / 3)] * 3)
    x_, minus_y, z_ = axes * [[1], [-1], [1]]
    angles = [math.degrees(math.atan2(v, u)) % 360 for u, v in (x_, minus_y, z_)]
    assert sorted(angles) == pytest.approx([90.0, 210.0, 330.0])


def test_project_oblique_draws_the_cube_about_the_work_areas_centre():
    cube = WorkArea(0, 1, 0, 1, 0, 1)
    path = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0), (1, 1, 1), (0, 1, 1)], dtype=float)
    wire = Wireframe(
        links=path,
        origins=path[:1],
        axes=path[None, 1:4],
        end_effector=path[-1],
        pedestal=None,
        floor_z=0.0,
        area=cube,
        below_floor=(),
        units="m",
    )
    scene = project_oblique(wire, Orbit())
    r2, r6 = math.sqrt(2), math.sqrt(6)
    centre = (1 / r2, 1 / r6)  # the projection of (0.5, 0.5, 0.5)
    by_hand = [(0, 0), (1 / r2, -1 / r6), (r2, 0), (r2, 2 / r6), (1 / r2, 3 / r6)]
    xs, ys = _by_role(scene, "link")
    assert np.column_stack([xs, ys]) == pytest.approx(np.subtract(by_hand, centre), abs=1e-12)
    assert scene.end_effector == pytest.approx((1 / r2 - centre[0], 3 / r6 - centre[1]))
    assert scene.view == ISO
    # worked out by hand: the floor's square turned to its widest is
    # hypot(.5, .5) across and from -2/sqrt6 to 0 up (its diagonal, sin(el) of
    # it deep, 0.5 cos(el) below the centre); the arm's highest point, its
    # tool at (0, 1, 1), is 2/sqrt6 up; 3% of the height above and below
    pad = PICTURE_MARGIN * 4 / r6
    assert scene.bounds == pytest.approx(
        (-math.sqrt(0.5), math.sqrt(0.5), -2 / r6 - pad, 2 / r6 + pad), abs=1e-12
    )


@pytest.mark.parametrize("name", ["puma560", "scara_pedestal", "stanford"])
@pytest.mark.parametrize("az", [0.0, 30.0, 45.0, -120.0, 180.0])
def test_looking_straight_down_is_the_top_view_turned_by_the_azimuth(name, az):
    robot, _ = load_robot(name)
    for q in _random_poses(robot, 3):
        wire = build_wireframe(robot, robot.kinematics.frames(q))
        top, oblique = project(wire, TOP), project_oblique(wire, Orbit(az, 90.0))
        a = math.radians(az)
        cx, cy, _ = _box_centre(wire.area)
        for role in ("link", "x", "y", "z"):
            x, y = _by_role(top, role)
            x, y = x - cx, y - cy
            # the viewpoint turns counter-clockwise, so the picture turns clockwise
            expected = (x * math.cos(a) + y * math.sin(a), -x * math.sin(a) + y * math.cos(a))
            scale = wire.area.zmax
            np.testing.assert_allclose(_by_role(oblique, role), expected, atol=1e-12 * scale)


@pytest.mark.parametrize(("az", "view"), [(0.0, FRONT), (90.0, SIDE)])
@pytest.mark.parametrize("name", BUNDLED)
def test_a_level_view_is_the_front_or_side_view(name, az, view):
    robot, _ = load_robot(name)
    for q in _random_poses(robot, 3):
        wire = build_wireframe(robot, robot.kinematics.frames(q))
        flat, oblique = project(wire, view), project_oblique(wire, Orbit(az, 0.0))
        centre = _box_centre(wire.area)
        roles = ["link", "x", "y", "z"] + (["pedestal"] if wire.pedestal is not None else [])
        for role in roles:
            x, y = _by_role(flat, role)
            expected = (x - centre[view.right], y - centre[view.up])
            np.testing.assert_allclose(_by_role(oblique, role), expected, atol=1e-9)


# -- bounds that hold still --------------------------------------------------------------


@pytest.mark.parametrize("name", BUNDLED)
def test_bounds_hold_the_floor_and_the_arm_and_the_floor_part_holds_still_while_turning(name):
    """The 3-D view frames the work area's floor as it shows at any azimuth
    (so turning the view leaves it be) and the arm as it shows now, no looser
    than that (issue 16: the seed's box made the view mostly empty)."""
    robot, home = _wire(name)
    corners = _box_corners(home.area)
    floor = corners[corners[:, 2] == corners[:, 2].min()].copy()
    floor[:, 2] = home.floor_z
    wires = [home] + [
        build_wireframe(robot, robot.kinematics.frames(q)) for q in _random_poses(robot, 4)
    ]
    for elevation in range(-90, 91, 15):
        floor_only = {
            project_oblique(
                Wireframe(**{**home.__dict__, "links": home.links[:1], "origins": home.origins[:1],
                             "axes": home.axes[:1], "end_effector": home.links[0]}),
                Orbit(az, elevation),
            ).bounds
            for az in range(-165, 181, 15)
        }  # fmt: skip
        for wire in wires:
            for az in (-120, 0, 45, 150):
                orbit = Orbit(az, elevation)
                scene = project_oblique(wire, orbit)
                xmin, xmax, ymin, ymax = scene.bounds
                tolerance = 1e-9 * (xmax - xmin)
                right, up = camera(orbit)
                centre = _box_centre(home.area)
                across, tall = (floor - centre) @ right, (floor - centre) @ up
                assert across.min() >= xmin - tolerance and across.max() <= xmax + tolerance
                assert tall.min() >= ymin - tolerance and tall.max() <= ymax + tolerance
                for role in ("link", "tool"):
                    xs, ys = (
                        _by_role(scene, role)
                        if role == "link"
                        else ([scene.end_effector[0]], [scene.end_effector[1]])
                    )
                    xs, ys = np.asarray(xs), np.asarray(ys)
                    assert np.all((xs >= xmin - tolerance) & (xs <= xmax + tolerance))
                    assert np.all((ys >= ymin - tolerance) & (ys <= ymax + tolerance))
        # the floor alone (an arm folded onto frame 0 of a pedestal) frames the
        # same from every azimuth at one elevation
        assert len({tuple(round(v, 6) for v in bounds) for bounds in floor_only}) == 1


def test_an_arm_hanging_through_the_floor_stays_in_bounds_and_marks_the_floor():
    probe = Robot(
        "probe", (Joint("prismatic", 0.0, 50.0, 0.0, 0.0, -400.0, 400.0),), base_z="-z", base_x="+x"
    )
    for q in ((-400.0,), (0.0,), (400.0,)):
        wire = build_wireframe(probe, probe.kinematics.frames(q))
        for orbit in ORBITS:
            scene = project_oblique(wire, orbit)
            xmin, xmax, ymin, ymax = scene.bounds
            ax0, ax1, ay0, ay1 = scene.arm_bounds
            assert xmin <= ax0 <= ax1 <= xmax and ymin <= ay0 <= ay1 <= ymax
    scene = project_oblique(build_wireframe(probe, probe.kinematics.frames(probe.home)))
    assert [line.role for line in scene.lines][:2] == ["grid", "floor_hit"]


# -- the floor grid ----------------------------------------------------------------------


def _is_nice(step: float) -> bool:
    power = 10.0 ** math.floor(math.log10(step) + 1e-9)
    return any(math.isclose(step, m * power, rel_tol=1e-9) for m in (1, 2, 5, 10))


@given(st.floats(1e-3, 1e6))
def test_grid_steps_are_nice_with_four_to_eight_lines_across(half):
    step = grid_step(-half, half)
    assert _is_nice(step)
    # multiples of the step strictly inside the square, plus its two edges
    inside = [k * step for k in range(-20, 21) if abs(k * step) < half * (1 - 1e-9)]
    count = len(inside) + 2
    assert 4 <= count <= 8
    assert len(grid_ticks(-half, half, step)) + 2 == count


@pytest.mark.parametrize("name", BUNDLED)
def test_the_floor_grid_lies_on_the_floor_at_multiples_of_its_step(name):
    _, wire = _wire(name)
    area = wire.area
    scene = project_oblique(wire, Orbit(0.0, 90.0))  # from above: picture = floor plane
    step = scene.grid_step
    assert _is_nice(step)
    cx, cy, _ = _box_centre(area)
    xs, ys = _by_role(scene, "grid")
    lifts = np.isnan(xs)
    strokes = np.split(np.column_stack([xs + cx, ys + cy]), np.nonzero(lifts)[0])
    strokes = [s[~np.isnan(s[:, 0])] for s in strokes]
    assert all(len(s) == 2 for s in strokes)
    upright = [s for s in strokes if s[0, 0] == pytest.approx(s[1, 0])]
    level = [s for s in strokes if s[0, 1] == pytest.approx(s[1, 1])]
    assert len(upright) + len(level) == len(strokes)
    for lines, k, (lo, hi) in ((upright, 0, area.limits("y")), (level, 1, area.limits("x"))):
        assert 4 <= len(lines) + 2 <= 8  # with the outline's two edges
        for s in lines:
            assert s[0, k] / step == pytest.approx(round(s[0, k] / step), abs=1e-9)
            assert sorted(s[:, 1 - k]) == pytest.approx([lo, hi])
    role = "floor_hit" if wire.below_floor else "floor"
    outline = np.add(np.column_stack(_by_role(scene, role)), (cx, cy))
    square = [(area.xmin, area.ymin), (area.xmax, area.ymin), (area.xmax, area.ymax)]
    square += [(area.xmin, area.ymax), (area.xmin, area.ymin)]
    np.testing.assert_allclose(outline, square, atol=1e-9 * area.xmax)
    # from any side, the grid is in the plane z = floor_z: it projects like that plane
    right, up = camera(Orbit())
    floor_point = np.array([0.0, 0.0, wire.floor_z]) - _box_centre(area)
    xs, ys = _by_role(project_oblique(wire, Orbit()), "grid")
    ok = ~np.isnan(xs)
    # back out x, y from the picture (right and up's x-y parts are independent when el != 0)
    plane = np.array([[right[0], right[1]], [up[0], up[1]]])
    world_xy = np.linalg.solve(
        plane, np.vstack([xs[ok] - floor_point @ right, ys[ok] - floor_point @ up])
    )
    assert world_xy.min() >= min(area.xmin, area.ymin) - 1e-9 * area.xmax
    assert world_xy.max() <= max(area.xmax, area.ymax) + 1e-9 * area.xmax


# -- nothing infinite, NaN only between strokes -------------------------------------------


@pytest.mark.parametrize("name", BUNDLED)
def test_everything_is_finite_but_the_pen_lifts(name):
    robot, _ = _wire(name)
    for q in _random_poses(robot, 2):
        wire = build_wireframe(robot, robot.kinematics.frames(q))
        for orbit in (Orbit(), Orbit(0, 90), Orbit(180, -90), Orbit(-90, 0), Orbit(123.4, 5.6)):
            scene = project_oblique(wire, orbit)
            assert all(math.isfinite(v) for v in (*scene.bounds, *scene.arm_bounds))
            assert all(math.isfinite(v) for v in scene.end_effector)
            assert all(math.isfinite(t.x) and math.isfinite(t.y) for t in scene.tips)
            assert math.isfinite(scene.grid_step) and scene.grid_step > 0
            for line in scene.lines:
                xs, ys = np.array(line.xs), np.array(line.ys)
                lifts = np.isnan(xs)
                assert np.array_equal(lifts, np.isnan(ys)), line.role
                assert not np.isinf(xs).any() and not np.isinf(ys).any(), line.role
                if lifts.any():
                    assert not lifts[0] and not lifts[-1], line.role
                    assert not (lifts[1:] & lifts[:-1]).any(), line.role

"""The workspace: a cloud of tool positions from random joint values within
the limits (batch FK), its summary, and the cloud drawn faintly behind the
arm in every view, in every colour depth, and gone again without a trace."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from conftest import reference_frames
from pilot_helpers import press, started
from rich.console import Console
from rich.segment import Segment
from rich.style import Style

from dhsim_tui.core import load_robot
from dhsim_tui.core.analysis.workspace import (
    MAX_SAMPLES,
    joint_samples,
    position_chunks,
    reach,
    sample_positions,
    sample_summary,
    workspace_summary,
)
from dhsim_tui.core.files.library import bundled_names
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics import robot_base
from dhsim_tui.render.cloud import ASCII_MARK, MONO_MARK, CloudLayer, sparse_cells
from dhsim_tui.render.picture import CELL_ROLES, NO_ROLE, ROLE_INDEX, Framing, Look, Picture
from dhsim_tui.render.plotext_picture import PlotextPainter, bare_picture
from dhsim_tui.scene import build_wireframe, project
from dhsim_tui.scene.cloud import cloud_dots, project_cloud
from dhsim_tui.scene.oblique import Orbit, picture_coordinates, project_oblique
from dhsim_tui.scene.projection import FRONT, ISO, SIDE, TOP, Polyline, ViewScene, per_dot_needed
from dhsim_tui.tui.widgets.arm_view import ArmView
from dhsim_tui.tui.widgets.view_style import role_styles
from dhsim_tui.tui.widgets.views_panel import ViewsPanel

CLOUD = ROLE_INDEX["cloud"]


def moved_base(robot):
    """The robot on a base moved and turned (frame 0 away from the world origin)."""
    return dataclasses.replace(robot, base_xyz=(120.0, -80.0, 250.0), base_rpy=(10.0, -20.0, 35.0))


# -- the cloud and its summary (core) ----------------------------------------------


@pytest.mark.parametrize("name", bundled_names())
def test_the_cloud_lies_within_reach_of_frame_0(name):
    robot, _ = load_robot(name)
    for arm in (robot, moved_base(robot)):
        points = sample_positions(arm, 5000, seed=3)
        assert points.shape == (5000, 3) and np.isfinite(points).all()
        origin = robot_base(arm)[:3, 3]
        distance = np.linalg.norm(points - origin, axis=1)
        bound = reach(arm)
        assert distance.max() <= bound + 1e-9 * max(bound, 1.0)
        summary = workspace_summary(arm, points)
        assert summary.reach_reached == pytest.approx(distance.max())
        assert summary.reach_bound == bound and summary.reach_reached <= bound * (1 + 1e-12)
        assert summary.origin == pytest.approx(tuple(origin))


@pytest.mark.parametrize("name", ["puma560", "puma560_modified", "stanford", "scara_pedestal"])
def test_the_cloud_is_the_reference_fk_of_joint_values_within_the_limits(name):
    robot, _ = load_robot(name)
    arm = moved_base(robot)
    qs = np.concatenate(list(joint_samples(arm, 3000, seed=11)))
    assert (qs >= np.array(arm.lower)).all() and (qs <= np.array(arm.upper)).all()
    points = sample_positions(arm, 3000, seed=11)
    for i in (0, 1, 7, 500, 2999):
        expected = reference_frames(arm, qs[i])[-1][:3, 3]
        assert points[i] == pytest.approx(expected, abs=1e-9 * max(reach(arm), 1.0))


def test_the_bounding_box_holds_every_point_and_touches_the_cloud():
    robot, _ = load_robot("puma560")
    points = sample_positions(moved_base(robot))
    summary = workspace_summary(robot, points)
    assert summary.count == len(points) == 20000
    assert summary.contains(points)
    assert np.array(summary.xyz_min) == pytest.approx(points.min(axis=0))
    assert np.array(summary.xyz_max) == pytest.approx(points.max(axis=0))
    assert summary.z_range == (summary.xyz_min[2], summary.xyz_max[2])
    assert 0 < summary.horizontal_radius <= summary.reach_reached * (1 + 1e-12)
    data = summary.as_dict()
    assert data["min"] == list(summary.xyz_min) and data["samples"] == 20000


def test_the_same_seed_gives_the_same_cloud_whatever_the_chunks():
    robot, _ = load_robot("ur5")
    whole = sample_positions(robot, 5000, seed=7)
    assert np.array_equal(whole, sample_positions(robot, 5000, seed=7))
    assert not np.array_equal(whole, sample_positions(robot, 5000, seed=8))
    pieces = list(position_chunks(robot, 5000, seed=7, chunk=777))
    assert len(pieces) == 7 and max(len(p) for p in pieces) == 777
    assert np.array_equal(np.concatenate(pieces), whole)
    # the summary chunk by chunk is the summary of the whole cloud
    assert sample_summary(robot, 5000, seed=7) == workspace_summary(robot, whole)


@pytest.mark.parametrize("n", [0, -1, MAX_SAMPLES + 1, 2.5, "100", True, None])
def test_a_bad_sample_count_is_refused(n):
    robot, _ = load_robot("planar2")
    with pytest.raises(DhsimError):
        sample_positions(robot, n)


def test_an_empty_cloud_has_no_summary():
    robot, _ = load_robot("planar2")
    with pytest.raises(DhsimError):
        workspace_summary(robot, np.empty((0, 3)))


# -- projection and cells (scene, render) ----------------------------------------


def test_the_cloud_projects_as_the_views_do():
    robot, _ = load_robot("puma560")
    wire = build_wireframe(robot, robot.kinematics.frames(robot.home))
    points = sample_positions(robot, 200)
    for view in (TOP, FRONT, SIDE):
        cloud = project_cloud(points, view, wire.area)
        assert np.array_equal(cloud.xs, points[:, view.right])
        assert np.array_equal(cloud.ys, points[:, view.up])
    orbit = Orbit().turned(30, -10)
    cloud = project_cloud(points, ISO, wire.area, orbit)
    xs, ys = picture_coordinates(wire.area, orbit)(points)
    assert np.array_equal(cloud.xs, xs) and np.array_equal(cloud.ys, ys)
    # the arm's tool lands where the arm's own projection puts it
    tip = wire.end_effector[None, :]
    assert project_cloud(tip, ISO, wire.area, orbit).xs[0] == pytest.approx(
        project_oblique(wire, orbit).end_effector[0]
    )


def test_points_off_the_picture_or_not_finite_draw_nothing():
    robot, _ = load_robot("puma560")
    wire = build_wireframe(robot, robot.kinematics.frames(robot.home))
    points = np.array([[np.nan, 0, 0], [1e9, 0, 0], [0, 0, np.inf], [0.0, 0.0, 0.0]])
    cloud = project_cloud(points, FRONT, wire.area)
    dots = cloud_dots(cloud, 10, 5, (-100.0, 100.0), (-50.0, 50.0))
    assert dots.shape == (20, 20) and dots.sum() == 1


def _scene(view, robot=None, q=None):
    robot = robot or load_robot("puma560")[0]
    wire = build_wireframe(robot, robot.kinematics.frames(robot.home if q is None else q))
    scene = project(wire, view) if not view.is_3d else project_oblique(wire, Orbit())
    return robot, wire, scene


def _framing(scene, cols, rows):
    b = scene.bounds
    return Framing(((b[0] + b[1]) / 2, (b[2] + b[3]) / 2), per_dot_needed(b, cols - 7, rows - 2))


def _cloud_for(view, robot, wire):
    return project_cloud(sample_positions(robot, 20000), view, wire.area, Orbit(), key=1)


LOOKS = [Look(), Look(mono=True), Look(ascii=True)]


def _assert_cloud_only_behind(before: Picture, after: Picture, look: Look) -> int:
    """Every cell ``after`` changed was empty in ``before`` and now holds the
    cloud; nothing else moved. Returns how many cloud cells there are."""
    assert after.size == before.size and after.canvas == before.canvas
    old = np.array([list(line) for line in before.lines])
    new = np.array([list(line) for line in after.lines])
    changed = (old != new) | (before.roles != after.roles)
    assert (after.roles[changed] == CLOUD).all()
    assert (before.roles[changed] == NO_ROLE).all() and (old[changed] == " ").all()
    left, top, cols, rows = after.canvas
    inside = np.zeros_like(changed)
    inside[top : top + rows, left : left + cols] = True
    assert not (changed & ~inside).any()  # never on the axes, ticks or labels
    marks = set(new[changed].tolist())
    if look.ascii:
        assert marks == {ASCII_MARK} and after.text().isascii()
    elif look.mono:
        assert marks == {MONO_MARK}
    else:
        assert all(0x2800 < ord(mark) <= 0x28FF for mark in marks)
    return int(changed.sum())


@pytest.mark.parametrize("look", LOOKS, ids=["colour", "mono", "ascii"])
@pytest.mark.parametrize("view", [TOP, FRONT, SIDE, ISO], ids=lambda v: v.key)
def test_cloud_cells_go_only_where_the_picture_is_empty(view, look):
    robot, wire, scene = _scene(view)
    cloud = _cloud_for(view, robot, wire)
    framing = _framing(scene, 60, 22)
    before = PlotextPainter().draw(scene, 60, 22, framing, look)
    after = CloudLayer().under(before, cloud, look)
    assert _assert_cloud_only_behind(before, after, look) > 50
    # every cell the arm drew is still there
    arm = before.roles != NO_ROLE
    assert np.array_equal(after.roles[arm], before.roles[arm])


@pytest.mark.parametrize("look", LOOKS, ids=["colour", "mono", "ascii"])
def test_the_braille_renderer_gets_the_cloud_too(look):
    robot, wire, scene = _scene(FRONT)
    cloud = _cloud_for(FRONT, robot, wire)
    framing = _framing(scene, 40, 16)
    before = bare_picture(scene, 40, 16, framing, look)
    assert _assert_cloud_only_behind(before, CloudLayer().under(before, cloud, look), look) > 20


def test_the_cells_are_made_once_while_the_arm_moves():
    robot, wire, scene = _scene(FRONT)
    cloud = _cloud_for(FRONT, robot, wire)
    painter, layer = PlotextPainter(), CloudLayer()
    framing = _framing(scene, 60, 22)
    for q in ((0, 0, 0, 0, 0, 0), (10, -20, 30, 0, 15, 0), (45, 10, -30, 5, 5, 5)):
        _, _, moved = _scene(FRONT, robot, q)
        layer.under(painter.draw(moved, 60, 22, framing, Look()), cloud, Look())
    assert layer.builds == 1
    zoomed = Framing(framing.centre, framing.per_dot / 2)
    layer.under(painter.draw(scene, 60, 22, zoomed, Look()), cloud, Look())
    assert layer.builds == 2  # new limits: the cells are made again
    assert layer.under(painter.draw(scene, 60, 22, zoomed, Look()), None, Look()).lines == (
        painter.draw(scene, 60, 22, zoomed, Look()).lines
    )


def _sgr(style, system: str) -> str:
    console = Console(color_system=system, force_terminal=True, width=10)
    return console._render_buffer([Segment("⢕", style)])


@pytest.mark.parametrize(
    ("system", "code"),
    [("truecolor", "38;2;68;68;68"), ("256", "38;5;238"), ("standard", "90")],
)
def test_the_cloud_is_a_dim_grey_in_every_colour_depth(system, code):
    styles = dict(zip(CELL_ROLES, role_styles(system), strict=True))
    cloud = styles["cloud"]
    colour = cloud.color.get_truecolor()
    assert colour.red == colour.green == colour.blue and colour.red < 100  # a dark grey
    assert code in _sgr(cloud, system)
    if system == "standard":  # the floor's grey: dim tells them apart
        assert cloud.dim and _sgr(cloud, system).startswith("\x1b[2;90m")
    ansi = dict(zip(CELL_ROLES, role_styles(system, ansi_theme=True), strict=True))["cloud"]
    assert ansi.color.name == "bright_black" and ansi.dim


def test_without_colour_the_cloud_is_dim_and_colourless():
    styles = dict(zip(CELL_ROLES, role_styles(None, mono=True), strict=True))
    assert styles["cloud"].dim and styles["cloud"].color is None


# -- the views panel (widgets) -----------------------------------------------------


def _shown(app) -> list[ArmView]:
    return [v for v in app.screen.query(ArmView) if v.display and v.size.area]


async def test_set_cloud_draws_behind_the_arm_in_every_view_and_none_restores_it(control_app):
    app = control_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        legend = panel.query_one(".legend")
        before = {v.view.key: v.picture for v in _shown(app)}
        screen_before = app.export_screenshot()
        legend_before = legend.render().plain
        assert "workspace" not in legend_before
        panel.set_cloud(sample_positions(app.screen.robot))
        await pilot.pause()
        assert panel.cloud is not None and "workspace" in legend.render().plain
        assert len(legend.render().plain) <= legend.size.width
        for view in _shown(app):
            assert _assert_cloud_only_behind(before[view.view.key], view.picture, Look()) > 20
        builds = {v.view.key: v._cloud_layer.builds for v in _shown(app)}
        # the arm moves: the cloud's cells are laid again, not made again
        await press(pilot, "right", "right", "left", "left")
        await pilot.pause()
        assert {v.view.key: v._cloud_layer.builds for v in _shown(app)} == builds
        for view in _shown(app):
            assert _assert_cloud_only_behind(before[view.view.key], view.picture, Look()) > 20
        # orbiting turns the 3-D view's cloud (made again there only)
        await press(pilot, "a")
        await pilot.pause()
        after_orbit = {v.view.key: v._cloud_layer.builds for v in _shown(app)}
        assert after_orbit == {**builds, "iso": builds["iso"] + 1}
        await press(pilot, "d")
        await pilot.pause()
        panel.set_cloud(None)
        await pilot.pause()
        assert panel.cloud is None and legend.render().plain == legend_before
        for view in _shown(app):
            assert view.picture.lines == before[view.view.key].lines
            assert np.array_equal(view.picture.roles, before[view.view.key].roles)
        assert app.export_screenshot() == screen_before


async def test_the_cloud_in_ascii_mode_is_dots(control_app):
    app = control_app(ascii=True)
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        panel.set_cloud(sample_positions(app.screen.robot, 5000))
        await pilot.pause()
        for view in _shown(app):
            picture = view.picture
            assert picture.text().isascii()
            cells = [
                line[x]
                for y, line in enumerate(picture.lines)
                for x in np.flatnonzero(picture.roles[y] == CLOUD)
            ]
            assert cells and set(cells) == {ASCII_MARK}
        assert ". workspace" in panel.query_one(".legend").render().plain


async def test_the_cloud_without_colour_is_a_dim_dot_pattern(monkeypatch, control_app):
    monkeypatch.setenv("NO_COLOR", "1")
    app = control_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        panel.set_cloud(sample_positions(app.screen.robot, 5000))
        await pilot.pause()
        front = app.screen.query_one("#view-front", ArmView)
        picture = front.picture
        y, x = np.argwhere(picture.roles == CLOUD)[0]
        assert picture.lines[y][x] == MONO_MARK
        style = front._styles[CLOUD]
        assert style == front._base_style + Style(dim=True)  # no colour of its own
        assert f"{MONO_MARK} workspace" in panel.query_one(".legend").render().plain


async def test_a_cloud_set_before_the_arm_is_shown_and_empty_clouds_are_harmless(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        panel.set_cloud(np.empty((0, 3)))
        await pilot.pause()
        panel.set_cloud(np.array([[np.nan, 0.0, 0.0], [0.0, 0.0, 0.0]]))
        await pilot.pause()
        (view,) = _shown(app)
        assert view.picture is not None
        panel.set_cloud(None)
        panel.set_cloud(None)  # twice: nothing to do
        await pilot.pause()
        assert panel.cloud is None


def test_without_colour_a_filled_region_is_its_edge_and_a_chessboard_inside():
    block = np.ones((6, 8), dtype=bool)
    marked = sparse_cells(block)
    edge = np.ones_like(block)
    edge[1:-1, 1:-1] = False
    assert marked[edge].all()  # the outline, whole
    inside = marked[1:-1, 1:-1]
    assert inside.sum() == inside.size // 2  # every other cell inside
    assert not sparse_cells(np.zeros((3, 3), dtype=bool)).any()


def test_a_tool_far_off_the_picture_never_reaches_plotext_in_ascii():
    # found by tests/scene/test_render.py's hypothesis search: plotext turned a
    # finite tool at 8e302 into inf and failed; a tool off the picture is skipped
    xs, ys = (0.0, 0.0), (8.149542211375831e302, 0.0)
    scene = ViewScene(
        FRONT,
        (Polyline(xs, ys, "link"), Polyline(ys, xs, "x")),
        (xs[0], ys[0]),
        (-1000.0, 1000.0, -500.0, 1200.0),
        "mm",
    )
    framing = _framing(scene, 50, 18)
    picture = PlotextPainter().draw(
        scene, 50, 18, Framing(framing.centre, framing.per_dot * 4), Look(ascii=True)
    )
    assert len(picture.lines) == 18 and "@" not in picture.text()

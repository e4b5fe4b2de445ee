"""The arm is the first thing you see (issue 27): the views open fitted to
the arm (and to the program's path while one is drawn), ``0`` goes back to
the work area and ``F`` toggles; z = 0 is on the floor's row at 80x24."""

from __future__ import annotations

import numpy as np
import pytest
from pilot_helpers import press, started

from dhsim_tui.render.picture import NO_ROLE, ROLE_INDEX
from dhsim_tui.scene import build_wireframe
from dhsim_tui.tui.widgets.arm_view import ArmView
from dhsim_tui.tui.widgets.views_panel import ViewsPanel


def shown(app) -> list[ArmView]:
    return [v for v in app.screen.query(ArmView) if v.display and v.size.area]


def link_share(view: ArmView) -> float:
    """The share of the canvas's rows or columns (the larger) the links span."""
    left, top, cols, rows = view.picture.canvas
    links = view.picture.roles[top : top + rows, left : left + cols] == ROLE_INDEX["link"]
    used_rows, used_cols = np.flatnonzero(links.any(axis=1)), np.flatnonzero(links.any(axis=0))
    if not used_rows.size:
        return 0.0
    return max((used_rows[-1] - used_rows[0] + 1) / rows, (used_cols[-1] - used_cols[0] + 1) / cols)


@pytest.mark.parametrize("size", [(80, 24), (120, 36)])
@pytest.mark.parametrize("name", ["puma560", "irb140", "scara_pedestal", "gantry"])
async def test_the_views_open_fitted_to_the_arm_without_a_key(name, size, control_app):
    """Before any key, every view on screen shows the arm large: its links
    span about half the picture one way or more (the work area left a Puma's
    links a quarter of the front view at 80x24)."""
    app = control_app(name)
    async with app.run_test(size=size) as pilot:
        await started(pilot)
        views = shown(app)
        assert len(views) == (1 if size == (80, 24) else 4)
        assert app.screen.query_one(ViewsPanel).fit
        for view in views:
            assert (view.picture.roles == ROLE_INDEX["tool"]).any(), view.view.key
            ax0, ax1, ay0, ay1 = view.scene.arm_bounds
            bx0, bx1, by0, by1 = view.scene.bounds
            if max(ax1 - ax0, ay1 - ay0) < 0.05 * max(bx1 - bx0, by1 - by0):
                continue  # the arm seen end-on (a point): F's smallest picture
            if not view.view.is_3d:  # the 3-D view keeps its floor in sight too
                assert link_share(view) >= 0.45, (view.view.key, view.picture.lines)
            assert "fit (F)" in str(view.border_subtitle)


async def test_0_shows_the_work_area_and_f_toggles_back_and_forth(control_app):
    app = control_app("puma560")
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        front = app.screen.query_one("#view-front", ArmView)
        fitted = front.picture.xlim
        fitted_share = link_share(front)
        await press(pilot, "0")
        await pilot.pause()
        assert not panel.fit and "fit" not in str(front.border_subtitle)
        whole = front.picture.xlim
        assert whole[1] - whole[0] > 2 * (fitted[1] - fitted[0])  # the whole work area
        area = front.scene.bounds
        assert whole[0] <= area[0] and whole[1] >= area[1]
        assert link_share(front) < fitted_share
        await press(pilot, "F")
        await pilot.pause()
        assert panel.fit and front.picture.xlim == pytest.approx(fitted)
        await press(pilot, "F")
        await pilot.pause()
        assert not panel.fit and front.picture.xlim == pytest.approx(whole)


async def test_the_views_fit_the_programs_path_while_it_is_drawn(control_app):
    """A path drawn (the trail the control screen hands the views) well away
    from the arm is in every fitted view; when it goes, the views fit the
    arm alone again."""
    app = control_app("puma560")
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        robot = app.screen.robot
        frames = robot.kinematics.frames(robot.home)
        arm_only = {v.view.key: v.picture.xlim for v in panel.views}
        far = np.array([[-700.0, -600.0, -300.0], [-650.0, 500.0, 600.0], [-600.0, 600.0, 650.0]])
        panel.show(build_wireframe(robot, frames, far))
        await pilot.pause()
        for view in panel.views[:3]:
            (x0, x1), (y0, y1) = view.picture.xlim, view.picture.ylim
            bx0, bx1, by0, by1 = view.scene.path_bounds
            assert x0 <= bx0 and bx1 <= x1 and y0 <= by0 and by1 <= y1, view.view.key
            left, top, cols, rows = view.picture.canvas
            canvas = view.picture.roles[top : top + rows, left : left + cols]
            assert (canvas == ROLE_INDEX["trail"]).any() and (canvas == ROLE_INDEX["link"]).any()
        panel.show(build_wireframe(robot, frames))
        await pilot.pause()
        for view in panel.views[:3]:
            assert view.picture.xlim == pytest.approx(arm_only[view.view.key]), view.view.key


@pytest.mark.parametrize("name", ["irb140", "ur5"])
async def test_z_0_is_on_the_floors_row_at_80x24(name, control_app):
    """The "0" of the front view's z axis is on the row the floor is drawn
    in, as the app opens (it was a row above it)."""
    app = control_app(name)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        for key in ("", "0"):  # fitted, then the work area
            if key:
                await press(pilot, key)
                await pilot.pause()
            front = app.screen.query_one("#view-front", ArmView)
            picture = front.picture
            left, _, _, rows = picture.canvas
            zero = [y for y in range(rows) if picture.lines[y][: left - 1].strip() == "0"]
            floor_roles = [ROLE_INDEX["floor"], ROLE_INDEX["floor_hit"]]
            floor = np.flatnonzero(np.isin(picture.roles[:rows, left:], floor_roles).any(axis=1))
            assert zero == floor.tolist(), picture.lines
            assert (picture.roles[:rows, left:] != NO_ROLE).any()

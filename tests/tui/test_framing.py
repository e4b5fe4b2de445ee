"""Framing that uses the space (issue 16): the 3-D view filled, F fitting
every view to the arm and holding while it moves, and a side panel with no
block of empty rows on a big terminal."""

from __future__ import annotations

import numpy as np
import pytest
from pilot_helpers import press, started

from dhsim_tui.core import bundled_names, load_robot
from dhsim_tui.render.picture import NO_ROLE, ROLE_INDEX
from dhsim_tui.scene import build_wireframe, project
from dhsim_tui.scene.figure import least_size
from dhsim_tui.scene.framing import fitted
from dhsim_tui.scene.oblique import Orbit, project_oblique
from dhsim_tui.scene.projection import VIEWS, limits_at
from dhsim_tui.scene.raster import rasterize
from dhsim_tui.tui.widgets.arm_view import ArmView
from dhsim_tui.tui.widgets.views_panel import ViewsPanel


def spans(picture, role: int | None = None) -> tuple[float, float, int, int]:
    """The share of the canvas's rows and columns drawn (by ``role``, or by
    anything), and the first and last drawn row."""
    left, top, cols, rows = picture.canvas
    roles = picture.roles[top : top + rows, left : left + cols]
    drawn = roles != NO_ROLE if role is None else roles == role
    used_rows = np.flatnonzero(drawn.any(axis=1))
    used_cols = np.flatnonzero(drawn.any(axis=0))
    if not used_rows.size:
        return 0.0, 0.0, -1, -1
    return (
        (used_rows[-1] - used_rows[0] + 1) / rows,
        (used_cols[-1] - used_cols[0] + 1) / cols,
        int(used_rows[0]),
        int(used_rows[-1]),
    )


# -- the 3-D view ---------------------------------------------------------------------


async def test_maximised_the_3d_view_is_filled_with_no_empty_band(control_app):
    """At 120x36, home: the drawing spans 80% of the height or width, from
    near the top to near the bottom (it used 16 of 32 rows, the top 14 empty)."""
    app = control_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await press(pilot, "4", "z")
        await pilot.pause()
        iso = app.screen.query_one("#view-iso", ArmView)
        tall, wide, first, last = spans(iso.picture)
        assert max(tall, wide) >= 0.8
        rows = iso.picture.canvas[3]
        assert first <= 0.1 * rows and last >= 0.9 * rows - 1


async def test_turning_the_3d_view_holds_its_framing_while_the_arm_stays_in_it(control_app):
    """Over the work area (fitted, it is fitted afresh as it turns)."""
    app = control_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await press(pilot, "0", "4", "z")
        await pilot.pause()
        iso = app.screen.query_one("#view-iso", ArmView)
        panel = app.screen.query_one(ViewsPanel)
        for _ in range(24):  # a whole turn
            before = iso._framing
            await press(pilot, "d")
            await pilot.pause()
            after = iso._framing
            if after != before:  # reframed: only because the arm left the picture
                (x0, x1), (y0, y1) = limits_at(
                    before.centre, before.per_dot, *panel._canvas(VIEWS[3])
                )
                bx0, bx1, by0, by1 = iso.scene.fit_bounds
                assert bx0 < x0 or bx1 > x1 or by0 < y0 or by1 > y1
        assert (iso.picture.roles == ROLE_INDEX["tool"]).any()  # the tool still shows


# -- F ---------------------------------------------------------------------------------


@pytest.mark.parametrize("name", bundled_names())
def test_f_fits_the_links_to_at_least_60_percent_of_every_view(name, rng):
    robot, _ = load_robot(name)
    for q in (robot.home, rng.uniform(robot.lower, robot.upper)):
        wire = build_wireframe(robot, robot.kinematics.frames(q))
        for view, (cols, rows) in zip(VIEWS, [(29, 13), (29, 13), (29, 13), (36, 15)], strict=True):
            scene = project_oblique(wire, Orbit()) if view.is_3d else project(wire, view)
            extent = np.ptp(np.asarray([scene.lines[-1].xs, scene.lines[-1].ys]), axis=1)
            if extent.max() < least_size(wire):
                continue  # the arm seen end-on (a point) gets F's smallest picture
            framing = fitted(scene, cols, rows, least_size(wire))
            raster = rasterize(
                scene, cols, rows, limits_at(framing.centre, framing.per_dot, cols, rows)
            )
            link = raster.palette.index("link")
            drawn = raster.colours == link
            used_rows = np.flatnonzero(drawn.any(axis=1))
            used_cols = np.flatnonzero(drawn.any(axis=0))
            tall = (used_rows[-1] - used_rows[0] + 1) / rows
            wide = (used_cols[-1] - used_cols[0] + 1) / cols
            assert max(tall, wide) >= 0.6, (name, view.key, tall, wide)


async def test_f_fits_holds_while_jogging_and_refits_when_the_arm_leaves(control_app):
    app = control_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        front = app.screen.query_one("#view-front", ArmView)
        fit = front._framing  # the views open fitted (issue 27)
        await press(pilot, "F")  # F: the work area
        await pilot.pause()
        whole = front._framing
        await press(pilot, "F")  # F again: fitted
        await pilot.pause()
        assert front._framing == fit
        assert fit.per_dot < whole.per_dot / 2  # much closer
        assert "fit (F)" in str(front.border_subtitle)
        tall, wide, _, _ = spans(front.picture, ROLE_INDEX["link"])
        assert max(tall, wide) >= 0.6
        await press(pilot, "down", "down", "right")  # Th3 one degree: the arm stays in
        await pilot.pause()
        assert front._framing == fit
        await press(
            pilot, "up", "right_square_bracket", "right_square_bracket", "right_square_bracket"
        )
        await press(pilot, *["right"] * 4)  # Th2 by 180 degrees: out of the picture
        await pilot.pause()
        assert front._framing != fit
        # and the arm is whole in the new framing
        assert (front.picture.roles == ROLE_INDEX["tool"]).any()
        await press(pilot, "F")  # F again: the work area
        await pilot.pause()
        assert front._framing == whole
        await press(pilot, "F", "0")  # or 0
        await pilot.pause()
        assert front._framing == whole and not app.screen.query_one(ViewsPanel).fit


# -- a big terminal --------------------------------------------------------------------------


@pytest.mark.parametrize("size", [(160, 48), (200, 60)])
async def test_a_big_terminal_shows_every_read_out_and_no_block_of_empty_rows(size, control_app):
    app = control_app()
    async with app.run_test(size=size) as pilot:
        await started(pilot)
        side = app.screen.query_one("#side-panel")
        pose = str(app.screen.query_one("#pose").render())
        for word in ("X", "O", "roll", "pitch", "yaw", "rotation"):
            assert word in pose
        keys = app.screen.query_one("#keys")
        hints = str(keys.render()).split("\n")
        # the side panel's rows: the panels stacked from the top, the keys under
        # them, at most a few rows to spare at the bottom
        spare = side.region.bottom - (keys.region.y + len(hints))
        assert spare <= 8, spare
        if size == (200, 60):
            assert len(hints) > 20  # one key a line: they fit
        # the views take the rest of the width
        views = app.screen.query_one(ViewsPanel)
        assert views.region.width == size[0] - side.region.width

"""Cartesian jogging in the WORLD or the TOOL frame (f): the core's moves, the
screen's key, the panel's title and rows, and the palette's command."""

from __future__ import annotations

import numpy as np
import pytest
from pilot_helpers import press, settled, until

from dhsim_tui.core import load_robot
from dhsim_tui.core.analysis.workspace import reach
from dhsim_tui.core.ik.numerical import rotation_error
from dhsim_tui.core.model.editing import set_pose
from dhsim_tui.core.model.orientation import rotx, roty, rotz
from dhsim_tui.core.motion.jog import TOOL, WORLD, move_pose, row_name
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.palette import commands_for
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel, cartesian_text

GOOD = (-20.0, 50.0, -170.0, 10.0, 40.0, 0.0)  # a Puma pose with room to move


def puma_app(ascii: bool = False) -> DhsimApp:
    robot, path = load_robot("puma560")
    return DhsimApp(set_pose(robot, "start", GOOD), path, animate=False, ascii=ascii)


async def go_start(pilot) -> ControlScreen:
    await press(pilot, *["p"] * len(pilot.app.robot.pose_names))  # 'start' is the last
    await pilot.pause()
    screen = pilot.app.screen
    assert isinstance(screen, ControlScreen) and screen.q == GOOD
    return screen


def tool_pose(app: DhsimApp) -> np.ndarray:
    return app.robot.kinematics.pose(app.screen.q)


# -- the core ------------------------------------------------------------------------
def _a_pose() -> np.ndarray:
    robot, _ = load_robot("puma560")
    return robot.kinematics.pose(GOOD)


@pytest.mark.parametrize("row", [0, 1, 2])
def test_tool_frame_moves_along_the_tools_own_axes(row):
    pose = _a_pose()
    moved = move_pose(pose, row, 7.5, TOOL)
    assert np.allclose(moved[:3, 3] - pose[:3, 3], 7.5 * pose[:3, row], atol=1e-12)
    assert np.array_equal(moved[:3, :3], pose[:3, :3])
    assert not np.array_equal(pose[:3, row], np.eye(3)[row])  # the test means something


@pytest.mark.parametrize("row", [0, 1, 2])
def test_world_frame_moves_along_the_worlds_axes(row):
    pose = _a_pose()
    moved = move_pose(pose, row, -3.0, WORLD)
    assert np.allclose(moved[:3, 3] - pose[:3, 3], -3.0 * np.eye(3)[row], atol=1e-12)
    assert np.array_equal(moved[:3, :3], pose[:3, :3])


@pytest.mark.parametrize("row", [3, 4, 5])
def test_turns_are_about_the_tool_or_the_world_axes_through_the_tool_point(row):
    pose = _a_pose()
    turn = (rotx, roty, rotz)[row - 3](12.0)
    tool = move_pose(pose, row, 12.0, TOOL)
    world = move_pose(pose, row, 12.0, WORLD)
    assert np.allclose(tool[:3, :3], pose[:3, :3] @ turn)
    assert np.allclose(world[:3, :3], turn @ pose[:3, :3])
    assert np.array_equal(tool[:3, 3], pose[:3, 3])  # the tool point stays
    assert np.array_equal(world[:3, 3], pose[:3, 3])
    assert np.array_equal(pose, _a_pose())  # a copy: the pose given is left alone


def test_an_unknown_frame_is_refused():
    with pytest.raises(ValueError, match="frame"):
        move_pose(np.eye(4), 0, 1.0, "user")


def test_rows_are_named_by_frame():
    assert [row_name(r) for r in range(6)] == ["X", "Y", "Z", "Rx", "Ry", "Rz"]
    assert [row_name(r, TOOL) for r in (0, 2, 5)] == ["x", "z", "Rz"]


# -- the panel -----------------------------------------------------------------------
def test_the_panel_text_names_the_frame_and_shows_the_tool_axes_in_ascii():
    axes = [(0.0, 0.0, -1.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)]
    text = cartesian_text((1, 2, 3), (0, 90, 0), 2, "mm", True, TOOL, axes).plain
    assert text.isascii()
    lines = text.splitlines()
    assert lines[2] == "> z  tool z = ( 1.00, 0.00, 0.00)"  # the approach, in the world
    assert "Rx tool x" in lines[3] and "deg" in lines[3]
    world = cartesian_text((1, 2, 3), (0, 90, 0), 0, "mm", False, WORLD, axes).plain
    assert "world X" in world.splitlines()[3] and "°" in world
    assert world.splitlines()[0].startswith("▶ X  world") and "1.00 mm" in world


# -- the screen ----------------------------------------------------------------------
async def test_a_step_along_tool_z_moves_the_tool_along_its_approach_vector():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        before = tool_pose(app)
        await press(pilot, "c", "f", "down", "down", "right_square_bracket")  # tool z, 10 mm
        await pilot.pause()
        assert (
            screen.query_one(CartesianPanel).frame == TOOL
            and screen.query_one(CartesianPanel).row == 2
        )
        await press(pilot, "right")
        await pilot.pause()
        after = tool_pose(app)
        step = after[:3, 3] - before[:3, 3]
        assert np.linalg.norm(step) == pytest.approx(10.0, abs=1e-6 * reach(app.robot))
        assert np.allclose(step, 10.0 * before[:3, 2], atol=1e-6 * reach(app.robot))
        assert np.linalg.norm(rotation_error(before[:3, :3], after[:3, :3])) < 1e-6
        await press(pilot, "left", "left")  # and back the other way, 10 mm past the start
        await pilot.pause()
        back = tool_pose(app)[:3, 3] - before[:3, 3]
        assert np.allclose(back, -10.0 * before[:3, 2], atol=1e-6 * reach(app.robot))


async def test_a_world_turn_keeps_the_tool_point_and_turns_about_world_z():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        before = tool_pose(app)
        await press(pilot, "c", *["down"] * 5, "right_square_bracket", "right")  # Rz 5 deg
        await pilot.pause()
        assert screen.query_one(CartesianPanel).frame == WORLD
        after = tool_pose(app)
        assert np.allclose(after[:3, 3], before[:3, 3], atol=1e-6 * reach(app.robot))
        expected = rotz(5.0) @ before[:3, :3]
        assert np.linalg.norm(rotation_error(expected, after[:3, :3])) < 1e-6


async def test_f_says_the_frame_in_the_panel_footer_and_status_and_only_in_cartesian():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await press(pilot, "f")  # joint mode: f does nothing
        await pilot.pause()
        panel = app.screen.query_one(CartesianPanel)
        assert panel.frame == WORLD and "f" not in app.screen.active_bindings
        await press(pilot, "c")
        await pilot.pause()
        assert "WORLD" in str(panel.border_title)
        assert panel.check_action("frame", ("tool",)) and not panel.check_action(
            "frame", ("world",)
        )
        assert app.screen.active_bindings["f"][1].id == "cartesian.tool_frame"
        await press(pilot, "f")
        await pilot.pause()
        assert panel.frame == TOOL and "TOOL" in str(panel.border_title)
        assert "TOOL frame" in str(app.screen.query_one("#status").render())
        rows = str(panel.render()).splitlines()
        assert rows[0].startswith("▶ x  tool x = (")
        assert panel.check_action("frame", ("world",))
        await press(pilot, "f")
        await pilot.pause()
        assert screen.query_one(CartesianPanel).frame == WORLD and "WORLD" in str(
            panel.border_title
        )


async def test_the_frame_shows_in_ascii_mode_too():
    app = puma_app(ascii=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await go_start(pilot)
        await press(pilot, "c", "f")
        await pilot.pause()
        panel = app.screen.query_one(CartesianPanel)
        assert "TOOL frame" in str(panel.border_title)
        text = str(panel.render())
        assert text.isascii() and text.startswith("> x  tool x")


async def test_the_palette_switches_the_frame_and_cartesian_mode_on():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        command = next(c for c in commands_for(app, screen) if c.title == "Jog in the tool frame")
        command.run()
        await until(pilot, lambda: screen.cartesian, "Cartesian mode")
        assert screen.cartesian and screen.query_one(CartesianPanel).frame == TOOL
        titles = [c.title for c in commands_for(app, screen)]
        assert "Jog in the world frame" in titles and "Jog in the tool frame" not in titles


async def test_typing_a_tool_z_distance_moves_that_far_along_the_approach():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await go_start(pilot)
        before = tool_pose(app)
        await press(pilot, "c", "f", "down", "down", "enter", "ctrl+u", *"-25", "enter")
        await until(pilot, lambda: app.screen.q != GOOD, "the typed move")
        after = tool_pose(app)
        assert np.allclose(
            after[:3, 3] - before[:3, 3], -25.0 * before[:3, 2], atol=1e-6 * reach(app.robot)
        )


async def test_the_frame_and_a_branch_read_without_colour(monkeypatch):
    monkeypatch.setenv("NO_COLOR", "1")
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await press(pilot, "c", "f", "b")
        await until(
            pilot, lambda: not screen.finding_branches and screen.q != GOOD, "the next branch"
        )
        await until(pilot, lambda: settled(app), "the next branch drawn")
        panel = app.screen.query_one(CartesianPanel)
        assert "TOOL frame" in str(panel.border_title)
        assert "branch 2/" in str(app.screen.query_one("#status").render())

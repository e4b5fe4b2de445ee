"""Cartesian jogging, the singularity and floor read-outs, saved poses and smooth
motion on the control screen, driven with Pilot."""

from __future__ import annotations

import numpy as np
import pytest
from pilot_helpers import frames_pass, press, until

from dhsim_tui.core import Joint, Robot, load, load_robot, save
from dhsim_tui.core.ik.numerical import rotation_error
from dhsim_tui.render.picture import ROLE_INDEX
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel
from dhsim_tui.tui.widgets.pose_panel import PosePanel
from tui.conftest import control

GOOD = (-20.0, 50.0, -170.0, 10.0, 40.0, 0.0)  # a Puma pose with room to move


async def go_start(pilot):
    """p cycles the Puma's poses; 'start' is the last one."""
    names = pilot.app.robot.pose_names
    await press(pilot, *["p"] * len(names))
    assert control(pilot.app).q == pilot.app.robot.pose("start")


async def test_c_switches_to_cartesian_and_back(control_app):
    app = control_app(q=GOOD)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "c")
        assert control(app).cartesian and app.screen.has_class("-cartesian")
        assert app.screen.query_one("#cartesian").display
        await press(pilot, "c")
        assert not control(app).cartesian


async def test_stepping_x_slides_the_tool_100mm_with_fixed_orientation(control_app):
    app = control_app(q=GOOD)
    async with app.run_test(size=(80, 24)) as pilot:
        await go_start(pilot)
        start = app.robot.kinematics.pose(control(app).q)
        await press(pilot, "c", "right_square_bracket")  # 10 mm steps
        for _ in range(10):
            await press(pilot, "right")
        q = control(app).q
        now = app.robot.kinematics.pose(q)
        assert np.allclose(now[:3, 3] - start[:3, 3], (100, 0, 0), atol=1e-3)
        assert np.linalg.norm(rotation_error(start[:3, :3], now[:3, :3])) < 1e-6
        assert q != app.robot.pose("start")  # the joints followed
        shown = str(app.screen.query_one("#cartesian").render())
        assert f"{now[0, 3]:.2f}" in shown


async def test_rows_select_and_rotations_turn_about_the_tool(control_app):
    app = control_app(q=GOOD)
    async with app.run_test(size=(80, 24)) as pilot:
        await go_start(pilot)
        start = app.robot.kinematics.pose(control(app).q)
        await press(pilot, "c", "f", "down", "down", "down", "down", "down")  # tool Rz
        assert control(app).query_one(CartesianPanel).row == 5
        await press(pilot, "right_square_bracket", "right")  # ladder 0.1, 1, 5: 5 deg
        now = app.robot.kinematics.pose(control(app).q)
        assert np.allclose(now[:3, 3], start[:3, 3], atol=1e-3)  # turned in place
        turn = start[:3, :3].T @ now[:3, :3]  # in the tool's own frame
        assert np.isclose(np.degrees(np.arctan2(turn[1, 0], turn[0, 0])), 5.0, atol=1e-4)


async def test_enter_sets_an_exact_cartesian_target(control_app):
    app = control_app(q=GOOD)
    async with app.run_test(size=(80, 24)) as pilot:
        await go_start(pilot)
        z = app.robot.kinematics.position(control(app).q)[2]
        await press(pilot, "c", "down", "down", "enter", "ctrl+u", *f"{z - 50:.3f}", "enter")
        assert app.robot.kinematics.position(control(app).q)[2] == pytest.approx(z - 50, abs=1e-3)


async def test_unreachable_step_moves_nothing_and_says_why(status, control_app):
    app = control_app(q=GOOD)
    async with app.run_test(size=(80, 24)) as pilot:
        await go_start(pilot)
        q = control(app).q
        await press(pilot, "c", "enter", "ctrl+u", *"5000", "enter")
        assert control(app).q == q
        assert "X:" in status(app) and ("reach" in status(app) or "limit" in status(app))


async def test_manipulability_warns_near_the_wrist_singularity(control_app):
    app = control_app(q=(0.0, 45.0, -135.0, 0.0, 0.5, 0.0))
    async with app.run_test(size=(80, 24)) as pilot:
        await go_start(pilot)
        text = str(app.screen.query_one(PosePanel).render())
        assert "μ" in text and "singular" in text
        await press(pilot, "down", "down", "down", "down")
        for _ in range(3):
            await press(pilot, "right_square_bracket")
        await press(pilot, "right")  # theta5 0.5 -> 45.5: away from it
        assert "singular" not in str(app.screen.query_one(PosePanel).render())


async def test_frames_below_the_floor_are_flagged():
    probe = Robot(
        "probe", (Joint("prismatic", 0.0, 50.0, 0.0, 0.0, -400.0, 400.0),), base_z="-z", base_x="+x"
    )
    app = DhsimApp(probe, None, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.screen.query_one("#view-front")
        await until(pilot, lambda: view.picture is not None, "the front view drawn")
        assert "below the floor: frame 1" in str(app.screen.query_one(PosePanel).render())
        assert ROLE_INDEX["floor_hit"] in view.picture.roles  # the floor is drawn as hit
        await press(pilot, "enter", "ctrl+u", *"-10", "enter")  # back above the floor
        assert "below the floor" not in str(app.screen.query_one(PosePanel).render())


async def test_save_pose_writes_the_robot_file(tmp_path, status):
    robot, _ = load_robot("puma560")
    file = tmp_path / "puma.toml"
    save(robot, file)
    app = DhsimApp(load(file), file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "right", "P", "ctrl+u", *"mine", "enter")
        assert "pose mine saved in" in status(app)
        await press(pilot, "h")
        await press(pilot, *["p"] * 5)  # the saved pose is last in the cycle
        assert control(app).q == (2.0, 0, 0, 0, 0, 0)
    assert load(file).pose("mine") == (2.0, 0, 0, 0, 0, 0)


async def test_save_pose_on_a_bundled_robot_keeps_it_in_memory(status, control_app):
    app = control_app(q=GOOD)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "P", "ctrl+u", *"here", "enter")
        assert "kept until you quit" in status(app)
        assert app.robot.pose("here") == (1.0, 0, 0, 0, 0, 0)


async def test_home_moves_smoothly_and_arrives(monkeypatch, control_app):
    monkeypatch.setattr("dhsim_tui.core.motion.smooth.DURATION", 2.0)
    passed = []  # where each tick of the move put Th1, however many the machine managed
    tick = ControlScreen._tick

    def recording_tick(self):
        tick(self)
        passed.append(self.q[0])

    monkeypatch.setattr(ControlScreen, "_tick", recording_tick)
    app = control_app(q=GOOD, animate=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right_square_bracket", "right_square_bracket", "right_square_bracket")
        await press(pilot, "right", "right")  # Th1 at 90
        await press(pilot, "h")
        await until(pilot, lambda: not control(app).moving, "the move home to end")
        assert control(app).q == app.robot.home
        assert any(0.0 < th1 < 90.0 for th1 in passed)  # it went there on its way, not at once


async def test_escape_interrupts_a_move_and_m_turns_motion_off(monkeypatch, status, control_app):
    monkeypatch.setattr("dhsim_tui.core.motion.smooth.DURATION", 20.0)  # still moving when stopped
    app = control_app(q=GOOD, animate=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right_square_bracket", "right_square_bracket", "right_square_bracket")
        await press(pilot, "right", "right", "h")
        await until(pilot, lambda: control(app).q[0] < 90.0, "the move home under way")
        await press(pilot, "escape")
        stopped = control(app).q[0]
        assert 0.0 < stopped < 90.0 and not control(app).moving
        assert status(app) == "stopped"
        await frames_pass(pilot, 15)  # as many ticks as the move had in 0.5 s
        assert control(app).q[0] == stopped  # it stays where it was stopped
        await press(pilot, "m", "h")
        assert control(app).q == app.robot.home  # at once


async def test_save_pose_that_cannot_be_written_says_so(tmp_path, monkeypatch, status):
    robot, _ = load_robot("gantry")
    file = tmp_path / "gantry.toml"
    save(robot, file)
    before = file.read_bytes()
    import os

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(os, "replace", refuse)
    app = DhsimApp(load(file), file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "P", "ctrl+u", *"spot", "enter")
        assert status(app).startswith("not saved:")
        assert "(pose spot is kept in memory)" in status(app)
        assert app.robot.pose("spot") == (501.0, 400.0, 300.0)
    assert file.read_bytes() == before

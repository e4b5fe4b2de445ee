"""Programs in the simulator: g shows the program panel, R records the pose
as a step, space plays the program in the views, the path check's problems
are said and n jumps to them (issue 19)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from pilot_helpers import press, started, until

from dhsim_tui.core import load_robot
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.model.text import counted
from dhsim_tui.core.motion.path_check import LIMIT, check_path
from dhsim_tui.core.motion.trajectory import sample
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.widgets.program_panel import ProgramPanel
from dhsim_tui.tui.widgets.views_panel import ViewsPanel

pytestmark = pytest.mark.usefixtures("in_tmp")


async def test_record_two_poses_and_play_them(status):
    robot = replace(load_robot("puma560")[0], programs=())
    app = DhsimApp(robot, animate=False)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        await press(pilot, "R")  # the home pose as step 1
        await press(pilot, "right", "right", "right", "right_square_bracket", "right")
        await pilot.pause()
        moved = screen.q
        assert moved != robot.home
        await press(pilot, "R")
        await pilot.pause()
        program = app.robot.program("program1")
        assert [s.move for s in program.steps] == ["joint", "joint"]
        assert np.allclose(program.steps[1].to, moved)
        assert screen.has_class("-program") and screen.query_one(ProgramPanel).display
        await press(pilot, "g")  # the panel takes the keys
        await pilot.pause()
        assert screen.focused is screen.query_one(ProgramPanel)
        await press(pilot, "up", "l")  # step 1 a linear move
        await pilot.pause()
        assert [s.move for s in app.robot.program("program1").steps] == ["linear", "joint"]
        await press(pilot, "ctrl+z")
        await pilot.pause()
        assert [s.move for s in app.robot.program("program1").steps] == ["joint", "joint"]
        await press(pilot, "space")
        await until(pilot, lambda: screen._programs.playback is not None, "playback")
        assert screen._programs.playback.duration > 0
        await until(pilot, lambda: "played program1" in status(app), "the end of playback")
        assert np.allclose(screen.q, moved, atol=1e-6)  # the last step's pose
        assert "kept until you quit" in status(app) or app.has_unsaved_poses


async def test_a_program_with_a_problem_says_it_and_n_jumps_to_it(monkeypatch, status):
    # the playback's clock stands still: however slow the machine, the
    # program is still playing when space pauses it
    monkeypatch.setattr("dhsim_tui.tui.screens.control_program.monotonic", lambda: 0.0)
    robot = load_robot("puma560")[0]
    to_limit = Program("edge", (Step("joint", (160.0, 0, 0, 0, 0, 0)), Step("wait", seconds=0.2)))
    robot = replace(robot, programs=(to_limit,))
    trajectory = sample(robot, to_limit, 100.0)
    problems = check_path(trajectory)
    assert problems and problems[0].kind == LIMIT  # computed here, independently of the screen
    app = DhsimApp(robot, animate=False)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        await press(pilot, "g", "space")
        await until(pilot, lambda: "playing edge" in status(app), "playback")
        assert counted(len(problems), "problem") in status(app)
        assert screen._programs.playing
        await press(pilot, "space")  # pause
        assert "paused" in status(app) and not screen._programs.playing
        assert abs(screen._programs.playback.duration - trajectory.duration) < 1e-9
        await press(pilot, "n")
        await pilot.pause()
        assert f"at {problems[0].time:.2f} s" in status(app) and "Th1" in status(app)
        assert "!" in str(screen.query_one(ProgramPanel).render())  # the step is marked
        await press(pilot, "full_stop", "full_stop", "full_stop")  # to the end
        await pilot.pause()
        assert np.allclose(screen.q, trajectory.q[-1], atol=1e-6)
        await press(pilot, "comma", "comma", "comma")
        await pilot.pause()
        assert np.allclose(screen.q, trajectory.q[0], atol=1e-6)


async def test_the_tools_path_is_drawn_in_every_view_while_a_program_is_loaded():
    robot = load_robot("puma560")[0]
    demo = robot.program("demo")
    app = DhsimApp(robot, animate=False)
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        views = screen.query_one(ViewsPanel)

        def trails():
            return [
                [line for line in view.scene.lines if line.role == "trail"] for view in views.views
            ]

        assert all(not found for found in trails())
        await press(pilot, "g", "space")
        await until(pilot, lambda: all(trails()), "the path in every view")
        # the front view (x right, z up) shows the sampled tool positions themselves
        trajectory = sample(robot, demo, 100.0, start=robot.home)
        (front,) = trails()[1]
        xs, zs = np.array(front.xs), np.array(front.ys)
        assert np.isclose(xs[-1], trajectory.xyz[-1, 0]) and np.isclose(
            zs[-1], trajectory.xyz[-1, 2]
        )
        assert xs.min() >= trajectory.xyz[:, 0].min() - 1e-9
        assert xs.max() <= trajectory.xyz[:, 0].max() + 1e-9
        assert "path" in str(views.query_one(".legend").render())
        await press(pilot, "space", "ctrl+up")  # pause; a change to the program: the path goes
        await pilot.pause()
        await until(pilot, lambda: not any(trails()), "the path gone")


async def test_play_faster_and_the_plot_at_the_time_played(status):
    robot = load_robot("puma560")[0]
    app = DhsimApp(robot, animate=False)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        await press(pilot, "g", "right_square_bracket", "right_square_bracket")
        assert screen._programs.speed == 4.0 and "×4" in status(app)
        began = screen._programs
        await press(pilot, "space")
        await until(pilot, lambda: began.playback is not None and began.playback.time > 0.5, "play")
        await until(pilot, lambda: "played demo" in status(app), "the end, four times as fast")
        # 7.85 s of program in about 2 s: well under the real-time length
        await press(pilot, "comma")
        await press(pilot, "t")
        await until(pilot, lambda: type(app.screen).__name__ == "ProgramPlot", "the plot")
        text = str(app.screen.query_one("#plot").render())
        assert "joints" in text and "tool speed" in text
        await press(pilot, "escape")
        await until(pilot, lambda: app.screen is screen, "back")


async def test_L_makes_R_record_linear_moves_and_the_title_says_so(status):
    robot = replace(load_robot("puma560")[0], programs=())
    app = DhsimApp(robot, animate=False)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        panel = screen.query_one(ProgramPanel)
        await press(pilot, "R")
        await pilot.pause()
        assert "L: record linear moves" in status(app)
        assert "R joint" in str(panel.border_title)
        await press(pilot, "L")
        await pilot.pause()
        assert "R records linear moves" in status(app)
        assert "R linear" in str(panel.border_title)
        await press(pilot, "right", "right", "R")  # the jogging keys still jog
        await pilot.pause()
        steps = app.robot.program("program1").steps
        assert [s.move for s in steps] == ["joint", "linear"]
        assert np.allclose(steps[1].to, screen.q)
        await press(pilot, "L", "left", "R")
        await pilot.pause()
        assert [s.move for s in app.robot.program("program1").steps] == ["joint", "linear", "joint"]
        assert "recorded step 3 of 3 in program1: a joint move" in status(app)
        # I in the panel: after the selected step, and said so: step 1 selected,
        # the new one is step 2 (R appends, above)
        await press(pilot, "g", "up", "up", "L", "I")
        await pilot.pause()
        steps = app.robot.program("program1").steps
        assert [s.move for s in steps] == ["joint", "linear", "linear", "joint"]
        assert "recorded step 2 of 4 in program1: a linear move" in status(app)
        assert screen.query_one(ProgramPanel).selected == 1

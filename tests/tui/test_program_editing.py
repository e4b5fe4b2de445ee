"""Programs made in the simulator (issue 27 §2): R appends, I inserts after
the selected step, D adds a wait, S sets a speed, enter edits a target
(joint values, or a linear move's tool pose), r renames, N starts a new
program, o shows the next; every change undone by ctrl+z. Long programs
scroll with the selection, and at 80×24 the XYZ/OAT read-out stays."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from pilot_helpers import press, started, until

from dhsim_tui.core import load_robot
from dhsim_tui.core.model.kinematics import read_out
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.widgets.pose_panel import PosePanel
from dhsim_tui.tui.widgets.program_panel import ProgramPanel

pytestmark = pytest.mark.usefixtures("in_tmp")

QN = (0.0, 45.0, -180.0, 0.0, 45.0, 0.0)
UP = (0.0, 45.0, -135.0, 0.0, 45.0, 0.0)


def steps(app, name: str = "p") -> tuple[Step, ...]:
    return app.robot.program(name).steps


def app_with(*programs: Program) -> DhsimApp:
    robot = replace(load_robot("puma560")[0], programs=programs)
    return DhsimApp(robot, animate=False)


async def type_in(pilot, text: str) -> None:
    """Type ``text`` into the dialog that is up (its text selected: replaced), then enter."""
    await until(pilot, lambda: pilot.app.screen.query("Input"), "a dialog")
    await press(
        pilot,
        "ctrl+u",
        *[{" ": "space", ",": "comma", ".": "full_stop", "-": "minus"}.get(c, c) for c in text],
        "enter",
    )


async def test_R_appends_and_I_inserts_after_the_selected_step(status):
    app = app_with(Program("p", (Step("joint", QN), Step("joint", UP), Step("wait", seconds=1.0))))
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        await press(pilot, "g")  # step 1 selected
        assert screen.query_one(ProgramPanel).selected == 0
        await press(pilot, "R")
        assert len(steps(app)) == 4 and steps(app)[3].move == "joint"
        assert "recorded step 4 of 4" in status(app)
        assert screen.query_one(ProgramPanel).selected == 3  # the new step
        await press(pilot, "up", "up", "up", "I")  # after step 1
        assert len(steps(app)) == 5 and steps(app)[1].to == tuple(round(v, 6) for v in screen.q)
        assert "recorded step 2 of 5" in status(app)
        await press(pilot, "ctrl+z", "ctrl+z")
        assert len(steps(app)) == 3


async def test_D_adds_a_wait_and_S_sets_a_speed_both_undone(status):
    app = app_with(Program("p", (Step("joint", QN), Step("linear", UP))))
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        await press(pilot, "g", "up", "up", "D")
        await type_in(pilot, "2.5")
        assert [s.move for s in steps(app)] == ["joint", "wait", "linear"]
        assert steps(app)[1].seconds == 2.5 and "step 2: wait 2.5 s" in status(app)
        await press(pilot, "down", "S")  # the linear move's speed, in mm/s
        await type_in(pilot, "120")
        assert steps(app)[2].speed == 120.0
        await press(pilot, "up", "up", "S")  # a joint move: percent, at most 100
        await type_in(pilot, "150")
        assert "out of range" in str(app.screen.query_one("#error").render())
        await type_in(pilot, "40")
        assert steps(app)[0].speed == 40.0
        await press(pilot, "S")
        await type_in(pilot, "")  # empty: the default
        assert steps(app)[0].speed is None
        await press(pilot, "ctrl+z", "ctrl+z", "ctrl+z", "ctrl+z")
        assert steps(app) == (Step("joint", QN), Step("linear", UP))


async def test_enter_edits_joint_values_and_a_linear_moves_tool_pose():
    puma = load_robot("puma560")[0]
    app = app_with(Program("p", (Step("joint", QN), Step("linear", UP))))
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        await press(pilot, "g", "up", "up", "enter")
        await type_in(pilot, "10, 40, -170, 0, 50, 0")
        assert steps(app)[0].to == (10.0, 40.0, -170.0, 0.0, 50.0, 0.0)
        # the linear move: its tool pose, moved 50 mm in z; the joints are solved
        await press(pilot, "down", "enter")
        await until(pilot, lambda: app.screen.query("OptionList"), "the choice")
        await press(pilot, "enter")  # "tool pose" is the one offered first
        end = read_out(puma.kinematics.pose(UP))
        x, y, z = end.xyz
        o, a, t = end.oat
        await type_in(pilot, f"{x:.4f}, {y:.4f}, {z + 50:.4f}, {o:.4f}, {a:.4f}, {t:.4f}")
        new = steps(app)[1].to
        assert steps(app)[1].move == "linear" and new != UP
        reached = puma.kinematics.pose(new)  # FK of what IK gave: the pose typed
        assert np.allclose(reached[:3, 3], (x, y, z + 50), atol=1e-3)
        assert np.allclose(reached[:3, :3], puma.kinematics.pose(UP)[:3, :3], atol=1e-5)
        assert np.max(np.abs(np.subtract(new, UP))) < 30  # the same branch, nearby


async def test_rename_new_program_and_the_next_one(status):
    app = app_with(Program("p", (Step("joint", QN),)), Program("q", (Step("wait", seconds=1.0),)))
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        panel = screen.query_one(ProgramPanel)
        await press(pilot, "g", "r")
        await type_in(pilot, "q")  # taken
        assert "already" in str(app.screen.query_one("#error").render())
        await type_in(pilot, "pick")
        assert app.robot.program_names == ("pick", "q") and "Program pick" in panel.border_title
        await press(pilot, "o")
        assert "Program q" in panel.border_title and "q (2 of 2)" in status(app)
        await press(pilot, "N")
        assert app.robot.program_names == ("pick", "q", "program1")
        assert "Program program1" in panel.border_title
        await press(pilot, "R")
        assert len(app.robot.program("program1").steps) == 1
        await press(pilot, "ctrl+z", "ctrl+z", "ctrl+z")  # the step, the new one, the rename
        assert app.robot.program_names == ("p", "q") and "Program p" in panel.border_title


async def test_a_long_program_scrolls_with_the_selection():
    many = Program("p", tuple(Step("wait", seconds=float(i + 1)) for i in range(20)))
    app = app_with(many)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        panel = screen.query_one(ProgramPanel)
        await press(pilot, "g")
        await until(pilot, lambda: "of 20" in str(panel.border_title), "the range")
        assert "1–" in str(panel.border_title)
        await press(pilot, *["down"] * 19)
        assert panel.selected == 19
        shown = str(panel.render())
        assert "20 wait 20 s" in shown and " 1 wait 1 s" not in shown
        assert f"{21 - panel.visible}–20 of 20" in str(panel.border_title)


async def test_at_80x24_the_program_shares_the_side_with_the_read_out():
    app = app_with(Program("p", tuple(Step("wait", seconds=1.0) for _ in range(8))))
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        await press(pilot, "g")
        pose, panel = screen.query_one(PosePanel), screen.query_one(ProgramPanel)
        await until(pilot, lambda: pose.compact, "the compact read-out")
        assert pose.display and panel.display and panel.size.height >= 3
        text = str(pose.render())
        assert "X " in text and "Y " in text and "O " in text and "T " in text
        assert pose.region.bottom <= screen.query_one("#status").region.y


async def test_the_cartesian_key_legend_never_runs_two_hints_together():
    from dhsim_tui.tui.screens.control_keys import KeyHints

    app = app_with()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        await press(pilot, "c")
        hints = screen.query_one(KeyHints)
        await until(pilot, lambda: "frame" in str(hints.render()), "the Cartesian legend")
        text = str(hints.render())
        assert "frameh" not in text and "world/tool frame" in text
        for line in text.splitlines()[1:]:  # two hints a line: a space at least between them
            assert "  " in line.strip() or len(line.split()) <= 3, line


async def test_a_value_the_robot_would_refuse_is_refused_in_its_dialog():
    # the wait fits 0..3600 s but not the program's hour; the speed is a number
    # but under the floor: each said under the input, the dialog kept, nothing changed
    app = app_with(Program("p", (Step("wait", seconds=3000.0), Step("linear", UP))))
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        await press(pilot, "g", "D")
        await type_in(pilot, "700")
        error = str(app.screen.query_one("#error").render())
        assert "at most 3600 s" in error and "step 2" in error
        await press(pilot, "escape")
        await press(pilot, "down", "S")
        await type_in(pilot, "0.001")
        assert "slower than any program needs" in str(app.screen.query_one("#error").render())
        await press(pilot, "escape")
        assert steps(app) == (Step("wait", seconds=3000.0), Step("linear", UP))


@pytest.mark.parametrize("ascii", [False, True])
def test_the_compact_read_out_fits_the_side_panel_whatever_the_angles(ascii):
    from dhsim_tui.tui.widgets.pose_panel import pose_text

    puma = load_robot("puma560")[0]
    end = read_out(puma.kinematics.pose((-160.0, 225.0, -225.0, 170.0, -100.0, 266.0)))
    for readout in ("oat", "rpy"):
        text = str(pose_text(end, readout, "mm", ascii=ascii, compact=True))
        lines = text.splitlines()
        # the side panel is 38 wide at 80x24: 36 inside its border
        assert len(lines) == 2 and all(len(line) <= 36 for line in lines), lines
        angles = end.oat if readout == "oat" else end.rpy
        shown = [float(v) for v in lines[1].split()[1:6:2]]
        assert np.allclose(shown, angles, atol=0.006)
        assert np.allclose([float(v) for v in lines[0].split()[1:6:2]], end.xyz, atol=0.006)


async def test_a_click_selects_the_step_under_the_pointer_when_scrolled():
    many = Program("p", tuple(Step("wait", seconds=float(i + 1)) for i in range(20)))
    app = app_with(many)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ProgramPanel)
        await press(pilot, "g", *["down"] * 19)
        top = 20 - panel.visible  # the last steps shown
        # offsets count from the panel's border: row 2 is the second step shown
        await pilot.click(ProgramPanel, offset=(6, 2))
        await until(pilot, lambda: panel.selected == top + 1, "the clicked step selected")
        await pilot.click(ProgramPanel, offset=(6, 0))  # on the border: nothing
        await pilot.pause()
        assert panel.selected == top + 1

"""Regression tests for defects a review found: markup in user text, odd CLI
arguments, special files, file modes, planar jogging, the quit guard."""

from __future__ import annotations

import os
import stat

import pytest
from pilot_helpers import press, started

from dhsim_tui.cli.main import main
from dhsim_tui.core import Joint, Robot, load, load_robot, save
from dhsim_tui.core.model.editing import set_pose, set_units
from dhsim_tui.core.motion.jog import cartesian_move, cartesian_target
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import SaveGuard
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.screens.value_entry import ValueEntry

BRACKETS = "arm [/] [b]x"


async def test_square_brackets_in_names_and_typed_text_are_shown_literally(tmp_path):
    robot = set_pose(Robot(BRACKETS, (Joint(a=100.0), Joint(a=50.0))), "[/p]", (1.0, 2.0))
    file = tmp_path / "odd.toml"
    save(robot, file)
    app = DhsimApp(load(file), file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "p")
        assert "[/p]" in str(app.screen.query_one("#status").render())
        shown = "\n".join(strip.text for strip in app.screen._compositor.render_strips())
        assert BRACKETS in shown  # what a person sees, brackets and all
        await press(pilot, "enter", "ctrl+u", "[", "/", "enter")
        assert isinstance(app.screen, ValueEntry)
        assert "'[/' is not a number" in str(app.screen.query_one("#error").render())
        await press(pilot, "escape", "question_mark")
        assert isinstance(app.screen, HelpScreen)
        await press(pilot, "escape", "e")
        assert isinstance(app.screen, EditorScreen)
        await press(pilot, "tab", "a", "ctrl+u", *"[/x]", "enter")
        assert "[/x]" in app.screen.robot.pose_names


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["fk", "puma560", "--q", "--"], "--q: expected one argument"),
        (["fk", "~nosuchuser/x"], "no such file"),
        (["check", "/dev/zero"], "not a regular file"),
        (["fk", "puma560", "--q", "1_0,0,0,0,0,0"], "('1_0') is not a number"),
        (["ik", "puma560", "--xyz", "1e308,0,0"], "not a finite number of sane size"),
    ],
)
def test_odd_arguments_get_one_line_and_exit_2(capsys, argv, message):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1


def test_save_keeps_the_files_mode_and_symlinks(tmp_path):
    robot, _ = load_robot("gantry")
    file = tmp_path / "g.toml"
    save(robot, file)
    os.chmod(file, 0o644)
    save(robot, file)
    assert stat.S_IMODE(file.stat().st_mode) == 0o644
    link = tmp_path / "link.toml"
    link.symlink_to(file)
    save(robot, link)
    assert link.is_symlink() and load(link) == robot


def test_unit_conversion_round_trips_without_float_noise():
    robot, _ = load_robot("stanford")
    there = set_units(robot, "cm")
    assert there.joints[2].min == 30.48
    assert set_units(there, "mm") == robot


def test_planar_arm_jogs_in_its_plane_and_says_what_it_cannot_do():
    planar, _ = load_robot("planar2")
    q = (30.0, 60.0)
    for row in (0, 1):
        assert cartesian_move(planar, q, cartesian_target(planar, q, row, 0.01)).moved
    assert "can't turn it" in cartesian_move(planar, q, cartesian_target(planar, q, 5, 1)).reason
    scara, _ = load_robot("cobra600")
    q = (10.0, 20.0, 50.0, 0.0)
    move = cartesian_move(scara, q, cartesian_target(scara, q, 3, 1.0))
    assert not move.moved and "no joint that moves the tool that way" in move.reason


async def test_ctrl_q_over_a_dialog_still_guards_unsaved_edits():
    robot, path = load_robot("gantry")
    app = DhsimApp(robot, path, start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "t", "question_mark", "ctrl+q")
        assert isinstance(app.screen, SaveGuard)
        await press(pilot, "escape")
        assert app.is_running


async def test_a_pose_kept_only_in_memory_counts_as_unsaved_in_the_editor():
    robot, path = load_robot("gantry")  # bundled: P keeps the pose in memory only
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "P", "enter", "e")
        assert isinstance(app.screen, EditorScreen) and app.screen.dirty
        await press(pilot, "escape")
        assert isinstance(app.screen, SaveGuard)
        await press(pilot, "escape")
        assert isinstance(app.screen, EditorScreen)


async def test_metre_robots_show_enough_decimals():
    robot, path = load_robot("planar2")
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "enter", "ctrl+u", *"10", "enter")
        assert isinstance(app.screen, ControlScreen)
        assert "1.96962 m" in str(app.screen.query_one("#pose").render())

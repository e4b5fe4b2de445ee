"""Every pose is saved or asked about: ``q`` (and ctrl+c) with poses kept only
in memory asks save, discard or stay; ``P`` never overwrites a robot file that
changed on disk since it was read (issue 8, step 5)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from pilot_helpers import press, started, until

from dhsim_tui.core import load, load_robot
from dhsim_tui.core.files.library import user_library_dir
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import FileChanged, SaveGuard
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.value_entry import ValueEntry

POSE = (1.0, 0.0, 0.0, 0.0, 0.0, 0.0)


@pytest.fixture
def robot_file(tmp_path: Path) -> Path:
    copy = tmp_path / "puma.toml"
    shutil.copyfile(load_robot("puma560")[1], copy)
    return copy


def bundled_app() -> DhsimApp:
    robot, path = load_robot("puma560")
    return DhsimApp(robot, path, animate=False)


async def save_pose(pilot, name: str = "here") -> None:
    """Step joint 1 by one degree and keep the joints as pose ``name`` (``P``)."""
    await press(pilot, "right", "P", "ctrl+u", *name, "enter")
    await pilot.pause()


async def test_q_with_a_pose_only_in_memory_asks_and_stay_stays():
    app = bundled_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await save_pose(pilot)
        assert app.has_unsaved_poses
        await press(pilot, "q")
        assert isinstance(app.screen, SaveGuard)
        await press(pilot, "escape")  # stay
        assert isinstance(app.screen, ControlScreen)
        assert app.return_code is None  # still running
        assert app.robot.pose("here") == POSE
        await press(pilot, "q", "d")  # discard
    assert app.return_code == 0


async def test_ctrl_c_asks_the_same_question():
    app = bundled_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await save_pose(pilot)
        await press(pilot, "ctrl+c")
        assert isinstance(app.screen, SaveGuard)
        await press(pilot, "escape")
        assert app.return_code is None


async def test_q_without_changes_quits_at_once():
    app = bundled_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "q")  # moving a joint is not a change to the robot
    assert app.return_code == 0


async def test_save_from_the_quit_question_asks_a_name_for_a_bundled_robot(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    bundled = load_robot("puma560")[1].read_bytes()
    app = bundled_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await save_pose(pilot)
        await press(pilot, "q", "s")
        await pilot.pause()
        assert isinstance(app.screen, ValueEntry)  # a bundled robot is a template
        await press(pilot, "ctrl+u", *"mypuma", "enter")
        await pilot.pause()
    assert app.return_code == 0
    saved = load(user_library_dir() / "mypuma.toml")  # a bare name: the user library
    assert saved.pose("here") == POSE
    assert saved.joints == load_robot("puma560")[0].joints
    assert load_robot("puma560")[1].read_bytes() == bundled  # the template is untouched


async def test_cancelling_the_name_stays(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    app = bundled_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await save_pose(pilot)
        await press(pilot, "q", "s")
        await pilot.pause()
        await press(pilot, "escape")  # no name: not saved, so not quitting either
        await pilot.pause()
        assert app.return_code is None
        assert app.has_unsaved_poses
        await press(pilot, "q", "d")
    assert not (tmp_path / "robots").exists()


async def test_a_pose_saved_in_its_own_file_quits_at_once(robot_file):
    app = DhsimApp(load(robot_file), robot_file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await save_pose(pilot)
        assert not app.has_unsaved_poses
        await press(pilot, "q")
    assert app.return_code == 0
    assert load(robot_file).pose("here") == POSE


async def test_the_editor_asks_once_for_poses_it_was_given():
    app = bundled_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await save_pose(pilot)
        await press(pilot, "e")
        await pilot.pause()
        assert isinstance(app.screen, EditorScreen) and app.screen.dirty
        await press(pilot, "ctrl+q")
        assert isinstance(app.screen, SaveGuard)
        await press(pilot, "d")
        await pilot.pause()
    assert app.return_code == 0  # not asked a second time by the simulator


def change_on_disk(path: Path) -> bytes:
    """Another program edits the file: a comment and a new pose."""
    text = path.read_text() + "\n# edited elsewhere\n"
    path.write_text(text.replace("[poses]", "[poses]\nelsewhere = [0, 0, 0, 0, 0, 0]", 1))
    return path.read_bytes()


async def test_P_never_overwrites_a_file_changed_on_disk(robot_file):
    app = DhsimApp(load(robot_file), robot_file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        theirs = change_on_disk(robot_file)
        await save_pose(pilot)
        assert isinstance(app.screen, FileChanged)
        await press(pilot, "c")  # cancel: nothing written, the pose stays in memory
        await pilot.pause()
        assert robot_file.read_bytes() == theirs
        assert app.robot.pose("here") == POSE and app.has_unsaved_poses
        await press(pilot, "q")  # ... and quitting asks about it
        assert isinstance(app.screen, SaveGuard)
        await press(pilot, "d")
    assert robot_file.read_bytes() == theirs


async def test_P_on_a_changed_file_can_overwrite(robot_file):
    app = DhsimApp(load(robot_file), robot_file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        change_on_disk(robot_file)
        await save_pose(pilot)
        await press(pilot, "o")  # overwrite, knowingly
        await pilot.pause()
        assert not app.has_unsaved_poses
        await save_pose(pilot, "again")  # the new stamp: no question this time
        assert isinstance(app.screen, ControlScreen)
        await press(pilot, "q")
    assert app.return_code == 0
    on_disk = load(robot_file)
    assert on_disk.pose("here") == POSE and on_disk.pose("again") == (2.0, 0, 0, 0, 0, 0)


async def test_P_on_a_changed_file_can_reload_it(robot_file):
    app = DhsimApp(load(robot_file), robot_file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        theirs = change_on_disk(robot_file)
        await save_pose(pilot)
        await press(pilot, "r")  # reload: the file's robot runs, my pose put back on top
        await until(
            pilot,
            lambda: isinstance(app.screen, ControlScreen) and "here" in app.robot.pose_names,
            "the reloaded robot running, with my pose",
        )
        assert "elsewhere" in app.robot.pose_names and "here" in app.robot.pose_names
        assert app.screen.robot == app.robot
        assert app.has_unsaved_poses  # mine, not written yet
        assert "your edits on top" in str(app.screen.query_one("#status").render())
        await press(pilot, "q")  # asks: discard
        await pilot.pause()
        await press(pilot, "d")
        await pilot.pause()
    assert app.return_code == 0
    assert robot_file.read_bytes() == theirs


async def test_the_quit_question_saves_into_a_changed_file_only_when_told(robot_file):
    """A pose kept in memory (the file changed), then q, s: the save asks again."""
    app = DhsimApp(load(robot_file), robot_file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        theirs = change_on_disk(robot_file)
        await save_pose(pilot)
        await press(pilot, "c")  # keep it in memory for now
        await pilot.pause()
        await press(pilot, "q", "s")
        await pilot.pause()
        assert isinstance(app.screen, FileChanged)
        await press(pilot, "c")  # not saved: stay
        await pilot.pause()
        assert app.return_code is None
        assert robot_file.read_bytes() == theirs
        await press(pilot, "q", "s")
        await pilot.pause()
        await press(pilot, "o")
        await pilot.pause()
    assert app.return_code == 0
    assert load(robot_file).pose("here") == POSE


async def test_ctrl_q_over_a_dialog_still_guards_unsaved_edits(editor_app):
    app = editor_app(*load_robot("gantry"))
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "t", "question_mark", "ctrl+q")
        assert isinstance(app.screen, SaveGuard)
        await press(pilot, "escape")
        assert app.is_running


async def test_a_pose_kept_only_in_memory_counts_as_unsaved_in_the_editor(control_app):
    app = control_app("gantry")  # bundled: P keeps the pose in memory only
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "P", "enter", "e")
        assert isinstance(app.screen, EditorScreen) and app.screen.dirty
        await press(pilot, "escape")
        assert isinstance(app.screen, SaveGuard)
        await press(pilot, "escape")
        assert isinstance(app.screen, EditorScreen)

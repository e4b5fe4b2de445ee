"""Recovery files (core/recovery.py) and how the app offers them back.

The end-to-end flows with real signals are in test_terminal.py; here the core
functions, and the app's start and unsaved-work logic with Textual's pilot.
"""

from __future__ import annotations

import os
import shutil
import stat
from datetime import datetime, timedelta, timezone
from pathlib import Path

import pytest
from pilot_helpers import press, started

from dhsim_tui.core import RobotFileError, load, load_robot
from dhsim_tui.core.files.recovery import (
    NEW_ROBOT,
    discard_recovery,
    find_recovery,
    read_recovery,
    recovery_dir,
    recovery_file,
    source_key,
    write_recovery,
)
from dhsim_tui.core.model.editing import new_robot, set_name, set_pose, toggle_type
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import Choice
from dhsim_tui.tui.screens.editor import EditorScreen


@pytest.fixture
def recovery_folder(tmp_path: Path, monkeypatch) -> Path:
    folder = tmp_path / "recovery"
    monkeypatch.setenv("DHSIM_RECOVERY_DIR", str(folder))
    return folder


@pytest.fixture
def robot_file(tmp_path: Path) -> Path:
    copy = tmp_path / "puma.toml"
    shutil.copyfile(load_robot("puma560")[1], copy)
    return copy


def changed(robot_file: Path):
    """The robot of ``robot_file`` with joint 1 turned prismatic (unsaved)."""
    return toggle_type(load(robot_file), 0)


# -- where recovery files live ---------------------------------------------------


def test_recovery_dir_follows_the_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.delenv("DHSIM_RECOVERY_DIR", raising=False)
    monkeypatch.delenv("XDG_STATE_HOME", raising=False)
    assert recovery_dir() == tmp_path / "home/.local/state/dhsim/recovery"
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    assert recovery_dir() == tmp_path / "state/dhsim/recovery"
    monkeypatch.setenv("XDG_STATE_HOME", "relative/state")  # not absolute: ignored (XDG spec)
    assert recovery_dir() == tmp_path / "home/.local/state/dhsim/recovery"
    monkeypatch.setenv("DHSIM_RECOVERY_DIR", str(tmp_path / "mine"))
    assert recovery_dir() == tmp_path / "mine"


# -- writing and finding -----------------------------------------------------------


def test_a_recovery_round_trips_with_its_source_and_time(recovery_folder, robot_file):
    robot = changed(robot_file)
    before = datetime.now(timezone.utc).replace(microsecond=0)
    file = write_recovery(robot, robot_file)
    assert file.parent == recovery_folder
    found = find_recovery(robot_file)
    assert found is not None
    assert found.robot == robot
    assert found.file == file
    assert found.source == robot_file.resolve()
    assert before <= found.saved_at <= datetime.now(timezone.utc) + timedelta(seconds=1)
    assert robot_file.name in file.read_text()  # a person can tell what it is for
    assert load(file) == robot  # and it is a robot file (header lines are comments)


def test_a_recovery_is_private_and_leaves_no_temporary_file(recovery_folder, robot_file):
    file = write_recovery(changed(robot_file), robot_file)
    assert stat.S_IMODE(file.stat().st_mode) == 0o600
    assert [p.name for p in recovery_folder.iterdir()] == [file.name]


def test_one_recovery_per_source_file(recovery_folder, robot_file, tmp_path, monkeypatch):
    first = write_recovery(changed(robot_file), robot_file)
    monkeypatch.chdir(tmp_path)
    link = tmp_path / "link.toml"
    link.symlink_to(robot_file)
    newer = set_name(changed(robot_file), "newer")
    # the same file by another spelling or a symlink: the same recovery, replaced
    assert write_recovery(newer, Path("./sub/../puma.toml")) == first
    assert write_recovery(newer, link) == first
    assert len(list(recovery_folder.iterdir())) == 1
    assert find_recovery(robot_file).robot.name == "newer"
    other = tmp_path / "other.toml"
    shutil.copyfile(robot_file, other)
    assert write_recovery(changed(other), other) != first
    assert find_recovery(tmp_path / "missing.toml") is None


def test_a_new_robot_has_its_own_recovery(recovery_folder):
    robot = new_robot("sketch", 3)
    file = write_recovery(robot, None)
    assert file == recovery_file(None)
    found = find_recovery(None)
    assert found is not None and found.robot == robot and found.source is None
    assert source_key(None) == NEW_ROBOT


def test_unusual_paths_round_trip(recovery_folder, tmp_path):
    odd = tmp_path / "we\x1bird [x] \udcff.toml"  # an escape, brackets, a non-UTF-8 byte
    robot = new_robot("odd", 2)
    file = write_recovery(robot, odd)
    assert file.name.isascii() and "\x1b" not in file.name
    assert "\x1b" not in file.read_text(encoding="utf-8")  # escaped in the header
    found = find_recovery(odd)
    assert found is not None and found.source == odd


def test_nothing_found_and_discard(recovery_folder, robot_file):
    assert find_recovery(robot_file) is None
    write_recovery(changed(robot_file), robot_file)
    found = find_recovery(robot_file)
    discard_recovery(found)
    assert find_recovery(robot_file) is None
    discard_recovery(found)  # twice is fine


def test_a_damaged_recovery_is_reported_naming_it(recovery_folder, robot_file):
    file = write_recovery(changed(robot_file), robot_file)
    file.write_text(file.read_text().replace("[[joints]]", "[[joints", 1))
    with pytest.raises(RobotFileError, match=str(file)):
        find_recovery(robot_file)
    file.write_text("name = 'no header'\n")
    with pytest.raises(RobotFileError, match="damaged recovery file"):
        read_recovery(file)
    file.write_bytes(b"\xff\xfe")
    with pytest.raises(RobotFileError, match="damaged recovery file"):
        read_recovery(file)


def test_a_recovery_naming_another_source_is_not_offered(recovery_folder, robot_file, tmp_path):
    other = tmp_path / "other.toml"
    shutil.copyfile(robot_file, other)
    text = write_recovery(changed(other), other).read_text()
    recovery_file(robot_file).write_text(text)  # e.g. a hash collision, or a copied file
    assert find_recovery(robot_file) is None


def test_a_recovery_that_cannot_be_written_raises(tmp_path, monkeypatch, robot_file):
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("")
    monkeypatch.setenv("DHSIM_RECOVERY_DIR", str(blocker / "recovery"))
    with pytest.raises(OSError):
        write_recovery(changed(robot_file), robot_file)


# -- what the app keeps -------------------------------------------------------------


async def test_the_app_keeps_an_editors_unsaved_changes(recovery_folder, robot_file):
    app = DhsimApp(load(robot_file), robot_file, start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert app.keep_unsaved_work() == []  # nothing unsaved: nothing written
        assert not recovery_folder.exists()
        await press(pilot, "t")
        messages = app.keep_unsaved_work(15)
        [file] = recovery_folder.iterdir()
        assert messages == [
            f"dhsim: SIGTERM: unsaved changes to Puma 560 ({robot_file}) kept in {file}; "
            "dhsim offers them back when you open it again"
        ]
        assert find_recovery(robot_file).robot == app.screen.robot


async def test_the_app_keeps_poses_kept_only_in_memory(recovery_folder):
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "P", "ctrl+u", *"here", "enter")
        await pilot.pause()
        app.keep_unsaved_work(1)
    found = find_recovery(path)  # keyed by the bundled file it came from
    assert found is not None and found.robot.pose("here") == (1.0, 0, 0, 0, 0, 0)


async def test_a_failed_recovery_write_says_so(tmp_path, monkeypatch, robot_file):
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("")
    monkeypatch.setenv("DHSIM_RECOVERY_DIR", str(blocker / "recovery"))
    app = DhsimApp(load(robot_file), robot_file, start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "t")
        [message] = app.keep_unsaved_work(1)
    assert (
        message.startswith("dhsim: SIGHUP: unsaved changes to Puma 560") and "NOT kept" in message
    )


# -- what the app offers back ---------------------------------------------------------


async def test_the_start_offers_a_recovery_and_restore_opens_the_editor(
    recovery_folder, robot_file
):
    robot = changed(robot_file)
    write_recovery(robot, robot_file)
    app = DhsimApp(load(robot_file), robot_file, animate=False, recovery=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert isinstance(app.screen, Choice)
        assert "Restore unsaved changes from" in app.screen.query_one("Vertical").border_title
        await press(pilot, "enter")  # restore
        await pilot.pause()
        editor = app.screen
        assert isinstance(editor, EditorScreen)
        assert editor.robot == robot and editor.dirty  # unsaved against the file
        assert editor.saved == load(robot_file)
        assert find_recovery(robot_file) is None  # now it lives in the editor
        await press(pilot, "ctrl+s")
        await pilot.pause()
    assert load(robot_file) == robot


@pytest.mark.parametrize(("keys", "kept"), [(("escape",), True), (("down", "enter"), False)])
async def test_later_keeps_it_and_discard_deletes_it(recovery_folder, robot_file, keys, kept):
    write_recovery(changed(robot_file), robot_file)
    app = DhsimApp(load(robot_file), robot_file, start="edit", animate=False, recovery=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert isinstance(app.screen, Choice)
        await press(pilot, *keys)
        await pilot.pause()
        editor = app.screen
        assert isinstance(editor, EditorScreen) and not editor.dirty  # `dhsim edit` goes on
    assert (find_recovery(robot_file) is not None) == kept


async def test_a_recovery_the_file_already_holds_is_not_offered(recovery_folder, robot_file):
    write_recovery(load(robot_file), robot_file)  # e.g. saved later by hand
    app = DhsimApp(load(robot_file), robot_file, animate=False, recovery=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert isinstance(app.screen, ControlScreen)
    assert find_recovery(robot_file) is None


async def test_a_damaged_recovery_is_reported_not_fatal(recovery_folder, robot_file):
    file = write_recovery(changed(robot_file), robot_file)
    file.write_text("garbage")
    app = DhsimApp(load(robot_file), robot_file, animate=False, recovery=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert isinstance(app.screen, ControlScreen)
        assert any(str(file) in n.message for n in app._notifications)
    assert file.exists()  # left for a person to look at


async def test_dhsim_new_offers_a_new_robots_recovery(recovery_folder):
    sketch = set_pose(new_robot("sketch", 2), "up", (10.0, 20.0))
    write_recovery(sketch, None)
    app = DhsimApp(new_robot("new robot"), None, start="new", animate=False, recovery=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert isinstance(app.screen, Choice)
        await press(pilot, "enter")
        await pilot.pause()
        assert isinstance(app.screen, EditorScreen)
        assert app.screen.robot == sketch and app.screen.dirty and app.screen.path is None


async def test_pilot_apps_never_look_for_recoveries(recovery_folder, robot_file):
    """Only a real session (run_app) offers them: tests and snapshots stay put."""
    write_recovery(changed(robot_file), robot_file)
    app = DhsimApp(load(robot_file), robot_file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert isinstance(app.screen, ControlScreen)
    assert os.path.exists(recovery_file(robot_file))


async def test_opening_a_robot_in_the_editor_offers_its_recovery(recovery_folder, robot_file):
    """ctrl+o in the editor, like the start, offers the changes a crash kept."""
    robot = changed(robot_file)
    write_recovery(robot, robot_file)
    app = DhsimApp(*load_robot("gantry"), start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        await pilot.pause()
        app.screen.query_one("#path").focus()
        for key in str(robot_file):
            await press(pilot, key)
        await press(pilot, "enter")
        await pilot.pause()
        assert isinstance(app.screen, Choice)
        await press(pilot, "enter")  # restore
        await pilot.pause()
        editor = app.screen
        assert isinstance(editor, EditorScreen)
        assert editor.robot == robot and editor.dirty
        assert editor.saved == load(robot_file) and editor.path == robot_file
    assert find_recovery(robot_file) is None

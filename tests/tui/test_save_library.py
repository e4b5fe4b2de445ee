"""The save dialog and the user library (issue 27 §1: your robots are yours):
a new robot, or a bundled one saved under a name, goes to
``$XDG_DATA_HOME/dhsim/robots/`` unless a path is typed, and the dialog
shows the full path before anything is written."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from pilot_helpers import press, showing, started, until

from dhsim_tui.cli.main import main
from dhsim_tui.core import load, load_robot
from dhsim_tui.core.files.library import bundled_path, find
from dhsim_tui.core.model.editing import new_robot
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.flows.save import SaveTarget
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.value_entry import ValueEntry
from tui.conftest import editor


@pytest.fixture
def mine(tmp_path, monkeypatch) -> Path:
    """This test's user library (not made yet: the first save makes it)."""
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    return tmp_path / "data" / "dhsim" / "robots"


@pytest.fixture
def work(tmp_path, monkeypatch) -> Path:
    """A working folder with a robots/ folder in it (as in a source checkout)."""
    folder = tmp_path / "work"
    (folder / "robots").mkdir(parents=True)
    monkeypatch.chdir(folder)
    return folder


def text_of(app, selector: str) -> str:
    return str(app.screen.query_one(selector).render())


async def new_robot_up_to_the_save_dialog(pilot) -> None:
    """``dhsim new``: two joints, then ctrl+s."""
    await started(pilot)
    assert isinstance(pilot.app.screen, ValueEntry)  # how many joints?
    await press(pilot, "ctrl+u", "2", "enter")
    await until(pilot, lambda: isinstance(pilot.app.screen, EditorScreen), "the editor")
    await press(pilot, "ctrl+s")
    await showing(pilot, SaveTarget)


async def test_new_saves_in_the_user_library_and_list_shows_it_as_yours(mine, work, capsys):
    """End to end: ``dhsim new irb120`` from a folder with a robots/ folder."""
    app = DhsimApp(new_robot("irb120"), None, start="new")
    async with app.run_test(size=(80, 24)) as pilot:
        await new_robot_up_to_the_save_dialog(pilot)
        target = mine / "irb120.toml"
        assert app.screen.query_one("#value").value == "irb120"
        hint = " ".join(text_of(app, "#hint").split())  # as the dialog wrapped it
        assert hint == f"saves to {target}"
        assert not target.exists() and not mine.exists()  # shown before anything is written
        await press(pilot, "enter")
        await until(pilot, lambda: not editor(app).dirty, "the save")
        assert editor(app).path == target
    assert load(target).name == "irb120" and load(target).dof == 2
    assert list((work / "robots").iterdir()) == []  # not beside the bundled ones
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    yours, bundled = out.split("\nbundled:\n")
    assert "  irb120 " in yours and f"({target})" in yours
    assert "irb120" not in bundled
    assert main(["list", "--json"]) == 0
    listed = json.loads(capsys.readouterr().out)
    assert [(e["name"], e["path"]) for e in listed["yours"]] == [("irb120", str(target))]
    assert "irb120" not in [e["name"] for e in listed["bundled"]]
    assert find("irb120").origin == "yours"


async def test_a_typed_path_is_shown_in_full_and_saved_there(mine, work):
    app = DhsimApp(new_robot("arm"), None, start="new")
    async with app.run_test(size=(80, 24)) as pilot:
        await new_robot_up_to_the_save_dialog(pilot)
        await press(pilot, "ctrl+u", *"robots/arm")
        hint = " ".join(text_of(app, "#hint").split())
        assert hint == f"saves to {work / 'robots' / 'arm.toml'}"
        await press(pilot, "enter")
        await until(pilot, lambda: not editor(app).dirty, "the save")
    assert load(work / "robots" / "arm.toml").dof == 2
    assert not mine.exists()


async def test_a_bundled_robots_file_is_refused_as_a_target(mine, work):
    puma = bundled_path("puma560")
    before = puma.read_bytes()
    app = DhsimApp(new_robot("arm"), None, start="new")
    async with app.run_test(size=(80, 24)) as pilot:
        await new_robot_up_to_the_save_dialog(pilot)
        await press(pilot, "ctrl+u", *str(puma), "enter")
        assert isinstance(app.screen, SaveTarget)  # still asking
        assert "puma560.toml is a robot dhsim ships" in text_of(app, "#error")
        await press(pilot, "escape")
    assert puma.read_bytes() == before


async def test_a_bundled_robot_saved_under_a_name_goes_to_the_user_library(mine, work):
    """A bundled robot is a template: ctrl+s offers its name in your library."""
    robot, path = load_robot("stanford")
    app = DhsimApp(robot, path, start="edit")
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, EditorScreen), "the editor")
        await press(pilot, "ctrl+s")
        await showing(pilot, SaveTarget)
        assert app.screen.query_one("#value").value == "stanford"
        hint = " ".join(text_of(app, "#hint").split())
        assert hint == f"saves to {mine / 'stanford.toml'}"
        await press(pilot, "enter")
        await until(pilot, lambda: not editor(app).dirty, "the save")
    assert load(mine / "stanford.toml") == robot
    found = find("stanford")  # the name now opens yours
    assert (found.origin, found.path) == ("yours", mine / "stanford.toml")


async def test_save_as_of_your_robot_offers_a_copy_beside_it(mine, work):
    mine.mkdir(parents=True)
    shutil.copyfile(bundled_path("planar2"), mine / "two.toml")
    robot = load(mine / "two.toml")
    app = DhsimApp(robot, mine / "two.toml", start="edit")
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, EditorScreen), "the editor")
        editor(app).action_save_as()
        await showing(pilot, SaveTarget)
        assert app.screen.query_one("#value").value == "two_copy"
        await press(pilot, "escape")


async def test_new_with_a_path_offers_that_path(mine, work, tmp_path):
    target = tmp_path / "arms" / "arm.toml"
    app = DhsimApp(new_robot("arm"), None, start="new")
    app.new_target = target
    async with app.run_test(size=(80, 24)) as pilot:
        await new_robot_up_to_the_save_dialog(pilot)
        assert app.screen.query_one("#value").value == str(target)
        assert " ".join(text_of(app, "#hint").split()) == f"saves to {target}"
        await press(pilot, "enter")
        await until(pilot, lambda: not editor(app).dirty, "the save")
    assert load(target).dof == 2 and not mine.exists()


async def test_the_status_line_says_which_robot_a_name_opened(mine):
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    app.notice = "opened the bundled puma560"
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert isinstance(app.screen, ControlScreen)
        assert text_of(app, "#status") == "opened the bundled puma560"


async def test_p_on_your_robot_writes_the_pose_to_its_file(mine):
    mine.mkdir(parents=True)
    shutil.copyfile(bundled_path("puma560"), mine / "puma560.toml")
    robot, path = load_robot("puma560")
    assert path == mine / "puma560.toml"
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "right", "P", "ctrl+u", *"here", "enter")
        await until(pilot, lambda: "here" in load(path).pose_names, "the pose in the file")
        assert not app.has_unsaved_poses


def test_the_open_dialog_lists_your_robots_first(mine, work):
    from dhsim_tui.tui.screens.open_robot import robot_files

    mine.mkdir(parents=True)
    shutil.copyfile(bundled_path("planar2"), mine / "two.toml")
    shutil.copyfile(bundled_path("gantry"), work / "robots" / "here.toml")
    files = robot_files()
    assert files[:2] == [mine / "two.toml", Path("robots") / "here.toml"]
    assert bundled_path("puma560") in files

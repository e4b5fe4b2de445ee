"""The open dialog imports .urdf and .csv files: the tip of a tree, the notes,
unsaved until saved as a .toml, and a bad file that changes nothing."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from pilot_helpers import press, showing, started, until
from textual.command import CommandList, CommandPalette
from textual.widgets import OptionList

from dhsim_tui.core import load, load_robot
from dhsim_tui.core.files.library import user_library_dir
from dhsim_tui.core.interop.export import export_text
from dhsim_tui.core.interop.importer import import_file
from dhsim_tui.core.model.errors import DhsimError, TipNeeded
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import Choice, SaveGuard
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.open_robot import ImportNotes, OpenRobot
from dhsim_tui.tui.screens.value_entry import ValueEntry
from tui.conftest import editor

pytestmark = pytest.mark.usefixtures("in_tmp")

URDFS = Path(__file__).resolve().parents[1] / "urdfs"

TREE = """<?xml version="1.0"?>
<robot name="forked">
  <link name="base"/>
  <link name="upper"/>
  <link name="fore"/>
  <link name="camera"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="fore"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="mount" type="fixed">
    <parent link="upper"/><child link="camera"/>
    <origin xyz="0.1 0 0.05"/>
  </joint>
</robot>
"""


async def run_palette(pilot, query: str, first: str) -> None:
    """ctrl+p, ``query``, and enter once the first command listed is ``first``."""
    app = pilot.app
    await press(pilot, "ctrl+p")
    await until(pilot, lambda: CommandPalette.is_open(app), "the palette")
    await press(pilot, *query)

    def found() -> bool:
        options = app.screen.query_one(CommandList)
        return options.option_count > 0 and options.get_option_at_index(0).hit.text == first

    await until(pilot, found, first)
    await press(pilot, "enter")
    await until(pilot, lambda: not CommandPalette.is_open(app), "the palette to close")


def error_text(app: DhsimApp) -> str:
    return str(app.screen.query_one("#error").render())


async def type_path(pilot, path: object) -> None:
    """In the open dialog: type a path, then enter."""
    assert await showing(pilot, OpenRobot)
    pilot.app.screen.query_one("#path").focus()
    await press(pilot, "ctrl+u", *str(path), "enter")
    await pilot.pause()


async def test_open_imports_a_urdf_as_an_unsaved_robot(in_tmp, editor_app):
    source = URDFS / "planar_elbow.urdf"
    expected = import_file(source)
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        await type_path(pilot, source)
        assert await showing(pilot, ImportNotes)  # what the importer checked
        notes = " ".join(str(app.screen.query_one("Label").render()).split())
        assert "checked at home and 200 random joint values" in notes
        library = user_library_dir()
        assert f"Not saved yet: ctrl+s saves it as {library}/<name>.toml (or a path you give)." in (
            notes
        )
        await press(pilot, "enter")
        screen = editor(app)
        await until(pilot, lambda: app.screen is screen, "the editor")
        assert screen.robot == expected.robot
        assert screen.path is None and screen.template is None
        assert screen.dirty  # no robot file yet
        assert "imported from planar_elbow.urdf" in str(
            screen.query_one("#joints-table").border_title
        )
        await press(pilot, "ctrl+s")  # asks a name in the user library
        assert await showing(pilot, ValueEntry)
        assert app.screen.query_one("Input").value == "planar_elbow"
        await press(pilot, "enter")
        await until(pilot, lambda: not screen.dirty, "the save")
        saved = library / "planar_elbow.toml"
        assert load(saved) == expected.robot
        assert saved.read_text().startswith("# Imported by dhsim from planar_elbow.urdf")
        assert not screen.dirty and screen.path == saved
    assert not (URDFS / "planar_elbow.toml").exists()


async def test_a_tree_asks_for_the_tip(in_tmp, editor_app):
    tree = in_tmp / "forked.urdf"
    tree.write_text(TREE)
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        await type_path(pilot, tree)
        assert await showing(pilot, Choice)
        options = app.screen.query_one(OptionList)
        leaves = [str(options.get_option_at_index(i).prompt) for i in range(options.option_count)]
        assert sorted(leaves) == ["camera", "fore"]
        await press(pilot, "escape")  # no tip: nothing is imported
        await until(
            pilot,
            lambda: isinstance(app.screen, OpenRobot) and "not imported" in error_text(app),
            "the message",
        )
        assert error_text(app).startswith("not imported: no tool link chosen — ")
        await type_path(pilot, tree)
        assert await showing(pilot, Choice)
        for _ in range(leaves.index("camera")):
            await press(pilot, "down")
        await press(pilot, "enter")
        assert await showing(pilot, ImportNotes)
        await press(pilot, "escape")
        assert await showing(pilot, EditorScreen)
        assert editor(app).robot == import_file(tree, tip="camera").robot
        assert editor(app).robot.dof == 1


async def test_the_ur5_tree_from_the_list(in_tmp, editor_app):
    (in_tmp / "robots").mkdir()
    shutil.copy(URDFS / "ur5.urdf", in_tmp / "robots" / "ur5.urdf")
    app = editor_app()
    async with app.run_test(size=(120, 40)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        assert await showing(pilot, OpenRobot)
        first = str(app.screen.query_one(OptionList).get_option_at_index(0).prompt)
        assert first.startswith("robots/ur5.urdf") and "a tree" in first
        await press(pilot, "enter")  # the first entry: ./robots/ur5.urdf
        assert await showing(pilot, Choice)
        leaves = import_file_leaves(in_tmp / "robots" / "ur5.urdf")
        for _ in range(leaves.index("tool0")):
            await press(pilot, "down")
        await press(pilot, "enter")
        assert await showing(pilot, ImportNotes)
        await press(pilot, "enter")  # closes the notes
        assert await showing(pilot, EditorScreen)
        expected = import_file(in_tmp / "robots" / "ur5.urdf", tip="tool0").robot
        assert editor(app).robot == expected


def import_file_leaves(path: Path) -> list[str]:
    try:
        import_file(path)
    except TipNeeded as exc:
        return list(exc.leaves)
    raise AssertionError("not a tree")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("<robot name='x'><link name='a'/>", "cannot import: "),
        ("not xml at all", "cannot import: "),
        ("<robot name='x'><link name='a'/></robot>", "cannot import: "),
    ],
)
async def test_a_bad_urdf_shows_its_error_and_changes_nothing(in_tmp, text, message, editor_app):
    bad = in_tmp / "bad.urdf"
    bad.write_text(text)
    try:
        import_file(bad)
    except DhsimError as exc:  # the importer's own one line
        reason = str(exc).removeprefix(f"{bad}: ")
    else:
        raise AssertionError("the importer took it")
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        before = editor(pilot.app).robot
        await press(pilot, "ctrl+o")
        await type_path(pilot, bad)
        await until(pilot, lambda: error_text(app), "the error")
        assert await showing(pilot, OpenRobot)  # still open: fix the path or escape
        error = error_text(app)
        assert error.startswith(message) and reason[:40] in error
        assert "\n" not in error.strip()
        await press(pilot, "escape")
        assert await showing(pilot, EditorScreen)
        assert editor(app).robot == before
        assert not editor(app).dirty
    assert not (in_tmp / "robots").exists()


async def test_a_csv_is_imported_too(in_tmp, editor_app):
    robot, _ = load_robot("gantry")
    (in_tmp / "robots").mkdir()
    csv = in_tmp / "robots" / "gantry.csv"
    csv.write_text(export_text(robot, "csv"))
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        assert await showing(pilot, OpenRobot)
        lines = app.screen.query_one(OptionList)
        first = str(lines.get_option_at_index(0).prompt)
        assert first.startswith("robots/gantry.csv") and "Cartesian gantry: 3 joints" in first
        await press(pilot, "enter")
        assert await showing(pilot, ImportNotes)
        await press(pilot, "enter")
        assert await showing(pilot, EditorScreen)
        assert editor(app).robot == import_file(csv).robot
        assert editor(app).path is None


async def test_importing_on_the_simulator_runs_the_robot_unsaved(in_tmp):
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    source = URDFS / "spherical_wrist.urdf"
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, ControlScreen) and app.screen._ready)
        await run_palette(pilot, "import", "Import a URDF or CSV file…")
        assert await showing(pilot, OpenRobot)
        assert app.screen.importing
        await type_path(pilot, source)
        assert await showing(pilot, ImportNotes)
        await press(pilot, "enter")
        assert await showing(pilot, ControlScreen)
        assert app.robot == import_file(source).robot
        assert app.robot_path is None and app.has_unsaved_poses
        await press(pilot, "q")  # quitting asks: it was never saved
        assert await showing(pilot, SaveGuard)
        await press(pilot, "s")
        assert await showing(pilot, ValueEntry)
        saved = user_library_dir() / "spherical_wrist.toml"  # a bare name: the user library
        await press(pilot, "enter")
        await until(pilot, saved.exists, "the save")
    assert load(saved) == import_file(source).robot


async def test_import_from_the_editors_palette_takes_only_urdf_and_csv(in_tmp, editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        before = editor(pilot.app).robot
        await run_palette(pilot, "import", "Import a URDF or CSV file…")
        assert await showing(pilot, OpenRobot)
        assert app.screen.importing
        assert app.screen.query_one(OptionList).option_count == 0  # no robots/ here
        await until(pilot, lambda: app.screen.focused is app.screen.query_one("#path"))
        await press(pilot, *"robots/x.toml", "enter")  # typed at once: the path has the focus
        await until(pilot, lambda: error_text(app), "the error")
        assert error_text(app) == (
            "cannot import: dhsim imports .urdf and .csv files — robots/x.toml"
        )
        await press(pilot, "escape")
        assert await showing(pilot, EditorScreen)
        assert editor(app).robot == before and not editor(app).dirty


async def test_typing_on_the_list_types_the_path(editor_app):
    """ctrl+o, then a path typed at once (the list has the focus), then enter."""
    source = URDFS / "planar_elbow.urdf"
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        assert await showing(pilot, OpenRobot)
        assert app.screen.focused is app.screen.query_one("OptionList")  # bundled robots
        await press(pilot, *str(source))
        await pilot.pause()
        assert app.screen.query_one("#path").value == str(source)  # every character
        await press(pilot, "enter")
        assert await showing(pilot, ImportNotes)

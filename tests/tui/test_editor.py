"""The table editor, driven with Pilot: every edit path, bad input, files, guard."""

from __future__ import annotations

from pathlib import Path

import pytest
from pilot_helpers import press, showing, started

from dhsim_tui.core import dumps, load, load_robot, loads, save
from dhsim_tui.core.files.library import user_library_dir
from dhsim_tui.core.model.editing import new_robot
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import Choice, Confirm, SaveGuard
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.editor_table import JOINT_COLUMNS
from dhsim_tui.tui.screens.open_robot import OpenRobot
from dhsim_tui.tui.screens.value_entry import ValueEntry
from tui.conftest import editor


@pytest.fixture(autouse=True)
def in_tmp(tmp_path, monkeypatch):
    """Each test works in its own folder, so robots/ is a fresh one."""
    monkeypatch.chdir(tmp_path)
    return tmp_path


def error_text(app: DhsimApp) -> str:
    return str(app.screen.query_one("#error").render())


async def type_in(pilot, text: str) -> None:
    await press(pilot, "ctrl+u", *text, "enter")
    await pilot.pause()  # the edit lands (or is refused) once the key is handled


async def edit_cell(pilot, row: int, column: int, text: str) -> None:
    """Move the joints table's cursor to (row, column) and type a value."""
    table = editor(pilot.app).query_one("#joints-table")
    table.focus()
    table.move_cursor(row=row, column=column)
    await press(pilot, "enter")
    await type_in(pilot, text)


async def test_edit_a_cell_and_undo_redo(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        original = editor(app).robot
        await edit_cell(pilot, 2, 5, "-45")  # joint 3 alpha
        assert editor(app).robot.joints[2].alpha == -45.0
        assert editor(app).dirty
        await edit_cell(pilot, 1, 4, "400")  # joint 2 a
        assert editor(app).robot.joints[1].a == 400.0
        await press(pilot, "ctrl+z")
        assert editor(app).robot.joints[1].a == 431.8
        await press(pilot, "ctrl+z")
        assert editor(app).robot == original
        assert not editor(app).dirty
        await press(pilot, "ctrl+y", "ctrl+y")
        assert editor(app).robot.joints[2].alpha == -45.0
        assert editor(app).robot.joints[1].a == 400.0
        assert editor(app).check_action("redo", ()) is None  # greyed: nothing to redo
        await press(pilot, "ctrl+y")
        assert editor(app).robot.joints[1].a == 400.0


@pytest.mark.parametrize(
    ("column", "typed", "message"),
    [
        ("alpha", "abc", "'abc' is not a number"),
        ("alpha", "", "type a number"),
        ("alpha", "nan", "NaN"),
        ("alpha", "inf", "out of range"),
        ("alpha", "1e400", "out of range"),
        ("theta", "200", "home value 200 deg is outside the joint's limits -160..160"),
        ("theta", "x", "joint 1 theta: 'x' is not a number"),
        ("offset", "1e400", "joint 1 offset: inf is out of range"),
        ("home", "200", "home value 200 deg is outside the joint's limits -160..160"),
        ("min", "160", "min (160) must be less than max (160)"),
        ("max", "-170", "min (-160) must be less than max (-170)"),
    ],
)
async def test_bad_values_are_rejected_where_typed(column, typed, message, in_tmp, editor_app):
    robot, _ = load_robot("puma560")
    file = in_tmp / "puma.toml"
    save(robot, file)
    before = file.read_bytes()
    app = editor_app(load(file), file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, JOINT_COLUMNS.index(column), typed)
        assert isinstance(app.screen, ValueEntry)
        assert message in error_text(app)
        assert app.screen.query_one("Input").value == typed  # kept to be fixed
        await press(pilot, "escape")
        assert editor(app).robot == robot
        assert not editor(app).dirty
    assert file.read_bytes() == before


async def test_an_offset_is_edited_in_its_column_and_keeps_home_drawn_the_same(status, editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        before = editor(app).robot
        await edit_cell(pilot, 1, 6, "-90")  # joint 2 offset
        assert isinstance(app.screen, Choice)  # which stays: theta (first), or home
        await press(pilot, "enter")
        robot = editor(app).robot
        assert robot.joints[1].offset == -90.0 and robot.joints[1].theta == 0.0
        assert robot.home[1] == 90.0  # joint value = theta - offset
        assert (
            robot.kinematics.pose(robot.home).tolist()
            == before.kinematics.pose(before.home).tolist()
        )
        assert "joint 2 offset = -90 deg (theta kept)" in status(app)
        table = editor(app).query_one("#joints-table")
        assert str(table.get_cell_at((1, 6))) == "-90"
        assert str(table.get_cell_at((1, JOINT_COLUMNS.index("home")))) == "90"


async def test_toggle_type_moves_the_variable(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        table = editor(app).query_one("#joints-table")
        table.move_cursor(row=2, column=3)
        await press(pilot, "t")
        joint = editor(app).robot.joints[2]
        assert joint.type == "prismatic" and joint.home == 150.05
        assert (joint.min, joint.max) == (-400.0, 400.0)
        table.move_cursor(row=2, column=1)
        await press(pilot, "enter")  # enter on the type column: a choice
        assert isinstance(app.screen, Choice)
        await press(pilot, "up", "enter")
        joint = editor(app).robot.joints[2]
        assert joint.type == "revolute"
        assert (joint.min, joint.max) == (-225.0, 45.0)  # its own limits, back


async def test_add_delete_and_move_joints(status, editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        robot = editor(app).robot
        table = editor(app).query_one("#joints-table")
        table.move_cursor(row=1)
        await press(pilot, "a")
        assert editor(app).robot.dof == 7
        assert editor(app).robot.joints[2].a == 0.0  # inserted after the cursor
        assert all(len(v) == 7 for _, v in editor(app).robot.poses)
        await press(pilot, "insert")
        assert editor(app).robot.dof == 8
        await press(pilot, "d")
        assert isinstance(app.screen, Confirm)
        await press(pilot, "n")
        assert editor(app).robot.dof == 8
        await press(pilot, "delete", "y")
        assert editor(app).robot.dof == 7
        await press(pilot, "ctrl+z", "ctrl+z", "ctrl+z")
        assert editor(app).robot == robot
        table.move_cursor(row=0)
        await press(pilot, "ctrl+down")
        assert editor(app).robot.joints[1] == robot.joints[0]
        assert editor(app).robot.pose("qr")[:2] == (90.0, 0.0)
        await press(pilot, "ctrl+up")
        assert editor(app).robot == robot
        await press(pilot, "ctrl+up")
        assert "already at the end" in status(app)


async def test_joint_count_stays_within_1_and_32(status, editor_app):
    one = new_robot("one", 1)
    app = editor_app(one, None)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "d")
        assert "at least 1 joint" in status(app)
        assert editor(app).robot.dof == 1
        for _ in range(35):
            await press(pilot, "a")
        assert editor(app).robot.dof == 32
        assert "at most 32 joints" in status(app)


async def test_robot_fields(in_tmp, editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        fields = editor(app).query_one("#fields-table")
        fields.focus()

        async def pick(row):
            fields.move_cursor(row=row)
            await press(pilot, "enter")
            await pilot.pause()  # the field's dialog is open

        await pick(0)
        await type_in(pilot, "My Puma")
        assert editor(app).robot.name == "My Puma"
        await pick(0)
        await type_in(pilot, "   ")
        assert "non-empty name" in error_text(app)
        await press(pilot, "escape")
        await pick(1)  # units -> m converts lengths
        assert isinstance(app.screen, Choice)
        await press(pilot, "down", "down", "enter")
        robot = editor(app).robot
        assert robot.units == "m" and robot.joints[1].a == pytest.approx(0.4318)
        assert robot.base_height == pytest.approx(0.67183)
        await pick(2)
        await press(pilot, "down", "enter")
        assert editor(app).robot.convention == "modified"
        await pick(3)
        await type_in(pilot, "-1")
        assert "below the floor" in error_text(app)
        await type_in(pilot, "0.25")
        assert editor(app).robot.base_height == 0.25
        await pick(4)  # base z: -z (the list starts on the current +z); base x stays +x
        await press(pilot, "down", "enter")
        assert (editor(app).robot.base_z, editor(app).robot.base_x) == ("-z", "+x")
        await pick(5)  # base x offers only axes perpendicular to z
        options = app.screen.query_one("OptionList")
        assert [options.get_option_at_index(i).id for i in range(options.option_count)] == [
            "+x",
            "-x",
            "+y",
            "-y",
        ]
        await press(pilot, "down", "down", "enter")
        assert editor(app).robot.base_x == "+y"
        await pick(6)  # base xyz: frame 0 moves, in the robot's unit
        await type_in(pilot, "0.1, 0, 0")
        assert editor(app).robot.base_xyz == (0.1, 0.0, 0.0)
        await pick(7)
        await type_in(pilot, "0, 0, 30")
        assert editor(app).robot.base_rpy == (0.0, 0.0, 30.0)
        await pick(8)
        await type_in(pilot, "0, 0, 0.1")
        assert editor(app).robot.tool.xyz == (0.0, 0.0, 0.1)
        await pick(9)
        await type_in(pilot, "1, 2")
        assert "expected 3 numbers" in error_text(app)
        await type_in(pilot, "0, 0, 90")
        assert editor(app).robot.tool.rpy == (0.0, 0.0, 90.0)


async def test_poses_add_edit_delete(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        fields = editor(app).query_one("#fields-table")
        fields.focus()
        await press(pilot, "a")
        await type_in(pilot, "qz")
        assert "already a pose named 'qz'" in error_text(app)
        await type_in(pilot, "mine")
        assert editor(app).robot.pose("mine") == editor(app).robot.home
        fields.move_cursor(row=fields.row_count - 1)
        await press(pilot, "enter")
        await type_in(pilot, "0, 0, 0, 300, 0, 0")
        assert "Th4 = 300 deg is outside its limits" in error_text(app)
        await type_in(pilot, "0, 10, 20, 30, 40, 50")
        assert editor(app).robot.pose("mine") == (0, 10, 20, 30, 40, 50)
        await press(pilot, "d", "y")
        assert "mine" not in editor(app).robot.pose_names


async def test_new_robot_save_reopen_change_alpha_undo(in_tmp, monkeypatch):
    """The issue's 'done when': the seed's SCARA from nothing, all by keyboard."""
    monkeypatch.setenv("HOME", str(in_tmp / "home"))  # "~" below: never outside this test
    app = DhsimApp(new_robot("my scara"), None, start="new")
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert isinstance(app.screen, ValueEntry)
        await type_in(pilot, "0")
        assert "whole number from 1 to 32" in error_text(app)
        await type_in(pilot, "4")
        assert editor(app).robot.dof == 4
        await edit_cell(pilot, 0, 4, "350")
        await edit_cell(pilot, 1, 4, "250")
        await edit_cell(pilot, 1, 5, "180")
        editor(app).query_one("#joints-table").move_cursor(row=2)
        await press(pilot, "t")
        await edit_cell(pilot, 2, JOINT_COLUMNS.index("max"), "200")
        await edit_cell(pilot, 2, JOINT_COLUMNS.index("min"), "0")
        fields = editor(app).query_one("#fields-table")
        fields.focus()
        fields.move_cursor(row=3)
        await press(pilot, "enter")
        await type_in(pilot, "250")
        robot = editor(app).robot
        assert robot.type_string == "RRPR" and robot.base_height == 250
        assert editor(app).query_one("#preview").views[1].scene is not None
        await press(pilot, "ctrl+s")
        # a slash makes a path (test_save_library); refused: the home folder
        # itself ("~" is not "<home's name>.toml" beside it), an unsafe name, none
        await type_in(pilot, "~")
        assert "the path ends in a folder" in error_text(app)
        await type_in(pilot, "..")
        assert "not a safe file name" in error_text(app)
        await type_in(pilot, "")
        assert "type a name" in error_text(app)
        saved = user_library_dir() / "my_scara.toml"  # a bare name: the user library
        await press(pilot, "ctrl+u", *"my_scara")
        assert " ".join(str(app.screen.query_one("#hint").render()).split()) == (
            f"saves to {saved}"
        )  # the full path, before anything is written
        assert not saved.exists()
        await press(pilot, "enter")
        await pilot.pause()
        assert load(saved) == robot
        assert not editor(app).dirty
        # reopen it, change one alpha, undo
        await press(pilot, "ctrl+o")
        assert isinstance(app.screen, OpenRobot)
        app.screen.query_one("#path").focus()
        await type_in(pilot, str(saved))
        assert editor(app).robot == robot
        await edit_cell(pilot, 1, 5, "0")
        assert editor(app).robot.joints[1].alpha == 0.0
        await press(pilot, "ctrl+z")
        assert editor(app).robot.joints[1].alpha == 180.0
        await press(pilot, "escape")
        assert isinstance(app.screen, ControlScreen)
        assert app.screen.robot == robot  # the simulator runs the saved robot
    assert load(saved) == robot
    assert list(in_tmp.iterdir()) == []  # nothing written in the working folder


async def test_open_a_bad_file_keeps_the_robot(in_tmp, editor_app):
    bad = in_tmp / "bad.toml"
    bad.write_text('name = "x"\n[[joints]]\nalhpa = 1\n')
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        robot = editor(app).robot
        await press(pilot, "ctrl+o")
        app.screen.query_one("#path").focus()
        await type_in(pilot, str(bad))
        assert "joints[1].alhpa: unknown key (did you mean 'alpha'?)" in error_text(app)
        await type_in(pilot, str(in_tmp / "missing.toml"))
        assert "no such file" in error_text(app)
        await press(pilot, "escape")
        assert editor(app).robot == robot


async def test_open_lists_robots_in_the_folder(in_tmp, editor_app):
    (in_tmp / "robots").mkdir()
    gantry, _ = load_robot("gantry")
    save(gantry, in_tmp / "robots" / "a_gantry.toml")
    app = editor_app()
    async with app.run_test(size=(120, 40)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        await pilot.pause()
        await press(pilot, "enter")  # the first entry: ./robots/a_gantry.toml
        assert editor(app).robot == gantry
        assert editor(app).path == Path("robots/a_gantry.toml")


async def test_saving_over_another_file_asks_first(in_tmp, status, editor_app):
    user_library_dir().mkdir(parents=True)
    other = user_library_dir() / "other.toml"  # where the bare name "other" saves
    other.write_text(dumps(load_robot("gantry")[0]))
    before = other.read_bytes()
    app = editor_app(new_robot("other", 2), None)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+s")
        await type_in(pilot, "other")
        assert isinstance(app.screen, Confirm)
        await press(pilot, "n")
        assert other.read_bytes() == before
        assert "not saved" in status(app)
        await press(pilot, "ctrl+s")
        await type_in(pilot, "other")
        await press(pilot, "y")
        assert load(other) == editor(app).robot


async def test_failed_save_loses_nothing(in_tmp, status, editor_app):
    library = user_library_dir()
    library.parent.mkdir(parents=True)
    library.write_text("a file where the folder should be")
    app = editor_app(new_robot("keep me", 3), None)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "100")
        robot = editor(app).robot
        await press(pilot, "ctrl+s")
        await type_in(pilot, "keep_me")
        assert "not saved" in status(app)
        assert editor(app).robot == robot and editor(app).dirty
    assert library.read_text() == "a file where the folder should be"


async def test_failed_save_to_a_read_only_file_keeps_the_old_file(
    in_tmp, monkeypatch, status, editor_app
):
    file = in_tmp / "arm.toml"
    robot = new_robot("arm", 2)
    save(robot, file)
    before = file.read_bytes()
    import os

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(os, "replace", refuse)  # what a read-only folder does to the rename
    app = editor_app(robot, file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "10")
        await press(pilot, "ctrl+s")
        assert "not saved" in status(app) and "permission denied" in status(app)
        assert editor(app).dirty
    assert file.read_bytes() == before
    assert [p.name for p in in_tmp.iterdir()] == ["arm.toml"]  # no temporary left


@pytest.mark.parametrize("key", ["escape", "ctrl+q"])
async def test_unsaved_changes_guard(key, in_tmp, editor_app):
    file = in_tmp / "arm.toml"
    robot = new_robot("arm", 2)
    save(robot, file)
    app = editor_app(robot, file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "10")
        await press(pilot, key)
        assert await showing(pilot, SaveGuard)  # the guard is a worker's dialog
        await press(pilot, "escape")  # stay
        assert await showing(pilot, EditorScreen) and editor(app).dirty
        await press(pilot, key, "d")  # discard
        if key == "escape":
            assert await showing(pilot, ControlScreen)
            assert app.screen.robot == robot
    assert load(file) == robot


async def test_guard_save_then_leave_runs_the_edited_robot(in_tmp, editor_app):
    file = in_tmp / "arm.toml"
    save(new_robot("arm", 2), file)
    app = editor_app(load(file), file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "10")
        edited = editor(app).robot
        await press(pilot, "escape", "s")
        assert isinstance(app.screen, ControlScreen)
        assert app.screen.robot == edited
    assert load(file) == edited


@pytest.mark.parametrize("name", ["puma560", "irb140"])
async def test_bundled_robots_are_templates(name, in_tmp, editor_app):
    """A bundled robot asks for a name on save, and offers its own file's name."""
    robot, path = load_robot(name)
    before = path.read_bytes()
    app = editor_app(robot, path)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+s")
        assert isinstance(app.screen, ValueEntry)
        assert app.screen.query_one("Input").value == name
        await press(pilot, "enter")
        saved = user_library_dir() / f"{name}.toml"  # the user library, not the bundled file
        assert loads(saved.read_text()) == editor(app).robot
        assert editor(app).path == saved
    assert path.read_bytes() == before


async def test_control_screen_e_opens_the_editor():
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "e")
        assert isinstance(app.screen, EditorScreen)
        await press(pilot, "escape")
        assert isinstance(app.screen, ControlScreen)


async def test_editor_at_160x48_shows_three_views(editor_app):
    app = editor_app()
    async with app.run_test(size=(160, 48)) as pilot:
        await started(pilot)
        assert editor(app).has_class("-wide")
        assert all(v.display for v in editor(app).query_one("#preview").views)

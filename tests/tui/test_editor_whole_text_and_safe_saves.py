"""Issue 8 in the editor: what it shows is whole and true, keys are applied in
order, saves never overwrite what was not read, file text cannot steer the
terminal, and odd folders or paths give a message instead of a traceback.

Screens are read as rendered text (what a user would see), not widget state.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest
from pilot_helpers import dialog_workers, press, settled, showing, started, until
from textual import events, work
from textual.app import App
from textual.containers import Vertical

from dhsim_tui.core import load, load_robot, save
from dhsim_tui.core.files.library import user_library_dir
from dhsim_tui.core.files.robotfile import read_stamp
from dhsim_tui.core.model.editing import (
    delete_joint,
    insert_joint,
    move_joint,
    new_robot,
    set_joint_field,
    set_name,
    set_pose,
    set_units,
)
from dhsim_tui.scene import VIEWS, build_wireframe, project
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.flows.save import SaveResult, save_flow
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import Choice, FileChanged, ReadOnly, SaveGuard
from dhsim_tui.tui.screens.editor import QUIT_HINT, EditorScreen
from dhsim_tui.tui.screens.editor_changes import describe_change
from dhsim_tui.tui.screens.editor_table import JOINT_COLUMNS, joint_labels, number
from dhsim_tui.tui.screens.open_robot import OpenRobot
from dhsim_tui.tui.screens.value_entry import ValueEntry
from tui.conftest import editor, robot_text, text_of

BOX = "│╭╮╰╯─┃━▎▊▔▁"


@pytest.fixture(autouse=True)
def in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def screen_lines(app: DhsimApp) -> list[str]:
    """The screen as the terminal would show it, one string per row."""
    return text_of(app).split("\n")


def region_text(app: DhsimApp, widget) -> str:
    """The words shown inside ``widget`` (borders dropped, lines joined)."""
    region = widget.region
    lines = screen_lines(app)[region.y : region.bottom]
    parts = [line[region.x : region.right].strip(BOX + " ") for line in lines]
    return " ".join(p for p in parts if p)


def flat(text: str) -> str:
    return re.sub(r"\s+", " ", text).strip()


def status_shown_whole(app: DhsimApp) -> str:
    """The status line's message, checked to be on screen in full."""
    status = editor(app).query_one("#editor-status")
    shown = flat(region_text(app, status))
    message = flat(str(status.render()))
    # beside the preview the line is narrow: a path may wrap at a slash
    assert shown.replace(" ", "") == message.replace(" ", ""), "the status line is cut"
    return message


async def edit_cell(pilot, row: int, column: int, text: str) -> None:
    table = editor(pilot.app).query_one("#joints-table")
    table.focus()
    table.move_cursor(row=row, column=column)
    await press(pilot, "enter", "ctrl+u", *text, "enter")
    await pilot.pause()


# -- step 6: whole values, whole messages ------------------------------------------


def test_numbers_are_never_shortened():
    assert number(70.125) == "70.125"
    assert number(123.4567891) == "123.4567891"
    assert number(0.089459) == "0.089459"
    assert number(-0.0) == "0"
    assert number(90.0) == "90"
    assert number(1e-05) == "1e-05"
    for value in (0.1 + 0.2, 1 / 3, -431.8, 2.5e-7, 999999.999999):
        assert float(number(value)) == value


async def test_cells_show_the_whole_value_after_each_edit(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "70.125")
        text = "\n".join(screen_lines(app))
        assert " 70.125 " in text
        await edit_cell(pilot, 1, 4, "123.4567891")
        assert "123.4567891" in "\n".join(screen_lines(app))
        fields = editor(app).query_one("#fields-table")
        fields.focus()
        fields.move_cursor(row=1)
        await press(pilot, "enter", "down", "down", "enter")  # units: mm -> m
        await pilot.pause()
        text = "\n".join(screen_lines(app))
        for shown in ("0.070125", "0.1234567891", "0.15005", "0.4318"):
            assert f" {shown} " in text, shown
        await press(pilot, "ctrl+z", "ctrl+z")  # back to 431.8: the column shrinks again
        await pilot.pause()
        table = editor(app).query_one("#joints-table")
        widths = {c.label.plain: c.width for c in table.columns.values()}
        assert widths["a\n(mm)"] == len("70.125")


async def test_ur5_in_metres_shows_every_digit(editor_app):
    robot, path = load_robot("ur5")
    app = editor_app(robot, path)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        fields = editor(app).query_one("#fields-table")
        fields.focus()
        fields.move_cursor(row=1)
        await press(pilot, "enter", "down", "down", "enter")
        await pilot.pause()
        assert editor(app).robot.units == "m"
        assert " 0.089459 " in "\n".join(screen_lines(app))


async def test_a_wide_table_scrolls_instead_of_cutting(editor_app):
    robot = set_joint_field(new_robot("wide", 3), 0, "a", 123456.78901234)
    robot = set_joint_field(robot, 0, "d", -98765.4321012)
    app = editor_app(robot, None)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        table = editor(app).query_one("#joints-table")
        assert table.virtual_size.width > table.scrollable_content_region.width
        text = "\n".join(screen_lines(app))
        assert "-98765.4321012" in text and "123456.78901234" in text
        table.move_cursor(row=0, column=JOINT_COLUMNS.index("max"))  # off the right edge
        await until(pilot, lambda: table.scroll_x > 0, "the table scrolled")
        assert " 180 " in screen_lines(app)[table.region.y + 3]


@pytest.mark.parametrize("size", [(80, 24), (120, 36)])
async def test_the_unsaved_changes_question_is_shown_whole(size, in_tmp, editor_app):
    file = in_tmp / "arm.toml"
    save(new_robot("a robot with a rather long name, as people write them", 2), file)
    app = editor_app(load(file), file)
    async with app.run_test(size=size) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "10")
        await press(pilot, "escape")
        await pilot.pause()
        assert isinstance(app.screen, SaveGuard)
        text = flat(region_text(app, app.screen.query_one(Vertical)))
        assert (
            "a robot with a rather long name, as people write them has changes that are "
            "not saved. Save before leaving the editor?"
        ) in text
        assert "s save · d discard · escape stay" in text


async def test_a_failed_save_with_a_long_path_says_why_first(in_tmp, monkeypatch, editor_app):
    folder = in_tmp
    while len(str(folder)) < 200:
        folder = folder / "a_rather_long_folder_name"
    folder.mkdir(parents=True)
    file = folder / "arm.toml"
    assert len(str(file)) > 200
    save(new_robot("arm", 2), file)
    before = file.read_bytes()

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    app = editor_app(load(file), file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "10")
        monkeypatch.setattr(os, "replace", refuse)
        await press(pilot, "ctrl+s")
        await pilot.pause()
        monkeypatch.undo()
        shown = status_shown_whole(app)
        assert shown.startswith("not saved: permission denied — ")
        assert shown.endswith("/arm.toml") and "…" in shown
        assert editor(app).dirty
    assert file.read_bytes() == before


# -- step 10: type-ahead -------------------------------------------------------------


async def test_keys_typed_while_the_dialog_opens_are_applied_in_order(monkeypatch, editor_app):
    """ctrl+u - 1 4 enter, arriving while the dialog is being built (nothing
    in it has the focus yet), set -14: none lost, none out of order."""
    app = editor_app()
    compose = ValueEntry.compose
    typed = []

    def compose_while_keys_arrive(screen):
        if not typed:
            typed.append(screen)
            for key, char in (("ctrl+u", None), ("minus", "-"), ("1", "1"), ("4", "4")):
                app.post_message(events.Key(key, char))
            app.post_message(events.Key("enter", None))
        return compose(screen)

    monkeypatch.setattr(ValueEntry, "compose", compose_while_keys_arrive)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        editor(app).query_one("#joints-table").move_cursor(row=1, column=4)  # joint 2 a
        await press(pilot, "enter")
        await pilot.pause()
        await pilot.pause()
        assert typed, "the dialog was not opened"
        assert isinstance(app.screen, EditorScreen)
        assert editor(app).robot.joints[1].a == -14.0


# -- step 12: a burst of keys ends on the right robot --------------------------------


async def test_after_a_burst_the_table_and_preview_show_the_final_robot(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        editor(app).query_one("#joints-table").move_cursor(row=2, column=0)
        workers = dialog_workers(app)
        for _ in range(301):
            app.post_message(events.Key("t", "t"))
        # the keys are handed on one at a time; then the burst's last draw
        await until(pilot, lambda: settled(app, workers), "301 presses of t handled and drawn")
        final = editor(app).robot
        assert final.joints[2].type == "prismatic"
        table = editor(app).query_one("#joints-table")
        assert [str(c) for c in table.get_row_at(2)][:4] == ["3", "P", "0", "150.05*"]
        scene = editor(app).query_one("#preview").views[1].scene
        wire = build_wireframe(final, final.kinematics.frames(final.home))
        assert repr(scene) == repr(project(wire, VIEWS[1]))  # NaN breaks the lines: != itself
        assert "joint 3 is now prismatic" in region_text(
            app, editor(app).query_one("#editor-status")
        )


# -- step 13: small things -----------------------------------------------------------


async def test_footer_shows_the_way_back_and_q_says_how_to_leave(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await until(pilot, lambda: "esc Back" in screen_lines(app)[-1], "the footer")
        footer = screen_lines(app)[-1]
        assert "esc Back" in footer and "? Help" in footer and "^s Save" in footer
        await press(pilot, "q")
        assert isinstance(app.screen, EditorScreen)
        assert status_shown_whole(app) == QUIT_HINT


async def test_column_headers_show_units(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        table = editor(app).query_one("#joints-table")
        header = screen_lines(app)[table.region.y + 1 : table.region.y + 3]
        assert re.search(r"theta.*d.*a.*alpha", header[0])
        assert re.search(r"theta.*d.*a.*alpha.*min.*max", header[0])
        assert re.search(r"\(deg\).*\(mm\).*\(mm\).*\(deg\).*\(deg\).*\(deg\)", header[1])


def test_limit_units_follow_the_joint_types():
    puma, stanford = load_robot("puma560")[0], load_robot("stanford")[0]
    gantry = load_robot("gantry")[0]
    assert joint_labels(puma)[6:] == ("offset\n(deg)", "home\n(deg)", "min\n(deg)", "max\n(deg)")
    assert joint_labels(gantry)[6:] == ("offset\n(mm)", "home\n(mm)", "min\n(mm)", "max\n(mm)")
    assert joint_labels(stanford)[6:] == (
        "offset\n(deg|mm)",
        "home\n(deg|mm)",
        "min\n(deg|mm)",
        "max\n(deg|mm)",
    )


async def test_undo_and_redo_say_what_they_changed(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 1, 5, "90")  # joint 2 alpha 0 -> 90
        status = editor(app).query_one("#editor-status")
        await press(pilot, "ctrl+z")
        await pilot.pause()
        assert region_text(app, status) == "undid: joint 2 alpha 90 -> 0"
        await press(pilot, "ctrl+y")
        await pilot.pause()
        assert region_text(app, status) == "redid: joint 2 alpha 0 -> 90"
        editor(app).query_one("#joints-table").move_cursor(row=0)
        await press(pilot, "t", "ctrl+z")
        await pilot.pause()
        assert region_text(app, status) == "undid: joint 1 prismatic -> revolute"


def test_describe_change_names_each_kind_of_edit():
    robot = new_robot("arm", 3)
    wide = new_robot("arm", 32)
    two = set_joint_field(robot, 1, "a", 5.0)
    assert describe_change(robot, two) == "joint 2 a 0 -> 5"
    assert describe_change(two, insert_joint(two, 0)) == "joint 2 added"
    assert describe_change(two, delete_joint(two, 1)) == "joint 2 deleted"
    assert describe_change(two, move_joint(two, 1, 1)) == "joint 2 swapped with joint 3"
    assert describe_change(robot, set_units(robot, "m")) == "units mm -> m"
    named = set_name(robot, "x" * 80)
    assert describe_change(robot, named) == "name changed"  # too long to quote
    posed = set_pose(wide, "p", tuple(range(32)))
    assert describe_change(wide, posed) == "pose p added"
    assert describe_change(posed, set_pose(posed, "p", (1,) * 32)) == "pose p changed"
    assert describe_change(robot, robot) == "nothing changed"


# -- step 7 and 8: file text and odd paths -------------------------------------------


async def test_file_names_with_escape_sequences_are_shown_escaped(in_tmp, editor_app):
    (in_tmp / "robots").mkdir()
    evil = in_tmp / "robots" / "a\x1b[2J\x1b]0;owned\x07\u202e.toml"
    save(new_robot("fine", 2), evil)
    app = editor_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        await pilot.pause()
        text = "\n".join(screen_lines(app))
        assert "a\\x1b[2J\\x1b]0;owned\\x07\\u202e.toml" in text
        app.screen.query_one("#path").value = str(in_tmp / "gone\x1b[2J.toml")
        app.screen.query_one("#path").focus()
        await press(pilot, "enter")
        error = str(app.screen.query_one("#error").render())
        assert "gone\\x1b[2J.toml" in error and "no such file" in error
        await press(pilot, "tab")
        app.screen.query_one("OptionList").focus()
        await press(pilot, "enter")  # the evil file opens; its name is escaped everywhere
        await pilot.pause()
        text = "\n".join(screen_lines(app))
        assert "\\x1b" in text
    for line in text.splitlines():
        assert not any(ord(c) < 32 or c == "\u202e" for c in line)


async def test_unreadable_robots_folder_is_a_message(in_tmp, monkeypatch, editor_app):
    (in_tmp / "robots").mkdir()
    real_iterdir = Path.iterdir

    def iterdir(self):
        if self.name == "robots" and not self.is_absolute():
            raise PermissionError(13, "Permission denied", str(self))
        return real_iterdir(self)

    monkeypatch.setattr(Path, "iterdir", iterdir)
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        await pilot.pause()
        assert isinstance(app.screen, OpenRobot)
        error = str(app.screen.query_one("#error").render())
        assert "robots/ cannot be read: permission denied" in error
        assert app.screen.query_one("OptionList").option_count > 0  # the bundled ones


async def test_a_path_longer_than_255_bytes_is_a_message(in_tmp, editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+o")
        await pilot.pause()
        path = app.screen.query_one("#path")
        path.value = str(in_tmp / ("x" * 300 + ".toml"))
        path.focus()
        await press(pilot, "enter")
        assert isinstance(app.screen, OpenRobot)
        error = flat(region_text(app, app.screen.query_one("#error")))
        assert error.startswith("cannot open: cannot read: File name too long — ")
        assert error.endswith("xxxx.toml") and "…" in error


async def test_a_deleted_working_folder_is_a_message(in_tmp, monkeypatch):
    work = in_tmp / "work"
    (work / "robots").mkdir(parents=True)
    save(new_robot("arm", 2), work / "robots" / "arm.toml")
    monkeypatch.chdir(work)
    relative = Path("robots") / "arm.toml"
    robot = load(relative)
    app = DhsimApp(robot, relative, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        (work / "robots" / "arm.toml").unlink()
        (work / "robots").rmdir()
        work.rmdir()
        await press(pilot, "e")  # used to raise FileNotFoundError from Path.cwd()
        await pilot.pause()
        assert isinstance(app.screen, EditorScreen)
        await press(pilot, "ctrl+o")
        await pilot.pause()
        assert isinstance(app.screen, OpenRobot)
        await press(pilot, "escape")
        await edit_cell(pilot, 0, 4, "10")
        await press(pilot, "ctrl+s")
        await pilot.pause()
        shown = status_shown_whole(app)
        assert shown.startswith("not saved:") and shown.endswith("— robots/arm.toml")
        assert editor(app).dirty


# -- step 3: never overwrite what was not read ---------------------------------------


#: the commented two-link arm, without its [poses] table
COMMENTED = robot_text("commented_arm").replace("[poses]\nhome = [0.0, 0.0]\n\n", "")


async def _changed_on_disk(in_tmp, pilot) -> tuple[Path, bytes]:
    """Edit in the editor, then let another program rewrite the file; ctrl+s."""
    file = in_tmp / "arm.toml"
    await edit_cell(pilot, 0, 4, "111")
    other = set_joint_field(load(file), 1, "a", 77.0)
    save(other, file)
    outside = file.read_bytes()
    await press(pilot, "ctrl+s")
    await pilot.pause()
    assert isinstance(pilot.app.screen, FileChanged)
    text = flat(region_text(pilot.app, pilot.app.screen.query_one(Vertical)))
    assert "changed on disk since you opened it" in text
    assert "reload it (the file as it is now, your changes put back on top)" in text
    return file, outside


@pytest.mark.parametrize("answer", ["o", "r", "c"])
async def test_external_change_asks_overwrite_reload_or_cancel(answer, in_tmp, editor_app):
    file = in_tmp / "arm.toml"
    file.write_text(COMMENTED)
    app = editor_app(load(file), file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        file, outside = await _changed_on_disk(in_tmp, pilot)
        mine = editor(app).robot
        await press(pilot, answer)
        await pilot.pause()
        assert isinstance(app.screen, EditorScreen)
        on_disk = load(file)
        if answer == "o":
            assert on_disk == mine and not editor(app).dirty
        elif answer == "r":
            # the file as the other program left it, with my edit on top
            assert file.read_bytes() == outside
            robot = editor(app).robot
            assert on_disk.joints[1].a == 77.0 and robot.joints[1].a == 77.0
            assert robot.joints[0].a == 111.0 and editor(app).dirty
            assert "your edits on top" in status_shown_whole(app)
            await press(pilot, "ctrl+z")  # undo takes out only my edit
            assert editor(app).robot == on_disk and not editor(app).dirty
        else:
            assert file.read_bytes() == outside
            assert editor(app).robot == mine and editor(app).dirty
            assert "not saved" in status_shown_whole(app)


@pytest.mark.parametrize("keep", ["mine", "theirs"])
async def test_reload_asks_about_a_value_both_changed_naming_it_and_both_values(
    keep, in_tmp, editor_app
):
    """The trial's case: I set joint 1 max to 150, the file's other editor
    set it to 155 and joint 5 min to -120. Reload asks about joint 1 max
    only; ctrl+z after it never reverts the other person's change."""
    file = in_tmp / "arm.toml"
    file.write_text(COMMENTED)
    app = editor_app(load(file), file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, JOINT_COLUMNS.index("max"), "150")
        theirs = set_joint_field(load(file), 0, "max", 155.0)
        theirs = set_joint_field(theirs, 1, "min", -120.0)
        save(theirs, file)
        await press(pilot, "ctrl+s")
        await pilot.pause()
        assert isinstance(app.screen, FileChanged)
        await press(pilot, "r")
        assert await showing(pilot, Choice)
        text = flat(region_text(app, app.screen.query_one(Vertical)))
        assert "joint 1 max" in text and "keep yours: 150" in text
        assert "keep the file's: 155" in text
        if keep == "theirs":
            await press(pilot, "down")
        await press(pilot, "enter")
        assert await showing(pilot, EditorScreen)
        robot = editor(app).robot
        assert robot.joints[1].min == -120.0  # theirs, never asked about
        assert robot.joints[0].max == (150.0 if keep == "mine" else 155.0)
        await press(pilot, "ctrl+z")
        assert editor(app).robot == load(file)  # back to the file's, not before it


async def test_overwrite_keeps_the_comments(in_tmp, editor_app):
    file = in_tmp / "arm.toml"
    file.write_text(COMMENTED)
    app = editor_app(load(file), file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "111")
        await press(pilot, "ctrl+s")
        await pilot.pause()
    text = file.read_text()
    assert "# my arm: keep this comment" in text and "# the upper arm" in text
    assert load(file).joints[0].a == 111.0


async def test_read_only_file_is_refused_and_save_as_works(in_tmp, editor_app):
    file = in_tmp / "arm.toml"
    file.write_text(COMMENTED)
    file.chmod(0o444)
    before = file.read_bytes()
    app = editor_app(load(file), file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "111")
        await press(pilot, "ctrl+s")
        await pilot.pause()
        assert isinstance(app.screen, ReadOnly)
        text = flat(region_text(app, app.screen.query_one(Vertical)))
        assert "not saved: the file is read-only" in text and "Save as another file?" in text
        await press(pilot, "c")
        await pilot.pause()
        assert status_shown_whole(app).startswith("not saved: the file is read-only — ")
        assert editor(app).dirty
        await press(pilot, "ctrl+s", "a")
        await pilot.pause()
        assert isinstance(app.screen, ValueEntry)
        assert app.screen.query_one("Input").value == "arm"
        await press(pilot, "enter")
        await pilot.pause()
        copy = user_library_dir() / "arm.toml"  # a bare name: the user library
        assert load(copy) == editor(app).robot and not editor(app).dirty
        assert editor(app).path == copy
        assert "# my arm: keep this comment" in copy.read_text()
    assert file.read_bytes() == before


async def test_save_as_key_writes_a_new_file_and_keeps_the_old(in_tmp, editor_app):
    file = in_tmp / "arm.toml"
    file.write_text(COMMENTED)
    app = editor_app(load(file), file)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "111")
        await press(pilot, "S")
        await pilot.pause()
        assert isinstance(app.screen, ValueEntry)
        await press(pilot, "ctrl+u", *"copy", "enter")
        await pilot.pause()
        copy = user_library_dir() / "copy.toml"  # a bare name: the user library
        assert load(copy).joints[0].a == 111.0
        assert "# the upper arm" in copy.read_text()
        assert editor(app).path == copy and not editor(app).dirty
        await press(pilot, "escape")
        assert isinstance(app.screen, ControlScreen)
    assert file.read_text() == COMMENTED


class FlowHost(App):
    """save_flow as the simulator's P and quit guard use it: no editor, no report."""

    def __init__(self, robot, path, stamp) -> None:
        super().__init__()
        self.args = (robot, path, stamp)
        self.result = "running"

    @work
    async def run_flow(self) -> None:
        self.result = await save_flow(self, *self.args)


async def test_save_flow_outside_the_editor(in_tmp):
    robot, path = load_robot("irb140")
    before = path.read_bytes()
    host = FlowHost(robot, path, None)
    async with host.run_test(size=(80, 24)) as pilot:
        host.run_flow()
        assert await showing(pilot, ValueEntry)
        assert host.screen.query_one("Input").value == "irb140"  # the bundled file's name
        await press(pilot, "enter")
        await until(pilot, lambda: host.result != "running", "the save")
    target = user_library_dir() / "irb140.toml"  # yours, never the bundled file
    assert isinstance(host.result, SaveResult) and host.result.kind == "saved"
    assert host.result.path == target and load(target) == robot
    assert host.result.stamp == read_stamp(target)
    assert "# " in target.read_text()  # the bundled file's comments came along
    assert path.read_bytes() == before


async def test_save_flow_never_writes_a_file_created_meanwhile(in_tmp):
    robot = new_robot("arm", 2)
    target = in_tmp / "arm.toml"
    host = FlowHost(robot, target, None)  # None: the file must not exist
    target.write_text("# somebody else's file\n")
    async with host.run_test(size=(80, 24)) as pilot:
        host.run_flow()
        assert await showing(pilot, FileChanged)
        await press(pilot, "c")
        await until(pilot, lambda: host.result != "running", "the answer")
        assert host.result is None
        assert any("not saved" in n.message for n in host._notifications)
    assert target.read_text() == "# somebody else's file\n"

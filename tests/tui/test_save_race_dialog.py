"""A change made on disk while dhsim saves is asked about like any other.

The editor's ctrl+s and the simulator's ``P``: another program writes the
robot file after dhsim wrote its temporary file and before the rename (the
change is made from ``os.fsync`` of the temporary file), or swaps a symbolic
link to a copy of the same bytes in after the file was read. The user gets
the usual question (overwrite, reload, cancel); the other program's change is
on disk until the user chooses to overwrite it.
"""

from __future__ import annotations

import os
import re
import shutil
from collections.abc import Callable
from pathlib import Path

import pytest
from pilot_helpers import press, showing, started, until
from textual.widgets import Label

from dhsim_tui.core import load
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import FileChanged
from dhsim_tui.tui.screens.editor import EditorScreen
from tui.conftest import editor, robot_text

pytestmark = pytest.mark.usefixtures("in_tmp")

TEXT = robot_text("commented_arm")


def while_saving(monkeypatch, path: Path, action: Callable[[], None]) -> list[str]:
    """Run ``action`` once, while a save's temporary file of ``path`` exists."""
    real_fsync = os.fsync
    done: list[str] = []

    def fsync(fd: int) -> None:
        real_fsync(fd)
        prefix = f".{path.name}."
        if not done and any(
            p.name.startswith(prefix) and p.suffix == ".tmp" for p in path.parent.iterdir()
        ):
            done.append(path.name)
            action()

    monkeypatch.setattr(os, "fsync", fsync)
    return done


def outside_edit(path: Path) -> Callable[[], None]:
    """Another program sets joint 2's a to 77 (in place, keeping the comments)."""

    def edit() -> None:
        path.write_text(TEXT.replace("a = 50.0", "a = 77.0"), encoding="utf-8")

    return edit


def dialog_text(app: DhsimApp) -> str:
    """The question's words, as the dialog's labels hold them."""
    return re.sub(r"\s+", " ", " ".join(str(label.render()) for label in app.screen.query(Label)))


async def edit_cell(pilot, row: int, column: int, text: str) -> None:
    table = editor(pilot.app).query_one("#joints-table")
    table.focus()
    table.move_cursor(row=row, column=column)
    await press(pilot, "enter", "ctrl+u", *text, "enter")


@pytest.mark.parametrize("answer", ["o", "r", "c"])
async def test_a_change_made_during_ctrl_s_asks_and_is_kept(answer, in_tmp, monkeypatch, status):
    file = in_tmp / "arm.toml"
    file.write_text(TEXT, encoding="utf-8")
    app = DhsimApp(load(file), file, start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "111")
        mine = editor(app).robot
        done = while_saving(monkeypatch, file, outside_edit(file))
        await press(pilot, "ctrl+s")
        assert await showing(pilot, FileChanged)
        assert done, "the other program wrote during the save"
        assert "changed on disk since you opened it" in dialog_text(app)
        assert "while it was being saved" in dialog_text(app)
        outside = file.read_bytes()
        assert load(file).joints[1].a == 77.0  # kept: nothing renamed over it
        await press(pilot, answer)
        assert await showing(pilot, EditorScreen)
        if answer == "o":  # overwrite, knowingly
            await until(pilot, lambda: not editor(app).dirty, "the save")
            assert load(file) == mine
        elif answer == "r":  # the file as the other program left it, my edit on top
            await until(pilot, lambda: editor(app).robot.joints[1].a == 77.0, "the reload")
            assert file.read_bytes() == outside
            robot = editor(app).robot
            assert robot.joints[0].a == 111.0 and editor(app).dirty
            await press(pilot, "ctrl+z")  # undo takes out only my edit
            assert editor(app).robot == load(file)
        else:
            assert file.read_bytes() == outside
            assert editor(app).robot == mine and editor(app).dirty
            assert "not saved" in status(app)
    if answer != "o":
        assert file.read_bytes() == outside
    assert sorted(p.name for p in in_tmp.iterdir() if p.name.startswith(".")) == []


async def test_a_change_made_during_P_asks_and_cancel_keeps_it(in_tmp, monkeypatch):
    file = in_tmp / "arm.toml"
    file.write_text(TEXT, encoding="utf-8")
    app = DhsimApp(load(file), file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        done = while_saving(monkeypatch, file, outside_edit(file))
        await press(pilot, "right", "P", "ctrl+u", *"here", "enter")
        assert await showing(pilot, FileChanged)
        assert done
        theirs = file.read_bytes()
        assert load(file).joints[1].a == 77.0
        await press(pilot, "c")  # cancel: nothing written, the pose stays in memory
        assert await showing(pilot, ControlScreen)
        assert app.robot.pose("here") is not None and app.has_unsaved_poses
        assert file.read_bytes() == theirs
        await press(pilot, "q")
        await press(pilot, "d")  # quit, discarding the pose
    assert file.read_bytes() == theirs


async def test_a_symlink_to_the_same_bytes_swapped_in_after_opening_asks(in_tmp, status):
    file = in_tmp / "arm.toml"
    file.write_text(TEXT, encoding="utf-8")
    app = DhsimApp(load(file), file, start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await edit_cell(pilot, 0, 4, "111")
        copy = in_tmp / "copy.toml"
        shutil.copyfile(file, copy)
        file.unlink()
        file.symlink_to(copy.name)  # the same bytes, another file
        await press(pilot, "ctrl+s")
        assert await showing(pilot, FileChanged)
        assert "another file now" in dialog_text(app)
        await press(pilot, "c")
        assert await showing(pilot, EditorScreen)
        assert editor(app).dirty and "not saved" in status(app)
    assert file.is_symlink() and copy.read_text(encoding="utf-8") == TEXT

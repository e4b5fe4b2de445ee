"""What a new user hit in the editor and around it (issue 17): a pose add
that renamed the robot, the cursor on "#", a simulator behind the first
question, the palette and dialogs answering keys that came too fast, and
an unexpected error ending in Textual's traceback."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from pilot_helpers import press, settled
from pty_screen import PtyScreen
from textual.containers import Vertical
from waiting import until

from dhsim_tui.core import load, load_robot, save
from dhsim_tui.core.model.editing import new_robot
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.app_exit import crash_line
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import Confirm, SaveGuard
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.editor_table import JOINT_COLUMNS
from dhsim_tui.tui.screens.palette import DhsimPalette
from dhsim_tui.tui.screens.start import StartScreen
from dhsim_tui.tui.screens.value_entry import ValueEntry

pytestmark = pytest.mark.usefixtures("in_tmp")


def editor(app: DhsimApp) -> EditorScreen:
    return next(s for s in reversed(app.screen_stack) if isinstance(s, EditorScreen))


async def type_text(pilot, text: str) -> None:
    await press(pilot, "ctrl+u", *text)


async def showing(pilot, kind: type, what: str) -> None:
    """Wait until a ``kind`` screen is in front, ready and drawn."""
    app = pilot.app
    await until(pilot, lambda: isinstance(app.screen, kind), what)
    await until(pilot, lambda: getattr(app.screen, "_ready", True) and settled(app), what)


async def test_the_editor_starts_on_the_first_editable_cell_and_says_why_about_the_number():
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await showing(pilot, EditorScreen, "the editor")
        table = editor(app).query_one("#joints-table")
        assert table.cursor_coordinate == (0, JOINT_COLUMNS.index("theta"))
        table.move_cursor(column=0)
        await press(pilot, "enter")
        status = editor(app).query_one("#editor-status")
        await until(pilot, lambda: "# is the joint's number" in str(status.render()), "why not")
        assert status.has_class("-error")
        assert app.screen is editor(app)  # no dialog


async def test_adding_a_pose_puts_the_cursor_on_it_and_enter_edits_the_pose_not_the_name(in_tmp):
    """The trial: a, "qr", enter; then enter and 45,60,45,30,45,30 renamed the robot."""
    file = in_tmp / "kr.toml"
    save(new_robot("KR5", 6), file)
    app = DhsimApp(load(file), file, start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await showing(pilot, EditorScreen, "the editor")
        await press(pilot, "tab")  # the fields table, cursor on "name"
        await press(pilot, "a")
        await showing(pilot, ValueEntry, "the name question")
        await type_text(pilot, "qr")
        await press(pilot, "enter")
        await until(pilot, lambda: "qr" in editor(app).robot.pose_names, "the pose")
        await showing(pilot, EditorScreen, "back in the editor, the pose drawn")
        await press(pilot, "enter")
        await showing(pilot, ValueEntry, "the pose's values")
        title = app.screen.query_one(Vertical).border_title
        assert "pose qr" in str(title)
        await type_text(pilot, "45, 60, 45, 30, 45, 30")
        await press(pilot, "enter")
        await showing(pilot, EditorScreen, "back in the editor")
        robot = editor(app).robot
        assert robot.name == "KR5"
        assert robot.pose("qr") == (45.0, 60.0, 45.0, 30.0, 45.0, 30.0)


@pytest.mark.parametrize("start", ["new", "edit"])
async def test_no_simulator_of_another_robot_behind_the_first_question(start):
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, start=start, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        first = ValueEntry if start == "new" else EditorScreen  # the count; the editor
        await showing(pilot, first, "the first question")
        assert not any(isinstance(s, ControlScreen) for s in app.screen_stack)
        assert isinstance(app.screen_stack[1], StartScreen)
        if start == "new":
            await press(pilot, "escape")
        await showing(pilot, EditorScreen, "the editor")
        await press(pilot, "escape")  # leave (nothing changed): the simulator now
        if start == "new":  # a new robot is unsaved: discard it
            await showing(pilot, SaveGuard, "the guard")
            await press(pilot, "d")
        await showing(pilot, ControlScreen, "the simulator")


async def test_the_palette_is_not_opened_again_while_one_is_opening_or_leaving():
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=(100, 30)) as pilot:
        await showing(pilot, ControlScreen, "the simulator")
        # ctrl+p, escape, ctrl+p and escape in one go: the keys a slow link delivers
        for _ in range(3):
            await pilot.press("ctrl+p", "escape", "ctrl+p", "escape", "ctrl+p")
            await until(pilot, lambda: settled(app), "the burst handled")
        palettes = [s for s in app.screen_stack if isinstance(s, DhsimPalette)]
        assert len(palettes) <= 1
        await press(pilot, "escape")
        await showing(pilot, ControlScreen, "the simulator again")
    assert app.return_code in (None, 0)


async def test_a_dialog_answers_once_however_fast_the_keys():
    """escape escape on a dialog over the editor: the first answers it, the
    second must not dismiss it again (InvalidStateError) nor pop the editor."""
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await showing(pilot, EditorScreen, "the editor")
        answers: list[bool] = []
        dialog = Confirm("Delete nothing?")
        app.push_screen(dialog, answers.append)
        await showing(pilot, Confirm, "the dialog")
        dialog.dismiss(True)
        dialog.dismiss(False)  # a second key already queued for it
        await until(pilot, lambda: answers and app.screen is not dialog, "the answer")
        await until(pilot, lambda: settled(app), "everything the answers did")
        assert answers == [True]
        assert isinstance(app.screen, EditorScreen)


def test_an_unexpected_error_ends_with_one_line_and_a_crash_report(monkeypatch, in_tmp):
    monkeypatch.setenv("DHSIM_RECOVERY_DIR", str(in_tmp / "state" / "recovery"))
    try:
        raise KeyError("boom")
    except KeyError as error:
        line = crash_line(error)
    assert line.startswith("dhsim: internal error: KeyError: 'boom'; the details are in ")
    report = line.rsplit(" ", 1)[-1]
    assert "Traceback" in Path(report).read_text(encoding="utf-8")
    assert "\n" not in line


def test_a_real_crash_shows_one_line_not_textuals_traceback(in_tmp):
    """A failure inside the running app (here an action made to raise) ends
    with status 1 and one line on the terminal, never the traceback."""
    script = in_tmp / "crash.py"
    script.write_text(
        "import sys\n"
        "from dhsim_tui.tui.app import run_app\n"
        "from dhsim_tui.core import load_robot\n"
        "from dhsim_tui.tui.screens.control import ControlScreen\n"
        "def boom(self):\n"
        "    raise RuntimeError('a bug')\n"
        "ControlScreen.action_help = boom\n"
        "robot, path = load_robot('puma560')\n"
        "sys.exit(run_app(robot, path))\n"
    )
    env = {"DHSIM_RECOVERY_DIR": str(in_tmp / "recovery")}
    with PtyScreen(command=[sys.executable, str(script)], env=env) as term:
        term.wait_for("Th6")
        term.send("?")
        status = term.wait_exit()
        text = term.raw_bytes().decode("utf-8", "replace")
    assert status == 1
    assert "dhsim: internal error: RuntimeError: a bug" in text
    assert "Traceback" not in text and "locals" not in text


async def test_long_numbers_scroll_the_table_sideways_and_keep_the_number_in_view(in_tmp):
    """Imported limits like -160.428182637 pushed the max column off an 80x24
    screen: the table scrolls sideways, and "#" stays on the left."""
    from dhsim_tui.core.model.editing import set_joint_field

    robot = set_joint_field(new_robot("long", 3), 0, "min", -160.428182637)
    robot = set_joint_field(robot, 0, "max", 171.123456789)
    file = in_tmp / "long.toml"
    save(robot, file)
    app = DhsimApp(load(file), file, start="edit", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await showing(pilot, EditorScreen, "the editor")
        table = editor(app).query_one("#joints-table")
        assert table.fixed_columns == 1

        def row_one() -> str:  # row 1 as drawn
            return table.render_line(table.header_height).text

        table.move_cursor(row=0, column=JOINT_COLUMNS.index("max"))
        # the table scrolls to the cursor after a refresh: wait until max is in view
        await until(pilot, lambda: table.scroll_x > 0 and "171.123456789" in row_one(), "max")
        line = row_one()
        assert line.lstrip().startswith("1") and "171.123456789" in line

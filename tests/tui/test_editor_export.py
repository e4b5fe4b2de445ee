"""Export from the editor (x) and from the simulator (the palette): a format,
a file name, a question before replacing a file, and where it went."""

from __future__ import annotations

import pytest
from pilot_helpers import press, showing, started, until
from textual.command import CommandList, CommandPalette

from dhsim_tui.core import load_robot
from dhsim_tui.core.files.formats import EXPORT_FORMATS
from dhsim_tui.core.interop.export import export_text
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import Choice, Confirm
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.editor_keys import EDITOR_BINDINGS, EDITOR_HELP_ROWS
from dhsim_tui.tui.screens.value_entry import ValueEntry
from tui.conftest import editor, status_of

pytestmark = pytest.mark.usefixtures("in_tmp")


def status(app: DhsimApp) -> str:
    """The editor's message, its wrapped lines joined with single spaces."""
    return " ".join(status_of(app).split())


async def choose_format(pilot, fmt: str) -> None:
    await press(pilot, "x")
    assert await showing(pilot, Choice)
    for _ in range(EXPORT_FORMATS.index(fmt)):
        await press(pilot, "down")
    await press(pilot, "enter")
    assert await showing(pilot, ValueEntry)


@pytest.mark.parametrize("fmt", EXPORT_FORMATS)
async def test_x_exports_what_export_text_gives(in_tmp, fmt, editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "t")  # an unsaved edit: exported as it is here
        await until(pilot, lambda: editor(app).dirty, "the edit")
        robot = editor(app).robot
        await choose_format(pilot, fmt)
        suffix = {"urdf": ".urdf", "csv": ".csv", "json": ".json"}[fmt]
        assert app.screen.query_one("Input").value == f"robots/puma560{suffix}"
        await press(pilot, "enter")
        await until(pilot, lambda: status(app).startswith("exported"), "the export")
        assert await showing(pilot, EditorScreen)
        written = in_tmp / "robots" / f"puma560{suffix}"
        assert written.read_text(encoding="utf-8") == export_text(robot, fmt)
        assert status(app) == f"exported {fmt.upper()} to robots/puma560{suffix}"
        assert editor(app).dirty  # exporting is not saving


async def test_an_existing_file_is_replaced_only_when_confirmed(in_tmp, editor_app):
    (in_tmp / "robots").mkdir()
    target = in_tmp / "robots" / "mine.csv"
    target.write_text("keep me\n")
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        robot = editor(pilot.app).robot
        await choose_format(pilot, "csv")
        await press(pilot, "ctrl+u", *"robots/mine", "enter")  # .csv is added
        assert await showing(pilot, Confirm)
        await press(pilot, "n")
        await until(pilot, lambda: status(app).startswith("not exported"), "the answer")
        assert target.read_text() == "keep me\n"
        assert status(app) == "not exported: robots/mine.csv is left as it was"
        await choose_format(pilot, "csv")
        await press(pilot, "ctrl+u", *"robots/mine.csv", "enter")
        assert await showing(pilot, Confirm)
        await press(pilot, "y")
        await until(pilot, lambda: status(app).startswith("exported"), "the export")
        assert target.read_text() == export_text(robot, "csv")


async def test_a_wrong_suffix_or_a_failure_is_said_and_writes_nothing(in_tmp, editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await choose_format(pilot, "urdf")
        await press(pilot, "ctrl+u", *"robots/arm.csv", "enter")
        await until(pilot, lambda: str(app.screen.query_one("#error").render()), "the error")
        assert await showing(pilot, ValueEntry)  # fix it or escape
        error = str(app.screen.query_one("#error").render())
        assert "a URDF file's name ends in .urdf, not .csv" in error
        await press(pilot, "ctrl+u", *"no/such/folder/arm", "enter")
        await until(pilot, lambda: status(app).startswith("not exported: "), "the failure")
        assert await showing(pilot, EditorScreen)
        assert status(app).endswith("— no/such/folder/arm.urdf")
        await press(pilot, "x", "escape")
        await until(pilot, lambda: status(app) == "not exported", "the cancel")
    assert not (in_tmp / "robots").exists() and not (in_tmp / "no").exists()


async def test_export_from_the_simulator_by_the_palette(in_tmp):
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, ControlScreen) and app.screen._ready)
        await press(pilot, "ctrl+p")
        await until(pilot, lambda: CommandPalette.is_open(app), "the palette")
        await press(pilot, *"export")

        def found() -> bool:
            options = app.screen.query_one(CommandList)
            return (
                options.option_count == 1 and options.get_option_at_index(0).hit.text == "Export…"
            )

        await until(pilot, found, "the export command")
        await press(pilot, "enter")
        assert await showing(pilot, Choice)
        await press(pilot, "down", "enter")  # csv
        assert await showing(pilot, ValueEntry)
        await press(pilot, "enter")
        written = in_tmp / "robots" / "puma560.csv"
        await until(pilot, written.exists, "the export")
        assert await showing(pilot, ControlScreen)
        assert written.read_text(encoding="utf-8") == export_text(robot, "csv")
        assert "exported CSV to robots/puma560.csv" in str(app.screen.query_one("#status").render())


def test_x_is_in_the_footer_and_the_help():
    binding = next(b for b in EDITOR_BINDINGS if b.action == "export")
    assert binding.key == "x" and binding.show and binding.id and binding.tooltip
    assert any(keys == "x" and "export" in text for keys, text in EDITOR_HELP_ROWS)
    assert any(keys == "ctrl+p" for keys, _ in EDITOR_HELP_ROWS)

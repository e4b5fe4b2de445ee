"""The command palette (ctrl+p): dhsim's commands, offered where they work."""

from __future__ import annotations

from dataclasses import replace

import pytest
from pilot_helpers import non_ascii_outside_views, press, showing, started, until
from textual.command import CommandInput, CommandList, CommandPalette, SearchIcon

from dhsim_tui.core import load_robot
from dhsim_tui.core.interop.convert import convert
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.widgets.views_panel import ViewsPanel
from tui.conftest import editor

pytestmark = pytest.mark.usefixtures("in_tmp")


def puma_app(**options) -> DhsimApp:
    robot, path = load_robot("puma560")
    return DhsimApp(robot, path, animate=False, **options)


def listed(app: DhsimApp) -> list[str]:
    """The commands the open palette lists (their names, not their help)."""
    options = app.screen.query_one(CommandList)
    return [str(options.get_option_at_index(i).hit.text) for i in range(options.option_count)]


def searching(app: DhsimApp) -> bool:
    """The palette is still gathering commands (a worker of its own)."""
    group = CommandPalette._GATHER_COMMANDS_GROUP
    return any(w.group == group and not w.is_finished for w in app.workers)


async def open_palette(pilot, query: str = "") -> list[str]:
    """ctrl+p (and a query): the names listed once the search has finished."""
    app = pilot.app
    await press(pilot, "ctrl+p")
    await until(pilot, lambda: CommandPalette.is_open(app), "the palette")
    if query:
        await press(pilot, *query)
    await until(
        pilot,
        lambda: (
            app.screen.query_one(CommandInput).value == query
            and not searching(app)
            and app.screen.query_one(CommandList).option_count > 0
        ),
        "the palette's search",
    )
    return listed(app)


async def run_command(pilot, query: str, name: str) -> None:
    """Search for ``query`` and run the command called ``name``."""
    names = await open_palette(pilot, query)
    assert name in names, names
    for _ in range(names.index(name)):
        await press(pilot, "down")
    await press(pilot, "enter")
    await until(pilot, lambda: not CommandPalette.is_open(pilot.app), "the palette to close")
    await pilot.pause()
    await pilot.pause()


async def test_the_palette_lists_dhsims_commands():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        names = await open_palette(pilot)
        for name in (
            "Open a robot…",
            "Import a URDF or CSV file…",
            "Save as…",
            "Export…",
            "Convert to modified D-H",
            "Go home",
            "Go to pose qz",
            "Go to pose qr",
            "View: top",
            "View: 3-D",
            "View: maximise",
            "Theme: light",
            "Theme: ansi",
            "Help",
            "Quit",
        ):
            assert name in names
        # nothing unsaved, no zoom, the dark theme: these would do nothing
        for name in ("Save", "View: reset zoom", "View: restore", "Theme: dark"):
            assert name not in names
        # Textual's own: a picker of dozens of themes, a keys panel, a screenshot
        for name in ("Theme", "Keys", "Screenshot", "Maximize"):
            assert name not in names
        await press(pilot, "escape")
        await pilot.pause()
        assert await showing(pilot, ControlScreen)


async def test_go_to_pose_qr_moves_the_arm_there():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await run_command(pilot, "pose qr", "Go to pose qr")
        screen = app.screen
        assert isinstance(screen, ControlScreen)
        assert screen.q == app.robot.pose("qr")
        assert "pose qr" in str(screen.query_one("#status").render())
        await press(pilot, "p")  # the next pose goes on from qr
        await until(pilot, lambda: screen.q == app.robot.pose("qs"), "pose qs")


async def test_views_zoom_and_theme_commands():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        screen = app.screen
        await run_command(pilot, "view top", "View: top")
        assert screen.query_one(ViewsPanel).selected == 0
        await press(pilot, "plus")
        await until(pilot, lambda: screen.query_one("#views").zoom != 1.0, "zoom")
        names = await open_palette(pilot, "view")
        assert "View: reset zoom" in names
        await press(pilot, "escape")
        await run_command(pilot, "reset zoom", "View: reset zoom")
        assert screen.query_one("#views").zoom == 1.0
        await run_command(pilot, "maximise", "View: maximise")
        assert screen.has_class("-max")
        names = await open_palette(pilot, "view")
        assert "View: restore" in names and "View: maximise" not in names
        await press(pilot, "escape")
        await run_command(pilot, "light", "Theme: light")
        assert app.theme == "dhsim-light"


async def test_save_is_offered_only_when_something_is_unsaved():
    app = puma_app(start="edit")
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        names = await open_palette(pilot)
        assert "Save" not in names and "Undo" not in names
        assert "Save as…" in names and "Export…" in names
        await press(pilot, "escape")
        await press(pilot, "t")  # an edit
        await until(pilot, lambda: editor(app).dirty, "the edit")
        names = await open_palette(pilot)
        assert "Save" in names and "Undo" in names and "Redo" not in names


async def test_convert_in_the_editor_is_one_undoable_edit():
    app = puma_app(start="edit")
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        original = editor(app).robot
        await run_command(pilot, "convert", "Convert to modified D-H")
        robot = editor(app).robot
        assert robot.convention == "modified"
        assert robot == convert(original, "modified")
        assert editor(app).dirty
        assert "converted from standard to modified" in str(
            editor(app).query_one("#editor-status").render()
        )
        names = await open_palette(pilot, "convert")
        assert "Convert to standard D-H" in names
        await press(pilot, "escape")
        await press(pilot, "ctrl+z")
        await until(pilot, lambda: editor(app).robot == original, "undo")
        assert not editor(app).dirty


async def test_convert_on_the_simulator_opens_the_editor_with_the_change():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        original = app.robot
        await run_command(pilot, "convert", "Convert to modified D-H")
        assert await showing(pilot, EditorScreen)
        assert editor(app).robot == convert(original, "modified")
        assert app.robot == original  # the simulator runs what it ran
        await press(pilot, "ctrl+z")
        await until(pilot, lambda: editor(app).robot == original, "undo")


async def test_no_palette_over_a_dialog():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "question_mark")
        await pilot.pause()
        assert await showing(pilot, HelpScreen)
        await press(pilot, "ctrl+p")
        await pilot.pause()
        assert await showing(pilot, HelpScreen)
        assert not CommandPalette.is_open(app)


async def test_a_pose_name_is_shown_as_text_not_markup(screen_text):
    robot, _ = load_robot("puma560")
    robot = replace(robot, poses=(("[b]x[/b]", robot.home), ("[red", robot.home)), programs=())
    app = DhsimApp(robot, None, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        names = await open_palette(pilot, "pose")
        assert "Go to pose [b]x[/b]" in names
        assert "Go to pose [red" in names
        shown = screen_text(app)
        assert "Go to pose [b]x[/b]" in shown and "Go to pose [red" in shown
        await press(pilot, "escape")
        await run_command(pilot, "[b]", "Go to pose [b]x[/b]")
        assert await showing(pilot, ControlScreen)


@pytest.mark.parametrize("start", ["control", "edit"])
async def test_the_palette_is_ascii_in_ascii_mode(start):
    app = puma_app(ascii=True, start=start)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        names = await open_palette(pilot)
        assert "Open a robot..." in names and "Export..." in names
        assert app.screen.query_one(SearchIcon).icon == ">"
        await pilot.pause()
        assert non_ascii_outside_views(app) == []
        await press(pilot, *"pose")
        await until(
            pilot,
            lambda: (
                app.screen.query_one(CommandInput).value == "pose"
                and not searching(app)
                and app.screen.query_one(CommandList).option_count > 0
            ),
            "the palette's search for pose",
        )
        assert non_ascii_outside_views(app) == []


async def test_a_list_key_while_the_palette_leaves_does_nothing():
    """The long monkey's crash: ``down`` reached a palette whose list had gone
    as it closed (NoMatches, the traceback in a crash report)."""
    app = DhsimApp(load_robot("puma560")[0])
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, ControlScreen), "the simulator")
        await press(pilot, "ctrl+p")
        await until(pilot, lambda: CommandPalette.is_open(app), "the palette")
        palette = app.screen
        await palette.query_one(CommandList).remove()  # as when it is taken down
        palette._action_command_list("cursor_down")  # no list: nothing
        assert palette._gather_commands("go") is None  # no search started either
        palette.dismiss()
        palette.dismiss()  # a command chosen as it leaves: no second pop
        palette._action_command_list("cursor_down")  # leaving: nothing
        await pilot.pause()
        assert app.return_code is None and isinstance(app.screen, ControlScreen)


async def test_a_press_on_a_widget_leaving_the_screen_is_dropped(monkeypatch):
    """The long monkey's other crash: Textual's text selection read the parent
    of a widget that had just left ('NoneType' ... 'region')."""
    from textual import events
    from textual.screen import Screen

    def gone(self, event):
        raise AttributeError("'NoneType' object has no attribute 'region'")

    app = DhsimApp(load_robot("puma560")[0])
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, ControlScreen), "the simulator")
        monkeypatch.setattr(Screen, "_forward_event", gone)
        down = events.MouseDown(None, 10, 3, 0, 0, 1, False, False, False, screen_x=10, screen_y=3)
        await app.on_event(down)  # as the driver hands a press to the app
        await pilot.pause()
        monkeypatch.undo()
        await press(pilot, "right")
        await pilot.pause()
        assert app.return_code is None and app.screen.q[0] != 0.0

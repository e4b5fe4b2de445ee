"""The editor is left once, and only from the front (the long monkey's blank
screens: Textual's dismiss pops whatever screen is in front, so a leave that
landed under a dialog, or twice, took the simulator away)."""

from __future__ import annotations

import pytest
from pilot_helpers import press, until

from dhsim_tui.core import load_robot
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.help import HelpScreen

pytestmark = pytest.mark.usefixtures("in_tmp")


async def test_a_leave_under_a_dialog_or_twice_keeps_the_simulator():
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, ControlScreen), "the simulator")
        await press(pilot, "e")
        await until(pilot, lambda: isinstance(app.screen, EditorScreen), "the editor")
        editor = app.screen
        await press(pilot, "question_mark")
        await until(pilot, lambda: isinstance(app.screen, HelpScreen), "the help")
        editor.dismiss(None)  # as a leave worker that finishes under the help
        await pilot.pause()
        assert isinstance(app.screen, HelpScreen) and editor in app.screen_stack
        await press(pilot, "escape")
        await until(pilot, lambda: app.screen is editor, "the editor again")
        editor.dismiss(None)
        editor.dismiss(None)  # a second leave: nothing
        await until(pilot, lambda: isinstance(app.screen, ControlScreen), "the simulator")
        await pilot.pause()
        assert isinstance(app.screen, ControlScreen)
        assert [type(s).__name__ for s in app.screen_stack][-1] == "ControlScreen"
        assert len(app.screen_stack) == 2  # Textual's default screen and the simulator

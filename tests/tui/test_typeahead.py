"""Keys typed ahead, as a slow link delivers them: a whole burst in one read.

Textual runs a key's bindings when the key bubbles back to the app, behind the
rest of the burst; without dhsim's one-key-at-a-time gate (dhsim_tui/terminal/typeahead.py)
the name typed after ``P`` went to the control screen and was lost.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from pilot_helpers import press, started, until
from textual import events

from dhsim_tui.core import load_robot
from dhsim_tui.core.files.robotfile import load, load_with_stamp
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.editor import EditorScreen

KEYS = {"enter": "\r", "ctrl+u": "\x15", "right": None, "escape": "\x1b"}


def burst(app: DhsimApp, *keys: str) -> None:
    """Post every key at once, as one read from the terminal would."""
    for key in keys:
        app.post_message(events.Key(key, KEYS.get(key, key)))


def robot_copy(tmp_path: Path, name: str = "puma560") -> Path:
    copy = tmp_path / f"{name}.toml"
    shutil.copyfile(load_robot(name)[1], copy)
    return copy


async def test_a_pose_name_typed_right_after_P_is_the_name_saved(tmp_path):
    path = robot_copy(tmp_path)
    app = DhsimApp(*load_with_stamp(path)[:1], path, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        burst(app, "right", "P", "ctrl+u", "l", "a", "b", "4", "enter", "right")
        await until(
            pilot,
            lambda: (
                isinstance(app.screen, ControlScreen)  # the dialog took enter; nothing else opened
                and app.screen.q[0] == 2.0  # and the step after it reached the control screen
                and "lab4" in load(path).pose_names
            ),
            "the save and the last step",
        )
    robot = load(path)
    assert "lab4" in robot.pose_names
    assert robot.pose("lab4")[0] == 1.0  # saved after the first step, before the last


async def test_a_value_typed_right_after_enter_lands_in_the_editor_cell(tmp_path):
    path = robot_copy(tmp_path)
    robot, stamp = load_with_stamp(path)
    app = DhsimApp(robot, path, start="edit", animate=False, stamp=stamp)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        editor = app.screen
        assert isinstance(editor, EditorScreen)
        # row 1, column "a" (the cursor starts on theta: theta, d, a): type -14 at once
        burst(app, "right", "right", "enter", "ctrl+u", "-", "1", "4", "enter")
        await until(
            pilot,
            lambda: app.screen is editor and editor.robot.joints[0].a == -14.0,
            "-14 in the cell",
        )
        assert app.screen is editor
        assert editor.robot.joints[0].a == -14.0


async def test_keys_in_flight_as_the_screens_go_at_quit_do_nothing():
    """The long monkey's last crash: a key's check-back ran as dhsim quit,
    with no screen left (ScreenStackError in a crash report)."""
    app = DhsimApp(load_robot("puma560")[0])
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, ControlScreen), "the simulator")
        stacks = app._screen_stacks
        mode = app._current_mode
        kept = stacks[mode]
        app._before = (app.screen, frozenset())
        app._held = [events.Key("right", None)]
        stacks[mode] = []  # as while the app closes its screens
        try:
            assert app._dialog_starting() is False
            assert app._settled() is True
            assert app._messages_waiting() is False
            await app._release()
            assert app._held == []
        finally:
            stacks[mode] = kept
        await press(pilot, "right")
        await pilot.pause()
        assert app.return_code is None and app.screen.q[0] != 0.0

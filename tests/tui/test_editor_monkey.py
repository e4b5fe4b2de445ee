"""A monkey at the keyboard: 300 random key sequences (fixed seeds) on the
editor never crash it and never leave an invalid robot in memory.

The sequences run one after another in a live editor (a fresh one whenever
the monkey leaves it), keys posted as fast as a terminal can send them."""

from __future__ import annotations

import random

import pytest
from textual import events
from textual.screen import ModalScreen

from dhsim_tui.core import Robot, dumps, load_robot, loads
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.editor import EditorScreen

KEYS = [
    "up",
    "down",
    "left",
    "right",
    "enter",
    "escape",
    "tab",
    "t",
    "a",
    "d",
    "y",
    "n",
    "s",
    "insert",
    "delete",
    "ctrl+up",
    "ctrl+down",
    "ctrl+z",
    "ctrl+y",
    "ctrl+s",
    "ctrl+o",
    "0",
    "1",
    "5",
    "9",
    "minus",
    "full_stop",
    "e",
    "x",
    "ctrl+u",
    "backspace",
    "2",
    "3",
    "question_mark",
    "space",
    "S",
    "q",
]
LENGTH = 12
CHARACTERS = {"minus": "-", "full_stop": ".", "space": " ", "question_mark": "?"}


def key_event(key: str) -> events.Key:
    """The event a terminal would send (as Pilot builds it, without its pauses)."""
    character = CHARACTERS.get(key, key if len(key) == 1 else None)
    return events.Key(key, character)


def _editor(app: DhsimApp) -> EditorScreen | None:
    for screen in reversed(app.screen_stack):
        if isinstance(screen, EditorScreen):
            return screen
    return None


@pytest.mark.parametrize("batch", range(3))
async def test_random_keys_never_crash_or_corrupt(batch, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, start="edit")
    seen_states = set()
    edits, before = 0, robot
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.pause()
        for seed in range(batch * 100, (batch + 1) * 100):
            rng = random.Random(seed)
            keys = [rng.choice(KEYS) for _ in range(LENGTH)]
            for key in keys:  # as fast as a person mashing keys: no pause between them
                app.post_message(key_event(key))
            await pilot.pause()
            editor = _editor(app)
            if editor is not None:
                current = editor.robot
                assert isinstance(current, Robot)
                assert loads(dumps(current)) == current, f"seed {seed}: {keys}"
                seen_states.add(current)
                edits += current != before
                before = current
            else:  # the monkey left the editor: the next sequence starts in a new one
                app.open_editor(robot, path)
                await pilot.pause()
            for _ in range(4):  # typed keys now reach the dialogs they open: leave them
                if not isinstance(app.screen, ModalScreen):
                    break
                await pilot.press("escape")
    # the monkey really edited things (keys now reach the dialogs they open, so
    # many sequences end typing into one): robots changed in many sequences
    assert edits >= 5 and len(seen_states) > 3, (edits, len(seen_states))

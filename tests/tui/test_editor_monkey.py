"""A monkey at the keyboard: 300 random key sequences (fixed seeds) on the
editor never crash it and never leave an invalid robot in memory.

The sequences run one after another in a live editor (a fresh one whenever
the monkey leaves it, in a fresh dhsim whenever it quits), keys posted as fast
as a terminal can send them; each sequence's keys are all handled before the
robot is checked."""

from __future__ import annotations

import random

import pytest
from pilot_helpers import dialog_workers, press, settled, started, until
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
#: sequences per batch (two batches: 120 in the suite; bench/monkey.py runs the long campaigns)
SEQUENCES = 60
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


@pytest.mark.slow  # a monkey: the long runs are the slow suite's
@pytest.mark.parametrize("batch", range(2))
async def test_random_keys_never_crash_or_corrupt(batch, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    robot, path = load_robot("puma560")
    seen_states = set()
    edits, before = 0, robot
    seeds = iter(range(batch * SEQUENCES, (batch + 1) * SEQUENCES))
    seed = next(seeds, None)
    while seed is not None:  # a fresh dhsim whenever the monkey quits this one
        app = DhsimApp(robot, path, start="edit")
        async with app.run_test(size=(80, 24)) as pilot:
            await started(pilot)
            while seed is not None:
                this, seed = seed, next(seeds, None)
                rng = random.Random(this)
                keys = [rng.choice(KEYS) for _ in range(LENGTH)]
                workers = dialog_workers(app)
                for key in keys:  # as fast as a person mashing keys: no pause between them
                    app.post_message(key_event(key))
                await until(
                    pilot,
                    lambda a=app, w=workers: settled(a, w),
                    f"seed {this}: {keys} handled",
                )
                if app._exit:  # the monkey quit dhsim
                    break
                editor = _editor(app)
                if editor is not None:
                    current = editor.robot
                    assert isinstance(current, Robot)
                    assert loads(dumps(current)) == current, f"seed {this}: {keys}"
                    seen_states.add(current)
                    edits += current != before
                    before = current
                else:  # the monkey left the editor: the next sequence starts in a new one
                    workers = dialog_workers(app)
                    app.open_editor(robot, path)
                    await until(
                        pilot,
                        lambda a=app, w=workers: _editor(a) is not None and settled(a, w),
                        "an editor",
                    )
                for _ in range(4):  # typed keys now reach the dialogs they open: leave them
                    if not isinstance(app.screen, ModalScreen):
                        break
                    await press(pilot, "escape")
    # the monkey really edited things (keys now reach the dialogs they open, so
    # many sequences end typing into one): robots changed in many sequences
    assert edits >= 5 and len(seen_states) > 3, (edits, len(seen_states))

"""Partial updates cropped on the left give the very screen Textual's own
method gives: the same frames fed to two pyte terminals, cell for cell."""

from __future__ import annotations

import pyte
import textual
from pilot_helpers import press
from textual._compositor import ChopsUpdate, LayoutUpdate

from dhsim_tui.core import load_robot
from dhsim_tui.terminal import partial_update
from dhsim_tui.tui.app import DhsimApp

KEYS = (
    "right", "right", "down", "right_square_bracket", "right", "left", "4", "d", "w",
    "plus", "right", "2", "minus", "0", "z", "right", "z", "v", "c", "right", "c", "h",
)  # fmt: skip


def test_textual_is_the_version_the_patch_was_written_for():
    assert textual.__version__ == "8.2.8"
    assert ChopsUpdate.render_segments is partial_update.render_segments
    assert partial_update.ORIGINAL is not partial_update.render_segments


def _cells(screen: pyte.Screen):
    return [
        [(c.data, c.fg, c.bg, c.bold, c.reverse) for c in (row[x] for x in range(screen.columns))]
        for row in (screen.buffer[y] for y in range(screen.lines))
    ]


async def test_left_cropped_updates_draw_the_same_screen():
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    size = (120, 36)
    theirs, ours = pyte.Screen(*size), pyte.Screen(*size)
    streams = pyte.Stream(theirs), pyte.Stream(ours)
    partial = {"ours": 0, "theirs": 0, "updates": 0}
    async with app.run_test(size=size) as pilot:
        original_display = app._display

        def display(screen, renderable) -> None:
            original_display(screen, renderable)
            if isinstance(renderable, LayoutUpdate):
                text = renderable.render_segments(app.console)
                streams[0].feed(text)
                streams[1].feed(text)
            elif isinstance(renderable, ChopsUpdate):
                a = partial_update.ORIGINAL(renderable, app.console)
                b = partial_update.render_segments(renderable, app.console)
                streams[0].feed(a)
                streams[1].feed(b)
                partial["theirs"] += len(a)
                partial["ours"] += len(b)
                partial["updates"] += 1

        app._display = display
        await pilot.pause()
        app.screen.refresh()  # a full frame both terminals start from
        await pilot.pause()
        for key in KEYS:
            await press(pilot, key)
            await pilot.pause()
            assert _cells(ours) == _cells(theirs), key
    assert partial["updates"] >= len(KEYS) // 2
    assert partial["ours"] < partial["theirs"]  # and it writes less

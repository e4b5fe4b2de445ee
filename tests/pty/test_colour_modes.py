"""Honest colour (issue 16), checked on the bytes a real dhsim writes to a
pseudo-terminal: NO_COLOR means no colour code at all, and in 16 colours
ANSI red, green and blue belong to the frame axes alone."""

from __future__ import annotations

import re

import pytest
from pty_screen import PtyScreen

SGR = re.compile(r"\x1b\[([0-9;:]*)m")
#: colour parameters of an SGR sequence: 30-37, 39 aside; 40-47; 90-97; 100-107; 38;...; 48;...
_COLOUR = re.compile(r"^(3[0-8]|4[0-8]|9[0-7]|10[0-7])$")
#: what pyte calls ANSI red, green and blue (bright or not)
RGB = {"red", "green", "blue", "brightred", "brightgreen", "brightblue"}
#: the glyphs a frame axis is drawn with, and the legend's axis mark
AXIS_GLYPHS = re.compile(r"[\u2800-\u28ff─]")


def _colour_codes(raw: bytes) -> list[str]:
    found = []
    for params in SGR.findall(raw.decode("utf-8", "replace")):
        parts = re.split("[;:]", params)
        if any(_COLOUR.match(part) for part in parts):
            found.append(params)
    return found


def _session(env: dict[str, str], size=(120, 36)) -> PtyScreen:
    screen = PtyScreen([], size=size, env=env)
    screen.wait_for("Th6")
    screen.wait_for(lambda text: "◆" in text or "@" in text)
    return screen


@pytest.mark.parametrize("value", ["1", "yes"])
def test_no_color_writes_no_colour_code_at_all(value):
    with _session({"NO_COLOR": value}) as screen:
        screen.send("right", "right", "x", "c", "c")
        screen.wait_for("2.00°")
        raw = screen.raw_bytes()
        assert _colour_codes(raw) == []
        # what stands out still does: the selected row, the footer's keys
        # (read while dhsim may still be writing: the last character can be cut)
        text = raw.decode("utf-8", errors="replace")
        assert "\x1b[7m" in text or ";7m" in text or "[7;" in text
        text = screen.screen_text()
        # axis letters sit at their tips: never a run of the same letter
        assert not re.search("xx|yy|zz", text), text
        screen.send("q")
        assert screen.wait_exit() == 0


def _rgb_cells(screen: PtyScreen) -> set[str]:
    """The red, green and blue the screen shows, each checked to be on an axis."""
    seen = set()
    for row in range(screen.screen.lines):
        line = screen.screen.buffer[row]
        for column in range(screen.screen.columns):
            cell = line[column]
            for colour in (cell.fg, cell.bg):
                if colour in RGB:
                    seen.add(colour)
                    assert AXIS_GLYPHS.match(cell.data), (row, column, cell.data, colour)
    return seen


def test_in_16_colours_red_green_and_blue_are_the_axes_alone():
    with _session({"TERM": "xterm"}) as screen:
        screen.send("right", "right", "]")
        screen.wait_for("fit (F)")  # the views open fitted to the arm
        assert {"brightred", "brightgreen", "brightblue"} <= _rgb_cells(screen)  # the axes
        screen.send("ctrl+p")  # the palette's chrome too (the screen behind it dimmed)
        screen.wait_for("Search")
        _rgb_cells(screen)
        screen.send("escape")
        screen.wait_for(lambda text: "Search" not in text and "Keys" in text)
        screen.send("q")
        assert screen.wait_exit() == 0

"""Few bytes per key press (issue 9): the SGR compactor changes nothing a person
sees, joint rows are a few styled runs, a step repaints only what changed,
and the side panels have ASCII variants. Behaviour only; the byte counts
themselves are measured by ``bench/bytes.py``."""

from __future__ import annotations

import pyte
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pilot_helpers import press, settled, started, until
from rich.console import Console
from rich.segment import Segment
from rich.style import Style
from textual.geometry import Region
from textual.strip import Strip

from dhsim_tui.core import Joint, load_robot
from dhsim_tui.terminal.sgr import compact
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel
from dhsim_tui.tui.widgets.joint_row import JointRow, slider
from dhsim_tui.tui.widgets.pose_panel import PosePanel, health_text

COLUMNS, ROWS = 24, 8

# -- two independent screens to compare on: pyte, and a small reference -------------


def pyte_cells(data: str, prefix: str = "") -> tuple:
    """Every cell (char and pyte's attributes), the cursor and its attributes."""
    screen = pyte.Screen(COLUMNS, ROWS)
    stream = pyte.Stream(screen)
    stream.feed(prefix)
    stream.feed(data)
    cells = tuple(tuple(tuple(screen.buffer[y][x]) for x in range(COLUMNS)) for y in range(ROWS))
    cursor = screen.cursor
    return cells, (cursor.x, cursor.y), tuple(cursor.attrs)


class Reference:
    """A terminal of the codes the compactor models, written from ECMA-48 (not
    from the compactor): SGR including dim, conceal, double underline and the
    off codes; CUP, CR, LF (scrolling at the bottom fills the new line with the
    background, reverse and blink, as the Linux console does), erase in line
    and display (current attributes), text without wrapping."""

    def __init__(self) -> None:
        self.attrs: frozenset[int] = frozenset()
        self.fg: tuple = ()
        self.bg: tuple = ()
        self.x = self.y = 0
        blank = self.blank()
        self.cells = [[blank] * COLUMNS for _ in range(ROWS)]

    def blank(self) -> tuple:
        return (" ", self.attrs, self.fg, self.bg)

    def sgr(self, params: str) -> None:
        codes = [int(p) if p else 0 for p in params.split(";")]
        attrs = set(self.attrs)
        offs = {22: {1, 2}, 23: {3}, 24: {4, 21}, 25: {5, 6}, 27: {7}, 28: {8}, 29: {9}}
        i = 0
        while i < len(codes):
            code = codes[i]
            if code == 0:
                attrs, self.fg, self.bg = set(), (), ()
            elif code in (1, 2, 3, 4, 5, 6, 7, 8, 9, 21):
                attrs.add(code)
            elif code in offs:
                attrs -= offs[code]
            elif 30 <= code <= 37 or 90 <= code <= 97:
                self.fg = (code,)
            elif 40 <= code <= 47 or 100 <= code <= 107:
                self.bg = (code,)
            elif code == 39:
                self.fg = ()
            elif code == 49:
                self.bg = ()
            elif code in (38, 48):
                n = 2 if codes[i + 1] == 5 else 4
                colour = tuple(codes[i + 1 : i + 1 + n])
                if code == 38:
                    self.fg = colour
                else:
                    self.bg = colour
                i += n
            i += 1
        self.attrs = frozenset(attrs)

    def feed(self, data: str) -> None:
        i = 0
        while i < len(data):
            char = data[i]
            if char == "\x1b":
                end = i + 2
                while not ("@" <= data[end] <= "~"):
                    end += 1
                params, final = data[i + 2 : end], data[end]
                if final == "m":
                    self.sgr(params)
                elif final == "H":
                    row, _, col = params.partition(";")
                    self.y = min(ROWS, max(1, int(row or 1))) - 1
                    self.x = min(COLUMNS, max(1, int(col or 1))) - 1
                elif final in "JK":
                    self.erase(final, int(params or 0))
                i = end + 1
                continue
            if char == "\r":
                self.x = 0
            elif char == "\n":
                if self.y == ROWS - 1:
                    fill = (
                        " ",
                        self.attrs & {5, 6, 7},
                        self.fg if 7 in self.attrs else (),
                        self.bg,
                    )
                    self.cells = [*self.cells[1:], [fill] * COLUMNS]
                else:
                    self.y += 1
            else:
                self.cells[self.y][self.x] = (char, self.attrs, self.fg, self.bg)
                self.x = min(self.x + 1, COLUMNS - 1)
            i += 1

    def erase(self, final: str, mode: int) -> None:
        line = self.cells[self.y]
        start, stop = {0: (self.x, COLUMNS), 1: (0, self.x + 1), 2: (0, COLUMNS)}[mode]
        for x in range(start, stop):
            line[x] = self.blank()
        if final == "J":
            rows = {0: range(self.y + 1, ROWS), 1: range(self.y), 2: range(ROWS)}[mode]
            for y in rows:
                self.cells[y] = [self.blank()] * COLUMNS

    def state(self) -> tuple:
        return self.cells, (self.x, self.y), (self.attrs, self.fg, self.bg)


def reference(data: str, prefix: str = "") -> tuple:
    screen = Reference()
    screen.feed(prefix)
    screen.feed(data)
    return screen.state()


def assert_same_screen(data: str, prefix: str = "", *, with_reference: bool = True) -> str:
    compacted = compact(data)
    assert pyte_cells(compacted, prefix) == pyte_cells(data, prefix)
    if with_reference:
        assert reference(compacted, prefix) == reference(data, prefix)
    return compacted


# -- what Textual writes: strips of styled segments ----------------------------------

COLOURS = st.one_of(
    st.none(),
    st.sampled_from(["red", "bright_blue", "default", "color(239)", "color(17)"]),
    st.tuples(st.integers(0, 255), st.integers(0, 255), st.integers(0, 255)).map(
        lambda rgb: "#{:02x}{:02x}{:02x}".format(*rgb)
    ),
)
STYLES = st.one_of(
    st.none(),
    st.just(Style()),
    st.builds(
        Style,
        color=COLOURS,
        bgcolor=COLOURS,
        bold=st.sampled_from([None, True]),
        dim=st.sampled_from([None, True]),
        italic=st.sampled_from([None, True]),
        underline=st.sampled_from([None, True]),
        reverse=st.sampled_from([None, True]),
        strike=st.sampled_from([None, True]),
        blink=st.sampled_from([None, True]),
    ),
)
SEGMENTS = st.lists(
    st.tuples(st.text(alphabet="ab ─│●°", min_size=1, max_size=4), STYLES),
    min_size=1,
    max_size=6,
)
#: a chop of a frame: where it goes and what it draws
CHOPS = st.lists(
    st.tuples(st.integers(0, ROWS - 1), st.integers(0, COLUMNS - 1), SEGMENTS),
    min_size=1,
    max_size=6,
)


def render_chops(chops, color_system: str) -> str:
    """A partial update as Textual's ``ChopsUpdate.render_segments`` writes it:
    a cursor move, each segment as SGR + text + reset, a newline between lines."""
    console = Console(color_system=color_system, force_terminal=True, width=COLUMNS)
    parts = []
    for i, (y, x, segments) in enumerate(chops):
        parts.append(f"\x1b[{y + 1};{x + 1}H")
        parts.append(Strip([Segment(text, style) for text, style in segments]).render(console))
        if i < len(chops) - 1:
            parts.append("\n")
    return "".join(parts)


@settings(max_examples=150, deadline=None)
@given(CHOPS, st.sampled_from(["truecolor", "256", "standard"]))
def test_compacting_textual_output_shows_the_same_cells(chops, color_system):
    data = render_chops(chops, color_system)
    compacted = assert_same_screen(data)
    assert len(compacted) <= len(data) + 2  # at most "0;" when the start is unknown


# -- any stream of the codes it deals with -------------------------------------------

SGR_PARAMS = st.lists(
    st.one_of(
        st.sampled_from(
            [
                *("", "0", "1", "2", "3", "4", "5", "7", "8", "9", "21", "22", "23", "24"),
                *("25", "27", "28", "29", "31", "39", "42", "49", "97", "104"),
            ]
        ),
        st.integers(0, 255).map(lambda n: f"38;5;{n}"),
        st.integers(0, 255).map(lambda n: f"48;5;{n}"),
        st.sampled_from(["38;2;1;2;3", "48;2;0;0;0", "38;2;255;0;0"]),
    ),
    min_size=1,
    max_size=4,
).map(lambda params: f"\x1b[{';'.join(params)}m")
TOKENS = st.one_of(
    SGR_PARAMS,
    SGR_PARAMS,
    st.just("\x1b[0m"),
    st.text(alphabet="xy ─", min_size=1, max_size=3),
    st.tuples(st.integers(1, ROWS), st.integers(1, COLUMNS)).map(
        lambda p: "\x1b[{};{}H".format(*p)
    ),
    st.sampled_from(["\n", "\r", "\x1b[K", "\x1b[1K", "\x1b[2K", "\x1b[J", "\x1b[2J"]),
)


@settings(max_examples=300, deadline=None)
@given(st.lists(TOKENS, max_size=40), st.lists(SGR_PARAMS, max_size=2))
def test_compacting_any_sgr_stream_shows_the_same_cells(tokens, prefix):
    """Whatever was in force before (``prefix``, not compacted), erasing,
    scrolling at the bottom line, dim and conceal included."""
    assert_same_screen("".join(tokens), "".join(prefix))


@settings(max_examples=100, deadline=None)
@given(
    st.lists(
        st.one_of(
            TOKENS,
            st.sampled_from(
                # not modelled: passed on, and nothing assumed afterwards
                [
                    *("\x1b7", "\x1b8", "\x1b[s", "\x1b[u", "\x1b[?25l", "\x1b[?1049l"),
                    *("\x1bc", "\x1b]0;title\x07", "\x1b[4:3m", "\x1b[58;5;3m", "\x1b[?2026h"),
                    *("\x1b[2A", "\x1b[3C", "\t", "\x07", "\x1b[S", "\x1b[L"),
                ]
            ),
        ),
        max_size=40,
    )
)
def test_compacting_with_other_sequences_on_pyte(tokens):
    assert_same_screen("".join(tokens), with_reference=False)


def test_every_change_between_attributes_that_share_an_off_code():
    """Bold and dim share 22, underline and double underline 24, both blinks
    25: from every combination to every other, drawn after a reset (known)
    and after nothing (unknown), the reference screen shows the same."""
    import itertools

    codes = (1, 2, 4, 21, 5, 6)
    combos = [c for n in range(len(codes) + 1) for c in itertools.combinations(codes, n)]
    for before, after in itertools.product(combos, repeat=2):
        first = "".join(f"\x1b[{code}m" for code in before)
        second = ";".join(str(code) for code in after)
        data = f"\x1b[0m{first}\x1b[31ma\x1b[0m\x1b[{second or 0};31mb\x1b[0m"
        compacted = compact(data)
        assert reference(compacted) == reference(data), (data, compacted)


def test_a_reset_and_the_same_colour_again_are_dropped():
    red = "\x1b[38;5;9m"
    data = f"\x1b[0m{red}a\x1b[0m{red}b\x1b[0m{red}c\x1b[0m"
    assert compact(data) == "\x1b[0;38;5;9mabc\x1b[0m"
    assert_same_screen(data)


def test_only_the_difference_is_written():
    grey = "38;5;7;48;5;0"
    data = f"\x1b[0m\x1b[{grey}mA\x1b[0m\x1b[1;{grey}mB\x1b[0m\x1b[{grey}mC\x1b[0m"
    assert compact(data) == f"\x1b[0;{grey}mA\x1b[1mB\x1b[22mC\x1b[0m"
    assert_same_screen(data)


def test_cursor_moves_do_not_flush_but_erasing_does():
    blue = "\x1b[44m"
    moved = compact(f"\x1b[0m{blue}a\x1b[0m\x1b[3;4H{blue}b\x1b[0m")
    assert moved == "\x1b[0;44ma\x1b[3;4Hb\x1b[0m"
    erased = compact(f"\x1b[0m{blue}a\x1b[0m\x1b[K")
    assert erased == "\x1b[0;44ma\x1b[0m\x1b[K"  # the line is cleared in the default colour
    assert_same_screen(f"\x1b[0m{blue}a\x1b[0m\x1b[K")


def test_a_pending_reset_at_the_end_is_written():
    assert compact("\x1b[0m\x1b[1mbold\x1b[0m").endswith("bold\x1b[0m")
    assert compact("\x1b[0m\x1b[1mbold\x1b[0m\x1b[1;1H").endswith("\x1b[1;1H\x1b[0m")


def test_unknown_attributes_pass_unchanged_until_a_reset():
    assert compact("\x1b[1mA\x1b[1mB") == "\x1b[1mA\x1b[1mB"
    assert compact("plain text") == "plain text"
    # after a sequence that may restore attributes, nothing is assumed
    data = "\x1b[0m\x1b[31ma\x1b8\x1b[31mb\x1b[0m"
    assert compact(data) == "\x1b[0;31ma\x1b8\x1b[31mb\x1b[0m"


async def test_a_real_control_screen_frame_compacts_to_the_same_screen():
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "down", "right")
        await pilot.pause()
        update = app.screen._compositor.render_update(full=True)
        data = update.render_segments(app.console)
    compacted = compact(data)
    assert len(compacted) < 0.8 * len(data)
    screens = []
    for text in (data, compacted):
        screen = pyte.Screen(80, 24)
        pyte.Stream(screen).feed(text)
        screens.append([[tuple(screen.buffer[y][x]) for x in range(80)] for y in range(24)])
    assert screens[0] == screens[1]


# -- the side panels: a few runs, repaint what changed --------------------------------


def row_strip(row: JointRow) -> list[Segment]:
    return list(row.render_lines(Region(0, 0, row.size.width, 1))[0])


@pytest.mark.parametrize("size", [(80, 24), (160, 48)])
async def test_a_joint_row_is_a_few_styled_runs(size, control_app):
    app = control_app()
    async with app.run_test(size=size) as pilot:
        rows = list(app.screen.query(JointRow))
        for row in rows:
            segments = row_strip(row)
            assert "├" in "".join(s.text for s in segments)
            # label, bar to the value, the value, the rest of the bar, the number,
            # the last column: never one segment per glyph, whatever the width
            assert len(segments) <= 7, [s.text for s in segments]
        await press(pilot, *["shift+right"] * 20)  # Th1 on its max limit: ▶ in red
        await pilot.pause()
        segments = row_strip(rows[0])
        assert "▶" in "".join(s.text for s in segments)
        assert len(segments) <= 7


def test_the_bar_is_three_runs():
    joint = Joint(min=-100.0, max=100.0)
    for value in (-100.0, -30.0, 0.0, 55.0, 100.0):
        bar = slider(joint, value, 30)
        assert len(bar.spans) == 3
        assert len(bar.plain) == 30


def painted(screen) -> bool:
    """Nothing waits to be painted: every change is on the terminal."""
    return not (screen._dirty_widgets or screen._layout_required or screen._repaint_required)


async def test_a_step_repaints_one_joint_row_and_the_changed_pose_lines(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "down")  # Th2 (choosing repaints the joint panel's caption)
        screen = app.screen
        await until(pilot, lambda: painted(screen), "the choice painted")
        side = screen.query_one("#side-panel").region
        rows = [row.region.y for row in screen.query(JointRow)]
        pose = screen.query_one(PosePanel).region
        spans: list[tuple[int, int, int]] = []
        original = app._display

        def display(screen_, renderable) -> None:
            spans.extend(getattr(renderable, "spans", None) or [])
            original(screen_, renderable)

        app._display = display
        redraws = screen.redraws
        await press(pilot, "right")
        await until(
            pilot,
            lambda: screen.redraws > redraws and settled(app) and painted(screen) and spans,
            "the step drawn and painted",
        )
        app._display = original
        touched = {y for y, x1, _ in spans if x1 < side.right}
        assert rows[1] in touched  # the stepped joint (Th2)
        assert not touched & set(rows[2:])  # no other joint row
        assert pose.y not in touched  # not the pose panel's title
        pose_lines = touched & set(range(pose.y, pose.bottom))
        assert 0 < len(pose_lines) < pose.height - 2
        # and each pose line is repainted only up to its last changed column
        # (the views' spans on the same rows are the views' own business)
        assert all(
            x2 < side.right - 1 for y, x1, x2 in spans if y in pose_lines and x1 < side.right
        )


async def test_the_pose_panel_still_shows_every_change(screen_text, control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        panel = app.screen.query_one(PosePanel)
        before = str(panel.render())
        await press(pilot, "right")
        await until(pilot, lambda: str(panel.render()) != before, "the pose to change")
        after = str(panel.render())
        shown = screen_text(app)
        for line in after.splitlines():
            assert line.strip() in shown


# -- ASCII -------------------------------------------------------------------------


def is_ascii(text: str) -> bool:
    return all(ord(char) < 128 for char in text)


async def test_ascii_mode_joint_rows_pose_and_cartesian_panels(control_app):
    app = control_app()
    app.ascii_mode = True  # the mode alone: no ASCII borders or scroll bars
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right")
        rows = [str(row.render()) for row in app.screen.query(JointRow)]
        assert all(is_ascii(row) for row in rows), rows
        assert rows[0].startswith(">") and "deg" in rows[0]
        assert "|" in rows[0] and "#" in rows[0] and "-" in rows[0]
        pose = app.screen.query_one(PosePanel)
        text = str(pose.render())
        assert is_ascii(text) and "deg" in text and "mu" in text, text
        await press(pilot, "v", "v")  # the 4x4 transform
        await until(pilot, lambda: "3x3" in str(pose.render()), "the 4x4 transform")
        assert is_ascii(str(pose.render())) and "3x3" in str(pose.render())
        assert is_ascii(pose.border_title or "")
        await press(pilot, "c")  # Cartesian jogging
        await until(pilot, lambda: app.screen.query(CartesianPanel), "the Cartesian panel")
        cartesian = str(app.screen.query_one(CartesianPanel).render())
        assert is_ascii(cartesian) and "deg" in cartesian
        assert cartesian.startswith(">")


def test_ascii_bar_limits_and_warnings():
    joint = Joint(theta=20.0, min=-100.0, max=100.0)
    assert slider(joint, -100.0, 12, ascii=True).plain == "|<----:----|"
    assert slider(joint, 100.0, 12, ascii=True).plain == "|-----:--->|"
    assert slider(joint, 0.0, 12, ascii=True).plain == "|----#:----|"
    assert slider(joint, 0.0, 12).plain == "├────●┊────┤"
    text = health_text(None, ("below the floor: frame 1",), ascii=True).plain
    assert is_ascii(text) and "!" in text


async def test_unicode_mode_keeps_its_glyphs(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        row = str(app.screen.query(JointRow)[0].render())
        assert row.startswith("▶") and "°" in row and "●" in row
        assert "μ" in str(app.screen.query_one(PosePanel).render())

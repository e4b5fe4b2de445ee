"""7-bit ASCII mode: when it is chosen, what it turns glyphs into, what the
screens show, and (one pseudo-terminal test) that under LC_ALL=C every byte
the real ``dhsim`` writes is ASCII."""

from __future__ import annotations

import io
import json
import os
import shutil
import subprocess
import sys
import unicodedata
from pathlib import Path

import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from pilot_helpers import non_ascii_outside_views, press, settled
from pty_screen import PtyScreen
from rich.cells import cell_len, get_character_cell_size
from textual.scrollbar import ScrollBar
from waiting import until

import dhsim_tui.tui.app
from dhsim_tui.cli import main as cli
from dhsim_tui.core import load_robot
from dhsim_tui.terminal.ascii_table import to_ascii
from dhsim_tui.terminal.charset import ascii_key, ascii_text
from dhsim_tui.terminal.locale_env import original_environ, wants_ascii
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import SaveGuard
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.screens.value_entry import ValueEntry

# -- which mode --------------------------------------------------------------------


@pytest.mark.parametrize(
    ("environ", "ascii"),
    [
        ({}, True),  # nothing set: the C locale
        ({"LANG": "C"}, True),
        ({"LANG": "POSIX"}, True),
        ({"LANG": "en_US"}, True),  # no codeset: Latin-1
        ({"LANG": "de_DE.ISO-8859-15"}, True),
        ({"LANG": "en_US.UTF-8"}, False),
        ({"LANG": "en_US.utf8"}, False),
        ({"LANG": "C.UTF-8"}, False),
        ({"LC_CTYPE": "UTF-8"}, False),  # macOS spelling
        ({"LC_ALL": "C", "LANG": "en_US.UTF-8"}, True),  # LC_ALL first
        ({"LC_ALL": "", "LC_CTYPE": "C", "LANG": "en_US.UTF-8"}, True),  # empty: skipped
        ({"LC_ALL": "", "LC_CTYPE": "", "LANG": "fr_FR.UTF-8"}, False),
        ({"LC_CTYPE": "en_US.UTF-8", "LANG": "C"}, False),
        ({"LANG": "en_US.UTF-8", "TERM": "linux"}, True),  # the Linux console
        ({"LANG": "en_US.UTF-8", "TERM": "xterm-256color"}, False),
    ],
)
def test_the_locale_and_term_decide(environ, ascii):
    assert wants_ascii(environ) is ascii


def test_ascii_and_unicode_flags_win():
    assert wants_ascii({"LANG": "en_US.UTF-8"}, force=True) is True
    assert wants_ascii({"LC_ALL": "C", "TERM": "linux"}, force=False) is False
    assert wants_ascii({}, force=None) is True


def _proc_file(tmp_path: Path, **variables: str) -> str:
    path = tmp_path / "environ"
    path.write_bytes(b"".join(f"{k}={v}".encode() + b"\0" for k, v in variables.items()))
    return str(path)


def test_original_environ_undoes_only_the_locale_coercion(tmp_path):
    # started with LANG=C; Python (PEP 538) then set LC_CTYPE=C.UTF-8 in os.environ
    coerced = {"LANG": "C", "LC_CTYPE": "C.UTF-8", "HOME": "/h"}
    proc = _proc_file(tmp_path, LANG="C", HOME="/h")
    assert wants_ascii(coerced) is False  # the trap
    original = original_environ(coerced, proc)
    assert original == {"LANG": "C", "HOME": "/h"}
    assert wants_ascii(original) is True
    # started with LC_CTYPE=C: put back
    proc = _proc_file(tmp_path, LC_CTYPE="C")
    assert original_environ(coerced, proc)["LC_CTYPE"] == "C"
    # the user really set C.UTF-8: kept
    proc = _proc_file(tmp_path, LC_CTYPE="C.UTF-8", LANG="C")
    assert original_environ(coerced, proc) == coerced
    # a value that is not what coercion writes (set by the program): kept
    mine = {"LC_CTYPE": "en_US.UTF-8"}
    assert original_environ(mine, _proc_file(tmp_path, LANG="C")) == mine
    # no /proc (not Linux): the environment as it is
    assert original_environ(coerced, str(tmp_path / "missing")) == coerced


@pytest.mark.skipif(not Path("/proc/self/environ").exists(), reason="needs Linux /proc")
@pytest.mark.parametrize(
    ("variables", "ascii"),
    [({"LANG": "C"}, True), ({"LC_ALL": "C"}, True), ({}, True), ({"LANG": "C.UTF-8"}, False)],
)
def test_a_real_interpreter_started_in_the_c_locale_is_seen_as_ascii(variables, ascii):
    """In a fresh Python started with LANG=C, os.environ says LC_CTYPE=C.UTF-8
    (PEP 538); /proc/self/environ still says what the process started with."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("LC_", "LANG"))}
    env.pop("PYTHONCOERCECLOCALE", None)
    env.update(variables)
    code = (
        "import json, os\n"
        "from dhsim_tui.terminal.locale_env import original_environ, wants_ascii\n"
        "print(json.dumps([os.environ.get('LC_CTYPE'), wants_ascii(os.environ),"
        " wants_ascii(original_environ())]))"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    ctype, naive, real = json.loads(result.stdout)
    assert real is ascii
    if variables == {"LANG": "C"} and ctype == "C.UTF-8":  # coerced (C.UTF-8 exists here)
        assert naive is False  # what reading os.environ would have got wrong


# -- the command line ----------------------------------------------------------------


@pytest.fixture
def launched(monkeypatch):
    """main() up to the app: what run_app was given (no terminal needed)."""
    calls: list[dict] = []
    monkeypatch.setattr(cli, "has_terminal", lambda: True)
    monkeypatch.setattr(dhsim_tui.tui.app, "run_app", lambda *a, **k: calls.append(k) or 0)
    for stream in ("stdout", "stderr"):  # ASCII mode reconfigures them: not pytest's
        monkeypatch.setattr(sys, stream, io.TextIOWrapper(io.BytesIO(), encoding="utf-8"))
    for name in ("LC_ALL", "LC_CTYPE", "LANG", "TERM"):
        monkeypatch.delenv(name, raising=False)
    return calls


@pytest.mark.parametrize(
    ("argv", "env", "ascii"),
    [
        (["puma560"], {"LANG": "en_US.UTF-8"}, False),
        (["puma560"], {"LC_ALL": "C"}, True),
        (["puma560", "--ascii"], {"LANG": "en_US.UTF-8"}, True),
        (["puma560", "--unicode"], {"LC_ALL": "C", "TERM": "linux"}, False),
        (["edit", "puma560", "--ascii"], {"LANG": "en_US.UTF-8"}, True),
        (["edit", "puma560"], {"LANG": "en_US.UTF-8", "TERM": "linux"}, True),
        (["new", "arm", "--unicode"], {"LANG": "C"}, False),
        (["new"], {"LANG": "C"}, True),
    ],
)
def test_the_tui_commands_pass_the_mode_to_the_app(launched, monkeypatch, argv, env, ascii):
    for name, value in env.items():
        monkeypatch.setenv(name, value)
    assert cli.main(argv) == 0
    assert launched[-1]["ascii"] is ascii
    if ascii:  # and what is printed after the app ends is ASCII too
        assert sys.stderr.encoding == "ascii"


def test_ascii_and_unicode_exclude_each_other(capsys):
    assert cli.main(["puma560", "--ascii", "--unicode"]) == 2
    err = capsys.readouterr().err
    assert "not allowed with" in err and len(err.strip().splitlines()) == 1
    assert cli.main(["--help"]) == 0
    assert "[--ascii | --unicode]" in capsys.readouterr().out


# -- the safety net: char for char, cell for cell ----------------------------------


@pytest.mark.parametrize(
    ("glyphs", "ascii"),
    [
        ("╭─╮│╰╯", "+-+|++"),  # round
        ("┏━┓┃┗┛", "+-+|++"),  # heavy
        ("╔═╗║╚╝", "+-+|++"),  # double
        ("┄┅┆┇┈┊╌╍╎╏", "--||-|--||"),  # dashed
        ("├┤┬┴┼╋", "++++++"),
        ("╱╲╳", "/\\X"),
        ("▁▄█▌▐░▒▓", "_=#||.:#"),
        ("⠀⠁⠃⠇⡇⣿", " ..::*"),  # braille by dots
        ("←→↑↓⇄", "<>^v="),
        ("◀▶▲▼", "<>^v"),
        ("…·●◆×°μµ⏎", "~.*@xouu<"),
        ("—–−", "---"),
        ("é Ü ²", "e U 2"),
        ("中文", "????"),  # wide: two cells each
        ("e\u0301\u200b", "e"),  # combining, zero width: nothing
        ("\x1b[1;31mok\x1b[0m\r\n", "\x1b[1;31mok\x1b[0m\r\n"),  # ASCII as it is
    ],
)
def test_glyphs_become_look_alikes(glyphs, ascii):
    assert to_ascii(glyphs) == ascii


def _characters(*ranges: tuple[int, int]) -> str:
    return "".join(chr(c) for low, high in ranges for c in range(low, high + 1))


CHARACTER_CLASSES = {
    "latin-1": _characters((0x80, 0xFF)),
    "general punctuation": _characters((0x2000, 0x206F)),
    "arrows": _characters((0x2190, 0x21FF)),
    "technical": _characters((0x2300, 0x23FF)),
    "box drawing": _characters((0x2500, 0x257F)),
    "block elements": _characters((0x2580, 0x259F)),
    "geometric shapes": _characters((0x25A0, 0x25FF)),
    "braille": _characters((0x2800, 0x28FF)),
    "greek": _characters((0x0370, 0x03FF)),
    "combining": _characters((0x0300, 0x036F)),
    "cjk": "中文字日本語한국어",
    "fullwidth": _characters((0xFF01, 0xFF20)),
    "emoji": "😀🤖⚠✓",
}


@pytest.mark.parametrize("name", sorted(CHARACTER_CLASSES))
def test_every_character_keeps_its_cell_width(name):
    for char in CHARACTER_CLASSES[name]:
        out = to_ascii(char)
        assert out.isascii() and out.isprintable(), (char, out)
        assert cell_len(out) == get_character_cell_size(char), (unicodedata.name(char, ""), out)


def test_emoji_presentation_and_joiners_keep_the_width_rich_measures():
    for text in ("⚠\ufe0f ok", "👨\u200d👩\u200d👧|", "a\ufe0f│", "#\ufe0f"):
        out = to_ascii(text)
        assert out.isascii() and cell_len(out) == cell_len(text), (text, out)


@given(st.text())
def test_any_text_comes_out_ascii(text):
    out = to_ascii(text)
    assert out.isascii()
    if text.isascii():
        assert out == text


@given(st.text())
def test_any_text_keeps_its_width(text):
    assume("\u200d" not in text and "\ufe0f" not in text)  # graphemes: checked above
    out = to_ascii(text)
    assert cell_len(out) == cell_len(text)
    assert to_ascii(out) == out


def test_words_at_the_source():
    assert ascii_text("↑↓ choose · enter picks…") == "up/down choose | enter picks..."
    assert ascii_text("OAT → roll/pitch/yaw → 4×4") == "OAT -> roll/pitch/yaw -> 4x4"
    assert ascii_text("90° μ ⇄ — ⏎") == "90 deg mu <-> - enter"
    assert ascii_key("↑↓") == "^/v" and ascii_key("←→") == "</>"
    assert ascii_key("^↑↓") == "^up/dn" and ascii_key("⏎") == "enter"
    assert ascii_key("^s") == "^s"


# -- the screens ---------------------------------------------------------------------


async def showing(pilot, kind: type) -> None:
    """Wait until a ``kind`` screen is in front, ready and drawn."""
    app = pilot.app
    await until(pilot, lambda: isinstance(app.screen, kind), kind.__name__)
    await until(pilot, lambda: getattr(app.screen, "_ready", True) and settled(app), kind.__name__)


async def test_the_screens_show_only_ascii_outside_the_views():
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False, ascii=True)
    async with app.run_test(size=(80, 24), notifications=True) as pilot:
        await showing(pilot, ControlScreen)
        await press(pilot, "right")
        assert non_ascii_outside_views(app) == []
        footer = app.screen._compositor.render_strips()[-1].text
        assert "^/v Joint" in footer and "q Quit" in footer  # fits 80 columns
        await press(pilot, "enter")  # a value entry: its box and its input's
        await showing(pilot, ValueEntry)
        assert non_ascii_outside_views(app) == []
        await press(pilot, "escape")
        await showing(pilot, ControlScreen)
        await press(pilot, "question_mark")
        await showing(pilot, HelpScreen)
        assert non_ascii_outside_views(app) == []
        await press(pilot, "escape")
        await showing(pilot, ControlScreen)
        await press(pilot, "e")
        await showing(pilot, EditorScreen)
        await press(pilot, "t")  # unsaved: the title's mark
        assert " * " in app.screen._compositor.render_strips()[0].text
        assert non_ascii_outside_views(app) == []
        await press(pilot, "tab", "down", "enter")  # a choice (units)
        await until(pilot, lambda: not isinstance(app.screen, EditorScreen), "the units choice")
        await until(pilot, lambda: settled(app), "the units choice drawn")
        assert non_ascii_outside_views(app) == []
        await press(pilot, "escape")
        await showing(pilot, EditorScreen)
        await press(pilot, "escape")  # leaving asks: save, discard, stay
        await showing(pilot, SaveGuard)
        assert non_ascii_outside_views(app) == []


async def test_ascii_scrollbars_have_no_partial_blocks():
    def bar_text() -> str:
        bar = ScrollBar.renderer.render_bar(size=10, virtual_size=35, window_size=10, position=3)
        return "".join(segment.text for segment in bar.segments)

    robot, path = load_robot("puma560")
    async with DhsimApp(robot, path, ascii=True).run_test(size=(80, 24)):
        assert bar_text().isascii()
    async with DhsimApp(robot, path).run_test(size=(80, 24)):
        assert not bar_text().isascii()  # Unicode apps in the same process: as before


# -- the real thing ------------------------------------------------------------------


@pytest.mark.skipif(shutil.which("stty") is None, reason="needs a POSIX terminal")
def test_under_lc_all_c_every_byte_on_the_terminal_is_ascii(tmp_path):
    env = {"LC_ALL": "C", "DHSIM_RECOVERY_DIR": str(tmp_path / "recovery")}
    with PtyScreen(["puma560"], env=env) as term:
        term.wait_for("Th1")
        term.send("right")
        term.wait_for(
            lambda screen: any("Th1" in row and "1.00" in row for row in screen.split("\n"))
        )
        term.send("?")
        term.wait_for("escape closes")
        term.send("escape")
        term.wait_for(lambda screen: "escape closes" not in screen)
        term.send("e")
        term.wait_for("D-H variable")
        term.send("escape")
        # back in the simulator, its frame drawn whole (it may arrive in several reads)
        screen = term.wait_for(
            lambda screen: (
                "D-H variable" not in screen and "+- Puma 560" in screen and "^/v Joint" in screen
            )
        )
        term.send("q")
        assert term.wait_exit() == 0
        raw = term.raw_bytes()
    assert "+- Puma 560" in screen and "^/v Joint" in screen
    bad = sorted({byte for byte in raw if byte >= 0x80})
    assert bad == [], f"{len(raw)} bytes, non-ASCII: {bad}"

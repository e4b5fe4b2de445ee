"""The real ``dhsim`` in a pseudo-terminal, under real signals.

Each test runs the installed console script (tests/pty_screen.py) on a copy of
a bundled robot, with its recovery folder in tmp_path, and reads the screen a
person would see (pyte) or the raw bytes the terminal got.
"""

from __future__ import annotations

import re
import shutil
import signal
from pathlib import Path

import pytest
from pty_screen import PtyScreen
from waiting import HANG

from dhsim_tui.core import load, load_robot
from dhsim_tui.core.files.recovery import write_recovery
from dhsim_tui.core.model.editing import toggle_type

pytestmark = pytest.mark.skipif(shutil.which("stty") is None, reason="needs a POSIX terminal")

#: the editor's title once the robot has unsaved changes
DIRTY = "Puma 560 ●"
MOUSE_MODES = (b"1000", b"1003", b"1015", b"1006")


@pytest.fixture
def robot_file(tmp_path: Path) -> Path:
    _, bundled = load_robot("puma560")
    copy = tmp_path / "puma.toml"
    shutil.copyfile(bundled, copy)
    return copy


@pytest.fixture
def recovery_env(tmp_path: Path) -> dict[str, str]:
    return {"DHSIM_RECOVERY_DIR": str(tmp_path / "recovery")}


def recovery_files(env: dict[str, str]) -> list[Path]:
    folder = Path(env["DHSIM_RECOVERY_DIR"])
    return sorted(folder.glob("*.toml")) if folder.is_dir() else []


def edit_with_a_change(robot_file: Path, env: dict[str, str]) -> PtyScreen:
    """``dhsim edit`` on the robot, with joint 1 toggled to prismatic (unsaved)."""
    term = PtyScreen(["edit", str(robot_file)], env=env)
    term.wait_for("* D-H variable")
    term.send("t")
    term.wait_for(DIRTY)
    return term


def test_sighup_keeps_the_changes_and_the_next_start_offers_them(robot_file, recovery_env):
    before = robot_file.read_bytes()
    with edit_with_a_change(robot_file, recovery_env) as term:
        term.kill(signal.SIGHUP)
        assert term.wait_exit() == 128 + signal.SIGHUP
    assert robot_file.read_bytes() == before  # the file is never touched
    [kept] = recovery_files(recovery_env)
    assert load(kept).joints[0].type == "prismatic"  # a robot file a person can read, too

    with PtyScreen(["edit", str(robot_file)], env=recovery_env) as term:
        term.wait_for("Restore unsaved changes from")
        term.send("enter")  # restore (the first choice)
        shown = term.wait_for(DIRTY)
        assert re.search(r"│ 1 +P ", shown), shown  # the recovered robot, marked unsaved
        assert not recovery_files(recovery_env)  # its changes now live in the editor
        term.send("ctrl+q")
        term.wait_for("Save before")
        term.send("d")
        assert term.wait_exit() == 0
    assert robot_file.read_bytes() == before


def test_a_real_hang_up_keeps_the_changes(robot_file, recovery_env):
    """The terminal is gone (master closed): every write fails; the recovery
    is written first and the process still ends."""
    before = robot_file.read_bytes()
    term = edit_with_a_change(robot_file, recovery_env)
    try:
        term.hang_up()
        assert term.wait_exit() == 128 + signal.SIGHUP
    finally:
        term.close()
    assert robot_file.read_bytes() == before
    [kept] = recovery_files(recovery_env)
    assert load(kept).joints[0].type == "prismatic"


def test_later_keeps_the_recovery_and_discard_deletes_it(robot_file, recovery_env, monkeypatch):
    monkeypatch.setenv("DHSIM_RECOVERY_DIR", recovery_env["DHSIM_RECOVERY_DIR"])
    write_recovery(toggle_type(load(robot_file), 0), robot_file)  # as a stopped dhsim would
    with PtyScreen([str(robot_file)], env=recovery_env) as term:  # plain `dhsim ROBOT`
        term.wait_for("Restore unsaved changes from")
        term.send("escape")  # decide later
        term.wait_for(lambda screen: "Restore" not in screen and "Th1" in screen)
        term.send("q")
        assert term.wait_exit() == 0
    assert len(recovery_files(recovery_env)) == 1
    with PtyScreen([str(robot_file)], env=recovery_env) as term:
        term.wait_for("Restore unsaved changes from")
        term.send("down", "enter")  # discard
        term.wait_for(lambda screen: "Restore" not in screen and "Th1" in screen)
        term.send("q")
        assert term.wait_exit() == 0
    assert not recovery_files(recovery_env)


def _last(raw: bytes, sequence: bytes) -> int:
    return raw.rfind(sequence)


def test_sigterm_gives_the_terminal_back(robot_file, recovery_env):
    with edit_with_a_change(robot_file, recovery_env) as term:
        term.kill(signal.SIGTERM)
        assert term.wait_exit() == 128 + signal.SIGTERM
        raw = term.raw_bytes()
    assert _last(raw, b"\x1b[?1049h") >= 0  # it was in the alternate screen ...
    assert _last(raw, b"\x1b[?1049l") > _last(raw, b"\x1b[?1049h")  # ... and left it
    for mode in MOUSE_MODES:  # mouse reporting was on, and is off at the end
        assert _last(raw, b"\x1b[?" + mode + b"l") > _last(raw, b"\x1b[?" + mode + b"h") >= 0
    assert _last(raw, b"\x1b[?25h") > _last(raw, b"\x1b[?25l")  # the cursor is visible
    tail = raw[_last(raw, b"\x1b[?1049l") :].decode()
    # nothing drawn after it: only where the unsaved changes were kept, as plain text
    [kept] = recovery_files(recovery_env)
    assert tail.startswith("\x1b[?1049l\x1b[?25h"), tail
    assert "\x1b" not in tail.removeprefix("\x1b[?1049l\x1b[?25h"), tail
    assert f"dhsim: SIGTERM: unsaved changes to Puma 560 ({robot_file}) kept in {kept}" in tail


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGQUIT], ids=["TERM", "QUIT"])
def test_without_changes_the_terminal_comes_back_and_nothing_is_kept(
    robot_file, recovery_env, signum
):
    with PtyScreen([str(robot_file)], env=recovery_env) as term:
        term.wait_for("Th1")
        term.kill(signum)
        assert term.wait_exit() == 128 + signum
        raw = term.raw_bytes()
    assert raw.rstrip().endswith(b"\x1b[?1049l\x1b[?25h")
    assert not recovery_files(recovery_env)


def test_ctrl_c_and_sigint_ask_about_unsaved_changes(robot_file, recovery_env):
    before = robot_file.read_bytes()
    with edit_with_a_change(robot_file, recovery_env) as term:
        term.send("ctrl+c")
        term.wait_for("Save before")
        term.send("escape")  # stay
        term.wait_for(lambda screen: "Save before" not in screen and DIRTY in screen)
        term.kill(signal.SIGINT)  # `kill -INT`: the same question, not a lost edit
        term.wait_for("Save before")
        term.send("d")
        assert term.wait_exit() == 0
    assert robot_file.read_bytes() == before
    assert not recovery_files(recovery_env)


def test_an_unexpected_error_exits_non_zero_and_keeps_the_changes(
    robot_file, recovery_env, tmp_path
):
    """A bug (injected from outside: ``?`` in the editor raises) ends dhsim with
    status 1, not 0, after writing the unsaved changes to a recovery file."""
    inject = tmp_path / "inject"
    inject.mkdir()
    (inject / "sitecustomize.py").write_text(
        "from dhsim_tui.tui.screens.editor import EditorScreen\n"
        "def broken(self):\n"
        "    raise RuntimeError('injected fault')\n"
        "EditorScreen.action_help = broken\n"
    )
    env = {**recovery_env, "PYTHONPATH": str(inject)}
    with edit_with_a_change(robot_file, env) as term:
        term.send("?")
        assert term.wait_exit() == 1
    [kept] = recovery_files(recovery_env)
    assert load(kept).joints[0].type == "prismatic"


def test_stop_and_cont_never_hang_q(robot_file, recovery_env):
    """Textual's SIGCONT handler started a second input thread; ``q`` then hung
    joining whichever of the two was blocked reading (about half the tries).
    Ten tries at once: five processes get STOP then CONT, five a lone CONT,
    twice each; every one must still draw its screen again and quit on ``q``."""
    terms = [PtyScreen([str(robot_file)], env=recovery_env) for _ in range(10)]
    stopped = terms[:5]
    # the ten share the machine: the first of them to draw may wait for all ten
    together = len(terms) * HANG
    try:
        for term in terms:
            term.wait_for("Th1", timeout=together)
        for _ in range(2):
            for term in stopped:
                term.kill(signal.SIGSTOP)
            for term in stopped:  # a stop still pending when CONT comes is dropped
                term.wait_stopped()
            for term in terms:
                term.clear_screen()
                term.kill(signal.SIGCONT)
            for term in terms:  # after a continue, the screen is drawn again
                term.wait_for("Th1", timeout=together)
        for term in terms:
            term.send("q")
        for term in terms:
            assert term.wait_exit(timeout=together) == 0
    finally:
        for term in terms:
            term.close()

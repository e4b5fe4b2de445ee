"""Stop and continue, in any order and at any spacing, never leave dhsim
stopped, deaf or unkillable.

The fault campaign: a SIGCONT within about 0.1 s of a SIGTSTP left dhsim
stopped (4 of 14); after TSTP/CONT cycles 5 of 32 processes outlived their
terminal, ignored SIGTERM and waited on a lock until killed, one with an
unsaved edit. Here every spacing the campaign used is tried on purpose (the
gaps between the signals are the subject of the tests, not a wait for
something), and after each sequence dhsim must draw again and take keys, and
a hang-up or SIGTERM must keep the unsaved edit and end the process.
"""

from __future__ import annotations

import re
import shutil
import signal
import subprocess
import time
from pathlib import Path

import pytest
from pty_screen import PtyScreen
from waiting import HANG, wait_until

from dhsim_tui.core import load, load_robot

pytestmark = pytest.mark.skipif(shutil.which("stty") is None, reason="needs a POSIX terminal")

#: seconds between SIGTSTP and SIGCONT: at once, within the campaign's 0.1 s, after it
GAPS = (0.0, 0.002, 0.01, 0.03, 0.06, 0.1, 0.2)
DIRTY = "Puma 560 ●"


@pytest.fixture
def robot_file(tmp_path: Path) -> Path:
    copy = tmp_path / "puma.toml"
    shutil.copyfile(load_robot("puma560")[1], copy)
    return copy


@pytest.fixture
def env(tmp_path: Path) -> dict[str, str]:
    return {"DHSIM_RECOVERY_DIR": str(tmp_path / "recovery")}


def kept(env: dict[str, str]) -> list[Path]:
    folder = Path(env["DHSIM_RECOVERY_DIR"])
    return sorted(folder.glob("*.toml")) if folder.is_dir() else []


#: dhsim gives the screen back (alternate screen off), and the last thing it
#: writes when it takes the terminal again, in raw mode with its key thread
#: running (bracketed paste on)
LEAVE, READY = b"\x1b[?1049l", b"\x1b[?2004h"


def stop_and_continue(term: PtyScreen, gap: float) -> None:
    """SIGTSTP, ``gap`` seconds, SIGCONT (the spacing is the point); then
    wait until dhsim runs and holds the terminal again: every time it gave
    the screen back since the SIGTSTP, it took it again, raw mode and all (a
    key typed while it suspends is flushed with the terminal's input, as
    Textual does; one typed before raw mode is back is the terminal's, cooked)."""
    mark = len(term.raw_bytes())
    term.kill(signal.SIGTSTP)
    if gap:
        time.sleep(gap)
    term.kill(signal.SIGCONT)

    def running_again() -> bool:
        since = term.raw_bytes()[mark:]
        left = since.rfind(LEAVE)
        return not stopped(term) and (left == -1 or since.rfind(READY) > left)

    wait_until(running_again, "dhsim to run and take the terminal again after the CONT")


def stopped(term: PtyScreen) -> bool:
    """The process is stopped now (its state, not a one-off stop report)."""
    try:
        stat = Path(f"/proc/{term.proc.pid}/stat").read_text()
    except OSError:  # no /proc: what ps says
        state = subprocess.run(
            ["ps", "-o", "stat=", "-p", str(term.proc.pid)], capture_output=True, text=True
        )
        return state.stdout.strip().startswith("T")
    return stat.rpartition(")")[2].split()[0] in ("T", "t")


def th1(term: PtyScreen) -> float | None:
    """Joint 1's value as shown (None while it is not on the screen)."""
    for row in term.screen_text().splitlines():
        if "Th1" in row:
            found = re.search(r"(-?\d+\.\d+)°", row)
            return float(found.group(1)) if found else None
    return None


def takes_keys_again(term: PtyScreen) -> float:
    """dhsim takes keys again: ``right`` steps joint 1. A key typed within
    about 0.1 s of the terminal coming back can be lost in Textual's resume
    (seen with and without dhsim's handlers; the docs say so), so the first
    step is retried until it lands (each try waits, as a person would, for
    the step to show); the value it reached."""
    before = th1(term)
    deadline = time.monotonic() + HANG
    while time.monotonic() < deadline:
        term.send("right")
        try:
            term.wait_for(lambda _: (th1(term) or 0.0) > (before or 0.0), timeout=1.0)
        except AssertionError:
            continue
        return th1(term)
    raise AssertionError(f"hung: dhsim took no key for {HANG:g} s after a continue")


@pytest.mark.parametrize("gap", GAPS)
def test_a_continue_at_any_gap_after_a_stop_leaves_dhsim_running(robot_file, env, gap):
    with PtyScreen([str(robot_file)], env=env) as term:
        term.wait_for("Th1")
        for _ in range(3):
            stop_and_continue(term, gap)
            reached = takes_keys_again(term)
            # once it takes keys, every key counts
            term.send("right", "right")
            term.wait_for(lambda _, reached=reached: th1(term) == reached + 2.0)
        term.send("q")
        assert term.wait_exit() == 0


@pytest.mark.parametrize("ending", ["SIGTERM", "SIGHUP", "hang-up"])
def test_after_stops_and_continues_an_ending_keeps_the_edit_and_exits(robot_file, env, ending):
    before = robot_file.read_bytes()
    term = PtyScreen(["edit", str(robot_file)], env=env)
    try:
        term.wait_for("* D-H variable")
        term.send("t")  # joint 1 to prismatic: an unsaved change
        term.wait_for(DIRTY)
        for gap in GAPS:
            stop_and_continue(term, gap)
        if ending == "hang-up":
            term.hang_up()
        else:
            term.kill(getattr(signal, ending))
        code = term.wait_exit()
        expected = {"SIGTERM": 128 + signal.SIGTERM}.get(ending, 128 + signal.SIGHUP)
        assert code == expected
    finally:
        term.close()
    assert robot_file.read_bytes() == before
    [recovered] = kept(env)
    assert load(recovered).joints[0].type == "prismatic"


def test_a_stop_while_stopped_and_a_burst_of_continues_leave_it_running(robot_file, env):
    with PtyScreen([str(robot_file)], env=env) as term:
        term.wait_for("Th1")
        term.kill(signal.SIGTSTP)
        term.wait_stopped(timeout=HANG)
        term.kill(signal.SIGTSTP)  # stopped already: pending until the continue
        for _ in range(5):
            term.kill(signal.SIGCONT)
        wait_until(lambda: not stopped(term), "dhsim to run again")
        takes_keys_again(term)
        term.send("q")
        assert term.wait_exit() == 0

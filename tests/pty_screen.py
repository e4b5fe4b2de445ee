"""Run the real ``dhsim`` console script in a pseudo-terminal and read its screen.

``PtyScreen`` spawns the installed ``dhsim`` script (the one beside the running
interpreter, so the test runs what a user runs) with ptyprocess at a given
size, reads everything it writes on a background thread, keeps the raw bytes
(to check escape sequences) and feeds them into a pyte screen (to check what a
person would see).

Nothing here waits for a time: ``wait_for`` polls the screen for what the test
expects, ``wait_exit`` the process for its end, ``wait_stopped`` for a stop.
Each gives up only after :data:`waiting.HANG`, a timeout that catches a hang
and nothing else, so the tests are as fast as the machine allows and pass
however slow (or busy) it is.

The child's environment is the test process's (``os.environ``, which
tests/conftest.py has made the same on every machine: its own HOME and XDG
folders, LANG=C.UTF-8, no LC_ALL or NO_COLOR), with TERM, the size and a
UTF-8 locale set here; a test that wants another (``LC_ALL=C``, ``NO_COLOR=1``,
``TERM=xterm``) passes it in ``env``.
"""

from __future__ import annotations

import os
import select
import shutil
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

import pyte
from ptyprocess import PtyProcess
from waiting import HANG, POLL

#: the pause after each key ``send`` types (s): input paced as a person types,
#: so the app reads keys one at a time as it does from a person, not in one
#: burst. Pacing only: no test relies on it to tell keys apart (a loaded
#: machine may still deliver several in one read), and none sends ``escape``
#: followed by another key in one call (that pair reads as alt+key).
KEY_GAP = 0.02

KEYS = {
    "enter": "\r",
    "escape": "\x1b",
    "tab": "\t",
    "up": "\x1b[A",
    "down": "\x1b[B",
    "right": "\x1b[C",
    "left": "\x1b[D",
    "ctrl+c": "\x03",
    "ctrl+p": "\x10",
    "ctrl+q": "\x11",
    "ctrl+s": "\x13",
    "ctrl+u": "\x15",
}


def dhsim_command() -> str:
    """The installed ``dhsim`` script of the interpreter running the tests."""
    beside = Path(sys.executable).parent / "dhsim"
    if beside.exists():
        return str(beside)
    found = shutil.which("dhsim")
    if found is None:
        raise RuntimeError("the dhsim console script is not installed (pip install -e .)")
    return found


class PtyScreen:
    """A ``dhsim`` process in a pseudo-terminal of ``size`` (columns, rows).

    ``command`` runs another program instead of the ``dhsim`` script (a
    Python script that starts the app with a fault injected, say); ``args``
    follow it."""

    def __init__(
        self,
        args: Sequence[str] = (),
        size: tuple[int, int] = (80, 24),
        env: Mapping[str, str] | None = None,
        cwd: str | os.PathLike[str] | None = None,
        command: Sequence[str] | None = None,
    ) -> None:
        columns, rows = size
        full_env = dict(os.environ)
        full_env.update({"TERM": "xterm-256color", "COLUMNS": str(columns), "LINES": str(rows)})
        # a UTF-8 terminal unless the test says otherwise: CI may have no locale at all
        # (tests/conftest.py does the same for the whole run; bench/monkey.py has no conftest)
        for name in ("LC_ALL", "LC_CTYPE", "LANG"):
            full_env.pop(name, None)
        full_env["LANG"] = "C.UTF-8"
        full_env.pop("TEXTUAL_ALLOW_SIGNALS", None)
        full_env.update(env or {})
        self.screen = pyte.Screen(columns, rows)
        self._stream = pyte.ByteStream(self.screen)
        self._lock = threading.Lock()
        self.raw = bytearray()
        self._stop = threading.Event()
        program = list(command) if command is not None else [dhsim_command()]
        self.proc = PtyProcess.spawn(
            [*program, *args],
            env=full_env,
            cwd=str(cwd) if cwd is not None else None,
            dimensions=(rows, columns),
        )
        self._reader = threading.Thread(target=self._read, name="pty-reader", daemon=True)
        self._reader.start()

    # -- reading --------------------------------------------------------------------
    def _read(self) -> None:
        # select with a timeout, not a blocking read: hang_up() must be able to
        # stop this thread before it closes the terminal's master side (the
        # timeout is how often it looks at that flag, not a wait for anything)
        while not self._stop.is_set():
            try:
                ready, _, _ = select.select([self.proc.fd], [], [], 0.05)
                if not ready:
                    continue
                data = self.proc.read(65536)
            except (EOFError, OSError, ValueError):  # EIO: the child's side is closed
                return
            with self._lock:
                self.raw.extend(data)
                self._stream.feed(data)

    def _finished(self) -> bool:
        """The process has ended and everything it wrote has been read."""
        return not self.proc.isalive() and not self._reader.is_alive()

    @property
    def pid(self) -> int:
        return self.proc.pid

    def screen_text(self) -> str:
        """The screen as a person reads it, one line per row."""
        with self._lock:
            return "\n".join(line.rstrip() for line in self.screen.display)

    def raw_bytes(self) -> bytes:
        with self._lock:
            return bytes(self.raw)

    def wait_for(self, text: str | Callable[[str], bool], timeout: float = HANG) -> str:
        """Wait until ``text`` is on the screen (or the predicate holds); the screen.
        Fails at once if dhsim ends without showing it, and after ``timeout``
        (a hang) if it never does."""
        check = text if callable(text) else (lambda screen: text in screen)
        deadline = time.monotonic() + timeout
        while True:
            finished = self._finished()  # before reading: then the screen is its last
            shown = self.screen_text()
            if check(shown):
                return shown
            if finished:
                raise AssertionError(f"dhsim exited waiting for {text!r}; the screen:\n{shown}")
            if time.monotonic() > deadline:
                raise AssertionError(
                    f"hung: waited {timeout:g} s for {text!r}; the screen:\n{shown}"
                )
            time.sleep(POLL)

    # -- writing --------------------------------------------------------------------
    def send(self, *keys: str) -> None:
        """Type keys: names from KEYS (``"enter"``, ``"ctrl+c"``) or literal text."""
        for key in keys:
            self.proc.write(KEYS.get(key, key).encode())
            time.sleep(KEY_GAP)  # pacing, as a person types (see KEY_GAP)

    def kill(self, signum: int) -> None:
        os.kill(self.proc.pid, signum)

    def wait_stopped(self, timeout: float = HANG) -> None:
        """Wait until the process is stopped (after SIGSTOP or SIGTSTP). A stop
        signal not yet acted on when SIGCONT comes is discarded, so a test that
        means "stopped, then continued" waits for the stop before continuing.
        Reads the stop with ``waitid(WSTOPPED)``, which never reaps an exit
        (ptyprocess keeps that for ``wait_exit``)."""
        deadline = time.monotonic() + timeout
        while not self._stopped():
            if not self.proc.isalive():
                raise AssertionError(
                    f"dhsim exited instead of stopping; the screen:\n{self.screen_text()}"
                )
            if time.monotonic() > deadline:
                raise AssertionError(f"hung: waited {timeout:g} s for dhsim to stop")
            time.sleep(POLL)

    def _stopped(self) -> bool:
        if hasattr(os, "waitid"):
            stop = os.waitid(os.P_PID, self.proc.pid, os.WSTOPPED | os.WNOHANG)
            return stop is not None and stop.si_code == os.CLD_STOPPED
        # no waitid (macOS before Python 3.13): what ps says, T for stopped
        state = subprocess.run(
            ["ps", "-o", "stat=", "-p", str(self.proc.pid)], capture_output=True, text=True
        )
        return state.stdout.strip().startswith("T")

    def hang_up(self) -> None:
        """What a dropped SSH connection does: close the terminal's master side.
        The kernel sends SIGHUP, and every write to the terminal fails from then on."""
        self._stop.set()
        self._join_reader()
        self.proc.fileobj.close()

    def clear_screen(self) -> None:
        """Forget what is drawn (to see whether the app draws it again)."""
        with self._lock:
            self.screen.reset()

    # -- ending ---------------------------------------------------------------------
    def _join_reader(self) -> None:
        """The reader ends within a select timeout once stopped or once the
        child's side is closed; HANG only turns a stuck one into a failure."""
        self._reader.join(timeout=HANG)
        if self._reader.is_alive():
            raise AssertionError(f"hung: the pseudo-terminal reader did not end in {HANG:g} s")

    def wait_exit(self, timeout: float = HANG) -> int:
        """Wait for the process to end; its exit status (128 + signal if killed).
        Everything it wrote is in ``raw_bytes()`` and on the screen by then.
        Raises AssertionError if it is still running after ``timeout`` (a hang)."""
        deadline = time.monotonic() + timeout
        while self.proc.isalive():
            if time.monotonic() > deadline:
                raise AssertionError(
                    f"hung: dhsim still running after {timeout:g} s; the screen:\n"
                    f"{self.screen_text()}"
                )
            time.sleep(POLL)
        self._join_reader()
        if self.proc.signalstatus is not None:
            return 128 + self.proc.signalstatus
        return self.proc.exitstatus

    def close(self) -> None:
        """Make sure nothing is left running (tests call this in a finally)."""
        self._stop.set()
        if self.proc.isalive():
            try:
                os.kill(self.proc.pid, signal.SIGCONT)
                os.kill(self.proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            self.proc.wait()
        self._reader.join(timeout=HANG)  # no raise: close runs in a finally
        if not self.proc.closed:
            self.proc.close(force=True)

    def __enter__(self) -> PtyScreen:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

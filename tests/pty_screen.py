"""Run the real ``dhsim`` console script in a pseudo-terminal and read its screen.

``PtyScreen`` spawns the installed ``dhsim`` script (the one beside the running
interpreter, so the test runs what a user runs) with ptyprocess at a given
size, reads everything it writes on a background thread, keeps the raw bytes
(to check escape sequences) and feeds them into a pyte screen (to check what a
person would see). ``wait_for`` polls the screen instead of sleeping, so the
tests are as fast as the machine allows and robust when it is slow.
"""

from __future__ import annotations

import os
import select
import shutil
import signal
import sys
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

import pyte
from ptyprocess import PtyProcess

#: how long to wait for the app to draw something, by default (slow, shared CI machines)
DEFAULT_TIMEOUT = 15.0

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
    """A ``dhsim`` process in a pseudo-terminal of ``size`` (columns, rows)."""

    def __init__(
        self,
        args: Sequence[str] = (),
        size: tuple[int, int] = (80, 24),
        env: Mapping[str, str] | None = None,
        cwd: str | os.PathLike[str] | None = None,
    ) -> None:
        columns, rows = size
        full_env = dict(os.environ)
        full_env.update({"TERM": "xterm-256color", "COLUMNS": str(columns), "LINES": str(rows)})
        # a UTF-8 terminal unless the test says otherwise: CI may have no locale at all
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
        self.proc = PtyProcess.spawn(
            [dhsim_command(), *args],
            env=full_env,
            cwd=str(cwd) if cwd is not None else None,
            dimensions=(rows, columns),
        )
        self._reader = threading.Thread(target=self._read, name="pty-reader", daemon=True)
        self._reader.start()

    # -- reading --------------------------------------------------------------------
    def _read(self) -> None:
        # select with a timeout, not a blocking read: hang_up() must be able to
        # stop this thread before it closes the terminal's master side
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

    def wait_for(self, text: str | Callable[[str], bool], timeout: float = DEFAULT_TIMEOUT) -> str:
        """Wait until ``text`` is on the screen (or the predicate holds); the screen."""
        check = text if callable(text) else (lambda screen: text in screen)
        deadline = time.monotonic() + timeout
        while True:
            shown = self.screen_text()
            if check(shown):
                return shown
            if time.monotonic() > deadline:
                raise AssertionError(
                    f"timed out after {timeout} s waiting for {text!r}; the screen:\n{shown}"
                )
            if not self.proc.isalive() and not self._reader.is_alive():
                raise AssertionError(f"dhsim exited waiting for {text!r}; the screen:\n{shown}")
            time.sleep(0.05)

    # -- writing --------------------------------------------------------------------
    def send(self, *keys: str) -> None:
        """Type keys: names from KEYS (``"enter"``, ``"ctrl+c"``) or literal text."""
        for key in keys:
            self.proc.write(KEYS.get(key, key).encode())
            time.sleep(0.02)  # one read per key, as a person types

    def kill(self, signum: int) -> None:
        os.kill(self.proc.pid, signum)

    def hang_up(self) -> None:
        """What a dropped SSH connection does: close the terminal's master side.
        The kernel sends SIGHUP, and every write to the terminal fails from then on."""
        self._stop.set()
        self._reader.join(timeout=5)
        self.proc.fileobj.close()

    def clear_screen(self) -> None:
        """Forget what is drawn (to see whether the app draws it again)."""
        with self._lock:
            self.screen.reset()

    # -- ending ---------------------------------------------------------------------
    def wait_exit(self, timeout: float = DEFAULT_TIMEOUT) -> int:
        """Wait for the process to end; its exit status (128 + signal if killed).
        Raises AssertionError if it is still running after ``timeout``."""
        deadline = time.monotonic() + timeout
        while self.proc.isalive():
            if time.monotonic() > deadline:
                raise AssertionError(
                    f"dhsim still running after {timeout} s; the screen:\n{self.screen_text()}"
                )
            time.sleep(0.05)
        self._reader.join(timeout=5)
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
        self._reader.join(timeout=5)
        if not self.proc.closed:
            self.proc.close(force=True)

    def __enter__(self) -> PtyScreen:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

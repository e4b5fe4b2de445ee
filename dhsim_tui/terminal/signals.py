"""The terminal and POSIX signals: nothing lost, nothing left behind, nothing hung.

Two things Textual 8 does not do for us:

* **SIGHUP, SIGTERM, SIGQUIT** (a dropped SSH connection, ``kill``) end the
  process without restoring the terminal (it stays in the alternate screen
  with mouse reporting on) and without a word about unsaved work.
  :class:`SignalGuard` first writes the unsaved work (a callback the app gives,
  run in the signal handler, which touches no lock), then, from a thread that
  was started beforehand, stops Textual's output thread, writes the sequences
  that give the terminal back, restores its modes and ends the process with
  status 128 + the signal's number. The terminal may be gone (after SIGHUP):
  every write is bounded by a timeout, so it can never hang the exit.

* **SIGINT** (``kill -INT``; ctrl+c itself is a key in the app's raw mode)
  ended the app at once, dropping unsaved work: it now asks the app to quit,
  through the same unsaved-changes question as ``q``, ctrl+q and ctrl+c.

* **SIGTSTP and SIGCONT** (``kill -TSTP``, job control): Textual suspends in
  the signal handler itself, wherever the handler interrupted the app (the
  writer's queue lock held, a thread being joined), then stops the process
  with SIGSTOP. A SIGCONT that came while it was suspending was spent before
  the stop, so the process stayed stopped (4 of 14 in a fault campaign with
  0.1 s between the two), and a later SIGTERM's exit waited for ever on the
  lock the interrupted code held. Here both handlers only note the signal and
  hand the work to the event loop: the suspend runs at a safe point, and the
  stop is skipped when a SIGCONT has come since the SIGTSTP.

* **SIGCONT** without a SIGTSTP before it (``kill -STOP`` then ``kill -CONT``,
  or a lone ``kill -CONT``): Textual's handler restarts application mode from
  the signal handler although it never stopped, which starts a second input
  thread on the same terminal. Both wait for input; one reads the next key and
  the other blocks in ``read()`` for ever, so ``q`` hangs joining it (about half
  the time: whichever thread wins the key). :class:`DhsimDriver` only restarts
  application mode when it really was suspended; otherwise it re-applies the
  terminal's modes and repaints, from the event loop rather than the handler.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import select
import signal
import sys
import termios
import threading
import tty
from collections.abc import Callable

from textual.app import App
from textual.drivers.linux_driver import LinuxDriver

from dhsim_tui.terminal.ascii_table import to_ascii
from dhsim_tui.terminal.charset import ascii_mode, ascii_text
from dhsim_tui.terminal.sgr import compact

#: signals that end dhsim after keeping unsaved work
EXIT_SIGNALS = (signal.SIGHUP, signal.SIGTERM, signal.SIGQUIT)
#: what gives the terminal back: abort any half-written sequence (CAN), end a
#: synchronized update, pop the kitty keyboard mode, mouse reporting off, bracketed
#: paste and focus events off, line wrap on, leave the alternate screen, cursor on
RESTORE_SEQUENCE = (
    "\x18"
    "\x1b[?2026l"
    "\x1b[<u"
    "\x1b[?1000l\x1b[?1003l\x1b[?1015l\x1b[?1006l\x1b[?1016l"
    "\x1b[?2004l"
    "\x1b[?1004l"
    "\x1b[?2048l"
    "\x1b[?7h"
    "\x1b[?1049l"
    "\x1b[?25h"
)
#: at most this long for Textual's output thread to finish what it was writing
WRITER_TIMEOUT = 0.5
#: at most this long for the terminal to accept the restoring bytes
TERMINAL_TIMEOUT = 0.5


class DhsimDriver(LinuxDriver):
    """Textual's Linux driver, with a SIGCONT that never starts a second input
    thread, and, for an app in ASCII mode, only 7-bit ASCII on the terminal."""

    _loop: asyncio.AbstractEventLoop | None = None

    def write(self, data: str) -> None:
        """In ASCII mode every character the app draws passes through
        :func:`to_ascii` (same cell width): the guarantee that no byte >= 0x80
        reaches the terminal, whatever a widget drew. Then :func:`compact`
        drops the colour codes that change nothing (fewer bytes a key)."""
        if ascii_mode(self._app):
            data = to_ascii(data)
        super().write(compact(data))

    #: SIGCONTs seen (counted in the handler itself, so a suspend can tell
    #: whether one came since the SIGTSTP it answers)
    _continues = 0
    _suspended_by_us = False

    def start_application_mode(self) -> None:
        self._loop = loop = asyncio.get_running_loop()
        super().start_application_mode()
        # Textual sets the handlers with signal.signal. A signal the kernel
        # hands to one of Textual's threads then runs its Python handler only
        # when the main thread next wakes, and an idle app sleeps in epoll with
        # nothing to wake it: a continued dhsim sometimes never repainted.
        # Registering them with the loop sets its wakeup fd, which wakes it at
        # once for every signal handled in Python (hang-up and terminate
        # included); the handlers proper are then set back to the driver's own,
        # which run at the next bytecode and only note the signal.
        for signum in (signal.SIGTSTP, signal.SIGCONT):
            with contextlib.suppress(RuntimeError, ValueError, NotImplementedError):
                loop.add_signal_handler(signum, _nothing)
        with contextlib.suppress(ValueError):
            signal.signal(signal.SIGTSTP, self._sigtstp_application)
            signal.signal(signal.SIGCONT, self._sigcont_application)

    def stop_application_mode(self) -> None:
        loop = self._loop
        if loop is not None and not loop.is_closed() and not self._suspended_by_us:
            for signum in (signal.SIGTSTP, signal.SIGCONT):
                with contextlib.suppress(RuntimeError, ValueError, NotImplementedError):
                    loop.remove_signal_handler(signum)
            with contextlib.suppress(ValueError):
                signal.signal(signal.SIGTSTP, self._sigtstp_application)
                signal.signal(signal.SIGCONT, self._sigcont_application)
        super().stop_application_mode()

    def _input_running(self) -> bool:
        return self._key_thread is not None and self._key_thread.is_alive()

    # -- the handlers: note the signal, hand the work to the loop ------------------
    def _sigtstp_application(self, *_) -> None:
        seen = self._continues
        if not self._call_in_loop(self._suspend_and_stop, seen):
            os.kill(os.getpid(), signal.SIGSTOP)  # no loop (yet, or any more): stop as asked

    def _sigcont_application(self, *_) -> None:
        self._continues += 1
        self._call_in_loop(self._continued)

    def _call_in_loop(self, callback, *args) -> bool:
        loop = self._loop
        if loop is None or loop.is_closed():
            return False
        try:
            loop.call_soon_threadsafe(callback, *args)
        except RuntimeError:  # closed meanwhile
            return False
        return True

    def _suspend_and_stop(self, continues_at_stop: int) -> None:
        """SIGTSTP, from the loop: give the terminal back, stop, and on
        SIGCONT take it again. Not stopped at all when a SIGCONT came since
        the SIGTSTP (it would have been spent: nothing would wake us)."""
        if self._continues != continues_at_stop:
            return  # continued before we got here: nothing to do
        if not self._auto_restart:  # App.suspend(): whoever suspended resumes
            os.kill(os.getpid(), signal.SIGSTOP)
            return
        if not self._input_running():
            return  # not in application mode: nothing to give back
        self._suspended_by_us = True
        try:
            self.suspend_application_mode()
            if self._continues == continues_at_stop:
                os.kill(os.getpid(), signal.SIGSTOP)
        finally:
            self._suspended_by_us = False
        self._must_signal_resume = True
        self.resume_application_mode()

    def _continued(self) -> None:
        """SIGCONT, from the loop: after our own stop the suspend above
        resumed; after a ``kill -STOP`` (no SIGTSTP) the terminal's modes are
        put back and everything repainted."""
        if self._auto_restart and self._input_running():
            self.reassert_terminal()

    def reassert_terminal(self) -> None:
        """After a stop: the shell may have reset the terminal and drawn over
        the screen. Put the modes back and repaint everything."""
        if not self._input_running() or self._writer_thread is None:
            return
        if os.isatty(self.fileno):
            with contextlib.suppress(termios.error):
                attrs = termios.tcgetattr(self.fileno)
                attrs[tty.LFLAG] = self._patch_lflag(attrs[tty.LFLAG])
                attrs[tty.IFLAG] = self._patch_iflag(attrs[tty.IFLAG])
                attrs[tty.CC][termios.VMIN] = 1
                termios.tcsetattr(self.fileno, termios.TCSANOW, attrs)
        self.write("\x1b[?1049h\x1b[?25l\x1b[?1004h\x1b[?2004h\x1b[?7l")
        self._enable_mouse_support()
        self.flush()
        self._app.refresh(layout=True)


def _nothing() -> None:
    """A loop signal callback that does nothing (the Python handler acts)."""


def terminal_fd() -> int | None:
    """The file descriptor Textual draws on (it writes to stderr)."""
    stream = sys.__stderr__
    try:
        return stream.fileno() if stream is not None else None
    except (OSError, ValueError):
        return None


def _bounded(work: Callable[[], object], timeout: float) -> None:
    """Run ``work`` for at most ``timeout`` seconds, on a thread of its own:
    a queue's ``put`` takes its lock with no timeout, and the code a signal
    interrupted may hold that lock for ever."""
    thread = threading.Thread(target=_quietly, args=(work,), name="dhsim-bounded", daemon=True)
    with contextlib.suppress(RuntimeError):  # no thread can start now: skip it
        thread.start()
        thread.join(timeout)


def _quietly(work: Callable[[], object]) -> None:
    with contextlib.suppress(Exception):
        work()


def _write_bounded(fd: int, data: bytes, timeout: float) -> None:
    """Write as much of ``data`` as the terminal takes within ``timeout``;
    never blocks for longer (a stalled or vanished terminal)."""
    while data:
        try:
            _, ready, _ = select.select([], [fd], [], timeout)
            if not ready:
                return
            written = os.write(fd, data[:512])  # a small write cannot block for long
        except (OSError, ValueError):
            return
        data = data[written:]


class SignalGuard:
    """SIGHUP, SIGTERM and SIGQUIT: keep unsaved work, give the terminal back,
    exit. SIGINT: the app's quit action (which asks about unsaved work).

    ``keep_work(signum)`` is called in the signal handler first; it writes what
    must not be lost and returns lines to print once the terminal is back.
    """

    def __init__(self, app: App, keep_work: Callable[[int], list[str]]) -> None:
        self._app = app
        self._keep_work = keep_work
        self._previous: dict[int, object] = {}
        self._fired = threading.Event()
        self._signum = 0
        self._messages: list[str] = []
        # started now, not in the handler: starting a thread takes locks
        self._thread = threading.Thread(
            target=self._exit_when_fired, name="dhsim-exit", daemon=True
        )

    def install(self) -> None:
        self._thread.start()
        for signum in EXIT_SIGNALS:
            self._previous[signum] = signal.signal(signum, self._handle)
        self._previous[signal.SIGINT] = signal.signal(signal.SIGINT, self._interrupt)

    def _interrupt(self, signum: int, frame) -> None:
        try:
            loop = asyncio.get_running_loop()  # the app's: the handler runs on its thread
        except RuntimeError:  # not running yet, or any more: as Python would
            signal.default_int_handler(signum, frame)
            return
        # not from the handler itself: it may have interrupted the loop anywhere
        loop.call_soon_threadsafe(self._app.call_later, self._app.run_action, "quit")

    def uninstall(self) -> None:
        for signum, handler in self._previous.items():
            with contextlib.suppress(TypeError, ValueError):
                signal.signal(signum, handler)  # type: ignore[arg-type]
        self._previous.clear()

    def _handle(self, signum: int, _frame) -> None:
        if self._fired.is_set():
            return  # already on the way out
        self._signum = signum
        try:
            self._messages = self._keep_work(signum)
        except Exception as exc:  # never let a failed write stop the exit
            self._messages = [f"dhsim: could not keep the unsaved changes: {exc}"]
        self._fired.set()

    def _exit_when_fired(self) -> None:
        self._fired.wait()
        try:
            self._give_terminal_back()
        finally:
            os._exit(128 + self._signum)

    def _give_terminal_back(self) -> None:
        driver = self._app._driver
        writer = getattr(driver, "_writer_thread", None)
        if writer is not None:  # let it finish what it was writing, then stop it
            _bounded(lambda: writer._queue.put(None), WRITER_TIMEOUT)
            with contextlib.suppress(Exception):
                writer.join(WRITER_TIMEOUT)
        fd = terminal_fd()
        if fd is None:
            return
        if os.isatty(fd):
            _write_bounded(fd, RESTORE_SEQUENCE.encode(), TERMINAL_TIMEOUT)
            attrs = getattr(driver, "attrs_before", None)
            if attrs is not None:
                # as a background process, tcsetattr would stop us: ignore SIGTTOU
                signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGTTOU})
                with contextlib.suppress(termios.error, OSError):
                    termios.tcsetattr(fd, termios.TCSANOW, attrs)
        if self._messages:
            text = "\n".join(self._messages) + "\n"
            if ascii_mode(self._app):
                text = ascii_text(text)
            _write_bounded(fd, text.encode(), TERMINAL_TIMEOUT)

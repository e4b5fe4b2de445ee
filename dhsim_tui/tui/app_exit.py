"""How a dhsim session ends: what is unsaved (an open editor's robot, else
the simulator's poses kept only in memory), the question quitting asks about
it, the recovery files it is written to when dhsim is stopped (SIGHUP,
SIGTERM, SIGQUIT) or breaks, and the one line and status 1 an unexpected
error ends with (the traceback goes to a crash report file, never to the
screen). The app's ``action_quit``, ``unsaved_work``, ``keep_unsaved_work``,
``_handle_exception`` and ``panic`` call these; ``run_app`` prints what was
kept once the terminal is back.
"""

from __future__ import annotations

import contextlib
import signal
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING

from rich.text import Text

from dhsim_tui.core.files.recovery import crash_report, source_key, write_recovery
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.tui.screens.dialogs import SaveGuard
from dhsim_tui.tui.screens.editor import EditorScreen

if TYPE_CHECKING:
    from dhsim_tui.tui.app import DhsimApp


def open_editors(app: DhsimApp) -> list[EditorScreen]:
    """The editors on ``app``'s screen stack, the top one first."""
    return [s for s in reversed(app.screen_stack) if isinstance(s, EditorScreen)]


def unsaved_work(app: DhsimApp) -> list[tuple[Robot, Path | None]]:
    """Every robot with changes not on disk, with its source file (None: a
    new robot). While an editor is open it has the simulator's poses (it
    started from them; none can be added meanwhile), so it alone counts."""
    editors = open_editors(app)
    if not editors:
        return [(app.robot, app.robot_path)] if app.has_unsaved_poses else []
    work: list[tuple[Robot, Path | None]] = []
    seen: set[str] = set()
    for editor in editors:
        source = editor.path or editor.template
        if editor.dirty and source_key(source) not in seen:
            seen.add(source_key(source))
            work.append((editor.robot, source))
    return work


async def may_quit(app: DhsimApp, editor: EditorScreen | None) -> bool:
    """Ask before quitting about ``editor``'s unsaved changes (None: the
    simulator's poses kept only in memory); True once nothing is lost
    (saved now, or discarded)."""
    if editor is not None:
        return await editor.guard("quitting")
    answer = await app.push_screen_wait(SaveGuard(app.robot.name, "quitting"))
    return answer == "discard" or (answer == "save" and await app.save_running_robot())


def crash_line(error: BaseException) -> str:
    """The one line an unexpected error ends dhsim with; the traceback is
    written to a crash report file (named in the line) when it can be."""
    where = crash_report(error)
    report = f"; the details are in {where}" if where else ""
    return printable(f"dhsim: internal error: {type(error).__name__}: {error}{report}")


def keep_in_recovery(
    work: Iterable[tuple[Robot, Path | None]], signum: int | None = None
) -> list[str]:
    """Write each unsaved robot (with its source file; None: a new robot) to
    a recovery file; what to tell the user. ``signum``: the signal that
    stops dhsim (None: an unexpected error). Safe in a signal handler (no
    lock, no terminal output)."""
    why = signal.Signals(signum).name if signum else "unexpected error"
    messages = []
    for robot, source in work:
        what = f"{robot.name} ({source if source is not None else 'new robot'})"
        try:
            file = write_recovery(robot, source)
        except (OSError, DhsimError) as exc:
            reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
            messages.append(f"dhsim: {why}: unsaved changes to {what} NOT kept: {reason}")
        else:
            messages.append(
                f"dhsim: {why}: unsaved changes to {what} kept in {file}; "
                "dhsim offers them back when you open it again"
            )
    return [printable(message) for message in messages]


def _keep_before_crash(app: DhsimApp) -> None:
    """A real session keeps its unsaved work (once: not again after a signal did)."""
    if app.recovery and not app.exit_messages:
        with contextlib.suppress(Exception):
            app.exit_messages = app.keep_unsaved_work()


def end_with_error(app: DhsimApp, error: Exception) -> None:
    """``app`` ends after an unexpected error: its unsaved work kept first,
    status 1, and one line instead of Textual's traceback. Sets what Textual's
    own ``_handle_exception`` sets (it has no public setters for them)."""
    _keep_before_crash(app)
    app._return_code = 1
    if app._exception is None:  # Pilot re-raises it in tests
        app._exception = error
        app._exception_event.set()
    app._exit_renderables.append(Text(crash_line(error)))
    app._close_messages_no_wait()


def before_panic(app: DhsimApp, renderables: tuple[object, ...]) -> Text:
    """Textual's panic is about to end ``app``: keep its unsaved work and set
    status 1 (Textual leaves it at 0; exit() would not stop a panic); the one
    line to end with instead of ``renderables``."""
    _keep_before_crash(app)
    app._return_code = 1  # no public setter
    text = " ".join(str(r) for r in renderables if isinstance(r, str))
    return Text(crash_line(RuntimeError(text or "Textual stopped")))

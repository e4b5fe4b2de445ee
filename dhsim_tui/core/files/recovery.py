"""Recovery files: unsaved work kept when dhsim has to stop before it is saved.

When the terminal goes away (SIGHUP, a dropped SSH connection), on SIGTERM or
SIGQUIT, or after an unexpected error, the app writes every robot with unsaved
changes to a recovery file; the next start (or open) of that robot offers it
back. There is one recovery file per source file, keyed by the source's
resolved path (``None``: a new robot that was never saved).

A recovery file is an ordinary robot TOML file (:func:`robotfile.dumps`) after
a few comment lines naming the original file and the time it was written, so
a person can also read it, or copy it by hand. Files live in
:func:`recovery_dir`: ``$DHSIM_RECOVERY_DIR``, else
``$XDG_STATE_HOME/dhsim/recovery``, else ``~/.local/state/dhsim/recovery``.

Writing is atomic and touches no lock another thread may hold, so it is safe
from a signal handler: the recovery is written before the terminal is touched.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
import traceback
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

from dhsim_tui.core.files.robotfile import dumps, loads
from dhsim_tui.core.model.errors import RobotFileError
from dhsim_tui.core.model.robot import Robot

RECOVERY_ENV = "DHSIM_RECOVERY_DIR"
#: the key of a robot that has no file yet
NEW_ROBOT = "new robot"
HEADER = "# dhsim recovery file: unsaved changes kept when dhsim stopped before saving."
_SOURCE = "# source: "
_SAVED_AT = "# saved_at: "
#: recovery files larger than this are not robots (a robot is < 10 kB)
MAX_RECOVERY_BYTES = 1_000_000


@dataclass(frozen=True)
class Recovery:
    """A recovery file found for a source: what it holds and where it came from."""

    file: Path
    robot: Robot
    source: Path | None  # None: a new robot that was never saved
    saved_at: datetime  # aware (UTC)

    @property
    def local_time(self) -> str:
        """When it was written, in local time: ``2024-05-01 14:03``."""
        return self.saved_at.astimezone().strftime("%Y-%m-%d %H:%M")


def recovery_dir() -> Path:
    """Where recovery files live (see the module's documentation)."""
    override = os.environ.get(RECOVERY_ENV)
    if override:
        return Path(override).expanduser()
    state = os.environ.get("XDG_STATE_HOME")
    base = Path(state) if state and Path(state).is_absolute() else Path.home() / ".local/state"
    return base / "dhsim" / "recovery"


def source_key(source: str | os.PathLike[str] | None) -> str:
    """What a recovery is filed under: the resolved path, or ``NEW_ROBOT``."""
    if source is None:
        return NEW_ROBOT
    path = Path(source)
    try:
        path = path.resolve()
    except (OSError, RuntimeError):  # a symlink loop: the path as written, made absolute
        path = Path(os.path.abspath(path))
    return str(path)


def recovery_file(source: str | os.PathLike[str] | None) -> Path:
    """The recovery file's path for ``source``: readable stem plus a hash of the key."""
    key = source_key(source)
    if source is None:
        return recovery_dir() / "new-robot.toml"
    digest = hashlib.sha256(os.fsencode(key)).hexdigest()[:16]
    stem = re.sub(r"[^A-Za-z0-9_-]+", "_", Path(key).stem)[:40].strip("_") or "robot"
    return recovery_dir() / f"{stem}-{digest}.toml"


def _header(source: str | os.PathLike[str] | None, saved_at: datetime) -> str:
    key = None if source is None else source_key(source)
    return "\n".join(
        [
            HEADER,
            "# dhsim offers it back when this robot is opened again; the robot follows.",
            _SOURCE + json.dumps(key),  # JSON: any path, escaped, on one ASCII line
            _SAVED_AT + saved_at.isoformat(timespec="seconds"),
            "",
            "",
        ]
    )


def write_recovery(robot: Robot, source: str | os.PathLike[str] | None) -> Path:
    """Write ``robot`` as the recovery of ``source``, atomically; its path.

    Raises OSError when it cannot be written (the caller says so)."""
    target = recovery_file(source)
    text = _header(source, datetime.now(timezone.utc)) + dumps(robot)
    target.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
    tmp = target.with_name(f".{target.name}.{os.getpid()}.tmp")
    flags = os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, "O_NOFOLLOW", 0)
    fd = os.open(tmp, flags, 0o600)  # private: it is the user's work
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    with contextlib.suppress(OSError):
        folder = os.open(target.parent, os.O_RDONLY)
        try:
            os.fsync(folder)
        finally:
            os.close(folder)
    return target


def crash_report(error: BaseException) -> Path | None:
    """Write ``error``'s traceback to ``crash-<time>.txt`` beside the recovery
    folder (private), for a bug report; its path, or None when it cannot be
    written (the caller still says what happened, in one line)."""
    stamp = datetime.now(timezone.utc).strftime("%Y%m%d-%H%M%S")
    target = recovery_dir().parent / f"crash-{stamp}-{os.getpid()}.txt"
    cause = getattr(error, "error", None)  # a failed worker carries the real error
    if isinstance(cause, BaseException):
        error = cause
    text = "".join(traceback.format_exception(type(error), error, error.__traceback__))
    try:
        target.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        fd = os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(fd, "w", encoding="utf-8", errors="backslashreplace") as handle:
            handle.write(text)
    except (OSError, ValueError):
        return None
    return target


def read_recovery(file: Path) -> Recovery:
    """Read one recovery file; a damaged one is a RobotFileError naming it."""
    try:
        if file.stat().st_size > MAX_RECOVERY_BYTES:
            raise RobotFileError(f"{file}: damaged recovery file: too large")
        text = file.read_text(encoding="utf-8")
    except OSError as exc:
        raise RobotFileError(f"{file}: cannot read: {exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        raise RobotFileError(
            f"{file}: damaged recovery file: invalid UTF-8 at byte {exc.start}"
        ) from None
    lines = text.splitlines()[:6]
    source_line = next((line for line in lines if line.startswith(_SOURCE)), None)
    time_line = next((line for line in lines if line.startswith(_SAVED_AT)), None)
    if not lines or lines[0] != HEADER or source_line is None or time_line is None:
        raise RobotFileError(f"{file}: damaged recovery file: its header is missing")
    try:
        source = json.loads(source_line.removeprefix(_SOURCE))
        saved_at = datetime.fromisoformat(time_line.removeprefix(_SAVED_AT))
    except ValueError:
        raise RobotFileError(f"{file}: damaged recovery file: its header is unreadable") from None
    if not (source is None or isinstance(source, str)) or saved_at.tzinfo is None:
        raise RobotFileError(f"{file}: damaged recovery file: its header is unreadable")
    robot = loads(text, str(file))
    return Recovery(file, robot, None if source is None else Path(source), saved_at)


def find_recovery(source: str | os.PathLike[str] | None) -> Recovery | None:
    """The recovery kept for ``source``, or None. A damaged recovery file raises
    RobotFileError (naming the file) rather than being silently ignored."""
    file = recovery_file(source)
    if not file.is_file():
        return None
    found = read_recovery(file)
    wanted = None if source is None else source_key(source)
    have = None if found.source is None else str(found.source)
    return found if have == wanted else None


def discard_recovery(recovery: Recovery) -> None:
    """Delete a recovery file (the user restored or discarded it)."""
    with contextlib.suppress(FileNotFoundError):
        recovery.file.unlink()

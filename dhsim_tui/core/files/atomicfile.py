"""Files written so that nothing is lost: atomic saves and careful reads.

A save goes to a temporary file ``.{name}.{pid}.{random}.tmp`` in the same
folder, is flushed and fsynced, keeps the replaced file's owner and mode, and
is renamed over the target; the folder is fsynced too. The rename is done
under an advisory lock (:func:`locked`, ``fcntl.flock`` on the sidecar
``.{name}.dhsim-lock``), right after a last check the caller gives (has the
file changed since it was read?), so two dhsim saves of one file never
interleave and the check is as late as it can be. Temporary files a killed
save left behind are removed later (:func:`remove_stale_temps`). Every
failure is a :class:`RobotFileError` naming the file, with any control
character in the path escaped.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import stat
import tempfile
import time
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

try:
    import fcntl
except ImportError:  # not POSIX: no advisory locks; the last check is still made
    fcntl = None  # type: ignore[assignment]

from dhsim_tui.core.model.errors import RobotFileError
from dhsim_tui.core.model.text import printable

#: a temporary file of a killed save is removed after this long even if its pid lives
STALE_TEMP_SECONDS = 3600
#: how long a save waits for another dhsim's save of the same file (which holds
#: the lock for a read and a rename: milliseconds) before it gives up
LOCK_WAIT_SECONDS = 10.0
#: how often a waiting save tries the lock again (s)
LOCK_POLL_SECONDS = 0.005
#: flock errors that mean "no locks here" (some network or FUSE file systems)
_NO_LOCKS = {errno.ENOLCK, errno.EOPNOTSUPP, errno.ENOTSUP, errno.EINVAL, errno.ENOSYS}


def file_error(message: str, kind: type[RobotFileError] = RobotFileError) -> RobotFileError:
    """An error whose text cannot steer a terminal (file content is escaped)."""
    return kind(printable(message))


def read_file(path: Path, limit: int) -> tuple[bytes, os.stat_result]:
    """The bytes of a regular file of at most ``limit`` bytes and its status."""
    try:
        # O_NONBLOCK: opening a pipe must not hang; fstat then refuses it
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        try:
            handle = open(fd, "rb")  # noqa: SIM115 (closed by the with below)
        except BaseException:
            os.close(fd)  # a folder: open() refuses it and would leave fd open
            raise
        with handle:
            info = os.fstat(handle.fileno())
            if stat.S_ISDIR(info.st_mode):
                raise file_error(f"{path}: is a folder, not a robot file")
            if not stat.S_ISREG(info.st_mode):
                raise file_error(f"{path}: is not a regular file (a device or a pipe?)")
            if info.st_size > limit:
                raise file_error(f"{path}: {info.st_size} bytes is too large for a robot file")
            raw = handle.read(limit + 1)
            info = os.fstat(handle.fileno())
    except FileNotFoundError:
        raise file_error(f"{path}: no such file") from None
    except PermissionError:
        raise file_error(f"{path}: permission denied") from None
    except IsADirectoryError:
        raise file_error(f"{path}: is a folder, not a robot file") from None
    except OSError as exc:
        raise file_error(f"{path}: cannot read: {exc.strerror or exc}") from None
    except ValueError as exc:  # e.g. a NUL byte in the path
        raise file_error(f"{path}: cannot read: {exc}") from None
    if len(raw) > limit:
        raise file_error(f"{path}: {len(raw)}+ bytes is too large for a robot file")
    return raw, info


def _temp_stem(name: str) -> str:
    """``.{name}.{pid}.`` shortened so the temporary name fits in 255 bytes."""
    room = 255 - len(f"..{os.getpid()}.XXXXXXXX.tmp")
    while len(os.fsencode(name)) > room:
        name = name[:-1]
    return name


def _temp_pattern(target: Path) -> re.Pattern[str]:
    return re.compile(rf"\.{re.escape(_temp_stem(target.name))}\.(\d+)\.[A-Za-z0-9_]+\.tmp")


def remove_stale_temps(target: Path) -> list[Path]:
    """Remove the temporary files a killed save of ``target`` left behind: those
    whose process is gone, or older than an hour. Nothing else is touched."""
    pattern = _temp_pattern(target)
    removed = []
    folder = target.parent if str(target.parent) else Path(".")
    try:
        entries = list(os.scandir(folder))
    except (OSError, ValueError):
        return removed
    for entry in entries:
        match = pattern.fullmatch(entry.name)
        if match is None:
            continue
        try:
            info = entry.stat(follow_symlinks=False)
            if not stat.S_ISREG(info.st_mode):
                continue
            age = time.time() - info.st_mtime
            if _alive(int(match.group(1))) and age < STALE_TEMP_SECONDS:
                continue
            os.unlink(entry.path)
            removed.append(Path(entry.path))
        except OSError:
            continue
    return removed


def _alive(pid: int) -> bool:
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # somebody else's process
    except (OSError, OverflowError):
        return False
    return True


def lock_path(target: Path) -> Path:
    """The sidecar lock of ``target``: ``.{name}.dhsim-lock`` in its folder."""
    return target.with_name(f".{_temp_stem(target.name)}.dhsim-lock")


@contextlib.contextmanager
def locked(target: Path, given: Path | None = None) -> Iterator[None]:
    """Hold dhsim's advisory lock on ``target`` (every dhsim write of a file
    renames under it, so a check made inside holds until the rename).

    The lock is ``fcntl.flock`` on a sidecar file, ``.{name}.dhsim-lock``,
    not on the target: the target is replaced by the rename (a lock on it
    would lock the old file, and a file that does not exist yet has nothing
    to lock), while the sidecar stays put. It is created when needed and
    removed before the lock is let go, so none is left behind; whoever then
    gets a lock on the removed one sees that the name is gone (or names
    another file) and locks again. A lock file that is not empty was not
    made by dhsim and is never removed. Where there are no advisory locks
    the body runs unlocked. Waits :data:`LOCK_WAIT_SECONDS` at most, then
    raises a :class:`RobotFileError` (another dhsim holds it: stopped?)."""
    lock = lock_path(target)
    held = _acquire(lock, given if given is not None else target)
    try:
        yield
    finally:
        if held is not None:
            fd, mine = held
            _remove_lock(lock, mine)  # while still holding it
            os.close(fd)


def _acquire(lock: Path, name: Path) -> tuple[int, os.stat_result] | None:
    """The locked lock file (descriptor and status); None when there are no locks."""
    if fcntl is None:
        return None
    deadline = time.monotonic() + LOCK_WAIT_SECONDS
    while True:
        fd = _open_lock(lock)
        try:
            mine = os.fstat(fd)
            if not stat.S_ISREG(mine.st_mode):
                raise file_error(f"{name}: cannot save: {lock} is not a regular file")
            if not _flock(fd, lock, name, deadline):  # no locks on this file system
                _remove_lock(lock, mine)
                os.close(fd)
                return None
        except BaseException:
            os.close(fd)
            raise
        if _same_file(lock, mine):
            return fd, mine
        os.close(fd)  # the save that held it removed it (or it was replaced): again


def _open_lock(lock: Path) -> int:
    """The lock file, made if needed (never through a symbolic link); read-only
    when it is somebody else's (flock needs no write permission)."""
    flags = os.O_CLOEXEC | getattr(os, "O_NOFOLLOW", 0)
    try:
        return os.open(lock, flags | os.O_RDWR | os.O_CREAT, 0o666)  # umask applies
    except PermissionError:
        return os.open(lock, flags | os.O_RDONLY)


def _flock(fd: int, lock: Path, name: Path, deadline: float) -> bool:
    """Wait for the lock; False when the file system has no locks."""
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return True
        except BlockingIOError:
            if time.monotonic() > deadline:
                raise file_error(
                    f"{name}: cannot save: another dhsim is saving this file right now "
                    f"(it holds {lock}); try again"
                ) from None
            time.sleep(LOCK_POLL_SECONDS)
        except OSError as exc:
            if exc.errno in _NO_LOCKS:
                return False
            raise


def _same_file(path: Path, info: os.stat_result) -> bool:
    try:
        now = os.stat(path, follow_symlinks=False)
    except OSError:
        return False
    return (now.st_dev, now.st_ino) == (info.st_dev, info.st_ino)


def _remove_lock(lock: Path, info: os.stat_result) -> None:
    """Remove the lock file this save made (an empty one, still the same file)."""
    with contextlib.suppress(OSError):
        if _same_file(lock, info) and os.stat(lock, follow_symlinks=False).st_size == 0:
            os.unlink(lock)


def write_atomic(
    target: Path,
    given: Path,
    data: bytes | Iterable[bytes],
    old: os.stat_result | None,
    check: Callable[[], None] | None = None,
) -> os.stat_result:
    """The atomic write itself; owner and mode of ``old`` (the replaced file) kept.
    ``data``: the bytes, or their pieces in order (written as they come, so a
    long export never sits whole in memory).

    ``check`` runs under :func:`locked`, after the temporary file is written
    and just before the rename; whatever it raises stops the save (the
    temporary file is removed, the target untouched)."""
    folder = target.parent if str(target.parent) else Path(".")
    tmp_name = None
    try:
        fd, tmp_name = tempfile.mkstemp(
            prefix=f".{_temp_stem(target.name)}.{os.getpid()}.", suffix=".tmp", dir=folder
        )
        try:
            if old is not None:
                _keep_owner(fd, old, given)
            os.chmod(tmp_name, _mode_for(old))  # mkstemp makes it private (0600)
        except BaseException:
            os.close(fd)
            raise
        with os.fdopen(fd, "wb") as handle:
            for piece in [data] if isinstance(data, bytes | bytearray) else data:
                handle.write(piece)
            handle.flush()
            os.fsync(handle.fileno())
        with locked(target, given):
            if check is not None:
                check()
            os.replace(tmp_name, target)
            tmp_name = None
        _fsync_folder(folder)
        return os.stat(target)
    except FileNotFoundError:
        raise file_error(f"{given}: cannot save: folder {folder} does not exist") from None
    except PermissionError:
        raise file_error(f"{given}: cannot save: permission denied") from None
    except OSError as exc:
        raise file_error(f"{given}: cannot save: {exc.strerror or exc}") from None
    finally:
        if tmp_name is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp_name)


def write_file(
    path: str | os.PathLike[str], data: bytes | Iterable[bytes], *, overwrite: bool = False
) -> Path:
    """Write ``data`` (bytes, or their pieces in order) to ``path`` atomically
    (an export, a picture) and return ``path``.

    An existing file is replaced only with ``overwrite`` (keeping its owner
    and mode); a folder, a device or a pipe never is. A symbolic link is
    followed: the file it points to is written. Every failure is a
    :class:`RobotFileError` naming the path (the check for an existing file
    and the rename are not one step, so a file created in between is replaced)."""
    given = Path(path)
    if not str(path):
        raise file_error("the file name is empty; give a name to write to")
    try:
        target = Path(os.path.realpath(given)) if given.is_symlink() else given
        info: os.stat_result | None = os.stat(target)
    except FileNotFoundError:
        info = None
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or exc
        raise file_error(f"{given}: cannot write: {reason}") from None
    if info is not None:
        if stat.S_ISDIR(info.st_mode):
            raise file_error(f"{given}: is a folder; give a file name to write to")
        if not overwrite:
            raise file_error(f"{given}: already exists; choose another name or overwrite it")
        if not stat.S_ISREG(info.st_mode):
            raise file_error(f"{given}: cannot write: not a regular file (a device or a pipe?)")
    remove_stale_temps(target)
    write_atomic(target, given, data, info)
    return given


def _keep_owner(fd: int, old: os.stat_result, given: Path) -> None:
    mine = os.fstat(fd)
    if (mine.st_uid, mine.st_gid) == (old.st_uid, old.st_gid):
        return
    try:
        os.fchown(fd, old.st_uid, old.st_gid)
    except PermissionError:
        raise file_error(
            f"{given}: cannot save: the file belongs to user {old.st_uid} (group "
            f"{old.st_gid}) and a save would change its owner; save it under another name"
        ) from None


def _mode_for(old: os.stat_result | None) -> int:
    """Keep an existing file's permissions; a new file gets the usual 0666 & ~umask."""
    if old is not None:
        return old.st_mode & 0o7777
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def _fsync_folder(folder: Path) -> None:
    """Make the rename itself durable (where the platform allows it)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)

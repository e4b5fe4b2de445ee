"""Robot files: TOML in, TOML out (the schema is in the README; its keys and
checks are :mod:`dhsim_tui.core.files.robotschema`'s).

Loading is strict: every key is checked for type and spelling and every
problem is reported as one :class:`RobotFileError` naming the file and the
field, with any control character from the file shown escaped (``\\x1b``)
and any long name or key shortened in the middle. One UTF-8 byte order mark
is accepted (not two). Before the TOML parser sees a file, it is scanned for
what would make the parser slow or greedy (a key of thousands of dotted
parts takes Python's parser minutes and gigabytes): a key path of more than
:data:`~dhsim_tui.core.files.tomlparse.MAX_KEY_PARTS` parts, a line of more
than :data:`~dhsim_tui.core.files.tomlparse.MAX_LINE_CHARS` characters, a
multi-line string of more than
:data:`~dhsim_tui.core.files.tomlparse.MAX_STRING_CHARS` characters, or more
table headers, poses, programs, keys or values in lists than any robot has, is
refused, naming the line (:mod:`dhsim_tui.core.files.tomlparse`). A URDF or a
CSV given as a robot file is named as such, with the ``dhsim import`` command
that reads it.

Saving is atomic (temporary file, fsync, rename) and ``load(save(robot)) ==
robot`` exactly. Saving over a robot file keeps the user's comments and
layout (:mod:`dhsim_tui.core.files.tomledit`), its owner, mode and byte order mark;
a read-only file is refused, and ``expect`` refuses to overwrite a file that
changed on disk since it was read (:class:`FileStamp`): its bytes, or the
file the path names (a symbolic link made, removed or pointed elsewhere,
even at the same bytes). That check is made twice: when the save starts,
and again just before the rename, under dhsim's lock on the file
(:func:`~dhsim_tui.core.files.atomicfile.locked`), against the very file the
save read: a change made while the temporary file was written is a
:class:`ChangedWhileSavingError` (a :class:`FileChangedError`), and the
change is kept.
"""

from __future__ import annotations

import hashlib
import os
import re
import shlex
import stat
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from types import EllipsisType

import tomli_w

from dhsim_tui.core.files.atomicfile import file_error as _error
from dhsim_tui.core.files.atomicfile import read_file, remove_stale_temps, write_atomic
from dhsim_tui.core.files.formats import IMPORT_SUFFIXES
from dhsim_tui.core.files.robotschema import file_defaults, robot_from_dict, robot_to_dict
from dhsim_tui.core.files.tomledit import update_text
from dhsim_tui.core.files.tomlitems import section_text
from dhsim_tui.core.files.tomlparse import parse_toml
from dhsim_tui.core.model.errors import DhsimError, RobotFileError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable, shortened

#: robot files larger than this are refused before parsing (a robot is < 10 kB)
MAX_FILE_BYTES = 1_000_000
BOM = b"\xef\xbb\xbf"


class FileChangedError(RobotFileError):
    """The file on disk is not the one the robot was read from (or expected absent)."""


class ChangedWhileSavingError(FileChangedError):
    """The file changed (or the path came to name another file) while it was
    being saved, after the save read it and before the rename: nothing was
    written; callers ask as for any :class:`FileChangedError`."""


class ReadOnlyError(RobotFileError):
    """The file has no write permission; refused whoever runs dhsim."""


@dataclass(frozen=True)
class FileStamp:
    """What a file held when it was read or written."""

    path: Path  # the real file (symlinks resolved): a save to a path that
    # resolves elsewhere now (a symlink made, removed or changed) is a change
    mtime_ns: int
    size: int
    digest: str  # sha256 of the bytes

    def __fspath__(self) -> str:  # a stamp names its file: load(save(...)) works
        return str(self.path)


# -- reading ---------------------------------------------------------------------


def loads(text: str, source: str = "<robot>") -> Robot:
    """Parse and validate robot TOML; errors start with ``source``."""
    data = parse_toml(text, source)
    try:
        return robot_from_dict(data)
    except DhsimError as exc:
        raise _error(f"{source}: {exc}") from None


def _decode(raw: bytes, path: Path) -> str:
    """The text of the file (a byte order mark kept: :func:`loads` takes one off)."""
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise _error(f"{path}: not a text file (invalid UTF-8 at byte {exc.start})") from None


def _real(path: Path) -> Path:
    return Path(os.path.realpath(path))


def _import_hint(path: Path, text: str, failed: bool) -> RobotFileError | None:
    """A URDF or a CSV given where a robot file is expected: the error that
    says so, with the ``dhsim import`` command that reads it (None: not one).
    XML is known by its start (TOML never starts with ``<``); a ``.urdf`` or
    ``.csv`` name only counts when the file did not load (``failed``)."""
    suffix = path.suffix.lower()
    xml = text.removeprefix("\ufeff").lstrip().startswith("<")
    if not xml and not (failed and suffix in IMPORT_SUFFIXES):
        return None
    source = path if suffix in IMPORT_SUFFIXES else path.with_suffix(".urdf")
    target = path.with_suffix(".toml")
    if target == path:
        target = path.with_name(f"{path.stem}-imported.toml")
    command = f"dhsim import {shlex.quote(str(source))} -o {shlex.quote(str(target))}"
    if suffix == ".csv":
        what = "a CSV file, not a dhsim robot file (TOML); if it is a D-H table, import it"
    elif suffix == ".urdf":
        what = "a URDF, not a dhsim robot file (TOML); import it"
    else:
        what = (
            "XML (a URDF?), not a dhsim robot file (TOML); dhsim imports a URDF "
            "from a .urdf file: give it that suffix and import it"
        )
    return _error(f"{path}: {what}: {command}")


def _load_text(path: Path, raw: bytes) -> Robot:
    text = _decode(raw, path)
    hint = _import_hint(path, text, failed=False)
    if hint is not None:
        raise hint
    try:
        return loads(text, str(path))
    except RobotFileError:
        hint = _import_hint(path, text, failed=True)
        if hint is not None:
            raise hint from None
        raise


def load(path: str | os.PathLike[str]) -> Robot:
    """Read a robot file; every failure is a RobotFileError naming the file."""
    path = Path(path)
    return _load_text(path, read_file(path, MAX_FILE_BYTES)[0])


def load_with_stamp(path: str | os.PathLike[str]) -> tuple[Robot, FileStamp]:
    """Like :func:`load`, plus the stamp of the very bytes parsed (for ``save(expect=)``).
    Temporary files left next to it by a killed save are removed."""
    path = Path(path)
    raw, info = read_file(path, MAX_FILE_BYTES)
    robot = _load_text(path, raw)
    real = _real(path)
    remove_stale_temps(real)
    return robot, FileStamp(real, info.st_mtime_ns, len(raw), hashlib.sha256(raw).hexdigest())


def read_stamp(path: str | os.PathLike[str]) -> FileStamp | None:
    """The stamp of what ``path`` holds now; None when there is no such file."""
    path = Path(path)
    try:
        raw, info = read_file(path, MAX_FILE_BYTES)
    except RobotFileError:
        if not os.path.lexists(path) or (path.is_symlink() and not path.exists()):
            return None
        raise
    return FileStamp(_real(path), info.st_mtime_ns, len(raw), hashlib.sha256(raw).hexdigest())


# -- writing ---------------------------------------------------------------------

#: an array of numbers tomli_w wrote one item per line
_NUMBER_COLUMN = re.compile(r"\[\n((?:    [-+0-9.eE]+(?:inf|nan)?,\n)+)\]")
#: the first ``[[joints]]`` header tomli-w wrote (strings are on one line: no
#: line of one starts with a bracket)
_JOINTS_HEADER = re.compile(r"^\[\[joints\]\]$", re.MULTILINE)


def dumps(robot: Robot) -> str:
    """A fresh robot file; arrays of numbers on one line, as people write them,
    and each program's steps one inline table a line, in a ``[programs]``
    table before the ``[[joints]]`` (or at the end, when tomli-w wrote the
    joints inline at the top)."""
    data = robot_to_dict(robot)
    programs = data.pop("programs", None)
    text = tomli_w.dumps(data, multiline_strings=False)
    text = _NUMBER_COLUMN.sub(
        lambda m: (
            "[" + ", ".join(item.strip().rstrip(",") for item in m.group(1).splitlines()) + "]"
        ),
        text,
    )
    if programs is None:
        return text
    section = section_text("programs", programs)
    joints = _JOINTS_HEADER.search(text)
    if joints is None:
        return f"{text}\n{section}"
    return f"{text[: joints.start()]}{section}\n{text[joints.start() :]}"


def _reads_back(text: str | None, robot: Robot) -> bool:
    try:
        return text is not None and loads(text) == robot
    except RobotFileError:
        return False


def render(robot: Robot, base_text: str | None = None) -> str:
    """The text to save: ``base_text`` updated in place when it is TOML (its
    comments and layout kept), else a fresh document. Always reads back as ``robot``."""
    if base_text is not None and len(base_text) <= MAX_FILE_BYTES:
        base = base_text.removeprefix("\ufeff")
        try:
            current = robot_to_dict(loads(base), full=True)
        except RobotFileError:
            current = None
        try:
            parse_toml(base)  # not TOML (or hostile): tomlkit is not given it
            data, defaults = robot_to_dict(robot, full=True), file_defaults(robot)
            text = update_text(base, data, defaults, current, ordered=("poses", "programs"))
            if "\r\n" in base and base.count("\n") == base.count("\r\n"):  # Windows lines
                text = text.replace("\r\n", "\n").replace("\n", "\r\n")
        except Exception:  # tomlkit fails in many ways; then a fresh document is written
            text = None
        if _reads_back(text, robot):
            return text  # type: ignore[return-value]
    text = dumps(robot)
    if not _reads_back(text, robot):
        raise RobotFileError(
            f"cannot save {printable(shortened(robot.name))!r}: it would not read back"
        )
    return text


def save(
    robot: Robot,
    path: str | os.PathLike[str],
    *,
    expect: FileStamp | EllipsisType | None = ...,
    base_text: str | None = None,
) -> FileStamp:
    """Write atomically: a temporary file in the same folder, flushed, fsynced,
    then renamed over ``path``. On any failure the old file is untouched.

    ``expect``: ``...`` does not check; None means the file must not exist;
    a stamp means the file must still hold what it held then, and the path
    still name the same real file (:class:`FileChangedError` otherwise).
    With a check, it is made again just before the rename, under the file's
    lock: the very file this save read, unchanged, through the same link
    (:class:`ChangedWhileSavingError` otherwise; nothing is written). An
    existing file is updated in place (comments kept); with no file,
    ``base_text`` is the starting point.
    Returns the stamp of what was written."""
    given = Path(path)
    linked = _link_state(given)
    target = linked[1] if linked[0] else given  # write the file, keep the link
    existing = _existing(target, given)
    _check_expect(given, expect, existing, linked[1])
    raw = existing[0] if existing else None
    old_text = _text_or_none(raw)
    text = render(robot, old_text if _is_toml(old_text) else base_text)
    had_bom = raw.startswith(BOM) if raw is not None else (base_text or "").startswith("\ufeff")
    data = (BOM if had_bom else b"") + text.encode("utf-8")
    remove_stale_temps(target)
    check = None if expect is ... else _still_as_read(given, target, linked, existing)
    info = write_atomic(target, given, data, existing[1] if existing else None, check)
    return FileStamp(_real(target), info.st_mtime_ns, len(data), hashlib.sha256(data).hexdigest())


def _link_state(given: Path) -> tuple[bool, Path]:
    """Whether ``given`` is a symbolic link, and the real file it names."""
    try:
        return given.is_symlink(), _real(given)
    except (OSError, ValueError) as exc:  # a NUL in the name, ...
        reason = getattr(exc, "strerror", None) or exc
        raise _error(f"{given}: cannot save: {reason}") from None


def _identity(info: os.stat_result) -> tuple[int, ...]:
    """What changes when a file is written, replaced, chmod-ed or chown-ed."""
    return (info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns, info.st_ctime_ns)


def _still_as_read(
    given: Path,
    target: Path,
    linked: tuple[bool, Path],
    existing: tuple[bytes, os.stat_result] | None,
) -> Callable[[], None]:
    """The last check before the rename (run under the file's lock): the path
    names the same file, through the same link, and the file is the very one
    the save read (same inode, time, size and bytes), or is still absent."""

    def check() -> None:
        changed = f"{given}: the file changed on disk since it was opened"
        if _link_state(given) != linked:
            raise _error(
                f"{changed}: it is another file now (a symbolic link was made, removed "
                "or changed while it was being saved)",
                ChangedWhileSavingError,
            )
        if existing is None:
            if os.path.lexists(target):
                raise _error(
                    f"{changed}: a file of that name was made while it was being saved",
                    ChangedWhileSavingError,
                )
            return
        try:
            raw, info = read_file(target, MAX_FILE_BYTES)
        except RobotFileError:
            gone = not os.path.lexists(target)
            raise _error(
                f"{changed}: it is gone (deleted or renamed)"
                if gone
                else f"{changed} (another program changed it while it was being saved)",
                ChangedWhileSavingError,
            ) from None
        if raw != existing[0] or _identity(info) != _identity(existing[1]):
            raise _error(
                f"{changed} (another program changed it while it was being saved)",
                ChangedWhileSavingError,
            )

    return check


def _existing(target: Path, given: Path) -> tuple[bytes, os.stat_result] | None:
    """The bytes and status of the file a save replaces (None: there is none)."""
    try:
        info = os.stat(target)
    except FileNotFoundError:
        return None
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or exc
        raise _error(f"{given}: cannot save: {reason}") from None
    if stat.S_ISDIR(info.st_mode):
        raise _error(f"{given}: is a folder, not a robot file")
    if not stat.S_ISREG(info.st_mode):
        raise _error(f"{given}: cannot save: not a regular file (a device or a pipe?)")
    if not info.st_mode & 0o222 or not os.access(target, os.W_OK):
        raise _error(
            f"{given}: the file is read-only (no write permission); "
            "save the robot under another name",
            ReadOnlyError,
        )
    return read_file(target, MAX_FILE_BYTES)


def _check_expect(given: Path, expect: object, existing: tuple | None, real: Path) -> None:
    if expect is ...:
        return
    changed = f"{given}: the file changed on disk since it was opened"
    if expect is None:
        if existing is not None:
            raise _error(f"{changed}: a file of that name exists now", FileChangedError)
        return
    if not isinstance(expect, FileStamp):
        raise TypeError(f"expect: a FileStamp, None or ..., not {type(expect).__name__}")
    if existing is None:
        raise _error(f"{changed}: it is gone (deleted or renamed)", FileChangedError)
    raw = existing[0]
    if (len(raw), hashlib.sha256(raw).hexdigest()) != (expect.size, expect.digest):
        raise _error(f"{changed} (another program wrote to it)", FileChangedError)
    if real != expect.path:  # the same bytes, but another file: a symlink swapped in
        raise _error(
            f"{changed}: it is another file now (a symbolic link was made, removed or changed)",
            FileChangedError,
        )


def _text_or_none(raw: bytes | None) -> str | None:
    try:
        return raw.removeprefix(BOM).decode("utf-8") if raw is not None else None
    except UnicodeDecodeError:
        return None


def _is_toml(text: str | None) -> bool:
    try:
        return text is not None and isinstance(parse_toml(text), dict)
    except RobotFileError:
        return False

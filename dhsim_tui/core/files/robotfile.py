"""Robot files: TOML in, TOML out (the schema is in the README).

Loading is strict: every key is checked for type and spelling and every
problem is reported as one :class:`RobotFileError` naming the file and the
field, with any control character from the file shown escaped (``\\x1b``)
and any long name or key shortened in the middle. One UTF-8 byte order mark
is accepted (not two). Before the TOML parser sees a file, it is scanned for
what would make the parser slow or greedy (a key of thousands of dotted
parts takes Python's parser minutes and gigabytes): a key path of more than
:data:`MAX_KEY_PARTS` parts or a line of more than :data:`MAX_LINE_CHARS`
characters is refused, naming the line. A URDF or a CSV given as a robot
file is named as such, with the ``dhsim import`` command that reads it.

Saving is atomic (temporary file, fsync, rename) and ``load(save(robot)) ==
robot`` exactly. Saving over a robot file keeps the user's comments and
layout (:mod:`dhsim_tui.core.files.tomledit`), its owner, mode and byte order mark;
a read-only file is refused, and ``expect`` refuses to overwrite a file that
changed on disk since it was read (:class:`FileStamp`).
"""

from __future__ import annotations

import difflib
import hashlib
import os
import re
import shlex
import stat
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from types import EllipsisType
from typing import Any

import tomli_w

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10: the same parser, as a package
    import tomli as tomllib

from dhsim_tui.core.files.atomicfile import file_error as _error
from dhsim_tui.core.files.atomicfile import read_file, remove_stale_temps, write_atomic
from dhsim_tui.core.files.formats import IMPORT_SUFFIXES
from dhsim_tui.core.files.tomledit import update_text
from dhsim_tui.core.model.errors import DhsimError, RobotFileError
from dhsim_tui.core.model.robot import Joint, Robot, Tool, default_limits
from dhsim_tui.core.model.text import counted, printable, shortened
from dhsim_tui.core.model.validation import check_choice, check_number

TOP_KEYS = (
    "name",
    "units",
    "convention",
    "base_height",
    "base_z",
    "base_x",
    "base_xyz",
    "base_rpy",
    "tool",
    "poses",
    "joints",
)
JOINT_KEYS = ("type", "theta", "d", "a", "alpha", "min", "max", "offset")
JOINT_REQUIRED = ("theta", "d", "a", "alpha")
TOOL_KEYS = ("xyz", "rpy")
#: robot files larger than this are refused before parsing (a robot is < 10 kB)
MAX_FILE_BYTES = 1_000_000
#: a key path (``a.b.c = 1``, ``[a.b]``, ``[[a.b]]``, ``{ a.b = 1 }``) of more
#: parts than this is refused before parsing: dhsim's files need at most 3
#: (``poses."a b" = ...`` under a header); Python's parser takes time and
#: memory growing with the square of the parts (20,000: 7 s and 1.6 GB)
MAX_KEY_PARTS = 16
#: a line longer than this is refused before parsing: the longest a robot
#: file needs is a pose of 32 values or a name (at most 1,000 characters)
MAX_LINE_CHARS = 10_000
BOM = b"\xef\xbb\xbf"


class FileChangedError(RobotFileError):
    """The file on disk is not the one the robot was read from (or expected absent)."""


class ReadOnlyError(RobotFileError):
    """The file has no write permission; refused whoever runs dhsim."""


@dataclass(frozen=True)
class FileStamp:
    """What a file held when it was read or written."""

    path: Path  # the real file (symlinks resolved)
    mtime_ns: int
    size: int
    digest: str  # sha256 of the bytes

    def __fspath__(self) -> str:  # a stamp names its file: load(save(...)) works
        return str(self.path)


# -- reading ---------------------------------------------------------------------

#: one part of a key: a bare word or a quoted string on one line. No nested
#: repetition (Python 3.10 has no possessive quantifiers): inside a repeat,
#: each alternative matches one character of a class of its own, so a failed
#: match backs off in linear time, never exponential.
_KEY_PART = r"""(?:[A-Za-z0-9_-]+|"(?:[^"\\\n]|\\.)*"|'[^'\n]*')"""
#: what the scan passes over whole: comments and strings (dots in them are no keys)
_SKIPPED = (
    r"#[^\n]*"
    r'|"""(?:[^"\\]|\\[\s\S]|"(?!""))*"{3,5}'
    r"|'''(?:[^']|'(?!''))*'{3,5}"
    r'|"(?:[^"\\\n]|\\.)*"'
    r"|'[^'\n]*'"
)
#: a run of more than MAX_KEY_PARTS dotted parts, a comment or string passed
#: over, or a quote that opens no string (the parser stops there: so does the scan).
#: Values have runs of at most 2 (``1.5``, ``07:32:00.25``); only keys have more.
_SCAN = re.compile(
    rf"(?P<deep>(?<![A-Za-z0-9_.-]){_KEY_PART}(?:[ \t]*\.[ \t]*{_KEY_PART}){{{MAX_KEY_PARTS}}})"
    rf"|{_SKIPPED}|(?P<stop>[\"'])"
)


def _hostile(text: str) -> str | None:
    """What in ``text`` would make the TOML parser slow or greedy, naming the
    line (None: nothing). Linear in the text: strings and comments are passed
    over once, and a run of dotted parts is tried from its first part only
    (from each part only when spaces stand around the dots: at most
    MAX_KEY_PARTS tries of a part)."""
    for match in _SCAN.finditer(text):
        if match.lastgroup == "stop":
            break
        if match.lastgroup == "deep":
            line = text.count("\n", 0, match.start()) + 1
            return (
                f"line {line}: a key path of more than {MAX_KEY_PARTS} dotted parts "
                f"({shortened(match.group(), 40)}); a robot file's keys have 1 to 3"
            )
    for number, line in enumerate(text.split("\n"), start=1):
        if len(line) > MAX_LINE_CHARS:
            return (
                f"line {number} is {len(line)} characters long; "
                f"a robot file's lines have at most {MAX_LINE_CHARS}"
            )
    return None


def parse_toml(text: str, source: str = "<robot>") -> dict[str, Any]:
    """The TOML document in ``text`` (one byte order mark may start it),
    refused before parsing when it holds what would make the parser hang
    (:func:`_hostile`); every failure is a RobotFileError starting with ``source``."""
    text = text.removeprefix("\ufeff")  # a byte order mark, as some editors write
    if text.startswith("\ufeff"):
        raise _error(f"{source}: starts with two byte order marks; a file may have one")
    problem = _hostile(text)
    if problem is not None:
        raise _error(f"{source}: {problem}")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise _error(f"{source}: not valid TOML: {exc}") from None
    except RecursionError:  # tomllib recurses into nested arrays and inline tables
        raise _error(f"{source}: not valid TOML: nested too deeply") from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise _error(f"{source}: not valid TOML: {exc}") from None


def _check_keys(table: Mapping[str, Any], allowed: tuple[str, ...], where: str) -> None:
    for key in table:
        if key not in allowed:
            close = difflib.get_close_matches(key, allowed, n=1)
            hint = (
                f" (did you mean {close[0]!r}?)" if close else f" (allowed: {', '.join(allowed)})"
            )
            raise DhsimError(printable(f"{where}{shortened(key)}: unknown key{hint}"))


def _table(value: object, where: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise DhsimError(printable(f"{where}: expected a table"))
    return value


def _string(value: object, where: str) -> str:
    if not isinstance(value, str):
        raise DhsimError(f"{where}: expected a text string in quotes")
    return value


def _triple(value: object, where: str) -> tuple[float, float, float]:
    if not isinstance(value, list) or len(value) != 3:
        raise DhsimError(f"{where}: expected a list of 3 numbers, like [0.0, 0.0, 0.0]")
    x, y, z = (check_number(v, f"{where}[{i}]") for i, v in enumerate(value, start=1))
    return (x, y, z)


def _joint(data: object, number: int, units: str) -> Joint:
    where = f"joints[{number}]"
    table = _table(data, where)
    _check_keys(table, JOINT_KEYS, f"{where}.")
    for key in JOINT_REQUIRED:
        if key not in table:
            raise DhsimError(f"{where}: missing key {key!r}")
    joint_type = check_choice(
        table.get("type", "revolute"), ("revolute", "prismatic"), f"{where}.type"
    )
    values = {key: check_number(table[key], f"{where}.{key}") for key in JOINT_REQUIRED}
    low, high = default_limits(joint_type, units)
    optional = {
        key: check_number(table[key], f"{where}.{key}") if key in table else default
        for key, default in (("min", low), ("max", high), ("offset", 0.0))
    }
    return Joint(type=joint_type, **values, **optional)  # type: ignore[arg-type]


def robot_from_dict(data: Mapping[str, Any]) -> Robot:
    """Build a robot from parsed TOML, checking every key; raises DhsimError."""
    _check_keys(data, TOP_KEYS, "")
    for key in ("name", "joints"):
        if key not in data:
            raise DhsimError(f"missing key {key!r}")
    units = check_choice(data.get("units", "mm"), ("mm", "cm", "m", "in"), "units")
    joints_data = data["joints"]
    if not isinstance(joints_data, list):
        raise DhsimError("joints: expected an array of tables, written [[joints]]")
    joints = tuple(_joint(j, i, units) for i, j in enumerate(joints_data, start=1))
    tool = Tool()
    if "tool" in data:
        tool_data = _table(data["tool"], "tool")
        _check_keys(tool_data, TOOL_KEYS, "tool.")
        tool = Tool(
            xyz=_triple(tool_data.get("xyz", [0.0, 0.0, 0.0]), "tool.xyz"),
            rpy=_triple(tool_data.get("rpy", [0.0, 0.0, 0.0]), "tool.rpy"),
        )
    poses: list[tuple[str, tuple[float, ...]]] = []
    for name, values in _table(data.get("poses", {}), "poses").items():
        where = printable(f"poses.{shortened(name)}")
        if not isinstance(values, list):
            raise DhsimError(f"{where}: expected a list of {counted(len(joints), 'number')}")
        numbers = tuple(check_number(v, f"{where}[{i}]") for i, v in enumerate(values, start=1))
        poses.append((name, numbers))
    base_height = data.get("base_height", 0.0)
    return Robot(
        name=_string(data["name"], "name"),
        joints=joints,
        units=units,
        convention=_string(data.get("convention", "standard"), "convention"),
        base_height=check_number(base_height, "base_height"),
        base_z=_string(data.get("base_z", "+z"), "base_z"),
        base_x=_string(data.get("base_x", "+x"), "base_x"),
        base_xyz=_triple(data.get("base_xyz", [0.0, 0.0, 0.0]), "base_xyz"),
        base_rpy=_triple(data.get("base_rpy", [0.0, 0.0, 0.0]), "base_rpy"),
        tool=tool,
        poses=tuple(poses),
    )


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


def robot_to_dict(robot: Robot, *, full: bool = False) -> dict[str, Any]:
    """The TOML document for a robot; every field written, so it reads back equal.
    ``full`` also writes an identity tool and an empty poses table."""
    data: dict[str, Any] = {
        "name": robot.name,
        "units": robot.units,
        "convention": robot.convention,
        "base_height": robot.base_height,
        "base_z": robot.base_z,
        "base_x": robot.base_x,
    }
    if full or not robot.base_is_shorthand:
        data["base_xyz"] = _floats(robot.base_xyz)
        data["base_rpy"] = _floats(robot.base_rpy)
    if full or not robot.tool.is_identity:
        data["tool"] = {"xyz": _floats(robot.tool.xyz), "rpy": _floats(robot.tool.rpy)}
    if full or robot.poses:
        data["poses"] = {name: _floats(values) for name, values in robot.poses}
    data["joints"] = [
        {"type": j.type} | dict(zip(JOINT_KEYS[1:7], _floats(_values(j)), strict=True))
        for j in robot.joints
    ]
    for row, j in zip(data["joints"], robot.joints, strict=True):
        if full or j.offset:
            row["offset"] = float(j.offset)
    return data


def _floats(values) -> list[float]:
    return [float(v) for v in values]


def _values(joint: Joint) -> tuple[float, ...]:
    return (joint.theta, joint.d, joint.a, joint.alpha, joint.min, joint.max)


def _defaults(robot: Robot) -> dict[str, Any]:
    """What a file may leave out, for this robot (limits depend on type and unit)."""
    return {
        "units": "mm",
        "convention": "standard",
        "base_height": 0.0,
        "base_z": "+z",
        "base_x": "+x",
        "base_xyz": [0.0, 0.0, 0.0],
        "base_rpy": [0.0, 0.0, 0.0],
        "tool": {"xyz": [0.0, 0.0, 0.0], "rpy": [0.0, 0.0, 0.0]},
        "poses": {},
        "joints": [
            dict(zip(("min", "max"), default_limits(j.type, robot.units), strict=True))
            | {"type": "revolute", "offset": 0.0}
            for j in robot.joints
        ],
    }


#: an array of numbers tomli_w wrote one item per line
_NUMBER_COLUMN = re.compile(r"\[\n((?:    [-+0-9.eE]+(?:inf|nan)?,\n)+)\]")


def dumps(robot: Robot) -> str:
    """A fresh robot file; arrays of numbers on one line, as people write them."""
    text = tomli_w.dumps(robot_to_dict(robot), multiline_strings=False)
    return _NUMBER_COLUMN.sub(
        lambda m: (
            "[" + ", ".join(item.strip().rstrip(",") for item in m.group(1).splitlines()) + "]"
        ),
        text,
    )


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
            data, defaults = robot_to_dict(robot, full=True), _defaults(robot)
            text = update_text(base, data, defaults, current, ordered=("poses",))
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
    a stamp means the file must still hold what it held then
    (:class:`FileChangedError` otherwise). An existing file is updated in
    place (comments kept); with no file, ``base_text`` is the starting point.
    Returns the stamp of what was written."""
    given = Path(path)
    target = _real(given) if given.is_symlink() else given  # write the file, keep the link
    existing = _existing(target, given)
    _check_expect(given, expect, existing)
    raw = existing[0] if existing else None
    old_text = _text_or_none(raw)
    text = render(robot, old_text if _is_toml(old_text) else base_text)
    had_bom = raw.startswith(BOM) if raw is not None else (base_text or "").startswith("\ufeff")
    data = (BOM if had_bom else b"") + text.encode("utf-8")
    remove_stale_temps(target)
    info = write_atomic(target, given, data, existing[1] if existing else None)
    return FileStamp(_real(target), info.st_mtime_ns, len(data), hashlib.sha256(data).hexdigest())


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


def _check_expect(given: Path, expect: object, existing: tuple | None) -> None:
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

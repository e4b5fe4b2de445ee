"""The bundled robots, the user's own robot library, and how a robot
argument (a path or a name) is resolved.

Bundled is what dhsim ships, by its own list (:data:`BUNDLED_ROBOTS`), never
"any file in that folder". The user's robots live in their library,
``$XDG_DATA_HOME/dhsim/robots/`` (else ``~/.local/share/dhsim/robots/``):
``dhsim new`` and the save dialog put a new robot there unless given a path.
A name is looked up there first, then among the bundled robots; an argument
that names an existing file, or holds a slash, is a path.
"""

from __future__ import annotations

import contextlib
import errno
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from dhsim_tui.core.analysis.workspace import arm_reach
from dhsim_tui.core.files.robotfile import load
from dhsim_tui.core.model.errors import RobotFileError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import counted, printable, shortened
from dhsim_tui.core.model.units import LENGTH_DECIMALS
from dhsim_tui.core.model.validation import fmt

DEFAULT_ROBOT = "puma560"


def bundled_dir() -> Path:
    """Where the bundled robot files are: inside the installed package, or
    the repository's ``robots/`` folder in a source checkout."""
    package = Path(__file__).resolve().parents[2]  # dhsim_tui/core/files/library.py
    packaged = package / "robots"
    if packaged.is_dir():
        return packaged
    return package.parent / "robots"


#: the robots dhsim ships, by its own list: a file the user saves into the
#: same folder (an editable install's ``robots/``) is the user's, never bundled
BUNDLED_ROBOTS = (
    "cobra600",
    "gantry",
    "irb140",
    "panda",
    "planar2",
    "puma560",
    "puma560_modified",
    "scara_pedestal",
    "stanford",
    "ur5",
)


#: the most files :func:`user_robots` lists (a library is a few dozen robots)
USER_LIBRARY_LIMIT = 10_000


def user_library_dir() -> Path:
    """The user's robot library: ``$XDG_DATA_HOME/dhsim/robots`` when that
    variable is an absolute path (the XDG rule: a relative one is ignored),
    else ``~/.local/share/dhsim/robots``. It may not exist yet.

    A :class:`RobotFileError` when there is no home folder to put it in."""
    data = os.environ.get("XDG_DATA_HOME", "")
    if data and Path(data).is_absolute():
        return Path(data) / "dhsim" / "robots"
    try:
        return Path.home() / ".local" / "share" / "dhsim" / "robots"
    except (RuntimeError, KeyError, OSError) as exc:  # no HOME, no passwd entry
        raise RobotFileError(
            "no folder for your robots: set HOME or XDG_DATA_HOME, or give a path"
        ) from exc


def _user_library_or_none() -> Path | None:
    try:
        return user_library_dir()
    except RobotFileError:
        return None


def user_robots(notes: list[str] | None = None) -> list[Path]:
    """The robot files (``*.toml``) in the user library, by name; none when
    it does not exist. A library that cannot be read adds a line to ``notes``."""
    folder = _user_library_or_none()
    if folder is None:
        return []
    try:
        if not folder.is_dir():
            return []
        found = []
        for entry in os.scandir(folder):
            if len(found) >= USER_LIBRARY_LIMIT:
                break
            if entry.name.lower().endswith(".toml") and not entry.name.startswith("."):
                found.append(Path(entry.path))
    except OSError as exc:
        if notes is not None:
            notes.append(f"{printable(str(folder))}: cannot be read: {_why(exc)}")
        return []
    except ValueError:
        return []
    return sorted(found, key=lambda path: (path.name.lower(), path.name))


def user_path(name: str) -> Path | None:
    """The user library's file for ``name`` (``irb120`` or ``irb120.toml``,
    any case), or None. A name with a slash is a path, never looked up."""
    if not name.strip() or _is_path(name):
        return None
    key = name.strip().removesuffix(".toml").removesuffix(".TOML")
    if key in ("", ".", ".."):
        return None
    files = user_robots()
    for path in files:  # the exact name first (two files may differ only by case)
        if path.stem == key:
            return path
    for path in files:
        if path.stem.lower() == key.lower():
            return path
    return None


def in_user_library(path: Path) -> bool:
    """Whether ``path`` is a file in the user library."""
    folder = _user_library_or_none()
    try:
        return folder is not None and path.resolve().parent == folder.resolve()
    except (OSError, RuntimeError, ValueError):
        return False


def bundled_names() -> list[str]:
    return list(BUNDLED_ROBOTS)


def bundled_path(name: str) -> Path | None:
    key = name.lower().removesuffix(".toml")
    for stem in BUNDLED_ROBOTS:
        if stem.lower() == key:
            return bundled_dir() / f"{stem}.toml"
    return None


def is_bundled_file(path: Path) -> bool:
    """Whether ``path`` is one of the files dhsim ships (by its list, not by
    the folder it lies in)."""
    try:
        found = bundled_path(path.stem) if path.suffix.lower() == ".toml" else None
        return found is not None and path.resolve() == found.resolve()
    except (OSError, RuntimeError, ValueError):
        return False


#: where a robot argument was found: a path as given, the user library, bundled
Origin = Literal["path", "yours", "bundled"]


@dataclass(frozen=True)
class Found:
    """A resolved robot argument: the file, and where it was found.
    ``shadows``: a bundled robot of the same name the user's file hides."""

    path: Path
    origin: Origin
    shadows: Path | None = None

    def opened(self) -> str:
        """What was opened, for the status line or stderr: ``opened your
        irb120: /home/me/.local/share/dhsim/robots/irb120.toml`` (``your
        puma560 (not the bundled one): …`` when it hides a bundled robot),
        ``opened the bundled puma560``, or ``opened PATH``. Escaped."""
        shown = printable(str(self.path))
        if self.origin == "yours":
            hides = " (not the bundled one)" if self.shadows is not None else ""
            return f"opened your {printable(self.path.stem)}{hides}: {shown}"
        if self.origin == "bundled":
            return f"opened the bundled {printable(self.path.stem)}"
        return f"opened {shown}"


def resolve(argument: str) -> Path:
    """The file a robot argument names (see :func:`find`)."""
    return find(argument).path


def find(argument: str) -> Found:
    """A robot argument is an existing path, else a name: the user library's
    robot of that name first, then the bundled one. An argument with a
    slash is only ever a path.

    Every way this can fail is a :class:`RobotFileError` that quotes the
    argument with control characters escaped: an empty argument, a name too
    long for the file system, a folder on the way that cannot be read, a
    relative path after the working folder was deleted.
    """
    if not argument.strip():
        raise RobotFileError(
            f"the robot argument {printable(repr(argument))} is empty: give a robot file "
            f"(.toml) or a bundled robot's name ({', '.join(bundled_names())})"
        )
    shown = printable(argument)
    path = Path(argument)
    with contextlib.suppress(RuntimeError):  # "~someone" with no such user: as written
        path = path.expanduser()
    try:
        if path.exists():
            return Found(path, "path")
        problem = None
    except OSError as exc:  # ENAMETOOLONG, EACCES on a folder on the way, ELOOP ...
        problem = _why(exc)
    except ValueError:  # a NUL byte in the path
        problem = "a path cannot hold a NUL character"
    bundled = bundled_path(argument)
    mine = user_path(argument)
    if mine is not None:
        return Found(mine, "yours", bundled)
    if bundled is not None:
        return Found(bundled, "bundled")
    if problem is not None:
        raise RobotFileError(f"{shown}: cannot read: {problem}")
    if not path.is_absolute() and not _working_folder_exists():
        raise RobotFileError(
            f"{shown}: no such file: the working folder was deleted, so a relative "
            "path finds nothing; give the full path or a bundled robot's name"
        )
    if _is_path(argument):
        raise RobotFileError(f"{shown}: no such file")
    where = _library_shown()
    raise RobotFileError(
        f"{shown}: no such file, and no robot of yours{where} or bundled one has that "
        f"name (bundled: {', '.join(bundled_names())}; see 'dhsim list')"
    )


def _is_path(argument: str) -> bool:
    """An argument with a slash is a path, never a robot's name."""
    return "/" in argument or os.sep in argument or "\\" in argument


def _library_shown() -> str:
    folder = _user_library_or_none()
    return "" if folder is None else f" (in {printable(str(folder))})"


def _why(exc: OSError) -> str:
    if exc.errno == errno.ENAMETOOLONG:
        return "the path is too long (255 bytes per name, 4096 in all)"
    if exc.errno == errno.EACCES:
        return "permission denied (a folder on the way cannot be read)"
    return printable(exc.strerror or str(exc))


def _working_folder_exists() -> bool:
    try:
        os.getcwd()
    except OSError:
        return False
    return True


def load_robot(argument: str | None = None) -> tuple[Robot, Path]:
    """Load a robot by path or name, the user's first (the bundled Puma 560
    when None)."""
    path = resolve(argument if argument is not None else DEFAULT_ROBOT)
    return load(path), path


def describe(robot: Robot) -> str:
    """The one-line summary ``dhsim check`` and ``dhsim list`` print (a long
    name shortened in the middle). The reach is the arm's own
    (:func:`~dhsim_tui.core.analysis.workspace.arm_reach`: the farthest the tool gets
    from frame 0's origin within the limits), the same in either convention,
    shown to the robot unit's decimals (a tiny reach to 6 significant digits)."""
    found = arm_reach(robot)
    total = round(found, LENGTH_DECIMALS[robot.units]) + 0.0
    if total == 0 and found > 0:  # a tiny arm: its reach, never "0"
        total = float(f"{found:.6g}")
    name = printable(shortened(robot.name))
    return (
        f"{name}: {counted(robot.dof, 'joint')}, {robot.type_string}, "
        f"{robot.convention} D-H, reach {fmt(total)} {robot.units}"
    )

"""The bundled robots and how a robot argument (a path or a name) is resolved."""

from __future__ import annotations

import contextlib
import errno
import os
from pathlib import Path

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


def resolve(argument: str) -> Path:
    """A robot argument is an existing path or the name of a bundled robot.

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
            return path
        problem = None
    except OSError as exc:  # ENAMETOOLONG, EACCES on a folder on the way, ELOOP ...
        problem = _why(exc)
    except ValueError:  # a NUL byte in the path
        problem = "a path cannot hold a NUL character"
    found = bundled_path(argument)
    if found is not None:
        return found
    if problem is not None:
        raise RobotFileError(f"{shown}: cannot read: {problem}")
    if not path.is_absolute() and not _working_folder_exists():
        raise RobotFileError(
            f"{shown}: no such file: the working folder was deleted, so a relative "
            "path finds nothing; give the full path or a bundled robot's name"
        )
    raise RobotFileError(
        f"{shown}: no such file, and no bundled robot has that name "
        f"(bundled: {', '.join(bundled_names())})"
    )


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
    """Load a robot by path or bundled name (the Puma 560 when None)."""
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

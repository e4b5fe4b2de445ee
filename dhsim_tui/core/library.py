"""The bundled robots and how a robot argument (a path or a name) is resolved."""

from __future__ import annotations

import contextlib
from pathlib import Path

from dhsim_tui.core.errors import RobotFileError
from dhsim_tui.core.model import Robot
from dhsim_tui.core.robotfile import load

DEFAULT_ROBOT = "puma560"


def bundled_dir() -> Path:
    """Where the bundled robot files are: inside the installed package, or
    the repository's ``robots/`` folder in a source checkout."""
    packaged = Path(__file__).resolve().parent.parent / "robots"
    if packaged.is_dir():
        return packaged
    return Path(__file__).resolve().parents[2] / "robots"


def bundled_names() -> list[str]:
    return sorted(p.stem for p in bundled_dir().glob("*.toml"))


def bundled_path(name: str) -> Path | None:
    key = name.lower().removesuffix(".toml")
    for stem in bundled_names():
        if stem.lower() == key:
            return bundled_dir() / f"{stem}.toml"
    return None


def resolve(argument: str) -> Path:
    """A robot argument is an existing path or the name of a bundled robot."""
    path = Path(argument)
    with contextlib.suppress(RuntimeError):  # "~someone" with no such user: as written
        path = path.expanduser()
    if path.exists():
        return path
    found = bundled_path(argument)
    if found is not None:
        return found
    raise RobotFileError(
        f"{argument}: no such file, and no bundled robot has that name "
        f"(bundled: {', '.join(bundled_names())})"
    )


def load_robot(argument: str | None = None) -> tuple[Robot, Path]:
    """Load a robot by path or bundled name (the Puma 560 when None)."""
    path = resolve(argument if argument is not None else DEFAULT_ROBOT)
    return load(path), path


def describe(robot: Robot) -> str:
    """The one-line summary ``dhsim check`` and ``dhsim list`` print."""
    from dhsim_tui.core.validation import fmt
    from dhsim_tui.core.workspace import reach

    return (
        f"{robot.name}: {robot.dof} joints, {robot.type_string}, {robot.convention} D-H, "
        f"reach {fmt(round(reach(robot), 3))} {robot.units}"
    )

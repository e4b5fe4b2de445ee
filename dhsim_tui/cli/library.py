"""``dhsim list`` and ``dhsim new``: the user's robots and the bundled ones.

``dhsim list`` shows two groups, "yours" (the robots in the user library,
with their paths) and "bundled" (what dhsim ships, by its own list);
``--json`` prints one object with both. ``dhsim new NAME`` starts a robot in
the table editor whose save goes to the user library, or to ``-o FILE``.
Which file a robot name opened is said on stderr when the user's robot
hides a bundled one of the same name (:func:`note_which`): never on stdout,
where a command's data goes.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from dhsim_tui.cli.streams import to_stderr
from dhsim_tui.core.analysis.workspace import arm_reach
from dhsim_tui.core.files.library import (
    bundled_names,
    bundled_path,
    describe,
    find,
    user_library_dir,
    user_robots,
)
from dhsim_tui.core.files.robotfile import load
from dhsim_tui.core.model.errors import DhsimError, RobotFileError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.units import LENGTH_DECIMALS

EXIT_USAGE = 2
#: the width of the name column of ``dhsim list``
NAME_WIDTH = 17


def _entry(name: str, path: Path, robot: Robot | None, error: str | None) -> dict:
    """One robot of ``dhsim list --json``."""
    entry: dict = {"name": name, "path": str(path)}
    if robot is None:
        entry["error"] = error
        return entry
    reach = arm_reach(robot)
    shown_reach = round(reach, LENGTH_DECIMALS[robot.units]) + 0.0
    entry.update(
        {
            "robot": robot.name,
            "dof": robot.dof,
            "types": robot.type_string,
            "convention": robot.convention,
            "units": robot.units,
            "reach": shown_reach if shown_reach or not reach else float(f"{reach:.6g}"),
        }
    )
    return entry


def _absolute(path: Path) -> Path:
    try:
        return path.absolute()
    except OSError:  # the working folder was deleted
        return path


def cmd_list(args: argparse.Namespace) -> int:
    """Your robots (with their paths), then the bundled ones."""
    status = 0
    notes: list[str] = []
    try:
        folder: Path | None = user_library_dir()
    except RobotFileError as exc:
        folder = None
        notes.append(str(exc))
    yours = []  # (its entry, its line's summary)
    for path in user_robots(notes):
        try:
            robot = load(path)
        except DhsimError as exc:
            reason = _reason(exc, path)
            yours.append((_entry(path.stem, _absolute(path), None, reason), None))
            continue
        yours.append((_entry(path.stem, _absolute(path), robot, None), describe(robot)))
    bundled = []
    for name in bundled_names():
        path = bundled_path(name)
        assert path is not None  # a name of the list
        try:
            robot = load(path)
        except DhsimError as exc:
            to_stderr(f"dhsim: error: {printable(str(exc))}")
            status = EXIT_USAGE
            continue
        bundled.append((name, path, robot))
    for note in notes:
        to_stderr(f"dhsim: {printable(note)}")
    if args.json:
        print(
            json.dumps(
                {
                    "library": None if folder is None else str(folder),
                    "yours": [entry for entry, _ in yours],
                    "bundled": [_entry(n, p, r, None) for n, p, r in bundled],
                }
            )
        )
        return status
    where = "" if folder is None else f" ({printable(str(folder))})"
    if not yours:
        print(f"yours{where}: none yet ('dhsim new NAME' saves one there)")
    else:
        print(f"yours{where}:")
    for entry, summary in yours:
        said = summary if summary is not None else f"(cannot be opened: {entry['error']})"
        print(printable(f"  {entry['name']:<{NAME_WIDTH}} {said}  ({entry['path']})"))
    print("bundled:")
    for name, _, robot in bundled:
        print(printable(f"  {name:<{NAME_WIDTH}} {describe(robot)}"))
    return status


def _reason(error: BaseException, path: Path) -> str:
    text = printable(str(error))
    return text.removeprefix(f"{printable(str(path))}: ")


def note_which(argument: str | None) -> None:
    """On stderr, when a robot name opened the user's robot rather than the
    bundled one of the same name: which file it was (stdout is the command's
    data, and stays as it was)."""
    if not argument:
        return
    try:
        found = find(argument)
    except DhsimError:
        return  # the command itself says what is wrong
    if found.origin == "yours" and found.shadows is not None:
        to_stderr(f"dhsim: {found.opened()}")


def opened_notice(argument: str | None) -> str | None:
    """What the simulator's status line says first about a robot given by
    name (your robot, or a bundled one); None for a path or no argument."""
    if not argument:
        return None
    try:
        found = find(argument)
    except DhsimError:
        return None
    return None if found.origin == "path" else found.opened()


def new_target(output: str | None) -> Path | None:
    """``dhsim new -o FILE``: where the new robot is saved (``.toml``
    added when missing); a folder that exists is refused, saying why."""
    if output is None:
        return None
    if not output.strip():
        raise RobotFileError("-o: the file name is empty; give a path to a .toml file")
    path = Path(output).expanduser()
    if path.suffix.lower() != ".toml":
        path = path.with_name(path.name + ".toml")
    try:
        if path.is_dir():
            raise RobotFileError(f"{printable(str(path))}: is a folder; give a file name")
    except (OSError, ValueError) as exc:
        raise RobotFileError(f"{printable(output)}: cannot be used: {exc}") from None
    return _absolute(path)

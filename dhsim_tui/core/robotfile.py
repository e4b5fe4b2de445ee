"""Robot files: TOML in, TOML out (the schema is in the README).

Loading is strict: every key is checked for type and spelling and every
problem is reported as one :class:`RobotFileError` naming the file and the
field. Saving is atomic (temporary file, fsync, rename), and
``load(save(robot)) == robot`` exactly.
"""

from __future__ import annotations

import contextlib
import difflib
import os
import tempfile
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import tomli_w

from dhsim_tui.core.errors import DhsimError, RobotFileError
from dhsim_tui.core.model import Joint, Robot, Tool, default_limits
from dhsim_tui.core.validation import check_choice, check_number

TOP_KEYS = (
    "name",
    "units",
    "convention",
    "base_height",
    "base_z",
    "base_x",
    "tool",
    "poses",
    "joints",
)
JOINT_KEYS = ("type", "theta", "d", "a", "alpha", "min", "max")
JOINT_REQUIRED = ("theta", "d", "a", "alpha")
TOOL_KEYS = ("xyz", "rpy")
#: robot files larger than this are refused before parsing (a robot is < 10 kB)
MAX_FILE_BYTES = 1_000_000


def _check_keys(table: Mapping[str, Any], allowed: tuple[str, ...], where: str) -> None:
    for key in table:
        if key not in allowed:
            close = difflib.get_close_matches(key, allowed, n=1)
            hint = (
                f" (did you mean {close[0]!r}?)" if close else f" (allowed: {', '.join(allowed)})"
            )
            raise DhsimError(f"{where}{key}: unknown key{hint}")


def _table(value: object, where: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise DhsimError(f"{where}: expected a table")
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
    limits = {
        key: check_number(table[key], f"{where}.{key}") if key in table else default
        for key, default in (("min", low), ("max", high))
    }
    return Joint(type=joint_type, **values, **limits)  # type: ignore[arg-type]


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
        if not isinstance(values, list):
            raise DhsimError(f"poses.{name}: expected a list of {len(joints)} numbers")
        numbers = tuple(
            check_number(v, f"poses.{name}[{i}]") for i, v in enumerate(values, start=1)
        )
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
        tool=tool,
        poses=tuple(poses),
    )


def loads(text: str, source: str = "<robot>") -> Robot:
    """Parse and validate robot TOML; errors start with ``source``."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise RobotFileError(f"{source}: not valid TOML: {exc}") from None
    except RecursionError:  # tomllib recurses into nested arrays and inline tables
        raise RobotFileError(f"{source}: not valid TOML: nested too deeply") from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise RobotFileError(f"{source}: not valid TOML: {exc}") from None
    try:
        return robot_from_dict(data)
    except DhsimError as exc:
        raise RobotFileError(f"{source}: {exc}") from None


def load(path: str | os.PathLike[str]) -> Robot:
    """Read a robot file; every failure is a RobotFileError naming the file."""
    path = Path(path)
    try:
        if path.is_dir():
            raise RobotFileError(f"{path}: is a folder, not a robot file")
        if path.exists() and not path.is_file():
            raise RobotFileError(f"{path}: is not a regular file (a device or a pipe?)")
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise RobotFileError(f"{path}: {size} bytes is too large for a robot file")
        raw = path.read_bytes()
    except FileNotFoundError:
        raise RobotFileError(f"{path}: no such file") from None
    except PermissionError:
        raise RobotFileError(f"{path}: permission denied") from None
    except OSError as exc:
        raise RobotFileError(f"{path}: cannot read: {exc.strerror or exc}") from None
    except RobotFileError:
        raise
    except ValueError as exc:  # e.g. a NUL byte in the path
        raise RobotFileError(f"{path}: cannot read: {exc}") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise RobotFileError(
            f"{path}: not a text file (invalid UTF-8 at byte {exc.start})"
        ) from None
    return loads(text, str(path))


def robot_to_dict(robot: Robot) -> dict[str, Any]:
    """The TOML document for a robot; every field written, so it reads back equal."""
    data: dict[str, Any] = {
        "name": robot.name,
        "units": robot.units,
        "convention": robot.convention,
        "base_height": robot.base_height,
        "base_z": robot.base_z,
        "base_x": robot.base_x,
    }
    if not robot.tool.is_identity:
        data["tool"] = {"xyz": list(robot.tool.xyz), "rpy": list(robot.tool.rpy)}
    if robot.poses:
        data["poses"] = {name: list(values) for name, values in robot.poses}
    data["joints"] = [
        {
            "type": j.type,
            "theta": j.theta,
            "d": j.d,
            "a": j.a,
            "alpha": j.alpha,
            "min": j.min,
            "max": j.max,
        }
        for j in robot.joints
    ]
    return data


def dumps(robot: Robot) -> str:
    return tomli_w.dumps(robot_to_dict(robot), multiline_strings=False)


def save(robot: Robot, path: str | os.PathLike[str]) -> Path:
    """Write atomically: a temporary file in the same folder, flushed, fsynced,
    then renamed over ``path``. On any failure the old file is untouched."""
    path = Path(path)
    text = dumps(robot)
    if path.is_symlink():  # write the file the link points to, keep the link
        path = path.resolve()
    folder = path.parent if str(path.parent) else Path(".")
    if path.is_dir():
        raise RobotFileError(f"{path}: is a folder, not a robot file")
    tmp_name = None
    try:
        fd, tmp_name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
        os.chmod(tmp_name, _mode_for(path))  # mkstemp makes it private (0600)
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp_name, path)
        tmp_name = None
        _fsync_folder(folder)
    except FileNotFoundError:
        raise RobotFileError(f"{path}: cannot save: folder {folder} does not exist") from None
    except PermissionError:
        raise RobotFileError(f"{path}: cannot save: permission denied") from None
    except OSError as exc:
        raise RobotFileError(f"{path}: cannot save: {exc.strerror or exc}") from None
    finally:
        if tmp_name is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp_name)
    return path


def _mode_for(path: Path) -> int:
    """Keep an existing file's permissions; a new file gets the usual 0666 & ~umask."""
    try:
        return path.stat().st_mode & 0o7777
    except OSError:
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

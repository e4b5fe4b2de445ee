"""Saving a robot from the UI: a name when it needs one, and never over a file
that changed on disk or may not be written, without asking.

Used by the editor's ctrl+s and "save as", and by the simulator's ``P`` and
quit guard. A robot without a file of its own (new, imported, or bundled: a
template) goes to the user library (``$XDG_DATA_HOME/dhsim/robots/``) under
the name typed, or to the path typed; the dialog shows the full path before
anything is written, and never writes over a bundled robot's file. Call it
from a ``@work`` worker (it asks questions with ``push_screen_wait``).
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from types import EllipsisType
from typing import Literal

from rich.text import Text
from textual.app import App
from textual.widgets import Input, Label

from dhsim_tui.core.files.library import in_user_library, is_bundled_file, user_library_dir
from dhsim_tui.core.files.robotfile import (
    FileChangedError,
    FileStamp,
    ReadOnlyError,
    load_with_stamp,
    read_stamp,
    save,
)
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError, RobotFileError
from dhsim_tui.core.model.merge import Side, merge
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal.charset import shown
from dhsim_tui.tui.screens.dialogs import (
    Choice,
    Confirm,
    FileChanged,
    ReadOnly,
    reason_of,
    short_path,
)
from dhsim_tui.tui.screens.value_entry import ValueEntry

#: how a flow tells the user something: (message, is_error)
Report = Callable[[str, bool], None]


@dataclass(frozen=True)
class SaveResult:
    """What is on disk now: ``saved`` (``robot`` was written) or ``reloaded``
    (the user chose the file's new content; ``robot`` is what it holds)."""

    kind: Literal["saved", "reloaded"]
    robot: Robot
    path: Path
    stamp: FileStamp


def is_bundled(path: Path | None) -> bool:
    """A bundled robot file is a template: saving it asks for a new name.
    Bundled is what dhsim ships by its own list, wherever the user's own
    files lie (an editable install saves beside the bundled ones)."""
    return path is not None and is_bundled_file(path)


#: a path in a message is at most this long, so it fits one line of the
#: editor's status at 80 columns (the reason comes first)
MESSAGE_PATH_LIMIT = 50
#: the most a file's text is read to keep its comments in a "save as"
BASE_TEXT_LIMIT = 1_000_000


def failure(error: BaseException, path: object) -> str:
    """``not saved: <reason> — <path shortened in the middle>``: the reason first."""
    reason = reason_of(error, path).removeprefix("cannot save: ")
    return f"not saved: {reason} — {short_path(path, MESSAGE_PATH_LIMIT)}"


async def save_flow(
    app: App,
    robot: Robot,
    path: Path | None,
    stamp: FileStamp | None,
    *,
    base_text: str | None = None,
    save_as: bool = False,
    report: Report | None = None,
) -> SaveResult | None:
    """Save ``robot`` to ``path`` (expecting the file ``stamp`` describes), or
    ask for a name when there is no path, it is a bundled file, or
    ``save_as``. None when cancelled or failed, after telling the user
    (``report``, else a notification); everything stays in memory.

    ``base_text`` (default: what ``path`` holds) is where a new file starts,
    so the comments of the file the robot came from are kept."""

    def tell(message: str, error: bool = False) -> None:
        message = shown(message, app)
        if report is not None:
            report(message, error)
        else:
            app.notify(message, severity="error" if error else "information", timeout=8)

    if base_text is None:
        base_text = file_text(path)
    target: Path | None = path
    expect: FileStamp | EllipsisType | None = stamp
    if path is None or save_as or is_bundled(path):
        asked = await _ask_target(app, robot, path, save_as)
        if asked is None:
            tell("not saved")
            return None
        target, expect = asked
    assert target is not None
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        where = short_path(target, MESSAGE_PATH_LIMIT)
        tell(f"not saved: cannot make its folder: {reason_of(exc, target.parent)} — {where}", True)
        return None
    while True:
        try:
            new_stamp = save(robot, target, expect=expect, base_text=base_text)
        except FileChangedError as exc:
            answer = await app.push_screen_wait(FileChanged(target, _why(exc)))
            if answer == "overwrite":
                expect = _stamp_now(target)
                continue
            if answer == "reload":
                return _reload(target, tell)
            tell("not saved: the file changed on disk; nothing was written")
            return None
        except ReadOnlyError as exc:
            if await app.push_screen_wait(ReadOnly(target, reason_of(exc, target))):
                return await save_flow(
                    app, robot, target, None, base_text=base_text, save_as=True, report=report
                )
            tell(
                f"not saved: the file is read-only — {short_path(target, MESSAGE_PATH_LIMIT)}", True
            )
            return None
        except (DhsimError, OSError, ValueError) as exc:
            tell(failure(exc, target), True)
            return None
        tell(f"saved {short_path(target, MESSAGE_PATH_LIMIT)}")
        return SaveResult("saved", robot, target, new_stamp)


def _why(error: FileChangedError) -> str:
    """The part of the core's message after 'changed on disk since it was opened'."""
    text = str(error)
    for mark in (": ", " ("):
        _, found, tail = text.rpartition("since it was opened" + mark)
        if found:
            return tail.removesuffix(")")
    return ""


def _stamp_now(target: Path) -> FileStamp | EllipsisType | None:
    """What "overwrite" expects: the file as it is now (no check if it cannot be read)."""
    try:
        return read_stamp(target)
    except RobotFileError:
        return ...


def _reload(target: Path, tell: Report) -> SaveResult | None:
    try:
        robot, stamp = load_with_stamp(target)
    except DhsimError as exc:
        where = short_path(target, MESSAGE_PATH_LIMIT)
        tell(f"cannot reload: {reason_of(exc, target)} — {where}", True)
        return None
    return SaveResult("reloaded", robot, target, stamp)


@dataclass(frozen=True)
class Reapplied:
    """After a reload: the robot to show (the file's with my edits on top),
    and what to say about it."""

    robot: Robot
    message: str
    combined: bool  # False: the two could not be combined; ``robot`` is mine


async def reapply_edits(app: App, base: Robot | None, mine: Robot, theirs: Robot) -> Reapplied:
    """The file as it is on disk (``theirs``) with my unsaved edits (against
    ``base``, what the file held when it was read) put back on top; each
    field both sides changed is asked about, naming it and both values
    (escape keeps the file's)."""
    found = merge(base if base is not None else theirs, mine, theirs)
    choices: dict[str, Side] = {}
    for conflict in found.conflicts:
        answer = await app.push_screen_wait(
            Choice(
                f"{conflict.label}: changed here and on disk",
                [
                    ("mine", f"keep yours: {conflict.mine}"),
                    ("theirs", f"keep the file's: {conflict.theirs}"),
                ],
                "mine",
                hint="↑↓ choose · enter picks · escape keeps the file's",
            )
        )
        choices[conflict.key] = "mine" if answer == "mine" else "theirs"
    try:
        merged = found.resolve(choices)
    except DhsimError as exc:
        return Reapplied(mine, f"{exc}; nothing changed here (ctrl+s asks again)", False)
    kept = sum(1 for side in choices.values() if side == "mine")
    asked = f"; {len(choices)} asked, {kept} of yours kept" if choices else ""
    if merged == theirs:
        return Reapplied(merged, f"the file's version (none of your edits left){asked}", True)
    return Reapplied(
        merged, f"the file's changes, with your edits on top{asked} (ctrl+z takes yours out)", True
    )


def file_text(path: Path | None) -> str | None:
    """The text of a robot file, to keep its comments when the robot is saved
    to a new file (None when there is none or it cannot be read)."""
    try:
        if path is None or path.stat().st_size > BASE_TEXT_LIMIT:
            return None
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError, ValueError):
        return None


def suggested_name(robot: Robot, path: Path | None, save_as: bool = False) -> str:
    """A file name to offer: the file's own (a bundled irb140 offers
    "irb140"), else one made from the robot's name; "save as" of a file
    already in the user library offers NAME_copy."""
    name = editing.slug(robot.name)
    if path is not None:
        with contextlib.suppress(DhsimError):
            name = editing.check_file_name(path.stem)
        if save_as and in_user_library(path):
            name = f"{name}_copy"
    return name


def save_target(text: str) -> Path:
    """The file the save dialog's text names, as a full path: a bare name is
    ``<user library>/<name>.toml``; text with a slash (or starting with
    ``~``) is a path (``.toml`` added when missing). A bundled robot's file
    is refused: a bundled robot is a template, and yours are never bundled.
    :class:`DhsimError` saying what is wrong."""
    typed = text.strip()
    if "/" in typed or "\\" in typed or typed.startswith("~"):
        path = Path(typed)
        with contextlib.suppress(RuntimeError):  # "~someone" with no such user: as typed
            path = path.expanduser()
        home_only = "/" not in typed and "\\" not in typed and path != Path(typed)
        if typed.endswith(("/", "\\")) or path.name in ("", ".", "..") or home_only:
            # "~" (or "~user") alone is a home folder, never "<its name>.toml" beside it
            raise DhsimError("file name: the path ends in a folder; add a file name")
        path = path.with_name(f"{editing.check_file_name(path.name)}.toml")
    else:
        path = user_library_dir() / f"{editing.check_file_name(typed)}.toml"
    with contextlib.suppress(OSError):  # the working folder was deleted: as typed
        path = path.absolute()
    if is_bundled_file(path):
        raise DhsimError(
            f"{printable(path.name)} is a robot dhsim ships; give another name "
            "(a bare name goes in your robot library)"
        )
    return path


def library_file_hint() -> str:
    """``/home/me/.local/share/dhsim/robots/<name>.toml`` (or a path you give)."""
    try:
        return f"{user_library_dir()}/<name>.toml (or a path you give)"
    except DhsimError:
        return "a path you give"


def _target_hint(text: str) -> str:
    """Under the save dialog's input: the full path the text saves to."""
    try:
        return f"saves to {save_target(text)}"
    except DhsimError:
        try:
            folder = user_library_dir()
        except DhsimError:
            return "type a path to a .toml file"
        return f"a name (saved in {folder}/) or a path"


class SaveTarget(ValueEntry):
    """The save dialog: a name (the user library) or a path, the full path it
    saves to shown under the input as it is typed, before anything is written.
    Dismisses with that :class:`~pathlib.Path` (None when cancelled)."""

    def __init__(self, value: str) -> None:
        super().__init__("save as", value, _target_hint(value), save_target)

    def on_input_changed(self, event: Input.Changed) -> None:
        super().on_input_changed(event)
        hint = shown(printable(_target_hint(event.value)), self.app)
        self.query_one("#hint", Label).update(Text(hint))


def _offered(app: App, robot: Robot, path: Path | None, save_as: bool) -> str:
    """What the save dialog starts with: a name for the user library, or the
    path ``dhsim new -o FILE`` gave for a new robot."""
    target = getattr(app, "new_target", None)
    if path is None and isinstance(target, Path):
        return str(target)
    return suggested_name(robot, path, save_as)


async def _ask_target(
    app: App, robot: Robot, path: Path | None, save_as: bool
) -> tuple[Path, FileStamp | None] | None:
    """Ask a file name or path; confirm replacing a different existing file.
    Returns the target and what it must hold when written (None: must not exist)."""
    target = await app.push_screen_wait(SaveTarget(_offered(app, robot, path, save_as)))
    if target is None:
        return None
    if path is None and target == getattr(app, "new_target", None):
        app.new_target = None  # type: ignore[attr-defined]  # offered once, then a name
    try:
        stamp = read_stamp(target)
    except RobotFileError:  # there is something, unreadable: the save will say why
        return target, None
    if stamp is None:
        return target, None
    same = path is not None and _same_file(path, target)
    if not same and not await app.push_screen_wait(
        Confirm(f"{short_path(target)} exists. Replace it?", "Replace a file")
    ):
        return None
    return target, stamp


def _same_file(one: Path, other: Path) -> bool:
    try:
        return one.samefile(other)
    except (OSError, ValueError):
        return False

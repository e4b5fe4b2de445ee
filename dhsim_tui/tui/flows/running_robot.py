"""The simulator's running robot and its file: the stamp a save checks (did
anybody change the file since it was read?), keeping a robot the simulator
changed (a saved pose) and writing it to its file, saving it with the poses
kept in memory (a name for a bundled, new or imported robot; a reload puts
the poses back on the file's robot), opening another robot file after asking
about unsaved poses, running an imported robot (unsaved until it is saved
under robots/), and opening the editor on it converted to the other D-H
convention. They change the app's running robot and its file fields
(``robot``, ``robot_path``, ``saved_robot``, ``first_robot``, ``stamp``,
``new_text``, ``imported_from``); the async ones are awaited from the app's
``@work`` workers.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from dhsim_tui.core.files.robotfile import (
    FileChangedError,
    FileStamp,
    ReadOnlyError,
    load_with_stamp,
    save,
)
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.tui.flows.recover import offer_recovery
from dhsim_tui.tui.flows.save import is_bundled, library_file_hint, reapply_edits, save_flow
from dhsim_tui.tui.screens.dialogs import SaveGuard
from dhsim_tui.tui.screens.open_robot import ImportNotes, Opened, OpenRobot, header_text

if TYPE_CHECKING:
    from dhsim_tui.tui.app import DhsimApp


#: a stamp no file matches: the file changed between loading the robot and stamping it
def _unknown_stamp(path: Path) -> FileStamp:
    return FileStamp(path, 0, -1, "")


def stamp_for(robot: Robot, path: Path | None) -> FileStamp | None:
    """What ``path`` holds now, if it still holds ``robot`` (a save then checks
    that nobody changed it since); bundled robots and new ones have none."""
    if path is None or is_bundled(path):
        return None
    try:
        on_disk, stamp = load_with_stamp(path)
    except DhsimError:
        return _unknown_stamp(path)
    return stamp if on_disk == robot else _unknown_stamp(path)


def _text_of(path: Path | None) -> str | None:
    """A robot file's text, so that saving under a new name keeps its comments."""
    try:
        return path.read_text(encoding="utf-8") if path is not None else None
    except (OSError, UnicodeDecodeError, ValueError):
        return None


def keep_running(app: DhsimApp, robot: Robot) -> Path | None:
    """The simulator changed the robot (a saved pose): keep it, and write it
    to its file when it has one of its own (bundled robots are templates:
    None, kept in memory until quitting asks). A failed save raises
    DhsimError; the robot is kept in memory either way. When the file
    changed on disk since it was read, or may not be written, it also asks
    (save_flow): overwrite, reload or cancel; save as."""
    app.robot = robot
    path = app.robot_path
    if path is None or is_bundled(path):
        return None
    try:
        app.stamp = save(robot, path, expect=app.stamp)
    except (FileChangedError, ReadOnlyError):
        app.save()  # the save flow, in a worker: it asks
        raise
    app.saved_robot = robot
    return path


async def save_running(app: DhsimApp, save_as: bool = False) -> bool:
    """Save the simulator's robot (its poses) with the UI's save flow: a
    name for a bundled, new or imported robot (or ``save_as``), a question
    when the file changed on disk. True once nothing is unsaved (saved;
    a reload puts the poses kept here back on the file's robot, which
    then are unsaved again)."""
    path = app.robot_path
    base, mine = app.saved_robot, app.robot
    result = await save_flow(
        app,
        app.robot,
        path,
        app.stamp,
        base_text=_text_of(path) if path is not None else app.new_text,
        save_as=save_as,
    )
    if result is None:
        return False
    app.saved_robot, app.stamp, app.robot_path = result.robot, result.stamp, result.path
    app.new_text = app.imported_from = None
    if result.kind == "reloaded":  # the file's robot, with my poses on top
        again = await reapply_edits(app, base, mine, result.robot)
        app.run_robot(again.robot, result.path)  # mine as it was, if they would not combine
        app.say(f"reloaded {result.path}: {again.message}", not again.combined)
        return not app.has_unsaved_poses
    return True


async def open_running(app: DhsimApp, importing: bool = False) -> None:
    """The simulator runs another robot: a robot file, or an import
    (``importing``: only .urdf/.csv), after asking about unsaved poses."""
    if app.has_unsaved_poses:
        answer = await app.push_screen_wait(SaveGuard(app.robot.name, "opening another robot"))
        if answer not in ("save", "discard"):
            return
        if answer == "save" and not await app.save_running_robot():
            return
    opened = await app.push_screen_wait(OpenRobot(importing=importing))
    if opened is None:
        return
    if opened.imported:
        app.run_import(opened)
        return
    robot, path = opened.robot, opened.source
    found = await offer_recovery(app, path, robot)  # changes kept by a crash
    app.saved_robot = app.first_robot = robot
    app.stamp = None if is_bundled(path) else opened.stamp
    app.new_text = app.imported_from = None
    app.run_robot(robot, path)
    if found is not None:
        app.open_editor(found.robot, path, saved=robot, stamp=app.stamp)


def run_imported(app: DhsimApp, opened: Opened) -> None:
    """The simulator runs an imported robot. It has no robot file: it is
    unsaved (quitting asks; saving asks a name in robots/)."""
    app.saved_robot = app.first_robot = None
    app.stamp = None
    app.new_text = header_text(opened.header)
    app.imported_from = opened.source
    app.run_robot(opened.robot, None)
    app.push_screen(
        ImportNotes(opened, f"the palette's Save (ctrl+p) saves it as {library_file_hint()}")
    )


def convert_running(app: DhsimApp, convention: str) -> None:
    """The running robot in the other D-H convention: the editor opens on
    it with the conversion as its one edit (the table is the editor's
    business; ctrl+z there undoes it, escape asks to save or discard)."""
    from dhsim_tui.core.interop.convert import convert  # loaded when first used

    before = app.robot.convention
    try:
        converted = convert(app.robot, convention)
    except DhsimError as exc:
        app.say(str(exc), error=True)
        return
    message = (
        f"converted from {before} to {convention} D-H: the same arm (ctrl+z undoes; ctrl+s saves)"
    )
    app.open_editor(
        app.robot,
        app.robot_path,
        saved=app.saved_robot,
        stamp=app.stamp,
        first_edit=(converted, message),
    )

"""The editor's file commands, as plain functions of the editor screen: save
(a name when the robot needs one; when the file changed on disk and the user
reloads it, the edits made here are put back on the file's robot, and undo
takes them out again), open another robot file (offering back the changes a
crash kept for it) and show an imported robot (no robot file yet: unsaved
until ctrl+s names one in robots/). They set the screen's robot and its file
fields (``history``, ``path``, ``template``, ``saved``, ``stamp``,
``new_text``, ``imported_from``) and redraw it; the async ones are awaited
from the screen's ``@work`` workers (they wait for answers with
``push_screen_wait``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from dhsim_tui.core.model import editing
from dhsim_tui.tui.flows.recover import offer_recovery
from dhsim_tui.tui.flows.save import is_bundled, library_file_hint, reapply_edits, save_flow
from dhsim_tui.tui.screens.dialogs import short_path
from dhsim_tui.tui.screens.open_robot import ImportNotes, Opened, OpenRobot, header_text

if TYPE_CHECKING:
    from dhsim_tui.tui.screens.editor import EditorScreen


async def save_edited(screen: EditorScreen, save_as: bool = False) -> bool:
    """Save the editor's robot (asking a name when needed); True once
    nothing is unsaved."""
    source = screen.path or screen.template
    base = screen.saved
    result = await save_flow(
        screen.app,
        screen.robot,
        source,
        screen.stamp,
        base_text=screen.new_text if source is None else None,
        save_as=save_as,
        report=screen.say,
    )
    if result is None:
        return False
    screen.path, screen.template = result.path, None
    screen.saved, screen.stamp = result.robot, result.stamp
    screen.new_text = screen.imported_from = None
    if result.kind == "reloaded":  # the file's content, my edits re-applied on top
        mine = screen.robot
        again = await reapply_edits(screen.app, base, mine, result.robot)
        if again.combined:  # undo takes out my edits, back to the file's
            screen.history = editing.History(result.robot)
            screen.history.push(again.robot)
        screen.say(f"reloaded {short_path(result.path, 40)}: {again.message}", not again.combined)
    screen.refresh_robot()
    return not screen.dirty


async def open_in_editor(screen: EditorScreen, importing: bool = False) -> None:
    """Open a robot file in the editor, or import a .urdf/.csv (``importing``:
    only those), once the unsaved changes are saved or discarded."""
    if not await screen.guard("opening another robot"):
        return
    opened = await screen.app.push_screen_wait(OpenRobot(importing=importing))
    if opened is None:
        return
    if opened.imported:
        show_import(screen, opened)
        return
    robot, path, stamp = opened.robot, opened.source, opened.stamp
    found = await offer_recovery(screen.app, path, robot)  # changes kept by a crash
    screen.history = editing.History(found.robot if found else robot)
    bundled = is_bundled(path)
    screen.path = None if bundled else path
    screen.template = path if bundled else None
    screen.saved, screen.stamp = robot, stamp
    screen.new_text = screen.imported_from = None
    screen.refresh_robot()
    screen.say(f"opened {short_path(path, 50)}")


def show_import(screen: EditorScreen, opened: Opened) -> None:
    """Edit an imported robot: it has no robot file yet, so it is unsaved
    and ctrl+s asks for a name in robots/. The importer's notes are shown."""
    screen.history = editing.History(opened.robot)
    screen.path = screen.template = None
    screen.saved, screen.stamp = None, None
    screen.new_text = header_text(opened.header)
    screen.imported_from = opened.source
    screen.refresh_robot()
    screen.say(f"imported {short_path(opened.source, 40)}; not saved yet: ctrl+s saves it")
    screen.app.push_screen(ImportNotes(opened, f"ctrl+s saves it as {library_file_hint()}"))

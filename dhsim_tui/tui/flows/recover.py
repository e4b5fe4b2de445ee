"""Offer back the unsaved changes a stopped dhsim kept (see core/recovery.py).

Called when dhsim starts (``dhsim``, ``dhsim edit``, ``dhsim new``) and when a
robot is opened from the editor: if a recovery file is kept for that robot,
ask once: restore, discard, or decide later (the file stays).
"""

from __future__ import annotations

from pathlib import Path

from textual.app import App
from textual.markup import escape

from dhsim_tui.core.files.recovery import Recovery, discard_recovery, find_recovery
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal.charset import shown
from dhsim_tui.tui.screens.dialogs import Choice

RESTORE_CHOICES = [
    ("restore", "restore them (in the editor, not saved yet)"),
    ("discard", "discard them (delete the recovery file)"),
    ("later", "decide later (ask again next time)"),
]


def _discard(app: App, found: Recovery) -> bool:
    try:
        discard_recovery(found)
    except OSError as exc:
        app.notify(
            shown(printable(f"could not delete {found.file}: {exc.strerror or exc}"), app),
            title="recovery file kept",
            severity="warning",
            markup=False,
        )
        return False
    return True


async def offer_recovery(app: App, source: Path | None, current: Robot | None) -> Recovery | None:
    """If unsaved changes to ``source`` (None: a new robot) were kept, ask what
    to do with them. ``current`` is the robot its file holds now (None if it
    can't be read). Returns the recovery to restore, its file already deleted
    (the changes then live in a dirty editor), or None to go on as usual."""
    try:
        found = find_recovery(source)
    except DhsimError as exc:
        app.notify(
            shown(printable(str(exc)), app),
            title="recovery file not used",
            severity="warning",
            markup=False,
        )
        return None
    if found is None:
        return None
    if current is not None and found.robot == current:
        _discard(app, found)  # the file already holds those changes: nothing to offer
        return None
    what = "a new robot" if source is None else str(source)
    hint = printable(
        f"{found.robot.name} ({what}) had changes that were not saved when dhsim stopped; "
        f"they are kept in {found.file}"
    )
    answer = await app.push_screen_wait(
        Choice(
            f"Restore unsaved changes from {found.local_time}?",
            RESTORE_CHOICES,
            "restore",
            hint=escape(hint) + "\n↑↓ choose · enter picks · escape decides later",
        )
    )
    if answer == "restore":
        _discard(app, found)
        return found
    if answer == "discard" and _discard(app, found):
        message = printable(f"discarded the unsaved changes to {found.robot.name}")
        app.notify(shown(message, app), markup=False)
    return None

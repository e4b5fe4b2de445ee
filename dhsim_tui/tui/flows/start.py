"""The first questions of a session: ``dhsim`` and ``dhsim edit`` first offer
back the unsaved changes a stopped dhsim kept (for the robot's file, then for
a new robot that was never saved) and work out which file a restored robot
belongs to (the editor opens on it); ``dhsim new`` asks how many joints the new robot has. The
questions are awaited from the app's ``@work`` workers (they wait for each
answer with ``push_screen_wait``).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from textual.app import App

from dhsim_tui.core.files.recovery import Recovery, source_key
from dhsim_tui.core.files.robotfile import FileStamp, load
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import MAX_JOINTS, Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.tui.flows.recover import offer_recovery
from dhsim_tui.tui.screens.value_entry import ValueEntry

if TYPE_CHECKING:
    from dhsim_tui.tui.app import DhsimApp


def joint_count(text: str) -> int:
    """The new robot's joint count as typed: a whole number from 1 to MAX_JOINTS."""
    value = editing.parse_number(text, "joints")
    if value != int(value) or not 1 <= value <= MAX_JOINTS:
        raise editing.DhsimError(f"joints: a whole number from 1 to {MAX_JOINTS}")
    return int(value)


async def ask_joint_count(app: App) -> int:
    """How many joints the new robot has (escape: 1)."""
    count = await app.push_screen_wait(
        ValueEntry(
            "new robot: number of joints",
            "3",
            f"1 to {MAX_JOINTS} revolute rows; escape starts with 1",
            joint_count,
        )
    )
    return count or 1


async def recovery_at_start(app: App, path: Path | None, saved: Robot | None) -> Recovery | None:
    """Offer back what a stopped dhsim kept: for ``path`` (the robot's file,
    which holds ``saved``; None: none to ask about), then for a new robot
    that was never saved. The changes the user restores, or None."""
    sources: list[Path | None] = [None]
    if path is not None:
        sources.insert(0, path)
    for source in sources:
        current = saved if source is not None else None
        found = await offer_recovery(app, source, current)
        if found is not None:
            return found
    return None


def restore_in_editor(app: DhsimApp, found: Recovery) -> None:
    """The editor on the recovered robot, unsaved against what the file holds."""
    path, saved, stamp = _restored_file(found, app.robot_path, app.saved_robot, app.stamp)
    app.open_editor(found.robot, path, saved=saved, stamp=stamp)
    app.notify(
        printable(f"restored the unsaved changes from {found.local_time}; ctrl+s saves them"),
        markup=False,
    )


def _restored_file(
    found: Recovery, path: Path | None, saved: Robot | None, stamp: FileStamp | None
) -> tuple[Path | None, Robot | None, FileStamp | None]:
    """The file a restored robot belongs to, what that file holds, and its
    stamp: ``path``'s ``saved`` and ``stamp`` when the recovery is for the
    running robot's file, else the file read again (None: gone or broken,
    everything counts as unsaved)."""
    source = found.source
    if source is not None and path is not None and source_key(path) == source_key(source):
        return path, saved, stamp
    if source is None:
        return None, None, None
    try:
        return source, load(source), None
    except DhsimError:
        return source, None, None

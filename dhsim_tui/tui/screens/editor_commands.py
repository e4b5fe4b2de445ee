"""The editor's commands in the palette (ctrl+p): each calls an action the
editor already has."""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from dhsim_tui.tui.screens.palette_command import VIEW_NAMES, PaletteCommand

if TYPE_CHECKING:
    from dhsim_tui.tui.screens.editor import EditorScreen


def editor_commands(app, screen: EditorScreen) -> Iterator[PaletteCommand]:
    yield PaletteCommand(
        "Open a robot…",
        "a robot file, or a .urdf or .csv to import (ctrl+o)",
        screen.action_open,
    )
    yield PaletteCommand(
        "Import a URDF or CSV file…",
        "edit the robot it gives; ctrl+s saves it as robots/<name>.toml",
        lambda: screen.action_open(importing=True),
    )
    if screen.dirty:
        yield PaletteCommand("Save", "save the robot (ctrl+s)", screen.action_save)
    yield PaletteCommand(
        "Save as…", "save under another name, robots/<name>.toml (S)", screen.action_save_as
    )
    yield PaletteCommand(
        "Export…", "write the robot as URDF, CSV or JSON (x)", screen.action_export
    )
    other = screen.other_convention()
    yield PaletteCommand(
        f"Convert to {other} D-H",
        f"the same arm as a {other} D-H table, in one edit (ctrl+z undoes)",
        screen.action_convert,
    )
    if screen.history.can_undo:
        yield PaletteCommand("Undo", "undo the last edit (ctrl+z)", screen.action_undo)
    if screen.history.can_redo:
        yield PaletteCommand("Redo", "redo the edit undone (ctrl+y)", screen.action_redo)
    for index, view in enumerate(VIEW_NAMES):
        yield PaletteCommand(
            f"Preview: {view}",
            f"the {view} view in the preview ({index + 1})",
            lambda index=index: screen.action_preview(index),
        )
    yield PaletteCommand(
        "Back to the simulator",
        "leave the editor (escape; asks about changes)",
        screen.action_leave,
    )
    yield PaletteCommand("Help", "every key of the editor (?)", screen.action_help)

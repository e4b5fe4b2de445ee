"""The app's own keys, on every screen: ctrl+p opens the command palette (on
the simulator and the editor; Textual's system commands are not offered) and
ctrl+c quits, through the same unsaved-changes question as q and ctrl+q. The
screens' keys are in :mod:`control_keys` and :mod:`editor_keys`.
"""

from __future__ import annotations

from textual.binding import Binding

from dhsim_tui.tui.keys import Keys

APP_BINDINGS = [
    Binding(
        "ctrl+p",
        "command_palette",
        "Commands",
        key_display="^p",
        id="app.palette",
        tooltip="The command palette: every command by name",
        show=False,
        priority=True,
        group=Keys(
            legend=False,
            help="command palette: open, import, save, export, convert, poses, views…",
        ),
    ),
    # Textual binds ctrl+c to "copy" (screens, inputs) and a "press ctrl+q" hint:
    # here it quits, through the same unsaved-changes question as q and ctrl+q
    Binding(
        "ctrl+c",
        "quit",
        "Quit",
        id="app.quit_ctrl_c",
        tooltip="Quit dhsim (asks first when something is not saved)",
        show=False,
        priority=True,
    ),
]

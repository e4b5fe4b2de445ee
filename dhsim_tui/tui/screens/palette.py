"""The command palette (ctrl+p): dhsim's commands by name.

:class:`DhsimCommands` is the palette's one command provider (Textual's
system commands are left out: its theme picker lists dozens of themes, its
key panel duplicates ``?``, its screenshot writes to a folder of its
choosing). Which commands it offers depends on the screen the palette was
opened from, and on its state: "Save" only when something is unsaved,
"Undo" only when there is an edit to undo, one "Go to pose" per pose of the
running robot. Every command calls an action the screen or the app already
has (or a flow of :mod:`open_robot`, :mod:`save_flow`, :mod:`export_dialog`);
nothing here computes anything about the robot.

Command names come partly from files (pose names): they are shown as plain
text (control characters escaped, never markup), and in ASCII in ASCII mode.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from textual.command import CommandPalette, DiscoveryHit, Hit, Hits, Provider, SearchIcon
from textual.content import Content
from textual.markup import escape

from dhsim_tui.core.model.text import printable
from dhsim_tui.core.model.validation import fmt
from dhsim_tui.core.motion.jog import TOOL, WORLD
from dhsim_tui.scene.wireframe import FRAME_MODE_NAMES, FRAME_MODES
from dhsim_tui.terminal.charset import ascii_mode, shown
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.widgets.views_panel import ViewsPanel

if TYPE_CHECKING:
    from dhsim_tui.tui.app import DhsimApp

#: the command that writes the screen to a file (found by "picture", "screen", "plot")
SAVE_PICTURE = "Save picture: a screenshot or plot of the screen (SVG)"
#: the views' names, in the order of the keys 1 2 3 4
VIEW_NAMES = ("top", "front", "side", "3-D")
#: what the themes are, by --theme's names (app.THEMES)
THEME_HELP = {
    "dark": "light text on a dark background (the default)",
    "light": "dark text on a light background",
    "ansi": "the terminal's own 16 colours",
}


@dataclass(frozen=True)
class PaletteCommand:
    """One line of the palette: its name, a line of help, what it runs."""

    title: str
    help: str
    run: Callable[[], Any]


def screens_with_commands() -> tuple[type, ...]:
    """The screens the palette opens on (not on a dialog: it has its own keys)."""
    return (ControlScreen, EditorScreen)


def commands_for(app: DhsimApp, screen: object) -> list[PaletteCommand]:
    """The commands that work on ``screen`` as it is now."""
    if isinstance(screen, ControlScreen):
        found = list(_control_commands(app, screen))
    elif isinstance(screen, EditorScreen):
        found = list(_editor_commands(app, screen))
    else:
        return []
    return found + list(_app_commands(app))


# -- the simulator ------------------------------------------------------------------
def _control_commands(app: DhsimApp, screen: ControlScreen) -> Iterator[PaletteCommand]:
    robot = app.robot
    yield PaletteCommand(
        "Open a robot…",
        "a robot file, or a .urdf or .csv to import; the simulator runs it",
        app.open_robot,
    )
    yield PaletteCommand(
        "Import a URDF or CSV file…",
        "the simulator runs the robot it gives (not saved until you save it)",
        lambda: app.open_robot(importing=True),
    )
    if app.has_unsaved_poses:
        what = "the poses kept in memory" if app.robot_path is not None else "this robot"
        yield PaletteCommand("Save", f"save {what} (asks a name when it has no file)", app.save)
    yield PaletteCommand(
        "Save as…", "save the robot under another name, robots/<name>.toml", app.save_as
    )
    yield PaletteCommand("Export…", "write the robot as URDF, CSV or JSON", app.export_robot)
    other = "modified" if robot.convention == "standard" else "standard"
    yield PaletteCommand(
        f"Convert to {other} D-H",
        "the same arm: opens the editor with the change (ctrl+z there undoes it)",
        lambda: app.convert_in_editor(other),
    )
    yield PaletteCommand("Edit the D-H table", "the table editor (e)", screen.action_edit)
    yield PaletteCommand(
        "Go home", "every joint home: the D-H table's values (h)", screen.action_home
    )
    for name in robot.pose_names:
        values = ", ".join(fmt(v) for v in robot.pose(name))
        yield PaletteCommand(
            f"Go to pose {name}",
            f"joints {values}",
            lambda name=name: screen.go_to_pose(name),
        )
    for index, view in enumerate(VIEW_NAMES):
        yield PaletteCommand(
            f"View: {view}",
            f"select the {view} view ({index + 1})",
            lambda index=index: screen.action_view(index),
        )
    views = screen.query_one(ViewsPanel)
    if views.maximised:
        yield PaletteCommand("View: restore", "all the panels back (z)", screen.action_maximise)
    else:
        yield PaletteCommand(
            "View: maximise", "the selected view over the whole screen (z)", screen.action_maximise
        )
    if views.zoom != 1.0:
        yield PaletteCommand(
            "View: reset zoom",
            "back to the whole work area (0)",
            lambda: screen.action_zoom(0),
        )
    if views.fit:
        yield PaletteCommand(
            "View: the work area", "every view back to the work area (F)", screen.action_fit
        )
    else:
        yield PaletteCommand(
            "View: fit the arm", "every view fitted to the arm as it stands (F)", screen.action_fit
        )
    following = FRAME_MODES[(FRAME_MODES.index(views.frames) + 1) % len(FRAME_MODES)]
    yield PaletteCommand(
        f"View: frames drawn: {FRAME_MODE_NAMES[following]}",
        f"the frame axes drawn: now {FRAME_MODE_NAMES[views.frames]} (x)",
        screen.action_frames,
    )
    if screen.cloud_state == "off":
        yield PaletteCommand(
            "View: show the workspace",
            "a faint cloud of points the tool can reach, in every view (W)",
            screen.action_workspace,
        )
    else:
        yield PaletteCommand(
            "View: hide the workspace", "the workspace cloud off (W)", screen.action_workspace
        )
    yield PaletteCommand(
        "Next IK branch",
        "the arm's next solution for this tool pose: the tool stays (b)",
        screen.action_next_branch,
    )
    frame = TOOL if screen.frame == WORLD else WORLD
    yield PaletteCommand(
        f"Jog in the {frame} frame",
        (
            "Cartesian jogging along and about the tool's own x, y, z (f)"
            if frame == TOOL
            else "Cartesian jogging along and about the world's X, Y, Z (f)"
        ),
        lambda frame=frame: _jog_in(screen, frame),
    )
    yield PaletteCommand("Help", "every key of the simulator (?)", screen.action_help)


def _jog_in(screen: ControlScreen, frame: str) -> None:
    """Cartesian jogging (switched on if it is off) in ``frame``."""
    if not screen.cartesian:
        screen.action_cartesian()
    screen.action_frame(frame)


# -- the editor ---------------------------------------------------------------------
def _editor_commands(app: DhsimApp, screen: EditorScreen) -> Iterator[PaletteCommand]:
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


# -- everywhere ---------------------------------------------------------------------
def _app_commands(app: DhsimApp) -> Iterator[PaletteCommand]:
    yield PaletteCommand(
        SAVE_PICTURE,
        "this screen as an SVG in the working folder, for a report (i on the simulator)",
        app.save_picture,
    )
    for name, theme in app.theme_choices().items():
        if app.theme != theme:
            yield PaletteCommand(
                f"Theme: {name}",
                THEME_HELP.get(name, ""),
                lambda name=name: app.set_theme(name),
            )
    yield PaletteCommand("Quit", "quit dhsim (asks about unsaved changes)", app.action_quit)


# -- the palette ----------------------------------------------------------------------
class DhsimCommands(Provider):
    """dhsim's commands for the screen the palette was opened from."""

    def _commands(self) -> list[PaletteCommand]:
        app: Any = self.app
        return commands_for(app, self.screen)

    def _title(self, command: PaletteCommand) -> str:
        return shown(printable(command.title), self.app)

    def _help(self, command: PaletteCommand) -> str:
        return escape(shown(printable(command.help), self.app))

    async def discover(self) -> Hits:
        for command in self._commands():
            title = self._title(command)
            yield DiscoveryHit(Content(title), command.run, text=title, help=self._help(command))

    async def search(self, query: str) -> Hits:
        matcher = self.matcher(query)
        for command in self._commands():
            title = self._title(command)
            score, offsets = matcher.fuzzy_search.match(matcher.query, title)
            if score > 0:
                content = Content(title)  # plain text: a pose's name is never markup
                for offset in offsets:
                    if not title[offset].isspace():
                        content = content.stylize(matcher.match_style, offset, offset + 1)
                yield Hit(score, content, command.run, text=title, help=self._help(command))


class DhsimPalette(CommandPalette):
    """Textual's palette with dhsim's commands; in ASCII mode its search icon
    and placeholder are ASCII too (its borders: the end of dhsim.tcss).

    Keys that arrive fast around it (``ctrl+p`` then ``escape`` then ``ctrl+p``
    in one read) used to end dhsim with Textual's traceback: a second palette
    pushed while the first was still leaving the screen (``DuplicateIds``),
    or one of its timers querying its list after it had gone (``NoMatches``).
    So the app opens no other until this one is ``gone`` (unmounted), and
    once closing it stops its timers and its watchers act on nothing."""

    def __init__(self) -> None:
        super().__init__(
            placeholder=shown("Search for commands… (escape closes)"), id="--command-palette"
        )
        self._leaving = False
        self.gone = False

    def on_unmount(self) -> None:
        self.gone = True

    def on_mount(self) -> None:
        if ascii_mode(self.app):
            self.query_one(SearchIcon).icon = ">"

    def dismiss(self, result=None):
        self._leaving = True
        self._stop_busy_countdown()
        self._stop_no_matches_countdown()
        return super().dismiss(result)

    def _watch__list_visible(self) -> None:
        if not self._leaving and self.is_mounted:
            super()._watch__list_visible()

    async def _watch__show_busy(self) -> None:
        if not self._leaving and self.is_mounted:
            await super()._watch__show_busy()

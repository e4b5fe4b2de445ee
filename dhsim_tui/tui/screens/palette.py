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

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from textual.await_complete import AwaitComplete
from textual.command import (
    CommandList,
    CommandPalette,
    DiscoveryHit,
    Hit,
    Hits,
    Provider,
    SearchIcon,
)
from textual.content import Content
from textual.markup import escape

from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal.charset import ascii_mode, shown
from dhsim_tui.tui.screens.palette_command import PaletteCommand

if TYPE_CHECKING:
    from dhsim_tui.tui.app import DhsimApp

#: the command that writes the screen to a file (found by "picture", "screen", "plot")
SAVE_PICTURE = "Save picture: a screenshot or plot of the screen (SVG)"
#: what the themes are, by --theme's names (colour.THEME_NAMES)
THEME_HELP = {
    "dark": "light text on a dark background (the default)",
    "light": "dark text on a light background",
    "ansi": "the terminal's own 16 colours",
}


def commands_for(app: DhsimApp, screen: object) -> list[PaletteCommand]:
    """The commands that work on ``screen`` as it is now: its own (a screen
    that has commands says so with ``palette_commands()``) and the app's."""
    own = getattr(screen, "palette_commands", None)
    if own is None:
        return []
    return [*own(), *_app_commands(app)]


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
        """Once, and only from the front (a command chosen as it leaves would
        pop the screen under it: the long monkey's ScreenStackError)."""
        if self._leaving or self.app.screen is not self:
            return AwaitComplete()
        self._leaving = True
        self._stop_busy_countdown()
        self._stop_no_matches_countdown()
        return super().dismiss(result)

    def _gather_commands(self, search_value: str):
        """A key typed while the palette leaves starts no search: its list may
        be gone already (the long monkey's NoMatches in Textual's worker)."""
        if self._leaving or not self.query(CommandList):
            return None
        return super()._gather_commands(search_value)

    def _action_command_list(self, action: str) -> None:
        """A list key (up, down, page...) that comes while the palette leaves:
        its list may be gone already (the monkey's NoMatches)."""
        if not self._leaving and self.query(CommandList):
            super()._action_command_list(action)

    def _watch__list_visible(self) -> None:
        if not self._leaving and self.is_mounted:
            super()._watch__list_visible()

    async def _watch__show_busy(self) -> None:
        if not self._leaving and self.is_mounted:
            await super()._watch__show_busy()


def palette_may_open(app: DhsimApp, last: DhsimPalette | None) -> bool:
    """ctrl+p opens a palette on ``app``: not over a dialog, and not while a
    palette is opening, open or still leaving the screen (``last``: the one
    opened before; ctrl+p, escape, ctrl+p in one read)."""
    return (
        app.use_command_palette
        and not CommandPalette.is_open(app)
        and (last is None or last.gone)
        and hasattr(app.screen, "palette_commands")  # a screen with commands
    )

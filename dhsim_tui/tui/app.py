"""The Textual application: holds the running robot and moves between screens.

Its methods stay thin where the work is done elsewhere: the questions a
session starts with in :mod:`flows.start`, the running robot's file (keep,
save, open, import, convert) in :mod:`flows.running_robot`, quitting and
ending after a signal or an error in :mod:`app_exit`, its keys in
:mod:`app_keys`, its themes in :mod:`colour`. :func:`run_app` is what the
command line calls.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

from textual import events, work
from textual.binding import Binding
from textual.driver import Driver
from textual.drivers.linux_driver import LinuxDriver

from dhsim_tui.core.files.robotfile import FileStamp
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal import partial_update
from dhsim_tui.terminal.charset import ascii_key, install_ascii_scrollbars, shown
from dhsim_tui.terminal.signals import DhsimDriver, SignalGuard
from dhsim_tui.terminal.typeahead import KeysInOrder
from dhsim_tui.tui.app_exit import (
    before_panic,
    end_with_error,
    keep_in_recovery,
    may_quit,
    open_editors,
    unsaved_work,
)
from dhsim_tui.tui.app_keys import APP_BINDINGS
from dhsim_tui.tui.colour import THEME_NAMES, install_colours
from dhsim_tui.tui.flows.export import export_flow
from dhsim_tui.tui.flows.running_robot import (
    convert_running,
    keep_running,
    open_running,
    run_imported,
    save_running,
    stamp_for,
)
from dhsim_tui.tui.flows.save import is_bundled
from dhsim_tui.tui.flows.start import ask_joint_count, recovery_at_start, restore_in_editor
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.open_robot import Opened
from dhsim_tui.tui.screens.palette import DhsimCommands, DhsimPalette, palette_may_open
from dhsim_tui.tui.screens.start import StartScreen
from dhsim_tui.tui.screenshot import write_picture

partial_update.install()  # a changed span is written from where it starts


class DhsimApp(KeysInOrder):
    """dhsim's terminal UI. Everything is reachable from the keyboard.

    ``start`` is ``"control"`` (the simulator), ``"edit"`` (the editor on
    ``robot``) or ``"new"`` (ask for a joint count, then the editor).
    ``recovery``: a real session (``dhsim``), which offers back unsaved changes
    a stopped dhsim kept, and keeps them itself after an unexpected error.
    """

    CSS_PATH = "dhsim.tcss"
    TITLE = "dhsim"
    #: ctrl+p: dhsim's commands by name (screens/palette.py), on the simulator
    #: and the editor; Textual's own system commands are not offered
    ENABLE_COMMAND_PALETTE = True
    COMMANDS = {DhsimCommands}
    BINDINGS = APP_BINDINGS

    def __init__(
        self,
        robot: Robot,
        path: Path | None = None,
        renderer: str = "plotext",
        start: str = "control",
        animate: bool = True,
        recovery: bool = False,
        stamp: FileStamp | None = None,
        ascii: bool = False,
        theme: str = "dark",
    ) -> None:
        """``stamp``: what ``path`` held when ``robot`` was read from it (read
        now when not given); a save refuses to overwrite a file that changed.
        ``ascii``: draw only 7-bit ASCII (see terminal.py). ``theme``: one of
        ``THEME_NAMES`` (``ansi``: the terminal's own 16-colour palette)."""
        super().__init__()
        install_colours(self, theme)  # NO_COLOR: no colour codes; 16 colours: RGB for the axes
        #: 7-bit ASCII only: widgets and screens read this (getattr(app, "ascii_mode", False))
        self.ascii_mode = ascii
        if ascii:
            self.add_class("-ascii")  # the stylesheet's ASCII borders
            install_ascii_scrollbars()
        self.animate = animate
        self.robot = robot
        self.robot_path = path
        #: the robot as its file holds it (a pose saved only in memory differs)
        self.saved_robot: Robot | None = robot if path is not None else None
        self.stamp = stamp if stamp is not None else stamp_for(robot, path)
        #: what the app started with: a robot without a file is "saved" as it came
        #: (None: the running robot was imported, and is unsaved as a whole)
        self.first_robot: Robot | None = robot
        #: an imported robot's file not written yet: the comments it starts
        #: with, and the file it came from
        self.new_text: str | None = None
        self.imported_from: Path | None = None
        self.renderer = renderer
        self.start = start
        self.recovery = recovery
        #: lines to print after the app has ended (where unsaved work was kept)
        self.exit_messages: list[str] = []
        self._palette: DhsimPalette | None = None  # the last one opened
        self.sub_title = robot.name
        #: the status line's first message: which robot a name opened
        #: (yours or the bundled one); run_app sets it
        self.notice: str | None = None
        #: where a new robot (``dhsim new -o FILE``) is saved: the save
        #: dialog offers it instead of the user library
        self.new_target: Path | None = None

    def get_key_display(self, binding: Binding) -> str:
        """The footer's name for a key; in ASCII mode ``^/v``, ``</>``, ``enter``."""
        display = super().get_key_display(binding)
        return ascii_key(display) if self.ascii_mode else display

    def get_driver_class(self) -> type[Driver]:
        driver = super().get_driver_class()
        return DhsimDriver if driver is LinuxDriver else driver

    def on_mount(self) -> None:
        # pushed (not the default screen) so that switch_screen can replace it;
        # the editor's own start shows no simulator behind its first question
        if self.start == "control":
            control = ControlScreen(self.robot, self.renderer, self.animate)
            if self.notice:
                control.say(self.notice)  # shown once the screen is up
            self.push_screen(control)
        else:
            what = "a new robot" if self.start == "new" else printable(self.robot.name)
            self.push_screen(StartScreen(shown(f"dhsim: opening the editor on {what}…", self)))
        if self.recovery:
            self._start_with_recovery()
        else:
            self._open_start()

    def _open_start(self) -> None:
        if self.start == "edit":
            self.action_edit()
        elif self.start == "new":
            self.start_new_robot()

    @work(exclusive=True, group="modal")
    async def _start_with_recovery(self) -> None:
        """First offer back what a stopped dhsim kept: for this robot's file,
        then for a new robot that was never saved (flows/start.py)."""
        path = self.robot_path if self.start != "new" else None
        found = await recovery_at_start(self, path, self.saved_robot)
        if found is not None:
            restore_in_editor(self, found)
        else:
            self.call_later(self._open_start)

    @work(exclusive=True, group="modal")
    async def start_new_robot(self) -> None:
        """The seed's guided start: how many joints? Then everything in the table."""
        count = await ask_joint_count(self)
        self.open_editor(editing.new_robot(self.robot.name, count), None, saved=None)

    def open_editor(
        self,
        robot: Robot,
        path: Path | None,
        saved: Robot | None = None,
        stamp: FileStamp | None = None,
        first_edit: tuple[Robot, str] | None = None,
    ) -> None:
        """The editor on ``robot``; ``saved`` is what its file holds (changes
        against it count as unsaved), ``stamp`` what the file held then;
        ``first_edit``: (robot, message), an edit made as it opens."""
        unfiled = path is None and robot is self.robot
        editor = EditorScreen(
            robot,
            path,
            self.renderer,
            saved=saved,
            stamp=stamp,
            new_text=self.new_text if unfiled else None,
            imported_from=self.imported_from if unfiled else None,
            first_edit=first_edit,
        )
        self.push_screen(editor, lambda result: self._editor_closed(result, editor.stamp))

    def action_edit(self) -> None:
        self.open_editor(self.robot, self.robot_path, saved=self.saved_robot, stamp=self.stamp)

    def convert_in_editor(self, convention: str) -> None:
        """The editor on the running robot converted to the other D-H
        convention, as its one edit (flows/running_robot.py)."""
        convert_running(self, convention)

    def _editor_closed(
        self, result: tuple[Robot, Path | None] | None, stamp: FileStamp | None = None
    ) -> None:
        """After the editor: the simulator runs the saved robot (or, the first
        time after ``dhsim edit``/``new``, the robot it started with)."""
        if result is not None:
            robot, path = result
            self.saved_robot = robot
            self.stamp = stamp if path is not None and not is_bundled(path) else None
            if path is not None:  # saved: no longer an import without a file
                self.new_text = self.imported_from = None
            if (robot, path) != (self.robot, self.robot_path):
                self.run_robot(robot, path)
                return
        if isinstance(self._simulator_place(), StartScreen):
            self.run_robot(self.robot, self.robot_path)

    def run_robot(self, robot: Robot, path: Path | None) -> None:
        """The simulator on another robot (after the editor, or a reload)."""
        self.robot, self.robot_path = robot, path
        self.sub_title = robot.name
        self.switch_screen(ControlScreen(robot, self.renderer, self.animate))

    def _simulator_place(self) -> object:
        """The screen the simulator runs on: the first one pushed."""
        stack = self.screen_stack
        return stack[1] if len(stack) > 1 else None

    def keep_robot(self, robot: Robot) -> Path | None:
        """The simulator changed the robot (a saved pose): keep it, and write it
        to its file when it has one of its own; its path, or None (a bundled
        robot, a new one). DhsimError when the save failed (the robot is kept
        in memory either way; a file changed on disk or read-only also asks:
        flows/running_robot.py)."""
        return keep_running(self, robot)

    async def save_running_robot(self, save_as: bool = False) -> bool:
        """Save the simulator's robot (its poses) with the UI's save flow: a
        name for a bundled, new or imported robot (or ``save_as``), a question
        when the file changed on disk. True once nothing is unsaved (saved;
        a reload puts the poses kept here back on the file's robot, which
        then are unsaved again). See flows/running_robot.py."""
        return await save_running(self, save_as)

    # -- the simulator's file commands (the command palette) ----------------------
    @work(exclusive=True, group="modal")
    async def save(self) -> None:
        """Save the running robot (the palette's Save on the simulator)."""
        await self.save_running_robot()

    @work(exclusive=True, group="modal")
    async def save_as(self) -> None:
        await self.save_running_robot(save_as=True)

    @work(exclusive=True, group="modal")
    async def export_robot(self) -> None:
        """Export the running robot (its poses too) as URDF, CSV or JSON."""
        await export_flow(self, self.robot, self.robot_path, report=self._report())

    @work(exclusive=True, group="modal")
    async def open_robot(self, importing: bool = False) -> None:
        """The simulator runs another robot: a robot file, or an import
        (``importing``: only .urdf/.csv), after asking about unsaved poses."""
        await open_running(self, importing)

    def run_import(self, opened: Opened) -> None:
        """The simulator runs an imported robot. It has no robot file: it is
        unsaved (quitting asks; saving asks a name in robots/)."""
        run_imported(self, opened)

    def _report(self) -> Callable[[str, bool], None] | None:
        """Where a flow on the simulator reports: its status line (else a toast)."""
        screen = self.screen
        return screen.say if isinstance(screen, ControlScreen) else None

    def say(self, message: str, error: bool = False) -> None:
        """A message on the simulator's status line, else as a toast."""
        report = self._report()
        if report is not None:
            report(message, error)
        else:
            self.notify(shown(printable(message), self), markup=False)

    # -- pictures for a report ------------------------------------------------------
    def save_picture(self) -> Path | None:
        """The screen as it is now, as an SVG in the working folder
        (``dhsim-<robot>-<date>-<time>.svg``, never over another file); says
        where, or why not. The file holds what the terminal shows, its
        colours as this terminal has them."""
        try:
            path = write_picture(self, self.robot.name)
        except DhsimError as exc:
            self.say(f"picture not saved: {exc}", error=True)
            return None
        from dhsim_tui.core.model.text import shortened

        # the path on a line of the status of its own, shortened in the middle: its name whole
        where, status = path.resolve(), next(iter(self.screen.query("#status")), None)
        room = max(status.content_size.width if status else 60, len(where.name) + 8)
        text = str(where)
        if len(text) > room:
            text = f"{shortened(str(where.parent), room - len(where.name) - 1)}/{where.name}"
        self.say(f"picture saved: {text}")
        return path

    def action_save_picture(self) -> None:
        self.save_picture()

    # -- the command palette and themes -------------------------------------------
    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """ctrl+p opens the palette on the simulator and the editor, not over
        a dialog (the key then goes on to it, which ignores it)."""
        if action == "command_palette":
            return palette_may_open(self, self._palette)
        return True

    def action_command_palette(self) -> None:
        if palette_may_open(self, self._palette):
            self._palette = DhsimPalette()
            self.push_screen(self._palette)

    def theme_choices(self) -> dict[str, str]:
        """--theme's names and the Textual themes they stand for."""
        return dict(THEME_NAMES)

    def set_theme(self, name: str) -> None:
        self.theme = THEME_NAMES[name]

    # -- unsaved work, and the way out (app_exit.py) -----------------------------
    @property
    def has_unsaved_poses(self) -> bool:
        """The running robot differs from its file: a pose kept only in memory."""
        baseline = self.saved_robot if self.saved_robot is not None else self.first_robot
        return baseline is None or self.robot != baseline

    def unsaved_work(self) -> list[tuple[Robot, Path | None]]:
        """Every robot with changes not on disk, with its source file (None: a
        new robot); see app_exit.py."""
        return unsaved_work(self)

    def keep_unsaved_work(self, signum: int | None = None) -> list[str]:
        """Write every unsaved robot to a recovery file; what to tell the user.
        Safe in a signal handler (no lock, no terminal output)."""
        return keep_in_recovery(self.unsaved_work(), signum)

    async def on_event(self, event: events.Event) -> None:
        """A press that lands on a widget as it leaves the screen is dropped:
        Textual's text selection reads the widget's parent, already gone
        (``'NoneType' object has no attribute 'region'``, found by the long
        monkey); anything else is raised as before."""
        if not isinstance(event, events.MouseDown):
            await super().on_event(event)
            return
        try:
            await super().on_event(event)
        except AttributeError as exc:
            if "'region'" not in str(exc):
                raise

    def _handle_exception(self, error: Exception) -> None:
        """An unexpected error ends the app (status 1): keep unsaved work
        first, and end with one line (the traceback goes to a crash report
        file, never to the screen)."""
        end_with_error(self, error)

    def panic(self, *renderables) -> None:
        """Textual's other way out after an error (e.g. its input thread failed):
        keep unsaved work, and end with status 1 (Textual leaves it at 0) and
        one line."""
        super().panic(before_panic(self, renderables))

    async def action_quit(self) -> None:
        """Quit, unless something is not saved: then ask, save, discard or stay.
        An open editor asks about its robot (a dialog on top of it must not let
        its changes slip; it started with the simulator's poses), else the
        simulator about poses kept only in memory."""
        editors = open_editors(self)
        dirty = next((editor for editor in editors if editor.dirty), None)
        if dirty is not None or (not editors and self.has_unsaved_poses):
            self._quit_after_asking(dirty)
        else:
            self.exit()

    @work(exclusive=True, group="modal")
    async def _quit_after_asking(self, editor: EditorScreen | None) -> None:
        if await may_quit(self, editor):
            self.exit()


def run_app(
    robot: Robot,
    path: Path | None = None,
    renderer: str = "plotext",
    start: str = "control",
    stamp: FileStamp | None = None,
    ascii: bool = False,
    theme: str = "dark",
    notice: str | None = None,
    new_target: Path | None = None,
) -> int:
    """Run the TUI in this terminal; the exit status (1 after an unexpected error,
    128 + the signal's number after SIGHUP, SIGTERM or SIGQUIT). ``notice``:
    the status line's first message; ``new_target``: where a new robot is saved."""
    app = DhsimApp(
        robot, path, renderer, start, recovery=True, stamp=stamp, ascii=ascii, theme=theme
    )
    app.notice, app.new_target = notice, new_target
    guard = SignalGuard(app, app.keep_unsaved_work)
    guard.install()
    try:
        app.run()
    finally:
        guard.uninstall()
    for message in app.exit_messages:
        print(printable(message), file=sys.stderr)
    return app.return_code or 0

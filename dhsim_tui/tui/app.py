"""The Textual application: holds the running robot and moves between screens."""

from __future__ import annotations

import contextlib
import re
import signal
import sys
import time
from collections.abc import Callable
from pathlib import Path

from rich.text import Text
from textual import work
from textual.binding import Binding
from textual.command import CommandPalette
from textual.driver import Driver
from textual.drivers.linux_driver import LinuxDriver

from dhsim_tui.core.files.atomicfile import write_file
from dhsim_tui.core.files.recovery import Recovery, crash_report, source_key, write_recovery
from dhsim_tui.core.files.robotfile import (
    FileChangedError,
    FileStamp,
    ReadOnlyError,
    load,
    load_with_stamp,
    save,
)
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import MAX_JOINTS, Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal import partial_update
from dhsim_tui.terminal.charset import ascii_key, install_ascii_scrollbars, shown
from dhsim_tui.terminal.signals import DhsimDriver, SignalGuard
from dhsim_tui.terminal.typeahead import KeysInOrder
from dhsim_tui.tui.colour import THEMES as DHSIM_THEMES
from dhsim_tui.tui.colour import install_filters
from dhsim_tui.tui.flows.export import export_flow
from dhsim_tui.tui.flows.recover import offer_recovery
from dhsim_tui.tui.flows.save import is_bundled, reapply_edits, save_flow
from dhsim_tui.tui.keys import Keys
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.dialogs import SaveGuard
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.open_robot import ROBOTS_DIR, ImportNotes, Opened, OpenRobot, header_text
from dhsim_tui.tui.screens.palette import DhsimCommands, DhsimPalette
from dhsim_tui.tui.screens.start import StartScreen
from dhsim_tui.tui.screens.value_entry import ValueEntry
from dhsim_tui.tui.screenshot import export_svg


#: a stamp no file matches: the file changed between loading the robot and stamping it
def _unknown_stamp(path: Path) -> FileStamp:
    return FileStamp(path, 0, -1, "")


def _stamp_for(robot: Robot, path: Path | None) -> FileStamp | None:
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


def crash_line(error: BaseException) -> str:
    """The one line an unexpected error ends dhsim with; the traceback is
    written to a crash report file (named in the line) when it can be."""
    where = crash_report(error)
    report = f"; the details are in {where}" if where else ""
    return printable(f"dhsim: internal error: {type(error).__name__}: {error}{report}")


def _joint_count(text: str) -> int:
    value = editing.parse_number(text, "joints")
    if value != int(value) or not 1 <= value <= MAX_JOINTS:
        raise editing.DhsimError(f"joints: a whole number from 1 to {MAX_JOINTS}")
    return int(value)


partial_update.install()  # a changed span is written from where it starts

#: the themes --theme offers, by short names: Textual's own with dhsim's
#: chrome colours (colour.py)
THEMES = {short: theme.name for short, theme in DHSIM_THEMES.items()}


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
    BINDINGS = [
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
        ``THEMES`` (``ansi``: the terminal's own 16-colour palette)."""
        super().__init__()
        for registered in DHSIM_THEMES.values():
            self.register_theme(registered)
        install_filters(self)  # NO_COLOR: no colour codes; 16 colours: RGB for the axes
        self.theme = THEMES[theme]
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
        self.stamp = stamp if stamp is not None else _stamp_for(robot, path)
        #: what the app started with: a robot without a file is "saved" as it came
        #: (None: the running robot was imported, and is unsaved as a whole)
        self._first_robot: Robot | None = robot
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
            self.push_screen(ControlScreen(self.robot, self.renderer, self.animate))
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
        then for a new robot that was never saved."""
        sources: list[Path | None] = [None]
        if self.start != "new" and self.robot_path is not None:
            sources.insert(0, self.robot_path)
        for source in sources:
            current = self.saved_robot if source is not None else None
            found = await offer_recovery(self, source, current)
            if found is not None:
                self._restore(found)
                return
        self.call_later(self._open_start)

    def _restore(self, found: Recovery) -> None:
        """The editor on the recovered robot, unsaved against what the file holds."""
        path = found.source
        saved: Robot | None = None
        stamp: FileStamp | None = None
        if (
            path is not None
            and self.robot_path is not None
            and (source_key(self.robot_path) == source_key(path))
        ):
            path, saved, stamp = self.robot_path, self.saved_robot, self.stamp
        elif path is not None:
            try:
                saved = load(path)
            except DhsimError:
                saved = None  # gone or broken: everything counts as unsaved
        self.open_editor(found.robot, path, saved=saved, stamp=stamp)
        self.notify(
            printable(f"restored the unsaved changes from {found.local_time}; ctrl+s saves them"),
            markup=False,
        )

    @work(exclusive=True, group="modal")
    async def start_new_robot(self) -> None:
        """The seed's guided start: how many joints? Then everything in the table."""
        count = await self.push_screen_wait(
            ValueEntry(
                "new robot: number of joints",
                "3",
                f"1 to {MAX_JOINTS} revolute rows; escape starts with 1",
                _joint_count,
            )
        )
        self.open_editor(editing.new_robot(self.robot.name, count or 1), None, saved=None)

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
        """The running robot in the other D-H convention: the editor opens on
        it with the conversion as its one edit (the table is the editor's
        business; ctrl+z there undoes it, escape asks to save or discard)."""
        from dhsim_tui.core.interop.convert import convert  # loaded when first used

        before = self.robot.convention
        try:
            converted = convert(self.robot, convention)
        except DhsimError as exc:
            self._say(str(exc), error=True)
            return
        message = (
            f"converted from {before} to {convention} D-H: the same arm "
            "(ctrl+z undoes; ctrl+s saves)"
        )
        self.open_editor(
            self.robot,
            self.robot_path,
            saved=self.saved_robot,
            stamp=self.stamp,
            first_edit=(converted, message),
        )

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
                self._run(robot, path)
                return
        if isinstance(self._simulator_place(), StartScreen):
            self._run(self.robot, self.robot_path)

    def _run(self, robot: Robot, path: Path | None) -> None:
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
        to its file when it has one of its own (bundled robots are templates:
        None, kept in memory until quitting asks). A failed save raises
        DhsimError; the robot is kept in memory either way. When the file
        changed on disk since it was read, or may not be written, it also asks
        (save_flow): overwrite, reload or cancel; save as."""
        self.robot = robot
        path = self.robot_path
        if path is None or is_bundled(path):
            return None
        try:
            self.stamp = save(robot, path, expect=self.stamp)
        except (FileChangedError, ReadOnlyError):
            self._save_running_robot()
            raise
        self.saved_robot = robot
        return path

    async def save_running_robot(self, save_as: bool = False) -> bool:
        """Save the simulator's robot (its poses) with the UI's save flow: a
        name for a bundled, new or imported robot (or ``save_as``), a question
        when the file changed on disk. True once nothing is unsaved (saved;
        a reload puts the poses kept here back on the file's robot, which
        then are unsaved again)."""
        path = self.robot_path
        base, mine = self.saved_robot, self.robot
        result = await save_flow(
            self,
            self.robot,
            path,
            self.stamp,
            base_text=_text_of(path) if path is not None else self.new_text,
            save_as=save_as,
        )
        if result is None:
            return False
        self.saved_robot, self.stamp, self.robot_path = result.robot, result.stamp, result.path
        self.new_text = self.imported_from = None
        if result.kind == "reloaded":  # the file's robot, with my poses on top
            again = await reapply_edits(self, base, mine, result.robot)
            self._run(again.robot, result.path)  # mine as it was, if they would not combine
            self._say(f"reloaded {result.path}: {again.message}", not again.combined)
            return not self.has_unsaved_poses
        return True

    @work(exclusive=True, group="modal")
    async def _save_running_robot(self) -> None:
        await self.save_running_robot()

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
        if self.has_unsaved_poses:
            answer = await self.push_screen_wait(
                SaveGuard(self.robot.name, "opening another robot")
            )
            if answer not in ("save", "discard"):
                return
            if answer == "save" and not await self.save_running_robot():
                return
        opened = await self.push_screen_wait(OpenRobot(importing=importing))
        if opened is None:
            return
        if opened.imported:
            self.run_import(opened)
            return
        robot, path = opened.robot, opened.source
        found = await offer_recovery(self, path, robot)  # changes kept by a crash
        self.saved_robot = self._first_robot = robot
        self.stamp = None if is_bundled(path) else opened.stamp
        self.new_text = self.imported_from = None
        self._run(robot, path)
        if found is not None:
            self.open_editor(found.robot, path, saved=robot, stamp=self.stamp)

    def run_import(self, opened: Opened) -> None:
        """The simulator runs an imported robot. It has no robot file: it is
        unsaved (quitting asks; saving asks a name in robots/)."""
        self.saved_robot = self._first_robot = None
        self.stamp = None
        self.new_text = header_text(opened.header)
        self.imported_from = opened.source
        self._run(opened.robot, None)
        self.push_screen(
            ImportNotes(opened, f"the palette's Save (ctrl+p) saves it as {ROBOTS_DIR}/<name>.toml")
        )

    def _report(self) -> Callable[[str, bool], None] | None:
        """Where a flow on the simulator reports: its status line (else a toast)."""
        screen = self.screen
        return screen.say if isinstance(screen, ControlScreen) else None

    def _say(self, message: str, error: bool = False) -> None:
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
        name = re.sub(r"[^A-Za-z0-9_-]+", "_", self.robot.name).strip("_")[:40] or "robot"
        stem = f"dhsim-{name}-{time.strftime('%Y%m%d-%H%M%S')}"
        data = export_svg(self, title=f"dhsim: {printable(self.robot.name)}").encode()
        try:
            for number in range(1, 100):
                path = Path(f"{stem}.svg" if number == 1 else f"{stem}-{number}.svg")
                if not path.exists():
                    write_file(path, data)
                    break
            else:
                raise DhsimError(f"{stem}.svg and 98 more exist already")
        except DhsimError as exc:
            self._say(f"picture not saved: {exc}", error=True)
            return None
        self._say(f"picture saved: {path.resolve()}")
        return path

    def action_save_picture(self) -> None:
        self.save_picture()

    # -- the command palette and themes -------------------------------------------
    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """ctrl+p opens the palette on the simulator and the editor, not over
        a dialog (the key then goes on to it, which ignores it)."""
        if action == "command_palette":
            return self._palette_allowed()
        return True

    def _palette_allowed(self) -> bool:
        """Not over a dialog, and not while a palette is opening, open or
        still leaving the screen (ctrl+p, escape, ctrl+p in one read)."""
        return (
            self.use_command_palette
            and not CommandPalette.is_open(self)
            and (self._palette is None or self._palette.gone)
            and hasattr(self.screen, "palette_commands")  # a screen with commands
        )

    def action_command_palette(self) -> None:
        if self._palette_allowed():
            self._palette = DhsimPalette()
            self.push_screen(self._palette)

    def theme_choices(self) -> dict[str, str]:
        """--theme's names and the Textual themes they stand for."""
        return dict(THEMES)

    def set_theme(self, name: str) -> None:
        self.theme = THEMES[name]

    # -- unsaved work ------------------------------------------------------------
    @property
    def has_unsaved_poses(self) -> bool:
        """The running robot differs from its file: a pose kept only in memory."""
        baseline = self.saved_robot if self.saved_robot is not None else self._first_robot
        return baseline is None or self.robot != baseline

    def _editors(self) -> list[EditorScreen]:
        return [s for s in reversed(self.screen_stack) if isinstance(s, EditorScreen)]

    def unsaved_work(self) -> list[tuple[Robot, Path | None]]:
        """Every robot with changes not on disk, with its source file (None: a
        new robot). While an editor is open it has the simulator's poses (it
        started from them; none can be added meanwhile), so it alone counts."""
        editors = self._editors()
        if not editors:
            return [(self.robot, self.robot_path)] if self.has_unsaved_poses else []
        work: list[tuple[Robot, Path | None]] = []
        seen: set[str] = set()
        for editor in editors:
            source = editor.path or editor.template
            if editor.dirty and source_key(source) not in seen:
                seen.add(source_key(source))
                work.append((editor.robot, source))
        return work

    def keep_unsaved_work(self, signum: int | None = None) -> list[str]:
        """Write every unsaved robot to a recovery file; what to tell the user.
        Safe in a signal handler (no lock, no terminal output)."""
        why = signal.Signals(signum).name if signum else "unexpected error"
        messages = []
        for robot, source in self.unsaved_work():
            what = f"{robot.name} ({source if source is not None else 'new robot'})"
            try:
                file = write_recovery(robot, source)
            except (OSError, DhsimError) as exc:
                reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
                messages.append(f"dhsim: {why}: unsaved changes to {what} NOT kept: {reason}")
            else:
                messages.append(
                    f"dhsim: {why}: unsaved changes to {what} kept in {file}; "
                    "dhsim offers them back when you open it again"
                )
        return [printable(message) for message in messages]

    def _keep_before_crash(self) -> None:
        if self.recovery and not self.exit_messages:
            with contextlib.suppress(Exception):
                self.exit_messages = self.keep_unsaved_work()

    def _handle_exception(self, error: Exception) -> None:
        """An unexpected error ends the app (status 1): keep unsaved work
        first, and end with one line (the traceback goes to a crash report
        file, never to the screen)."""
        self._keep_before_crash()
        self._return_code = 1
        if self._exception is None:  # Pilot re-raises it in tests
            self._exception = error
            self._exception_event.set()
        self._exit_renderables.append(Text(crash_line(error)))
        self._close_messages_no_wait()

    def panic(self, *renderables) -> None:
        """Textual's other way out after an error (e.g. its input thread failed):
        keep unsaved work, and end with status 1 (Textual leaves it at 0) and
        one line."""
        self._keep_before_crash()
        self._return_code = 1  # no public setter; exit() would not stop a panic
        text = " ".join(str(r) for r in renderables if isinstance(r, str))
        super().panic(Text(crash_line(RuntimeError(text or "Textual stopped"))))

    async def action_quit(self) -> None:
        """Quit, unless something is not saved: then ask, save, discard or stay.
        An open editor asks about its robot (a dialog on top of it must not let
        its changes slip; it started with the simulator's poses), else the
        simulator about poses kept only in memory."""
        editors = self._editors()
        if editors:
            dirty = next((editor for editor in editors if editor.dirty), None)
            if dirty is None:
                self.exit()
            else:
                self._quit_after_editor(dirty)
        elif self.has_unsaved_poses:
            self._quit_after_poses()
        else:
            self.exit()

    @work(exclusive=True, group="modal")
    async def _quit_after_editor(self, editor: EditorScreen) -> None:
        if await editor.guard("quitting"):
            self.exit()

    @work(exclusive=True, group="modal")
    async def _quit_after_poses(self) -> None:
        answer = await self.push_screen_wait(SaveGuard(self.robot.name, "quitting"))
        if answer == "discard" or (answer == "save" and await self.save_running_robot()):
            self.exit()


def run_app(
    robot: Robot,
    path: Path | None = None,
    renderer: str = "plotext",
    start: str = "control",
    stamp: FileStamp | None = None,
    ascii: bool = False,
    theme: str = "dark",
) -> int:
    """Run the TUI in this terminal; the exit status (1 after an unexpected error,
    128 + the signal's number after SIGHUP, SIGTERM or SIGQUIT)."""
    app = DhsimApp(
        robot, path, renderer, start, recovery=True, stamp=stamp, ascii=ascii, theme=theme
    )
    guard = SignalGuard(app, app.keep_unsaved_work)
    guard.install()
    try:
        app.run()
    finally:
        guard.uninstall()
    for message in app.exit_messages:
        print(printable(message), file=sys.stderr)
    return app.return_code or 0

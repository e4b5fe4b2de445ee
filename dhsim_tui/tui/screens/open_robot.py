"""The open dialog: your robots (the user library), those in ``./robots/``
and the bundled ones, or a path.

A ``.toml`` file is a robot file; a ``.urdf`` or ``.csv`` file is imported
(:func:`dhsim_tui.core.interop.importer.import_file`): the robot it gives has no
robot file yet, so saving it asks for a name (saved in the user library). A URDF whose
links form a tree asks which leaf link is the tool.

Nothing a folder or a typed path can do raises: an unreadable folder, a
working folder that was deleted, a path too long for the system, a file
name with control characters: each becomes a message (escaped, never
markup), and the dialog stays open.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from pathlib import Path

from rich.text import Text
from textual import events, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.markup import escape
from textual.widgets import Input, Label, OptionList
from textual.widgets.option_list import Option

from dhsim_tui.core.files.formats import IMPORT_SUFFIXES
from dhsim_tui.core.files.library import bundled_dir, describe, user_library_dir
from dhsim_tui.core.files.robotfile import FileStamp, load, load_with_stamp
from dhsim_tui.core.model.errors import DhsimError, TipNeeded
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal.charset import shown
from dhsim_tui.tui.screens.dialogs import DIALOG_CSS, Choice, reason_of, short_path
from dhsim_tui.tui.screens.modal import Dialog

ROBOTS_DIR = Path("robots")
#: what the dialog lists: robot files, and files it imports
ROBOT_SUFFIXES = (".toml",)
OPEN_SUFFIXES = (*ROBOT_SUFFIXES, *IMPORT_SUFFIXES)
#: the list imports at most this many files to summarise them (each is checked
#: at 200 joint values); the others say they are imported when opened
SUMMARY_IMPORTS = 24


@dataclass(frozen=True)
class Opened:
    """What the dialog opened. ``source`` is the file chosen; for a robot file
    ``stamp`` is what it held when read. An import (``.urdf``, ``.csv``) has
    no robot file: ``notes`` are the importer's remarks, ``header`` the
    comment lines for the top of the robot file it is saved to."""

    robot: Robot
    source: Path
    stamp: FileStamp | None = None
    notes: tuple[str, ...] = ()
    header: tuple[str, ...] = ()

    @property
    def imported(self) -> bool:
        return is_import(self.source)

    @property
    def path(self) -> Path | None:
        """The robot's file: None for an import (saving it asks for a name)."""
        return None if self.imported else self.source


def is_import(path: Path) -> bool:
    """A file the importer reads (``.urdf``, ``.csv``), not a robot file."""
    return path.suffix.lower() in IMPORT_SUFFIXES


def header_text(header: tuple[str, ...]) -> str | None:
    """An import's header lines as the comments a new robot file starts with."""
    if not header:
        return None
    return "".join(f"# {printable(line)}\n" for line in header) + "\n"


def _key(path: Path) -> Path:
    """What identifies a file (its real path; as given when that cannot be known)."""
    try:
        return path.resolve()
    except (OSError, RuntimeError, ValueError):
        return path


def robot_files(
    notes: list[str] | None = None, suffixes: tuple[str, ...] = ROBOT_SUFFIXES
) -> list[Path]:
    """Files a user may want: their robot library's robots first (when
    ``suffixes`` has ``.toml``), then ./robots/ (robot files, and the imports
    ``suffixes`` asks for), then the bundled robots. A folder that cannot be
    read is skipped, with a line in ``notes``."""
    files: list[Path] = []
    seen: set[Path] = set()
    robots = ".toml" in suffixes
    folders = ([_library()] if robots else []) + [ROBOTS_DIR] + ([bundled_dir()] if robots else [])
    for folder in folders:
        try:
            if not folder.is_dir():
                continue
            found = sorted(p for p in folder.iterdir() if p.suffix.lower() in suffixes)
        except OSError as exc:
            if notes is not None:
                notes.append(f"{short_path(folder, 50)}/ cannot be read: {reason_of(exc, folder)}")
            continue
        for path in found:
            if _key(path) not in seen:
                seen.add(_key(path))
                files.append(path)
    return files


def _library() -> Path:
    """The user library (a folder that is not there when there is no home)."""
    try:
        return user_library_dir()
    except DhsimError:
        return ROBOTS_DIR


def import_file(path: Path, tip: str | None = None):
    """:func:`dhsim_tui.core.interop.importer.import_file`, loaded when first used:
    the XML and CSV readers would cost ~20 ms of every start."""
    from dhsim_tui.core.interop.importer import import_file as read

    return read(path, tip=tip)


def summary(path: Path, imports_left: int = SUMMARY_IMPORTS) -> str:
    """One line about a file: the robot it holds, or why it cannot be opened."""
    if is_import(path):
        if imports_left <= 0:
            return f"({path.suffix.lower()[1:].upper()}: imported when opened)"
        try:
            return describe(import_file(path).robot)
        except TipNeeded as exc:
            return f"(a tree: choose the tool among {len(exc.leaves)} leaf links when opening)"
        except (DhsimError, OSError, ValueError, RuntimeError) as exc:
            return f"(cannot be imported: {reason_of(exc, path)})"
    try:
        return describe(load(path))
    except DhsimError as exc:
        return f"(cannot be opened: {reason_of(exc, path)})"


class OpenRobot(Dialog[Opened | None]):
    """Pick a file from the list or type a path; a bad file shows the loader's
    (or importer's) message and nothing else changes. Dismisses with
    :class:`Opened`. ``importing``: only imports (``.urdf``, ``.csv``)."""

    BINDINGS = [
        Binding(
            "escape", "cancel", "Cancel", id="open.cancel", tooltip="Close without opening anything"
        )
    ]
    DEFAULT_CSS = """
    OpenRobot { align: center middle; }
    OpenRobot > Vertical {
        width: 90; max-width: 100%; height: auto; max-height: 100%;
        border: round $accent; background: $surface; padding: 0 1;
    }
    OpenRobot OptionList { height: auto; max-height: 12; }
    OpenRobot Label { width: 100%; }
    OpenRobot #error { color: $error; }
    OpenRobot .hint { color: $text-muted; }
    """

    def __init__(self, importing: bool = False) -> None:
        super().__init__()
        self.importing = importing

    def compose(self) -> ComposeResult:
        notes: list[str] = []
        suffixes = IMPORT_SUFFIXES if self.importing else OPEN_SUFFIXES
        self._files = robot_files(notes, suffixes)
        imports_left = SUMMARY_IMPORTS
        lines = []
        for path in self._files:
            lines.append(f"{short_path(path, 60)}  {summary(path, imports_left)}")
            imports_left -= is_import(path)
        with Vertical() as box:
            if self.importing:
                box.border_title = "Import a URDF or CSV file"
                placeholder = "or type a path to a .urdf or .csv file, then enter"
            else:
                box.border_title = "Open a robot"
                placeholder = "or type a path to a .toml, .urdf or .csv file, then enter"
            yield OptionList(
                *(Option(Text(shown(line)), id=str(i)) for i, line in enumerate(lines))
            )
            yield Input(placeholder=placeholder, id="path", select_on_focus=False)
            yield Label(Text(shown("\n".join(notes))), id="error")
            yield Label(
                shown("↑↓ choose · enter opens · type or tab for a path · escape cancels"),
                classes="hint",
            )

    def on_mount(self) -> None:
        if not self._files:  # nothing to pick (no robots/ yet): type a path
            self.query_one("#path", Input).focus()

    def on_key(self, event: events.Key) -> None:
        """Typing on the list starts a path: the key goes to the path box
        (so ``ctrl+o`` then a path and enter opens it, as people expect)."""
        if event.is_printable and event.character and isinstance(self.focused, OptionList):
            path = self.query_one("#path", Input)
            path.focus()
            path.insert_text_at_cursor(event.character)
            event.stop()
            event.prevent_default()

    def _say(self, message: str) -> None:
        self.query_one("#error", Label).update(Text(shown(printable(message))))

    def _open(self, path: Path) -> None:
        """Load a robot file, or import a .urdf/.csv; a URDF that is a tree
        first asks for its tip (:meth:`_import_with_tip`)."""
        if is_import(path):
            opened = self._import(path)
        elif self.importing:
            self._say(
                f"cannot import: dhsim imports {' and '.join(IMPORT_SUFFIXES)} files "
                f"— {short_path(path)}"
            )
            return
        else:
            opened = self._load(path)
        if opened is not None:
            self.dismiss(opened)

    def _load(self, path: Path) -> Opened | None:
        try:
            robot, stamp = load_with_stamp(path)
        except (DhsimError, OSError, ValueError, RuntimeError) as exc:
            self._say(f"cannot open: {reason_of(exc, path)} — {short_path(path)}")
            return None
        return Opened(robot, path, stamp)

    def _import(self, path: Path, tip: str | None = None) -> Opened | None:
        try:
            result = import_file(path, tip=tip)
        except TipNeeded as exc:
            if tip is None and exc.leaves:
                self._import_with_tip(path, exc.leaves)
            else:  # a chosen tip is one of the leaves: not refused as a tree again
                self._say(f"cannot import: {reason_of(exc, path)} — {short_path(path)}")
            return None
        except (DhsimError, OSError, ValueError, RuntimeError) as exc:
            self._say(f"cannot import: {reason_of(exc, path)} — {short_path(path)}")
            return None
        return Opened(result.robot, path, None, result.notes, result.header)

    @work(exclusive=True, group="modal")
    async def _import_with_tip(self, path: Path, leaves: tuple[str, ...]) -> None:
        tip = await self._ask_tip(path, leaves)
        if tip is None:
            self._say(f"not imported: no tool link chosen — {short_path(path)}")
            return
        opened = self._import(path, tip)
        if opened is not None:
            self.dismiss(opened)

    async def _ask_tip(self, path: Path, leaves: tuple[str, ...]) -> str | None:
        """The URDF's links form a tree: which leaf link is the tool?"""
        choice = await self.app.push_screen_wait(
            Choice(
                f"{path.name}: which link is the tool?",
                [(str(i), leaf) for i, leaf in enumerate(leaves)],
                hint="the links form a tree: the chain runs from the base to the link "
                "chosen\n↑↓ choose · enter picks · escape cancels",
            )
        )
        return None if choice is None else leaves[int(choice)]

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        event.stop()
        self._open(self._files[int(event.option.id or 0)])

    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        text = event.value.strip()
        if not text:
            self._say("type a path to a robot file")
            return
        path = Path(text)
        with contextlib.suppress(RuntimeError):  # "~someone" with no such user: as typed
            path = path.expanduser()
        self._open(path)

    def action_cancel(self) -> None:
        self.dismiss(None)


class ImportNotes(Dialog[None]):
    """What an import did: the importer's notes (what it checked, what is
    odd), and that the robot is not saved yet. ``enter`` or ``escape`` closes."""

    BINDINGS = [
        Binding(
            "enter,escape,q",
            "close",
            "Close",
            id="import_notes.close",
            tooltip="Close the notes and go on with the imported robot",
        )
    ]
    DEFAULT_CSS = DIALOG_CSS.format(name="ImportNotes") + "ImportNotes > Vertical { width: 72; }"

    def __init__(self, opened: Opened, where: str) -> None:
        """``where``: what happens next, e.g. "ctrl+s saves it as robots/<name>.toml"."""
        super().__init__()
        self._opened = opened
        self._where = where

    def compose(self) -> ComposeResult:
        opened = self._opened
        lines = [f"- {printable(note)}" for note in opened.notes]
        lines.append(f"Not saved yet: {printable(self._where)}.")
        with Vertical() as box:
            box.border_title = escape(shown(f"Imported {printable(opened.source.name)}"))
            yield Label(Text(shown("\n".join(lines))))
            yield Label(shown("enter or escape closes"), classes="hint")

    def action_close(self) -> None:
        self.dismiss(None)

"""The open dialog: the robots in ``robots/`` (and the bundled ones), or a path.

Nothing a folder or a typed path can do raises: an unreadable folder, a
working folder that was deleted, a path too long for the system, a file
name with control characters: each becomes a message (escaped, never
markup), and the dialog stays open.
"""

from __future__ import annotations

import contextlib
from pathlib import Path

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Input, Label, OptionList
from textual.widgets.option_list import Option

from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.library import bundled_dir, describe
from dhsim_tui.core.model import Robot
from dhsim_tui.core.robotfile import FileStamp, load, load_with_stamp
from dhsim_tui.core.text import printable
from dhsim_tui.screens.dialogs import reason_of, short_path
from dhsim_tui.terminal import shown

ROBOTS_DIR = Path("robots")


def _key(path: Path) -> Path:
    """What identifies a file (its real path; as given when that cannot be known)."""
    try:
        return path.resolve()
    except (OSError, RuntimeError, ValueError):
        return path


def robot_files(notes: list[str] | None = None) -> list[Path]:
    """Robot files a user may want: ./robots/*.toml first, then the bundled ones.
    A folder that cannot be read is skipped, with a line in ``notes``."""
    files: list[Path] = []
    seen: set[Path] = set()
    for folder in (ROBOTS_DIR, bundled_dir()):
        try:
            if not folder.is_dir():
                continue
            found = sorted(p for p in folder.iterdir() if p.suffix == ".toml")
        except OSError as exc:
            if notes is not None:
                notes.append(f"{short_path(folder, 50)}/ cannot be read: {reason_of(exc, folder)}")
            continue
        for path in found:
            if _key(path) not in seen:
                seen.add(_key(path))
                files.append(path)
    return files


def summary(path: Path) -> str:
    try:
        return describe(load(path))
    except DhsimError as exc:
        return f"(cannot be opened: {reason_of(exc, path)})"


class OpenRobot(ModalScreen[tuple[Robot, Path, FileStamp] | None]):
    """Pick a file from the list or type a path; a bad file shows the loader's
    message and nothing else changes. Dismisses with (robot, path, stamp)."""

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

    def compose(self) -> ComposeResult:
        notes: list[str] = []
        self._files = robot_files(notes)
        with Vertical() as box:
            box.border_title = "Open a robot"
            yield OptionList(
                *(
                    Option(Text(shown(f"{short_path(path, 60)}  {summary(path)}")), id=str(i))
                    for i, path in enumerate(self._files)
                )
            )
            yield Input(placeholder="or type a path to a .toml file, then enter", id="path")
            yield Label(Text(shown("\n".join(notes))), id="error")
            yield Label(
                shown("↑↓ choose · enter opens · tab to the path · escape cancels"),
                classes="hint",
            )

    def _say(self, message: str) -> None:
        self.query_one("#error", Label).update(Text(shown(printable(message))))

    def _open(self, path: Path) -> None:
        try:
            robot, stamp = load_with_stamp(path)
        except (DhsimError, OSError, ValueError, RuntimeError) as exc:
            self._say(f"cannot open: {reason_of(exc, path)} — {short_path(path)}")
            return
        self.dismiss((robot, path, stamp))

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

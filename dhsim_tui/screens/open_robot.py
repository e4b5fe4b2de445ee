"""The open dialog: the robots in ``robots/`` (and the bundled ones), or a path."""

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
from dhsim_tui.core.robotfile import load

ROBOTS_DIR = Path("robots")


def robot_files() -> list[Path]:
    """Robot files a user may want: ./robots/*.toml first, then the bundled ones."""
    files: list[Path] = []
    seen: set[Path] = set()
    for folder in (ROBOTS_DIR, bundled_dir()):
        if folder.is_dir():
            for path in sorted(folder.glob("*.toml")):
                if path.resolve() not in seen:
                    seen.add(path.resolve())
                    files.append(path)
    return files


def summary(path: Path) -> str:
    try:
        return describe(load(path))
    except DhsimError as exc:
        return f"(cannot be opened: {str(exc).removeprefix(str(path) + ': ')})"


class OpenRobot(ModalScreen[tuple[Robot, Path] | None]):
    """Pick a file from the list or type a path; a bad file shows the loader's
    message and nothing else changes."""

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
    OpenRobot #error { color: $error; }
    OpenRobot .hint { color: $text-muted; }
    """

    def compose(self) -> ComposeResult:
        self._files = robot_files()
        with Vertical() as box:
            box.border_title = "Open a robot"
            yield OptionList(
                *(
                    Option(Text(f"{path}  {summary(path)}"), id=str(i))
                    for i, path in enumerate(self._files)
                )
            )
            yield Input(placeholder="or type a path to a .toml file, then enter", id="path")
            yield Label("", id="error")
            yield Label(
                "↑↓ choose · enter opens · tab to the path · escape cancels", classes="hint"
            )

    def _open(self, path: Path) -> None:
        try:
            robot = load(path)
        except DhsimError as exc:
            self.query_one("#error", Label).update(Text(str(exc)))
            return
        self.dismiss((robot, path))

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        event.stop()
        self._open(self._files[int(event.option.id or 0)])

    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        text = event.value.strip()
        if not text:
            self.query_one("#error", Label).update("type a path to a robot file")
            return
        path = Path(text)
        with contextlib.suppress(RuntimeError):  # "~someone" with no such user: as typed
            path = path.expanduser()
        self._open(path)

    def action_cancel(self) -> None:
        self.dismiss(None)

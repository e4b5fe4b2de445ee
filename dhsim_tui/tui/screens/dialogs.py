"""Small modal questions: yes/no, one of several, the unsaved-changes guard
and the questions of a save (file changed on disk, file read-only).

Every text is shown whole: labels wrap inside the box, and a long path is
shortened in the middle (:func:`short_path`) so the reason stays in view.
Text that came from a file (names, paths) is escaped, never markup.
"""

from __future__ import annotations

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.markup import escape
from textual.widgets import Label, OptionList
from textual.widgets.option_list import Option

from dhsim_tui.core.model.text import printable
from dhsim_tui.terminal.charset import ascii_mode, shown
from dhsim_tui.tui.screens.modal import Dialog

DIALOG_CSS = """
    {name} {{ align: center middle; }}
    {name} > Vertical {{
        width: 60; max-width: 100%; height: auto; max-height: 100%;
        border: round $accent; background: $surface; padding: 0 1;
    }}
    {name} OptionList {{ height: auto; max-height: 16; border: none; padding: 0; }}
    {name} Label {{ width: 100%; }}
    {name} .hint {{ color: $text-muted; }}
"""

#: the longest path a dialog shows before shortening it in the middle
PATH_LIMIT = 110


def short_path(path: object, limit: int = PATH_LIMIT) -> str:
    """``path`` as text, escaped, and at most ``limit`` characters: the start
    and the end (the file's name) stay, the middle becomes ``…`` (``...`` when
    the running app is in ASCII mode)."""
    text = printable(str(path))
    if len(text) <= limit:
        return text
    limit = max(limit, 8)
    mark = "..." if ascii_mode() else "…"
    tail = max(limit * 2 // 3, limit - 1 - limit // 3)
    head = max(0, limit - len(mark) - tail)
    return f"{text[:head]}{mark}{text[-tail:]}"


def reason_of(error: BaseException, path: object) -> str:
    """The reason of a file error without the path it starts with (escaped)."""
    if isinstance(error, OSError) and error.strerror:
        return printable(error.strerror.lower())
    text = printable(str(error))
    for prefix in (printable(str(path)), printable(str(path)).rstrip("/")):
        text = text.removeprefix(f"{prefix}: ")
    return text


class Confirm(Dialog[bool]):
    """A yes/no question: ``y`` or ``enter`` for yes, ``n`` or ``escape`` for no."""

    BINDINGS = [
        Binding("y,enter", "answer(True)", "Yes", id="confirm.yes", tooltip="Yes"),
        Binding("n,escape", "answer(False)", "No", id="confirm.no", tooltip="No"),
    ]
    DEFAULT_CSS = DIALOG_CSS.format(name="Confirm")

    def __init__(self, question: str, title: str = "Are you sure?") -> None:
        super().__init__()
        self._question = question
        self._title = title

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = escape(shown(printable(self._title)))
            yield Label(Text(shown(printable(self._question))))
            yield Label(shown("y yes · n no"), classes="hint")

    def action_answer(self, yes: bool) -> None:
        self.dismiss(yes)


class Choice(Dialog[str | None]):
    """Pick one of ``choices`` with the arrows and ``enter``; ``escape`` cancels.

    ``disabled`` values are listed (their text says why) but cannot be picked;
    ``question``, when given, is shown above the choices."""

    BINDINGS = [Binding("escape", "cancel", "Cancel", id="choice.cancel", tooltip="Cancel")]
    DEFAULT_CSS = DIALOG_CSS.format(name="Choice")

    def __init__(
        self,
        title: str,
        choices: list[tuple[str, str]],
        current: str | None = None,
        hint: str = "",
        *,
        disabled: tuple[str, ...] = (),
        question: str = "",
    ) -> None:
        """``choices`` are (value, what the user reads)."""
        super().__init__()
        self._title = title
        self._choices = choices
        self._current = current
        self._hint = hint
        self._disabled = disabled
        self._question = question

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = escape(shown(printable(self._title)))
            if self._question:
                yield Label(Text(shown(printable(self._question))))
            options = OptionList(
                *(
                    Option(Text(shown(printable(text))), id=value, disabled=value in self._disabled)
                    for value, text in self._choices
                )
            )
            yield options
            hint = self._hint or "↑↓ choose · enter picks · escape cancels"
            yield Label(shown(hint), classes="hint")

    def on_mount(self) -> None:
        options = self.query_one(OptionList)
        values = [value for value, _ in self._choices]
        open_ = [value for value in values if value not in self._disabled]
        current = self._current if self._current in open_ else (open_ or [None])[0]
        if current is not None:
            options.highlighted = values.index(current)
        options.focus()

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        event.stop()
        self.dismiss(event.option.id)

    def action_cancel(self) -> None:
        self.dismiss(None)


class SaveGuard(Dialog[str]):
    """Unsaved changes: ``s`` save, ``d`` discard, ``escape`` stay."""

    BINDINGS = [
        Binding("s", "answer('save')", "Save", id="guard.save", tooltip="Save, then go on"),
        Binding(
            "d",
            "answer('discard')",
            "Discard",
            id="guard.discard",
            tooltip="Throw the changes away, then go on",
        ),
        Binding(
            "escape,c", "answer('stay')", "Stay", id="guard.stay", tooltip="Go back to the editor"
        ),
    ]
    DEFAULT_CSS = DIALOG_CSS.format(name="SaveGuard")

    def __init__(self, name: str, doing: str) -> None:
        super().__init__()
        self._name = name
        self._doing = doing

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = "Unsaved changes"
            name = printable(self._name)
            yield Label(
                Text(shown(f"{name} has changes that are not saved. Save before {self._doing}?"))
            )
            yield Label(shown("s save · d discard · escape stay"), classes="hint")

    def action_answer(self, answer: str) -> None:
        self.dismiss(answer)


class FileChanged(Dialog[str]):
    """The file changed on disk since it was read: ``o`` overwrite, ``r`` reload
    (the file as it is, the changes made here put back on top), ``c``/``escape``
    cancel."""

    BINDINGS = [
        Binding(
            "o",
            "answer('overwrite')",
            "Overwrite",
            id="changed.overwrite",
            tooltip="Write this robot over the file's new content",
        ),
        Binding(
            "r",
            "answer('reload')",
            "Reload",
            id="changed.reload",
            tooltip="Read the file again and put the changes made here back on top",
        ),
        Binding(
            "c,escape",
            "answer('cancel')",
            "Cancel",
            id="changed.cancel",
            tooltip="Save nothing; keep everything in memory",
        ),
    ]
    DEFAULT_CSS = DIALOG_CSS.format(name="FileChanged")

    def __init__(self, path: object, why: str = "") -> None:
        super().__init__()
        self._path = path
        self._why = why

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = "Changed on disk"
            why = f" ({printable(self._why)})" if self._why else ""
            yield Label(
                Text(
                    shown(
                        f"{short_path(self._path)} changed on disk since you opened it{why}. "
                        "Overwrite it, reload it (the file as it is now, your changes "
                        "put back on top), or cancel?"
                    )
                )
            )
            yield Label(shown("o overwrite · r reload · c cancel"), classes="hint")

    def action_answer(self, answer: str) -> None:
        self.dismiss(answer)


class ReadOnly(Dialog[bool]):
    """The file cannot be written: ``a`` save as another file, ``c``/``escape`` cancel."""

    BINDINGS = [
        Binding(
            "a,enter",
            "answer(True)",
            "Save as",
            id="readonly.save_as",
            tooltip="Save under another name",
        ),
        Binding(
            "c,escape",
            "answer(False)",
            "Cancel",
            id="readonly.cancel",
            tooltip="Save nothing; keep everything in memory",
        ),
    ]
    DEFAULT_CSS = DIALOG_CSS.format(name="ReadOnly")

    def __init__(self, path: object, reason: str = "read-only") -> None:
        super().__init__()
        self._path = path
        self._reason = reason

    def compose(self) -> ComposeResult:
        with Vertical() as box:
            box.border_title = "Not saved"
            yield Label(
                Text(
                    shown(
                        f"not saved: {printable(self._reason)} — {short_path(self._path)}. "
                        "Nothing was changed on disk and your edits are kept. "
                        "Save as another file?"
                    )
                )
            )
            yield Label(shown("a save as · c cancel"), classes="hint")

    def action_answer(self, save_as: bool) -> None:
        self.dismiss(save_as)

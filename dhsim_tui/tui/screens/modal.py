"""dhsim's dialogs: Textual's modal screen, answered once.

Two keys in one read (``escape escape``, ``enter`` and ``escape``) both reach
a dialog before it has left the screen. Textual's ``dismiss`` would deliver
the second answer too: the waiting flow's future was already done
(``InvalidStateError``), and the second ``pop_screen`` took away the screen
under the dialog. Here a dialog's result is delivered once; a later answer,
or one given when the dialog is no longer in front, is ignored.
"""

from __future__ import annotations

from typing import Generic, TypeVar

from textual.await_complete import AwaitComplete
from textual.screen import ModalScreen

Result = TypeVar("Result")


class Dialog(ModalScreen[Result], Generic[Result]):
    """A modal screen whose result is delivered once."""

    _answered = False

    def dismiss(self, result: Result | None = None) -> AwaitComplete:
        if self._answered or self.app.screen is not self:
            return AwaitComplete()
        self._answered = True
        return super().dismiss(result)

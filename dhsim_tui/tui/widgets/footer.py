"""The footer: Textual's, without the memory it keeps on every change of keys.

Textual 8.2.8's ``Footer`` recomposes itself whenever the screen's bindings
change, which is on every change of focus (``c``, ``g`` and ``tab`` in dhsim).
Each ``FooterKey`` it composes is ``data_bind``-ed to the footer's ``compact``:
that puts a ``(key, setter)`` pair in the footer's list of watchers of
``compact``, and the setter's closure holds the key. Nothing takes the pair out
when the key is removed; Textual drops the pairs of closed widgets only when
the watched reactive is next set, and a footer's ``compact`` never changes. So
every recompose left its ten-odd keys (their styles, tooltips, renders) alive
for good: 0.3–0.65 MB a mode switch (docs/upstream/textual-footer-leak.md).

:class:`KeysFooter` does two things about it, through public API only:

* it recomposes only when what it shows has changed (a change of focus that
  leaves the same keys, labels and states costs nothing), and
* after a recompose it sets ``compact`` again (``mutate_reactive``), which is
  what makes Textual drop the watchers of the keys just removed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from textual.widgets import Footer

if TYPE_CHECKING:
    from textual.app import ComposeResult


class KeysFooter(Footer):
    """A footer of the screen's keys that recomposes only for a change it
    shows, and lets go of the keys it has replaced."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        #: what the footer shows now (:meth:`_shows`); None: nothing yet
        self._shown: tuple | None = None

    def _shows(self) -> tuple:
        """Everything ``Footer.compose`` makes the keys from: each shown
        binding with its key's name, label, state and tooltip, in order, the
        palette's key and the footer's own settings."""
        app = self.app
        active = self.screen.active_bindings
        keys = tuple(
            (
                binding.key,
                app.get_key_display(binding),
                binding.description,
                binding.action,
                binding.group,
                binding.tooltip,
                enabled,
                tooltip,
            )
            for _, binding, enabled, tooltip in active.values()
            if binding.show
        )
        palette = active.get(app.COMMAND_PALETTE_BINDING)
        palette_key = None
        if palette is not None:
            _, binding, enabled, _ = palette
            palette_key = (
                binding.key,
                app.get_key_display(binding),
                binding.description,
                binding.tooltip,
                enabled,
            )
        return (
            keys,
            palette_key,
            self.compact,
            self.show_command_palette,
            app.ENABLE_COMMAND_PALETTE,
        )

    def compose(self) -> ComposeResult:
        shows = self._shows()
        made = False
        for widget in super().compose():
            made = True
            yield widget
        # nothing made: the bindings were not ready yet (or there are none)
        self._shown = shows if made else None

    async def recompose(self) -> None:
        """Recompose (Textual's footer does on every change of the screen's
        bindings, so on every change of focus) only if the keys it would
        show have changed; then let go of the keys it replaced."""
        if self.is_attached and self._shown is not None and self._shows() == self._shown:
            return
        await super().recompose()
        if self.is_attached:
            self._let_go_of_old_keys()

    def _let_go_of_old_keys(self) -> None:
        """Drop the watchers the keys just removed left on ``compact``.

        Textual 8.2.8 keeps a ``(key, setter)`` pair for each data-bound key
        in the footer's watchers of ``compact`` until ``compact`` is next set;
        setting it then drops the pairs of closed keys (the removed ones have
        closed by now: ``recompose`` awaits their removal). It re-applies the
        same value to the keys still shown: nothing on screen changes."""
        self.mutate_reactive(Footer.compact)

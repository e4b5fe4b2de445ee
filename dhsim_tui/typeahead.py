"""Keys typed ahead reach the screen they were meant for, in order.

Over a slow link a burst such as ``P l a b 4 enter`` arrives in one read.
Textual forwards each key to the focused widget, and runs the bindings (``P``:
save a pose, which opens a dialog) only when the key bubbles back up to the
app: behind every other key of the burst, which by then have all been handed
to the old screen. ``lab4`` was lost and ``enter`` opened another dialog.

Here the app takes one key at a time: a key from the terminal is forwarded,
and the keys behind it wait until it has been handled — it came back and its
binding ran, or a widget used it — and any dialog it opened is ready for
typing. Then the next key goes to whatever screen is in front.
"""

from __future__ import annotations

import asyncio

from textual import events
from textual.app import App
from textual.screen import Screen

#: rounds of the event loop a binding's worker gets to push its dialog
SETTLE_ROUNDS = 12
#: how long a waiting key checks back (s), and the longest one key may hold
#: the keys behind it (s) before they go on regardless
POLL = 0.001
HOLD_LIMIT = 0.5


class KeysInOrder(App):
    """An App that hands the terminal's keys on one at a time."""

    _in_flight: events.Key | None = None
    _since = 0.0
    _held: list[events.Key]
    _polling = False

    @property
    def keys_waiting(self) -> bool:
        """More keys of a burst are still to come: a screen may put off
        drawing until they are handled (see :func:`draw_later`)."""
        return bool(getattr(self, "_held", None))

    async def on_event(self, event: events.Event) -> None:
        if not isinstance(event, events.Key):
            await super().on_event(event)
            return
        if not event.is_forwarded:  # straight from the terminal
            if not hasattr(self, "_held"):
                self._held = []
            if self._in_flight is not None or self._held:
                self._held.append(event)
                self._poll_soon()
                return
            await self._send(event)
            return
        workers, screen = len(self.workers), self.screen
        await super().on_event(event)  # a key coming back: its bindings run here
        if event is self._in_flight:
            if len(self.workers) != workers or self.screen is not screen:
                await self._settle(screen)  # it may be opening a dialog
            self._in_flight = None
            await self._release()

    async def _send(self, event: events.Key) -> None:
        self._in_flight = event
        self._since = asyncio.get_running_loop().time()
        await super().on_event(event)
        if event.is_forwarded:
            self._poll_soon()
        else:  # a priority binding took it, here and now
            await self._settle()
            self._in_flight = None

    def _poll_soon(self) -> None:
        if not self._polling:
            self._polling = True
            self.set_timer(POLL, self._poll)

    async def _poll(self) -> None:
        self._polling = False
        key = self._in_flight
        if key is not None:
            used = key._stop_propagation  # a widget used it: it will not come back
            late = asyncio.get_running_loop().time() - self._since > HOLD_LIMIT
            if not (used or late):
                self._poll_soon()
                return
            if used:
                await self._settle()
            self._in_flight = None
        await self._release()

    async def _release(self) -> None:
        """Hand on the keys that waited, one at a time."""
        held = getattr(self, "_held", None)
        while held and self._in_flight is None:
            await self._send(held.pop(0))
        if held:
            self._poll_soon()

    async def _settle(self, screen: Screen | None = None) -> None:
        """Let a binding's worker run; if it put a screen in front of
        ``screen`` (default: the one in front now), wait (briefly) until that
        screen and its focused widget are mounted."""
        screen = self.screen if screen is None else screen
        for _ in range(SETTLE_ROUNDS):
            if self.screen is not screen:
                break
            await asyncio.sleep(0)
        if self.screen is screen:
            return
        loop = asyncio.get_running_loop()
        deadline = loop.time() + HOLD_LIMIT
        while loop.time() < deadline:
            front = self.screen
            focused = front.focused
            if front.is_mounted and (focused is None or focused.is_mounted):
                return
            await asyncio.sleep(POLL)


#: a frame (s): how long a screen that put off drawing waits before it looks again
FRAME = 1 / 60
#: while a burst lasts, a screen still draws this often (s), to show progress
PROGRESS = 0.1


def draw_later(app: App, drawn_at: float, now: float) -> bool:
    """True when a screen should put off drawing: keys of a burst are still
    waiting (they will change what it shows) and it drew less than
    :data:`PROGRESS` ago. A burst of auto-repeat is then drawn once, at its
    end, plus a few times along the way."""
    return bool(getattr(app, "keys_waiting", False)) and now - drawn_at < PROGRESS

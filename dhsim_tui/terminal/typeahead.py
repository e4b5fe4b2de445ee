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

The gate must never stop listening. Its check-backs are armed on asyncio's
own clock and delivered as a message in the app's queue (not through
Textual's timers and ``call_next`` list, where a fault campaign saw one lost:
a key held 22-49 s, 40 keys behind it, the "polling" flag set and nothing
pending). A watchdog, on a task of its own, releases the keys whenever one
has been held past :data:`HOLD_LIMIT` and no check-back is pending, whatever
happened; and the quit keys (``ctrl+q``, ``ctrl+c``) never wait behind
another key.
"""

from __future__ import annotations

import asyncio

from textual import events
from textual.app import App
from textual.screen import Screen

#: rounds for the messages a key's binding posted, when it started no worker
MESSAGE_ROUNDS = 8
#: how long a waiting key checks back (s), and the longest one key may hold
#: the keys behind it (s) before they go on regardless
POLL = 0.001
HOLD_LIMIT = 0.5
#: how often the watchdog looks at the gate (s)
WATCHDOG = 0.25
#: keys that never wait behind another: quitting always works
QUIT_KEYS = frozenset({"ctrl+q", "ctrl+c"})


class KeysInOrder(App):
    """An App that hands the terminal's keys on one at a time."""

    _in_flight: events.Key | None = None
    _since = 0.0
    _held: list[events.Key]
    _settling = False
    _before: tuple[Screen, frozenset[int]]
    #: the check-back armed on asyncio's clock, or its message on its way
    _wake: asyncio.TimerHandle | None = None
    _wake_posted = False
    _watchdog: asyncio.Task | None = None
    #: how many times the watchdog had to release keys (tests, benches)
    watchdog_releases = 0

    @property
    def keys_waiting(self) -> bool:
        """More keys of a burst are still to come: a screen may put off
        drawing until they are handled (see :func:`draw_later`)."""
        return bool(getattr(self, "_held", None))

    @property
    def _polling(self) -> bool:
        """A check-back is armed or on its way."""
        return self._wake is not None or self._wake_posted

    async def on_event(self, event: events.Event) -> None:
        if not isinstance(event, events.Key):
            await super().on_event(event)
            return
        if not event.is_forwarded:  # straight from the terminal
            if not hasattr(self, "_held"):
                self._held = []
            self._start_watchdog()
            if event.key in QUIT_KEYS:  # never behind a key that may not come back
                await super().on_event(event)
                return
            if self._in_flight is not None or self._held:
                self._held.append(event)
                self._poll_soon()
                return
            await self._send(event)
            return
        if self._exit or not self.screen_stack:  # quitting: no screen is left to take it
            if event is self._in_flight:
                self._in_flight = None
            return
        await super().on_event(event)  # a key coming back: its bindings run here
        if event is self._in_flight:
            await self._handled()

    async def _send(self, event: events.Key) -> None:
        self._in_flight = event
        self._before = (self.screen, self._modal_workers())  # what the key may change
        self._since = asyncio.get_running_loop().time()
        self._settling = False
        await super().on_event(event)
        if event.is_forwarded:
            self._poll_soon()  # the app's loop must run: the binding runs there
        else:  # a priority binding took it, here and now
            await self._handled()

    async def _handled(self) -> None:
        """The key in flight was handled: let the messages its binding posted
        run for a few rounds (a table's ``enter`` posts CellSelected, whose
        handler starts a dialog worker). Unless a dialog is on its way, hand
        on the next key at once; otherwise check back until it is ready."""
        self._settling = True
        for _ in range(MESSAGE_ROUNDS):
            if self._dialog_starting() or not self._messages_waiting():
                break
            await asyncio.sleep(0)
        if self._settled():
            await self._done()
        else:
            self._poll_soon()  # the app's loop must run for the worker to go on

    def _poll_soon(self) -> None:
        """Check back in :data:`POLL` s (once: a check-back already armed or
        on its way does)."""
        if self._polling:
            return
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:  # no loop: the app is gone
            return
        self._wake = loop.call_later(POLL, self._post_poll)

    def _post_poll(self) -> None:
        """The check-back's time: run :meth:`_poll` in the app's queue."""
        self._wake = None
        self._wake_posted = self.post_message(events.Callback(callback=self._poll))

    async def _poll(self) -> None:
        self._wake_posted = False
        key = self._in_flight
        late = asyncio.get_running_loop().time() - self._since > HOLD_LIMIT
        if key is not None and not late:
            if not self._settling:
                if key._stop_propagation:  # a widget used it: it will not come back
                    await self._handled()
                else:
                    self._poll_soon()
                return
            if not self._settled():
                self._poll_soon()
                return
        await self._done()

    async def _done(self) -> None:
        self._in_flight = None
        self._settling = False
        await self._release()

    async def _release(self) -> None:
        """Hand on the keys that waited, one at a time."""
        held = getattr(self, "_held", None)
        if held and not self.screen_stack:  # quitting: no screen is left to take them
            held.clear()
        while held and self._in_flight is None:
            await self._send(held.pop(0))
        if held:
            self._poll_soon()

    # -- the watchdog ---------------------------------------------------------------
    def _start_watchdog(self) -> None:
        if self._watchdog is None or self._watchdog.done():
            self._watchdog = asyncio.get_running_loop().create_task(
                self._watch(), name="dhsim key gate watchdog"
            )

    async def _watch(self) -> None:
        """Every :data:`WATCHDOG` s: a key held past the hold limit with no
        check-back pending is a lost wake-up; release the keys behind it.
        Ends with the app."""
        while not self._exit and self.is_running:
            await asyncio.sleep(WATCHDOG)
            if self.stalled():
                self.watchdog_releases += 1
                self._wake_posted = False
                if not self.post_message(events.Callback(callback=self._done)):
                    return

    def stalled(self) -> bool:
        """A key (or keys behind one) is held past the hold limit, with no
        check-back armed: nothing would ever hand the keys on."""
        busy = self._in_flight is not None or bool(getattr(self, "_held", None))
        if not busy or self._wake is not None:
            return False
        age = asyncio.get_running_loop().time() - self._since
        return age > HOLD_LIMIT + WATCHDOG

    def _dialog_starting(self) -> bool:
        """The key put a screen in front, or started a dialog worker
        (``@work(group="modal")``) that has not finished."""
        if not self.screen_stack:  # quitting: the screens are gone, no dialog is coming
            return False
        screen, workers = self._before
        return self.screen is not screen or bool(self._modal_workers() - workers)

    def _settled(self) -> bool:
        """Nothing the key started is still on its way: no dialog is coming,
        or the one that came is mounted with its focus handled (an Input
        selects its text then), so the next key is typed into it."""
        if not self.screen_stack:  # quitting: nothing is on its way
            return True
        screen, _ = self._before
        if self.screen is screen:
            return not self._dialog_starting()
        focused = self.screen.focused
        return self.screen.is_mounted and (
            focused is None or (focused.is_mounted and focused._message_queue.empty())
        )

    def _modal_workers(self) -> frozenset[int]:
        """The dialog workers (``@work(group="modal")``) not finished yet."""
        return frozenset(
            id(worker)
            for worker in self.workers
            if worker.group == "modal" and not worker.is_finished
        )

    def _messages_waiting(self) -> bool:
        """A message waits in the focused widget or one of its ancestors up to
        the screen (where the effects of a key bubble)."""
        if not self.screen_stack:
            return False
        node = self.focused or self.screen
        while node is not None:
            if not node._message_queue.empty():
                return True
            if node is self.screen:
                return False
            node = node._parent
        return False


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

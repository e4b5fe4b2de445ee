"""What the Pilot tests share: waiting for a condition (never for a time, see
tests/waiting.py), pressing keys and waiting until the app has handled them,
and reading the composed screen. Their fresh working folder is the ``in_tmp``
fixture of tests/conftest.py."""

from __future__ import annotations

from rich.cells import get_character_cell_size
from waiting import HANG, until

__all__ = [
    "HANG",
    "dialog_workers",
    "dialogs_done",
    "drawn",
    "frames_pass",
    "keys_handled",
    "non_ascii_outside_views",
    "palette_searching",
    "press",
    "screen_quiet",
    "settled",
    "showing",
    "started",
    "until",
]


def keys_handled(app) -> bool:
    """Every key the app was sent has been handled: none waits at its key
    gate (``_held``, dhsim_tui/terminal/typeahead.py), none is in flight, and
    no message a key posted waits in the app or on the way up from the
    focused widget. True once the app is quitting (no screen takes keys)."""
    if app._exit or not app.screen_stack:
        return True
    return (
        not getattr(app, "_held", None)
        and getattr(app, "_in_flight", None) is None
        and app._message_queue.empty()
        and not (hasattr(app, "_messages_waiting") and app._messages_waiting())
    )


def drawn(screen) -> bool:
    """The screen shows its latest state: no redraw is still queued (the
    control screen's ``_dirty``, the editor's ``_redraw_pending``). A smooth
    move or a program playing queues one every frame: then it counts as drawn."""
    if getattr(screen, "moving", False):
        return True
    programs = getattr(screen, "_programs", None)
    if programs is not None and programs.playing:
        return True
    return not getattr(screen, "_dirty", False) and not getattr(screen, "_redraw_pending", False)


def dialog_workers(app) -> frozenset[int]:
    """The dialog workers (``@work(group="modal")``) not finished yet."""
    return frozenset(
        id(worker) for worker in app.workers if worker.group == "modal" and not worker.is_finished
    )


def dialogs_done(app, before: frozenset[int] = frozenset()) -> bool:
    """No dialog worker started since ``before`` (:func:`dialog_workers`) is
    still on its way: each one has finished, or waits for the answer of the
    dialog in front."""
    if app._exit or not app.screen_stack:
        return True
    waiting = any(
        callback.future is not None and not callback.future.done()
        for callback in app.screen._result_callbacks
    )
    return waiting or not (dialog_workers(app) - before)


def screen_quiet(app) -> bool:
    """Nothing the screen in front put off until after its refresh is still
    to run: a footer recomposed because the keys changed (it is empty for a
    moment, then whole), a callback after the refresh."""
    from textual.widgets import Footer

    if app._exit or not app.screen_stack:
        return True
    screen = app.screen
    return (
        not app._batch_count
        and not screen._callbacks
        and not screen._next_callbacks
        and all(footer._message_queue.empty() for footer in screen.query(Footer))
    )


def settled(app, before: frozenset[int] = frozenset()) -> bool:
    """Every key handled (:func:`keys_handled`), what they started in a dialog
    worker done (:func:`dialogs_done`; ``before``: the dialog workers already
    under way, see :func:`dialog_workers`), every screen drawn (:func:`drawn`)
    and the one in front quiet (:func:`screen_quiet`)."""
    if app._exit:
        return True
    return (
        keys_handled(app)
        and dialogs_done(app, before)
        and all(drawn(screen) for screen in app.screen_stack)
        and screen_quiet(app)
    )


def palette_searching(app) -> bool:
    """The command palette is still gathering commands (a worker of its own;
    it shows what it found so far now and then, in any order)."""
    from textual.command import CommandPalette

    group = CommandPalette._GATHER_COMMANDS_GROUP
    return any(worker.group == group and not worker.is_finished for worker in app.workers)


async def press(pilot, *keys: str) -> None:
    """``pilot.press(*keys)``, then wait until the app has handled them, what
    they started in a dialog worker is done (or waits for an answer) and what
    they changed is drawn. Pilot's own wait guesses from CPU time whether the
    app is idle, which a loaded machine fools."""
    app = pilot.app
    before = dialog_workers(app)
    await pilot.press(*keys)
    await until(pilot, lambda: settled(app, before), f"the keys {keys} handled and drawn")


async def frames_pass(pilot, count: int) -> None:
    """Let the app run until a timer of its own at 30 Hz (a smooth move's,
    a program's) has fired ``count`` times: to show that nothing moves once
    it is stopped, in ticks the app actually ran rather than in seconds."""
    fired = []
    timer = pilot.app.set_interval(1 / 30, lambda: fired.append(None))
    try:
        await until(pilot, lambda: len(fired) >= count, f"{count} ticks of a 30 Hz timer")
    finally:
        timer.stop()


async def started(pilot) -> None:
    """The app is up: its screen in front is mounted (the simulator's and the
    editor's say ``_ready``), and whatever it started with is handled and drawn."""
    app = pilot.app

    def up() -> bool:
        if not app.screen_stack:
            return False
        screen = app.screen
        return screen.is_mounted and getattr(screen, "_ready", True) and settled(app)

    await until(pilot, up, "the app to start")


async def showing(pilot, kind: type) -> bool:
    """True once a ``kind`` screen is in front (waiting for it, see :func:`until`)."""
    await until(pilot, lambda: isinstance(pilot.app.screen, kind), kind.__name__)
    return True


def non_ascii_outside_views(app) -> list[str]:
    """Non-ASCII cells on the composed screen, except in the arm views."""
    views = [
        view.region for screen in app.screen_stack for view in screen.query(".view") if view.region
    ]
    found = []
    for y, strip in enumerate(app.screen._compositor.render_strips()):
        x = 0
        for char in strip.text:
            if not char.isascii() and not any(r.contains(x, y) for r in views):
                found.append(f"{char!r} at {x},{y}")
            x += get_character_cell_size(char)
    return found

"""What the Pilot tests of the dialogs share: waiting for a worker's dialog
(or what follows its last answer) to land, and reading the composed screen.
Their fresh working folder is the ``in_tmp`` fixture of tests/conftest.py."""

from __future__ import annotations

from rich.cells import get_character_cell_size


async def until(pilot, condition, what: str = "") -> None:
    """Wait (up to 3 s) until ``condition()`` holds: a dialog a worker opens,
    or what it does after the last answer, lands a few message rounds after
    the key (later under load)."""
    for _ in range(150):
        await pilot.pause()
        if condition():
            return
        await pilot.pause(0.02)
    raise AssertionError(f"timed out waiting for {what or condition}")


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

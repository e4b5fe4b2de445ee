"""What the Pilot tests of the dialogs share: waiting for a worker's dialog
(or what follows its last answer) to land. Their fresh working folder is the
``in_tmp`` fixture of tests/conftest.py."""

from __future__ import annotations


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

"""How the tests wait: for a condition, never for a time.

A test that waits for something to happen polls for it; the one timeout,
:data:`HANG`, exists only to turn a hang into a failure with a message. It is
generous on purpose: on a busy machine everything is slower, and a slow
machine must not fail a test. No test compares a duration with a budget;
speed targets live in ``bench/`` (figures in ``docs/performance.md``).

``DHSIM_TEST_HANG`` (seconds) overrides it, e.g. to find a hang quickly.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable

#: the one timeout (s): how long any test waits before it calls a thing hung
HANG = float(os.environ.get("DHSIM_TEST_HANG", "60"))
#: how often a waiting test looks again (s)
POLL = 0.01


def _describe(what: object) -> str:
    return str(what) if what else "a condition"


async def until(pilot, condition: Callable[[], object], what: str = "") -> None:
    """Let the app run until ``condition()`` holds (a dialog a worker opens,
    a redraw behind a burst of keys, ...). Fails only after :data:`HANG`."""
    deadline = time.monotonic() + HANG
    while True:
        await pilot.pause()
        if condition():
            return
        if time.monotonic() > deadline:
            raise AssertionError(f"hung: waited {HANG:g} s for {_describe(what or condition)}")
        await pilot.pause(POLL)


def wait_until(condition: Callable[[], object], what: str = "") -> None:
    """The same for a test outside an app: a file, a process, a thread."""
    deadline = time.monotonic() + HANG
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(f"hung: waited {HANG:g} s for {_describe(what or condition)}")
        time.sleep(POLL)

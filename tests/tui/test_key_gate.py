"""The key gate never stops listening (dhsim_tui/terminal/typeahead.py).

A fault campaign saw a key held in the gate for 22-49 s with 40 keys behind
it: the gate's check-back was lost, and escape, q and ctrl+q did nothing
until a signal ended dhsim. These tests lose the check-back on purpose (every
way it may be delivered: Textual's ``call_next``, a message in the app's
queue) and check that the keys behind still arrive and that quitting works.
"""

from __future__ import annotations

from textual import events
from waiting import until

from dhsim_tui.core import load_robot
from dhsim_tui.terminal import typeahead
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen


def burst(app: DhsimApp, *keys: str) -> None:
    """Post every key at once, as one read from the terminal would."""
    for key in keys:
        app.post_message(events.Key(key, None))


def lose_check_backs(monkeypatch, app: DhsimApp, count: int | None) -> list[int]:
    """The gate's next ``count`` check-backs (None: every one) vanish on
    their way, as the campaign's did, whichever way they travel."""
    lost = [0]

    def is_check_back(callback) -> bool:
        target = getattr(callback, "func", callback)
        return getattr(target, "__name__", "") == "_poll"

    def losing(original):
        def deliver(thing, *args, **kwargs):
            callback = getattr(thing, "callback", thing)
            if is_check_back(callback) and (count is None or lost[0] < count):
                lost[0] += 1
                return True  # "posted": and never seen again
            return original(thing, *args, **kwargs)

        return deliver

    monkeypatch.setattr(app, "call_next", losing(app.call_next))
    monkeypatch.setattr(app, "post_message", losing(app.post_message))
    return lost


async def test_keys_behind_a_lost_check_back_still_arrive(monkeypatch):
    """``P`` opens a dialog: the gate checks back until it is ready, and the
    name typed behind it waits. Every check-back is lost here; the watchdog
    hands the keys on after the hold limit."""
    app = DhsimApp(load_robot("puma560")[0], animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, ControlScreen) and app.screen.is_mounted)
        lost = lose_check_backs(monkeypatch, app, count=None)
        burst(app, "right", "P", "z", "enter")
        await until(pilot, lambda: "z" in app.robot.pose_names, "the pose named z")
        assert lost[0] >= 1  # the fault happened, and the gate got over it
        assert app.watchdog_releases >= 1
        await until(pilot, lambda: not app.keys_waiting and app._in_flight is None, "the gate")


async def test_ctrl_q_quits_while_a_key_never_comes_back(monkeypatch):
    """No watchdog here: quitting must not depend on it."""
    monkeypatch.setattr(typeahead.KeysInOrder, "_start_watchdog", lambda self: None, raising=False)
    app = DhsimApp(load_robot("puma560")[0], animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, ControlScreen) and app.screen.is_mounted)
        lose_check_backs(monkeypatch, app, count=None)  # the gate is stuck for good
        burst(app, "P", "z", "ctrl+q")  # P: a dialog the gate waits for, in vain
        await until(pilot, lambda: app._exit, "dhsim to quit")
    assert app.return_code in (0, None)


async def test_the_watchdog_leaves_a_gate_that_works_alone():
    """With nothing lost, the watchdog has nothing to do."""
    app = DhsimApp(load_robot("puma560")[0], animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: isinstance(app.screen, ControlScreen) and app.screen.is_mounted)
        screen = app.screen
        burst(app, *["right"] * 20)
        await until(pilot, lambda: screen.q[0] == 20.0, "twenty steps")
        assert app.watchdog_releases == 0

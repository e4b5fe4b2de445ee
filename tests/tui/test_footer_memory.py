"""The footer keeps no memory per mode switch.

Textual 8.2.8's footer recomposes on every change of focus, and each key it
composed stayed alive for good (data-bound to the footer's ``compact``, held
by the watcher's closure): 0.3–0.65 MB per ``c`` or ``g``
(docs/upstream/textual-footer-leak.md). dhsim's :class:`KeysFooter` lets go of
them. Memory is measured here by counting live objects after a collection,
not by RSS or time: a leak of widgets shows up exactly, on any machine.
"""

from __future__ import annotations

import gc

from pilot_helpers import settled, started, until
from textual.widget import Widget
from textual.widgets._footer import FooterKey

from dhsim_tui.core import load_robot
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.widgets.footer import KeysFooter

#: mode switches in all (``c`` and ``g`` presses)
SWITCHES = 200
#: the switches before the first count: the footer has shown every mode once
WARM_UP = 8
#: how many more live objects than after the warm-up still count as no leak
#: (a footer's worth of keys is 10-12; a leak adds that per switch)
SLACK = 6

#: one round: Cartesian, back to the joints, the program panel, back again
ROUND = ("c", "c", "g", "g")


def live() -> tuple[int, int]:
    """Live ``FooterKey`` and ``Widget`` objects, after a full collection."""
    gc.collect()
    keys = widgets = 0
    for thing in gc.get_objects():
        if isinstance(thing, Widget):
            widgets += 1
            keys += isinstance(thing, FooterKey)
    return keys, widgets


def footer_labels(app: DhsimApp) -> set[str]:
    return {key.description for key in app.screen.query(FooterKey)}


def mode(app: DhsimApp) -> str:
    screen = app.screen
    assert isinstance(screen, ControlScreen)
    if screen.focused is screen._program_panel:
        return "program"
    return "cartesian" if screen.cartesian else "joints"


async def switch(pilot, key: str) -> None:
    """Press ``key`` and wait until the mode has switched, the footer shows
    the keys of the new mode (its ``c`` names the other one) and the app has
    settled (the footer's recompose done)."""
    app = pilot.app
    was = mode(app)

    def switched() -> bool:
        now = mode(app)
        other = "Joints" if now == "cartesian" else "Cartesian"
        return now != was and other in footer_labels(app) and settled(app)

    await pilot.press(key)
    await until(pilot, switched, f"{key} to switch from {was} and the footer to follow")


async def test_mode_switches_leave_no_footer_keys_or_widgets_behind():
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, "plotext", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert isinstance(app.screen.query_one(KeysFooter), KeysFooter)
        for n in range(WARM_UP):
            await switch(pilot, ROUND[n % len(ROUND)])
        keys_before, widgets_before = live()
        for n in range(WARM_UP, SWITCHES):
            await switch(pilot, ROUND[n % len(ROUND)])
        keys_after, widgets_after = live()
        shown = len(app.screen.query(FooterKey))
        assert keys_after <= keys_before + SLACK, (
            f"{keys_after - keys_before} more FooterKeys alive after "
            f"{SWITCHES - WARM_UP} mode switches ({shown} shown)"
        )
        assert widgets_after <= widgets_before + SLACK, (
            f"{widgets_after - widgets_before} more widgets alive after "
            f"{SWITCHES - WARM_UP} mode switches"
        )
        # the keys alive are about the ones the footer shows
        assert keys_after <= shown + SLACK


async def test_trips_to_the_editor_leave_no_views_panels_behind():
    """The views panel followed the app's theme with a watcher on the app,
    which kept every panel (and its screen) alive after it was removed: two
    a trip to the editor and back. It follows the theme's signal now."""
    from dhsim_tui.tui.screens.editor import EditorScreen
    from dhsim_tui.tui.widgets.views_panel import ViewsPanel

    def panels() -> int:
        gc.collect()
        return sum(isinstance(thing, ViewsPanel) for thing in gc.get_objects())

    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, "plotext", animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)

        async def trip() -> None:
            await pilot.press("e")
            await until(pilot, lambda: isinstance(app.screen, EditorScreen) and settled(app))
            await pilot.press("escape")
            await until(pilot, lambda: isinstance(app.screen, ControlScreen) and settled(app))

        for _ in range(2):
            await trip()
        before = panels()
        for _ in range(8):
            await trip()
        assert panels() <= before, f"{panels() - before} more views panels alive after 8 trips"

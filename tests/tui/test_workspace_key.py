"""W: the workspace cloud, sampled in a worker and shown faintly behind the
arm in every view; W again takes it away. Keys go on while it is sampled."""

from __future__ import annotations

import threading

import numpy as np
from pilot_helpers import HANG, press, started, until

from dhsim_tui.core import load_robot
from dhsim_tui.core.analysis import workspace
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control_jobs import CLOUD_POINTS
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.screens.palette import commands_for
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel
from dhsim_tui.tui.widgets.views_panel import ViewsPanel


def puma_app(ascii: bool = False) -> DhsimApp:
    robot, path = load_robot("puma560")
    return DhsimApp(robot, path, animate=False, ascii=ascii)


class Gate:
    """position_chunks held at a gate: the sampling takes as long as the test says,
    however long its keys take on a busy machine."""

    def __init__(self, monkeypatch) -> None:
        self.open = threading.Event()
        self.calls = 0
        real = workspace.position_chunks

        def held(*args, **kwargs):
            self.calls += 1
            for chunk in real(*args, **kwargs):
                self.open.wait(HANG)  # (HANG: only a test that failed leaves it shut)
                yield chunk

        monkeypatch.setattr(workspace, "position_chunks", held)


async def test_w_shows_and_hides_the_workspace_cloud(status):
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        views = screen.query_one(ViewsPanel)
        assert views.cloud is None and screen.cloud_state == "off"
        await press(pilot, "W")
        await until(pilot, lambda: screen.cloud_state == "on", "the cloud")
        await pilot.pause()
        assert views.cloud is not None and views.cloud.shape == (CLOUD_POINTS, 3)
        assert "workspace" in status(app)
        # every point is a position the tool reaches, within the reach of frame 0
        base = app.robot.kinematics.frames(app.robot.home)[0][:3, 3]
        distances = np.linalg.norm(views.cloud - base, axis=1)
        assert distances.max() <= workspace.reach(app.robot) * (1 + 1e-9)
        await press(pilot, "W")
        await pilot.pause()
        assert views.cloud is None and screen.cloud_state == "off"
        assert "workspace cloud off" in status(app)


async def test_keys_go_on_while_the_cloud_is_sampled(monkeypatch, status):
    gate = Gate(monkeypatch)
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        views = screen.query_one(ViewsPanel)
        home = screen.q
        await press(pilot, "W")
        await until(pilot, lambda: screen.cloud_state == "computing", "the sampling")
        assert "sampling the workspace" in status(app)
        await press(pilot, "right", "3", "v")  # a joint step, the side view, a read-out
        await pilot.pause()
        assert (
            screen.q != home
            and screen.query_one(ViewsPanel).selected == 2
            and screen.readout == "rpy"
        )
        assert views.cloud is None and screen.cloud_state == "computing"
        gate.open.set()
        await until(pilot, lambda: screen.cloud_state == "on", "the cloud")
        await pilot.pause()
        assert views.cloud is not None
        await press(pilot, "W", "W")  # off, and on again: the points were kept
        await pilot.pause()
        assert screen.cloud_state == "on" and views.cloud is not None and gate.calls == 1


async def test_w_again_while_sampling_never_shows_the_cloud(monkeypatch):
    gate = Gate(monkeypatch)
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        views = screen.query_one(ViewsPanel)
        await press(pilot, "W")
        await until(pilot, lambda: screen.cloud_state == "computing", "the sampling")
        await press(pilot, "W")
        await pilot.pause()
        assert screen.cloud_state == "off"
        gate.open.set()
        await until(
            pilot,
            lambda: not any(w.group == "workspace" and not w.is_finished for w in app.workers),
            "the worker to stop",
        )
        await pilot.pause()
        assert views.cloud is None and screen.cloud_state == "off"


async def test_the_palette_shows_and_hides_the_workspace(status):
    app = puma_app(ascii=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        views = screen.query_one(ViewsPanel)
        titles = [c.title for c in commands_for(app, screen)]
        assert "View: show the workspace" in titles and "View: hide the workspace" not in titles
        next(c for c in commands_for(app, screen) if c.title == "View: show the workspace").run()
        await until(pilot, lambda: screen.cloud_state == "on", "the cloud")
        await pilot.pause()
        assert views.cloud is not None and status(app).isascii()
        next(c for c in commands_for(app, screen) if c.title == "View: hide the workspace").run()
        await pilot.pause()
        assert views.cloud is None


async def test_w_b_and_f_are_in_the_help_and_have_tooltips():
    app = puma_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        keys = {b.key: b for b in [*screen.BINDINGS, *CartesianPanel.BINDINGS]}
        for key in ("W", "b", "f"):
            assert keys[key].id and keys[key].tooltip
        await press(pilot, "question_mark")
        await pilot.pause()
        assert isinstance(app.screen, HelpScreen)
        rows = dict(app.screen._rows)
        assert "workspace" in rows["W"] and "IK branch" in rows["b"] and "tool" in rows["f"]

"""A long program is sampled in a thread (issue 26): the screen answers
keys meanwhile, a bar shows how far it is, the program plays as soon as
its first seconds are there, and escape stops it."""

from __future__ import annotations

import threading
from dataclasses import replace

import pytest
from pilot_helpers import press, started, until
from waiting import HANG

from dhsim_tui.core import load_robot
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.motion.trajectory import Sampling
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens import control_program
from dhsim_tui.tui.widgets.program_panel import ProgramPanel

pytestmark = pytest.mark.usefixtures("in_tmp")

QN = (0.0, 45.0, -180.0, 0.0, 45.0, 0.0)
#: to the nominal pose, a linear move of about 165 s (16,500 IK solves), back
LONG = Program(
    "long",
    (Step("joint", QN), Step("linear", (0, 45, -135, 0, 45, 0), speed=2.0), Step("joint", QN)),
)


class Gate:
    """Holds the sampling thread once it has made ``seconds`` of the program,
    until :meth:`open`: what the screen does meanwhile is then certain,
    however fast or slow the machine."""

    def __init__(self, seconds: float) -> None:
        self.seconds = seconds
        self.opened = threading.Event()
        self.holding = threading.Event()

    def open(self) -> None:
        self.opened.set()

    def sampling_class(self):
        gate = self

        class Gated(Sampling):
            def advance(self) -> bool:
                if self.ready >= gate.seconds and not gate.opened.is_set():
                    gate.holding.set()
                    gate.opened.wait(HANG)
                return super().advance()

        return Gated


@pytest.fixture
def gate(monkeypatch):
    """A :class:`Gate` in place of the player's Sampling (opened at the end,
    whatever happened)."""
    made = Gate(seconds=5.0)
    monkeypatch.setattr(control_program, "Sampling", made.sampling_class())
    yield made
    made.open()


def robot():
    return replace(load_robot("puma560")[0], programs=(LONG,))


async def test_a_long_program_plays_while_the_rest_is_sampled(monkeypatch, gate, status):
    monkeypatch.setattr(control_program, "monotonic", lambda: 0.0)  # the clock stands still
    app = DhsimApp(robot(), animate=False)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        player = screen._programs
        await press(pilot, "g", "space")
        await until(pilot, lambda: player.playing, "playing the first seconds")
        assert player.sampling and not player.playback.trajectory.complete
        assert "sampling the rest" in status(app)
        panel = screen.query_one(ProgramPanel)
        assert "esc stops" in str(panel.border_subtitle)
        await until(pilot, gate.holding.is_set, "the sampling held at 5 s")
        # the keys are answered meanwhile
        await press(pilot, "space")
        assert "paused" in status(app) and not player.playing and player.sampling
        gate.open()
        await until(pilot, lambda: not player.sampling, "the whole program sampled")
        trajectory = player.playback.trajectory
        assert trajectory.complete and len(trajectory.spans) == 3
        assert "sampling" not in str(panel.border_subtitle)


async def test_escape_stops_the_sampling_and_the_path_goes(gate, status):
    app = DhsimApp(robot(), animate=False)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        player = screen._programs
        await press(pilot, "g", "space")
        await until(pilot, gate.holding.is_set, "the sampling held")
        assert player.sampling
        assert "esc stops" in str(screen.query_one(ProgramPanel).border_subtitle)
        await press(pilot, "escape")
        assert not player.sampling and not player.playing and player.playback is None
        assert "stopped sampling long" in status(app)
        gate.open()  # the thread ends without a word
        await until(
            pilot,
            lambda: not any(w.group == "sampling" and not w.is_finished for w in app.workers),
            "the thread's end",
        )
        assert player.playback is None and "stopped sampling long" in status(app)


async def test_n_on_a_program_not_yet_sampled_jumps_once_it_is(status):
    to_limit = Program("edge", (Step("joint", (160.0, 0, 0, 0, 0, 0)), Step("wait", seconds=0.2)))
    app = DhsimApp(replace(load_robot("puma560")[0], programs=(to_limit,)), animate=False)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        await press(pilot, "g", "n")
        await until(pilot, lambda: "Th1" in status(app), "the first problem said")
        assert screen._programs.playback.trajectory.complete
        assert abs(screen.q[0] - 160.0) < 1e-6


async def test_a_program_over_the_hour_from_where_the_arm_is_is_refused_before_sampling(status):
    # from home the move takes no time; from where the arm is jogged to, the
    # hour is passed: refused in closed form, naming the step
    back = Program(
        "back", (Step("joint", (0, 0, 0, 0, 0, 0), speed=0.01), Step("wait", seconds=3599.0))
    )
    app = DhsimApp(replace(load_robot("puma560")[0], programs=(back,)), animate=False)
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        screen = pilot.app.screen
        await press(pilot, "right", "right", "right")
        assert screen.q[0] != 0.0
        await press(pilot, "g", "space")
        assert "step 2" in status(app) and "at most 3600 s" in status(app)
        assert not screen._programs.sampling and screen._programs.playback is None

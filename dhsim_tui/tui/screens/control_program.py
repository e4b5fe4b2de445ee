"""The simulator's programs: record a step (``R``), change the steps (the
program panel's keys), play them in the views (``space``), seek a step or
the next problem.

:class:`ProgramPlayer` is the control screen's, made with it and told what
it may use (:class:`Host`): the robot and the joints, the status line and
the app's ``keep_robot``. The numbers are the core's: the program's edits
(:mod:`dhsim_tui.core.model.program`), its samples and path check
(:mod:`dhsim_tui.core.motion.trajectory`, :mod:`~dhsim_tui.core.motion.path_check`)
and where the arm is at a time (:mod:`~dhsim_tui.core.motion.playback`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from time import monotonic
from typing import Protocol

import numpy as np
from textual.timer import Timer
from textual.worker import Worker, get_current_worker

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.program import (
    Program,
    Step,
    moved_step,
    new_program_name,
    toggled_step,
    with_changed_step,
    with_program,
    with_step,
    without_step,
)
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import counted
from dhsim_tui.core.motion.path_check import check_path
from dhsim_tui.core.motion.playback import Playback
from dhsim_tui.core.motion.trajectory import Sampling, Trajectory
from dhsim_tui.tui.flows.program_steps import (
    ask_program_name,
    ask_speed,
    ask_target,
    ask_wait,
)
from dhsim_tui.tui.flows.values import shorten_path_in
from dhsim_tui.tui.screens.program_plot import ProgramPlot
from dhsim_tui.tui.widgets.joint_row import ascii_mode
from dhsim_tui.tui.widgets.program_panel import ProgramPanel

#: how many samples a second a program is played from
PLAY_RATE = 100.0
#: how often the views follow a program playing (s)
PLAY_FRAME = 1 / 30
#: the playback speeds [ and ] choose from (1: real time)
SPEEDS = (0.25, 0.5, 1.0, 2.0, 4.0)
#: the most points the tool's path is drawn with
TRAIL_POINTS = 400
NO_PROGRAM = "no program to play: R records the current pose as a step"
#: a program starts playing once this much of it is sampled (s of program time)
PLAY_AHEAD = 2.0
#: how often the sampling's progress is shown (s)
PROGRESS_EVERY = 0.1
#: the progress bar's width (cells)
BAR_WIDTH = 6


class Host(Protocol):
    """What the player uses of its screen."""

    robot: Robot
    q: tuple[float, ...]
    app: object

    def say(self, message: str, error: bool = False) -> None: ...
    def set_interval(self, interval: float, callback) -> Timer: ...
    def run_worker(self, work, **kwargs) -> Worker: ...
    def refresh_bindings(self) -> None: ...
    def stop_moving(self) -> None: ...
    def refresh_views(self) -> None: ...


class ProgramPlayer:
    """A robot's program as the simulator records, changes and plays it."""

    def __init__(self, host: Host, panel: ProgramPanel) -> None:
        self.host = host
        self.panel = panel
        robot = host.robot
        self.name = robot.programs[0].name if robot.programs else "program1"
        # the programs, and the one shown, before each change
        self._undo: list[tuple[tuple[Program, ...], str]] = []
        self.playback: Playback | None = None
        self._timer: Timer | None = None
        self._from = (0.0, 0.0)  # (monotonic time, time played) when play last began
        self.speed = 1.0  # times real time
        self.record_move = "joint"  # what R records: "joint" or "linear" (L)
        self._sampler: Worker | None = None  # the program being sampled, in a thread
        self._progress = 0.0  # its share sampled so far
        self._planned = 0.0  # its duration, in closed form
        self._then: Callable[[], None] | None = None  # what to do once it is all sampled
        self._play_when_ready = False  # space came while it was being sampled
        panel.show(self.program())

    @property
    def playing(self) -> bool:
        return self._timer is not None

    @property
    def sampling(self) -> bool:
        """The program is being sampled (in a thread)."""
        return self._sampler is not None

    @property
    def trail(self) -> np.ndarray | None:
        """The tool's path of the program sampled (at most :data:`TRAIL_POINTS`
        points), for the views; None when there is none."""
        if self.playback is None:
            return None
        xyz = self.playback.trajectory.xyz
        every = max(1, -(-len(xyz) // TRAIL_POINTS))
        return np.vstack([xyz[::every], xyz[-1:]])

    def program(self) -> Program | None:
        robot = self.host.robot
        return robot.program(self.name) if self.name in robot.program_names else None

    # -- changes ---------------------------------------------------------------------
    def record(self, insert: bool = False) -> None:
        """R: the current pose as a joint (or, after ``L``, a linear) move at
        the end of the program; ``insert`` (I in the panel): after the
        selected step."""
        program = self.program() or Program(self.name)
        at = self.panel.selected if insert and program.steps else None
        step = Step(self.record_move, tuple(round(v, 6) for v in self.host.q))
        other = "joint" if step.move == "linear" else "linear"
        number = at + 2 if at is not None else len(program.steps) + 1
        total = len(program.steps) + 1
        done = (
            f"recorded step {number} of {total} in {program.name}: a {step.move} move"
            f" (L: record {other} moves)"
        )
        if self._set(with_step(program, step, at), done):
            self.panel.selected = number - 1

    def toggle_record_move(self) -> None:
        """L: R records linear moves from now on, or joint moves again."""
        self.record_move = "linear" if self.record_move == "joint" else "joint"
        self.panel.record_move = self.record_move
        self.host.say(f"R records {self.record_move} moves from now on")

    def change(self, change: str, index: int) -> None:
        """The program panel's ``kind``, ``delete``, ``up``, ``down``,
        ``undo``, ``insert``, ``wait``, ``speed``, ``target``, ``rename``,
        ``new`` or ``next_program``."""
        if change == "undo":
            if not self._undo:
                self.host.say("nothing to undo in the program", error=True)
                return
            programs, self.name = self._undo.pop()
            self._keep(replace(self.host.robot, programs=programs), "undid the last change")
            return
        if change == "insert":
            self.record(insert=True)
            return
        if change == "new":
            self._new_program()
            return
        if change == "next_program":
            self._next_program()
            return
        program = self.program()
        if change == "wait":
            self._ask(self._add_wait(program or Program(self.name), index))
            return
        if change == "rename":
            if program is None:
                self.host.say(f"{self.name} has no steps yet: R records one", error=True)
                return
            self._ask(self._rename(program))
            return
        if program is None or not program.steps:
            self.host.say("the program has no steps: R records one", error=True)
            return
        if change == "kind":
            changed = toggled_step(program, index)
            self._set(changed, f"step {index + 1}: a {changed.steps[index].move} move")
        elif change == "delete":
            self._set(without_step(program, index), f"step {index + 1} deleted")
        elif change == "speed":
            self._ask(self._change_step(program, index, "speed"))
        elif change == "target":
            self._ask(self._change_step(program, index, "target"))
        else:
            delta = -1 if change == "up" else 1
            if self._set(moved_step(program, index, delta), f"step {index + 1} moved"):
                self.panel.selected = min(max(index + delta, 0), len(program.steps) - 1)

    # -- the panel's questions (dialogs, in a worker) ---------------------------------
    def _ask(self, flow) -> None:
        self.pause()
        self.host.run_worker(flow, group="modal", exclusive=True)

    def _fits(self, change) -> Callable[[Step], object]:
        """A dialog's check that the program with ``change(step)`` makes a
        valid robot (raises what the core says; the dialog shows it)."""
        return lambda step: replace(
            self.host.robot, programs=with_program(self.host.robot.programs, change(step))
        )

    async def _add_wait(self, program: Program, index: int) -> None:
        at = index if program.steps else None
        seconds = await ask_wait(
            self.host.app, fits=self._fits(lambda step: with_step(program, step, at))
        )
        if seconds is None:
            return
        number = (at + 2) if at is not None else 1
        step = Step("wait", seconds=seconds)
        if self._set(with_step(program, step, at), f"step {number}: {step.describe()}"):
            self.panel.selected = number - 1

    async def _change_step(self, program: Program, index: int, what: str) -> None:
        app, robot = self.host.app, self.host.robot
        fits = self._fits(lambda step: with_changed_step(program, index, step))
        if what == "speed" or program.steps[index].is_wait:  # a wait's number: its seconds
            step = await ask_speed(app, robot, program.steps[index], fits)
        else:
            step = await ask_target(app, robot, program, index, fits)
        if step is not None:
            changed = with_changed_step(program, index, step)
            self._set(changed, f"step {index + 1}: {step.describe()}")

    async def _rename(self, program: Program) -> None:
        robot = self.host.robot
        programs = await ask_program_name(self.host.app, robot, program.name)
        if programs is None:
            return
        new = next(p.name for p, old in zip(programs, robot.programs, strict=True) if p is not old)
        self._set_programs(programs, f"program {program.name} is now {new}", name=new)

    def _new_program(self) -> None:
        name = new_program_name(self.host.robot.programs)
        self._set_programs(
            with_program(self.host.robot.programs, Program(name)),
            f"new program {name}: R records its first step",
            name=name,
        )
        self.panel.selected = 0

    def _next_program(self) -> None:
        names = self.host.robot.program_names
        if not names or (len(names) == 1 and names[0] == self.name):
            self.host.say("there is no other program: N starts a new one", error=True)
            return
        at = names.index(self.name) if self.name in names else -1
        self.name = names[(at + 1) % len(names)]
        self.pause()
        self._stop_sampling()
        had_path = self.playback is not None
        self.playback = None
        self.panel.selected = 0
        self.panel.show(self.program())
        self._show()
        self.host.say(f"program {self.name} ({names.index(self.name) + 1} of {len(names)})")
        if had_path:
            self.host.refresh_views()

    def _set(self, program: Program, message: str) -> bool:
        """The robot with ``program`` (the core checks it), kept as poses are."""
        return self._set_programs(with_program(self.host.robot.programs, program), message)

    def _set_programs(
        self, programs: tuple[Program, ...], message: str, name: str | None = None
    ) -> bool:
        """The robot with ``programs`` (checked by the core; undone by ctrl+z),
        showing program ``name`` from now on when given."""
        robot = self.host.robot
        try:
            changed = replace(robot, programs=programs)
        except DhsimError as exc:
            self.host.say(str(exc), error=True)
            return False
        self._undo.append((robot.programs, self.name))
        if name is not None:
            self.name = name
        self._keep(changed, message)
        return True

    def _keep(self, robot: Robot, message: str) -> None:
        """Its file saved (or kept until quit for a bundled robot), as P does."""
        self.pause()
        self._stop_sampling()
        had_path = self.playback is not None
        self.playback = None
        self.host.robot = robot
        app = self.host.app
        try:
            saved_to = app.keep_robot(robot)  # type: ignore[attr-defined]
        except DhsimError as exc:
            reason = shorten_path_in(str(exc), app.robot_path)  # type: ignore[attr-defined]
            self.host.say(f"{message}; not saved: {reason} (kept in memory)", error=True)
        else:
            where = "" if saved_to else " (kept until you quit: e, ctrl+s saves)"
            self.host.say(message + where)
        self.panel.show(self.program())
        self.host.refresh_bindings()
        if had_path:
            self.host.refresh_views()  # the old path goes

    # -- playing -----------------------------------------------------------------------
    def toggle(self) -> None:
        """space: play from the start (or on from a pause); again: pause.
        A program is played as soon as its first seconds are sampled."""
        if self.playing:
            self.pause()
            self.host.say(f"paused at {self.playback.time:.2f} s (space goes on)")
            return
        if self.sampling and self.playback is None:
            self._play_when_ready = not self._play_when_ready
            self._show()
            return
        if self.playback is not None and self.playback.done:
            self.playback = None
        if self.playback is None:
            self._play_when_ready = True
            self._sample()
            return
        self._play()

    def _play(self) -> None:
        self._play_when_ready = False
        self.host.stop_moving()
        problems = self.playback.problems
        found = (
            f"; {counted(len(problems), 'problem')} (n: the next)"
            if problems
            else "; the path check found no problem"
        )
        duration = self.playback.duration
        if not self.playback.trajectory.complete:
            found = f"; sampling the rest ({self._percent()} done)"
            duration = self._planned
        self.host.say(f"playing {self.name}: {duration:.2f} s{found}", error=bool(problems))
        self._start()

    def pause(self) -> bool:
        """Stop where it is; True if it was playing."""
        if self._timer is None:
            return False
        self._timer.stop()
        self._timer = None
        return True

    def _ready(self, then: Callable[[], None], what: str) -> bool:
        """The whole program sampled (from where the arm is) and checked: True;
        else it is sampled (in a thread), ``then`` runs when it is, and the
        status line says ``what`` will happen then."""
        if self.playback is not None and self.playback.trajectory.complete:
            return True
        self._then = then
        self._sample()
        if self.sampling:
            self.host.say(f"sampling {self.name} ({self._percent()} done): {what} then")
        return False

    # -- sampling, in a thread ---------------------------------------------------------
    def _sample(self) -> None:
        """Start sampling the program, unless it is under way."""
        if self.sampling:
            self._show()
            return
        program = self.program()
        if program is None or not program.steps:
            self._then = None
            self._play_when_ready = False
            self.host.say(NO_PROGRAM, error=True)
            return
        try:  # the program's length, in closed form: refused before any sample
            sampling = Sampling(self.host.robot, program, PLAY_RATE, start=self.host.q)
        except DhsimError as exc:
            self._then = None
            self._play_when_ready = False
            self.host.say(str(exc), error=True)
            return
        self._progress = 0.0
        self._planned = sampling.planned
        self._sampler = self.host.run_worker(
            lambda: self._sample_in_thread(sampling),
            thread=True,
            group="sampling",
            exit_on_error=False,
        )
        self._show()

    def _sample_in_thread(self, sampling: Sampling) -> None:
        """The worker: piece after piece; the progress shown now and then, the
        samples handed over when the first seconds are there, then each time
        they double (so the work of handing over stays a share of the whole),
        and at the end."""
        worker = get_current_worker()
        call = self.host.app.call_from_thread  # type: ignore[attr-defined]
        shown = monotonic()
        handed = 0.0
        try:
            while sampling.advance():
                if worker.is_cancelled:
                    return
                if monotonic() - shown >= PROGRESS_EVERY:
                    shown = monotonic()
                    call(self._sampled, worker, sampling.progress, None)
                ahead = min(PLAY_AHEAD, sampling.planned)
                if sampling.ready >= max(ahead, 2 * handed) and sampling.ready > handed:
                    handed = sampling.ready
                    trajectory = sampling.trajectory()
                    call(self._sampled, worker, sampling.progress, self._checked(trajectory))
            if not worker.is_cancelled:
                trajectory = sampling.trajectory()
                call(self._sampled, worker, 1.0, self._checked(trajectory))
        except DhsimError as exc:
            if not worker.is_cancelled:
                call(self._failed, worker, str(exc))

    @staticmethod
    def _checked(trajectory: Trajectory) -> Playback:
        return Playback(trajectory, check_path(trajectory))

    def _sampled(self, worker: Worker, progress: float, playback: Playback | None) -> None:
        """From the worker: how far it is, and (now and then) the samples so far."""
        if worker is not self._sampler:
            return  # cancelled, or another program's
        self._progress = progress
        if playback is not None:
            first = self.playback is None
            if not first:
                playback.time = self.playback.time
            self.playback = playback
            if playback.trajectory.complete:
                self._sampler = None
            if first:
                self.host.refresh_views()  # the path, in every view
            if first and self._play_when_ready:
                self._play()
            elif playback.trajectory.complete and self.playing:
                problems = playback.problems
                if problems:
                    self.host.say(
                        f"playing {self.name}: {counted(len(problems), 'problem')} (n: the next)",
                        error=True,
                    )
            if playback.trajectory.complete:
                self.host.refresh_views()
                then, self._then = self._then, None
                if then is not None:
                    then()
        self._show()

    def _failed(self, worker: Worker, message: str) -> None:
        if worker is not self._sampler:
            return
        self._sampler = None
        self._then = None
        self._play_when_ready = False
        self.pause()
        self.playback = None
        self.host.say(message, error=True)
        self._show()

    def cancel_sampling(self) -> bool:
        """escape: stop sampling (and playing what was sampled); True if it was
        under way."""
        if not self.sampling:
            return False
        self.pause()
        self._stop_sampling()
        had_path = self.playback is not None
        self.playback = None
        self.host.say(f"stopped sampling {self.name} at {self._percent()}")
        self._show()
        if had_path:
            self.host.refresh_views()
        return True

    def _stop_sampling(self) -> None:
        if self._sampler is not None:
            self._sampler.cancel()
        self._sampler = None
        self._then = None
        self._play_when_ready = False

    def _percent(self) -> str:
        return f"{int(self._progress * 100)} %"

    def _bar(self) -> str:
        """The sampling's progress: a bar, the share and how to stop it."""
        full, empty = ("#", "-") if ascii_mode(self.panel) else ("█", "░")
        filled = min(BAR_WIDTH, int(self._progress * BAR_WIDTH))
        return f"{full * filled}{empty * (BAR_WIDTH - filled)} {self._percent()} esc stops"

    def _start(self) -> None:
        self._from = (monotonic(), self.playback.time)
        self._timer = self.host.set_interval(PLAY_FRAME, self._tick)
        self._show()

    def _tick(self) -> None:
        playback = self.playback
        if playback is None:
            return
        began, at = self._from
        # a program still being sampled plays up to its last sample, and waits there
        end = playback.duration if playback.trajectory.complete else playback.ready
        playback.time = min(at + (monotonic() - began) * self.speed, end)
        self.host.q = playback.at(playback.time)
        self._show()
        if playback.done:
            self.pause()
            self.host.say(f"played {self.name}: {playback.duration:.2f} s")

    def _show(self) -> None:
        playback = self.playback
        if playback is None:
            self.panel.show(self.program())
            self.panel.border_subtitle = f"sampling {self._bar()}" if self.sampling else ""
            return
        step = playback.step_at(playback.time)
        self.panel.show(self.program(), step, playback.problems_per_step())
        if self.sampling:
            self.panel.border_subtitle = f"{playback.time:.2f} s  {self._bar()}"
            return
        speed = f"  ×{self.speed:g}" if self.speed != 1 else ""
        self.panel.border_subtitle = f"{playback.time:.2f} / {playback.duration:.2f} s{speed}"

    def change_speed(self, delta: int) -> None:
        """[ ]: play slower or faster (×¼ to ×4), from where it is."""
        index = SPEEDS.index(self.speed) if self.speed in SPEEDS else SPEEDS.index(1.0)
        self.speed = SPEEDS[min(max(index + delta, 0), len(SPEEDS) - 1)]
        if self.playing:
            self.pause()
            self._start()
        self.host.say(f"playback at ×{self.speed:g}")

    def plot(self) -> None:
        """t: the joints and the tool speed against time, at the time played."""
        if self._ready(self.plot, "the plot opens"):
            title = f"{self.name}: joints and tool speed against time"
            playback = self.playback
            self.host.app.push_screen(  # type: ignore[attr-defined]
                ProgramPlot(title, playback.trajectory, playback.problems, playback.time)
            )

    def seek(self, steps: int) -> None:
        """To the start of the step ``steps`` before or after."""
        if self._ready(lambda: self.seek(steps), "the step is sought"):
            self.playback.seek_step(steps)
            self._jump()

    def next_problem(self) -> None:
        if not self._ready(self.next_problem, "the first problem is shown"):
            return
        problem = self.playback.next_problem()
        if problem is None:
            self.host.say("the path check found no problem")
            return
        self._jump()
        self.host.say(
            f"step {problem.step} at {problem.time:.2f} s: {problem.message}",
            error=True,
        )

    def _jump(self) -> None:
        """The arm to the time played; the step there selected in the panel."""
        playing = self.pause()
        step = self.playback.step_at(self.playback.time)
        if step:
            self.panel.selected = step - 1
        self.host.q = self.playback.at(self.playback.time)
        self._show()
        if playing:
            self._start()

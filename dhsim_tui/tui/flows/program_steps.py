"""The program panel's questions, each a ValueEntry (or a Choice) dialog: a
wait's seconds, a step's speed, a step's target (joint values, or for a
linear move the tool pose as XYZ and OAT) and a program's name.

Each is a plain flow: ``await`` it from a worker; it returns the answer, or
None when the dialog was cancelled. The numbers are checked by the core
(:mod:`dhsim_tui.core.model.program`, :mod:`~dhsim_tui.core.model.editing`);
a tool pose becomes joint values by IK from the step's own joints
(:func:`dhsim_tui.core.ik.nearest.inverse`), so the move ends on the same
branch.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np
from textual.app import App

from dhsim_tui.core.ik.nearest import inverse
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics import read_out
from dhsim_tui.core.model.orientation import oat_matrix
from dhsim_tui.core.model.program import (
    MAX_WAIT,
    Program,
    Step,
    check_values,
    renamed_program,
    shown_number,
    target_joints,
)
from dhsim_tui.core.model.program_timing import MIN_JOINT_PERCENT
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.tui.screens.dialogs import Choice
from dhsim_tui.tui.screens.value_entry import ValueEntry

#: what a speed dialog takes for "the default"
DEFAULT_WORDS = ("", "default")
#: a step's check against the whole robot (a program too long, a name taken...):
#: raises DhsimError, shown under the input, so the dialog stays until it fits
Fits = Callable[[Step], object] | None


def _fitting(step: Step, fits: Fits) -> Step:
    if fits is not None:
        fits(step)
    return step


async def ask_wait(app: App, seconds: float = 1.0, fits: Fits = None) -> float | None:
    """A wait's length in seconds (``fits``: the wait step's check in its program)."""

    def check(text: str) -> float:
        value = editing.parse_number(text, "wait")
        if not 0 <= value <= MAX_WAIT:
            raise DhsimError(f"wait: {shown_number(value)} s is outside 0..{MAX_WAIT:g} s")
        _fitting(Step("wait", seconds=value), fits)
        return value

    hint = f"seconds the arm holds its pose, 0 to {MAX_WAIT:g} · enter sets · escape cancels"
    return await app.push_screen_wait(ValueEntry("wait (s)", shown_number(seconds), hint, check))


async def ask_speed(app: App, robot: Robot, step: Step, fits: Fits = None) -> Step | None:
    """The step with a new speed (a wait: new seconds); empty: the default."""
    if step.is_wait:
        seconds = await ask_wait(app, step.seconds, fits)
        return None if seconds is None else Step("wait", seconds=seconds)
    if step.move == "joint":
        title, unit = "joint move speed (% of top speed)", "%"
        hint = f"{MIN_JOINT_PERCENT:g} to 100 % of each joint's top speed; empty: 100"
    else:
        title, unit = f"linear move speed ({robot.units}/s)", f"{robot.units}/s"
        hint = f"the tool's speed in {robot.units}/s; empty: the default"

    def check(text: str) -> Step:
        if text.strip().lower() in DEFAULT_WORDS:
            return _fitting(Step(step.move, step.to), fits)
        value = editing.parse_number(text, "speed")
        if value <= 0 or (step.move == "joint" and value > 100):
            raise DhsimError(f"speed: {shown_number(value)} {unit} is out of range ({hint})")
        return _fitting(Step(step.move, step.to, value), fits)

    now = "" if step.speed is None else shown_number(step.speed)
    return await app.push_screen_wait(ValueEntry(title, now, hint + " · escape cancels", check))


async def ask_target(
    app: App, robot: Robot, program: Program, index: int, fits: Fits = None
) -> Step | None:
    """The step with new target numbers: joint values, or for a linear move
    (by choice) the tool pose, XYZ and OAT, solved from the step's joints."""
    step = program.steps[index]
    joints = target_joints(robot, program.name, index + 1, step)
    how = "joints"
    if step.move == "linear":
        how = await app.push_screen_wait(
            Choice(
                f"step {index + 1}: the target as",
                [("joints", "joint values"), ("pose", "tool pose: XYZ and OAT")],
                current="pose",
            )
        )
        if how is None:
            return None
    if how == "joints":
        labels = ", ".join(j.label(i + 1) for i, j in enumerate(robot.joints))

        def check_joints(text: str) -> Step:
            values = editing.parse_numbers(text, robot.dof, "target")
            changed = Step(step.move, check_values(robot, values, "target"), step.speed)
            return _fitting(changed, fits)

        return await app.push_screen_wait(
            ValueEntry(
                f"step {index + 1}: joint values",
                ", ".join(shown_number(v) for v in joints),
                f"{labels}, in order · enter sets · escape cancels",
                check_joints,
            )
        )
    end = read_out(robot.kinematics.pose(joints))

    def check_pose(text: str) -> Step:
        x, y, z, o, a, t = editing.parse_numbers(text, 6, "tool pose")
        target = np.eye(4)
        target[:3, :3] = oat_matrix(o, a, t)
        target[:3, 3] = (x, y, z)
        result = inverse(robot, target, joints)
        if not result.success:
            raise DhsimError(f"tool pose: the arm can't get there ({result.reason})")
        values = tuple(round(v, 6) for v in result.q)
        changed = Step(step.move, check_values(robot, values, "tool pose"), step.speed)
        return _fitting(changed, fits)

    numbers = [*end.xyz, *end.oat]
    return await app.push_screen_wait(
        ValueEntry(
            f"step {index + 1}: tool pose",
            ", ".join(shown_number(round(v, 4)) for v in numbers),
            f"x, y, z ({robot.units}), o, a, t (deg), world · the branch of the step kept",
            check_pose,
        )
    )


async def ask_program_name(app: App, robot: Robot, name: str) -> tuple[Program, ...] | None:
    """The robot's programs with program ``name`` renamed."""

    def check(text: str) -> tuple[Program, ...]:
        programs = renamed_program(robot.programs, name, text.strip())
        replace(robot, programs=programs)  # the robot's own checks: a name's characters, length
        return programs

    return await app.push_screen_wait(
        ValueEntry("rename the program", name, "a new name · enter sets · escape cancels", check)
    )

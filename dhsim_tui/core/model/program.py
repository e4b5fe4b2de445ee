"""Programs: named lists of moves, the robot file's ``[programs]`` table.

A step is a joint move (every joint starts and stops together), a linear
move (the tool point in a straight line, its orientation on the shortest
rotation) or a wait::

    [programs]
    demo = [
      { move = "joint", to = "qr" },                    # to a named pose
      { move = "linear", to = "ready", speed = 250 },   # robot units/s
      { move = "joint", to = [0, 45, -90, 0, 45, 0], speed = 50 },  # % of top speed
      { wait = 0.5 },                                   # seconds
    ]

``to`` is a pose name or one joint value per joint. A joint move's
``speed`` is a percentage of each joint's top speed (default
:data:`JOINT_SPEED_PERCENT`); a linear move's is the tool's speed in robot
units a second (default :data:`LINEAR_SPEED_MM` mm/s in the robot's unit).
Each joint's top speed and acceleration are its ``vmax`` and ``amax``
(:func:`top_speed`, :func:`top_acceleration`; defaults below). Checking a
program against its robot is :func:`check_programs` (the pose names, the
lengths, the speeds; start and end poses within the limits).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.text import control_character, printable, shortened
from dhsim_tui.core.model.units import mm_to_unit

MOVES = ("joint", "linear")
#: a joint move's default speed: percent of each joint's top speed
JOINT_SPEED_PERCENT = 100.0
#: a linear move's default tool speed (mm/s, in the robot's unit)
LINEAR_SPEED_MM = 250.0
#: the default top speed and acceleration of a revolute joint (deg/s, deg/s²)
REVOLUTE_VMAX = 90.0
REVOLUTE_AMAX = 360.0
#: ... and of a prismatic one (mm/s, mm/s², in the robot's unit)
PRISMATIC_VMAX_MM = 250.0
PRISMATIC_AMAX_MM = 1000.0
#: the longest wait (s) and the most steps a program may have
MAX_WAIT = 3600.0
MAX_STEPS = 1000
#: the longest program name (as a pose name: validation.MAX_NAME_CHARS)
MAX_PROGRAM_NAME = 1000


#: decimals a step's numbers are shown with, at most (float noise dropped)
SHOWN_DECIMALS = 6


def shown_number(value: float) -> str:
    """A step's number as a person writes it: at most :data:`SHOWN_DECIMALS`
    decimals, no trailing zeros, never ``-0`` (``10.000000000000002`` is
    ``10``, ``-0.0`` is ``0``, ``431.8`` stays)."""
    rounded = round(float(value), SHOWN_DECIMALS) + 0.0  # + 0.0: -0.0 becomes 0.0
    if not math.isfinite(rounded):
        return str(rounded)
    text = f"{rounded:.{SHOWN_DECIMALS}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


@dataclass(frozen=True)
class Step:
    """One step: ``move`` "joint", "linear" or "wait"; ``to`` a pose name or
    joint values (moves); ``speed`` (moves; None: the default); ``seconds``
    (waits)."""

    move: str
    to: str | tuple[float, ...] | None = None
    speed: float | None = None
    seconds: float = 0.0

    @property
    def is_wait(self) -> bool:
        return self.move == "wait"

    def describe(self) -> str:
        """``joint to qr``, ``linear to [0, 45, ...] at 250``, ``wait 0.5 s``."""
        if self.is_wait:
            return f"wait {shown_number(self.seconds)} s"
        if isinstance(self.to, str):
            to = self.to
        else:
            to = "[" + ", ".join(shown_number(v) for v in self.to or ()) + "]"
        speed = ""
        if self.speed is not None:
            speed = f" at {shown_number(self.speed)}" + ("%" if self.move == "joint" else "/s")
        return f"{self.move} to {to}{speed}"


@dataclass(frozen=True)
class Program:
    """A named list of steps, played from the pose the arm is in."""

    name: str
    steps: tuple[Step, ...] = ()


def top_speed(joint, units: str) -> float:
    """A joint's top speed: its ``vmax``, or the default (deg/s or units/s)."""
    if joint.vmax is not None:
        return joint.vmax
    return REVOLUTE_VMAX if joint.is_revolute else mm_to_unit(PRISMATIC_VMAX_MM, units)


def top_acceleration(joint, units: str) -> float:
    """A joint's top acceleration: its ``amax``, or the default."""
    if joint.amax is not None:
        return joint.amax
    return REVOLUTE_AMAX if joint.is_revolute else mm_to_unit(PRISMATIC_AMAX_MM, units)


def linear_speed(step: Step, units: str) -> float:
    """A linear move's tool speed (robot units a second)."""
    return step.speed if step.speed is not None else mm_to_unit(LINEAR_SPEED_MM, units)


def step_where(program: str, number: int, field: str | None = None) -> str:
    """``programs.demo, step 2, speed`` (the place a message names)."""
    where = f"programs.{printable(shortened(program))}, step {number}"
    return f"{where}, {field}" if field else where


def _finite_positive(value: float, where: str, what: str) -> float:
    if not isinstance(value, int | float) or isinstance(value, bool) or not math.isfinite(value):
        raise DhsimError(f"{where}: {what} must be a finite number")
    if value <= 0:
        raise DhsimError(f"{where}: {what} must be greater than 0, not {value:g}")
    return float(value)


def check_programs(robot) -> None:
    """Raise :class:`DhsimError`, naming the program, the step and the field,
    on the first thing wrong with ``robot``'s programs: a name used twice, a
    move of another kind, an unknown pose, a target of the wrong length or
    outside the limits, a speed that is not a positive number (a joint
    move's at most 100 %), a wait below 0 or over :data:`MAX_WAIT`."""
    seen: set[str] = set()
    for program in robot.programs:
        name = program.name
        if not isinstance(name, str) or not name.strip():
            raise DhsimError("programs: a program needs a non-empty name")
        where = f"programs.{printable(shortened(name))}"
        found = control_character(name)
        if found is not None:  # shown on the screen: as pose names, none (or one said)
            raise DhsimError(f"{where}: a program name may not hold control characters ({found})")
        if len(name) > MAX_PROGRAM_NAME:
            raise DhsimError(
                f"{where}: a program name has at most {MAX_PROGRAM_NAME} characters; "
                f"this one has {len(name)}"
            )
        if name in seen:
            raise DhsimError(f"{where}: the name is used twice")
        seen.add(name)
        if len(program.steps) > MAX_STEPS:
            raise DhsimError(
                f"programs.{printable(shortened(name))}: at most {MAX_STEPS} steps, "
                f"not {len(program.steps)}"
            )
        for number, step in enumerate(program.steps, start=1):
            _check_step(robot, name, number, step)


def _check_step(robot, program: str, number: int, step: Step) -> None:
    if step.is_wait:
        seconds = step.seconds
        where = step_where(program, number, "wait")
        if not isinstance(seconds, int | float) or not math.isfinite(seconds):
            raise DhsimError(f"{where}: seconds must be a finite number")
        if not 0 <= seconds <= MAX_WAIT:
            raise DhsimError(f"{where}: {seconds:g} s is outside 0..{MAX_WAIT:g} s")
        return
    if step.move not in MOVES:
        raise DhsimError(
            f"{step_where(program, number, 'move')}: {printable(shortened(str(step.move)))!r} "
            f"is not a move (joint, linear or a wait)"
        )
    target_joints(robot, program, number, step)
    if step.speed is not None:
        speed = _finite_positive(step.speed, step_where(program, number, "speed"), "speed")
        if step.move == "joint" and speed > 100:
            raise DhsimError(
                f"{step_where(program, number, 'speed')}: a joint move's speed is a percentage "
                f"of each joint's top speed, at most 100, not {speed:g}"
            )


def target_joints(robot, program: str, number: int, step: Step) -> tuple[float, ...]:
    """A move's target as joint values (a pose's, or its own), checked."""
    where = step_where(program, number, "to")
    if isinstance(step.to, str):
        if step.to not in robot.pose_names:
            known = printable(shortened(", ".join(robot.pose_names) or "none"))
            raise DhsimError(
                f"{where}: no pose named {printable(shortened(step.to))!r} (poses: {known})"
            )
        return robot.pose(step.to)
    if step.to is None:
        raise DhsimError(f"{where}: a move needs a target, a pose name or joint values")
    return check_values(robot, step.to, where)


def check_values(robot, values: Sequence[float], where: str) -> tuple[float, ...]:
    """Joint values of the right length, finite, within the limits."""
    try:
        return robot.check_q(values)  # the model's own check, with its messages
    except DhsimError as exc:
        text = str(exc)
        raise DhsimError(f"{where}: {text.split(': ', 1)[-1]}") from None


# -- editing a program (each returns a new one; the robot checks it when replaced) ----
def with_step(program: Program, step: Step, at: int | None = None) -> Program:
    """``step`` added after step ``at`` (0-based; at the end when None)."""
    steps = list(program.steps)
    steps.insert(len(steps) if at is None else at + 1, step)
    return Program(program.name, tuple(steps))


def without_step(program: Program, index: int) -> Program:
    steps = list(program.steps)
    if 0 <= index < len(steps):
        del steps[index]
    return Program(program.name, tuple(steps))


def moved_step(program: Program, index: int, delta: int) -> Program:
    """Step ``index`` moved ``delta`` places (kept within the program)."""
    steps = list(program.steps)
    target = min(max(index + delta, 0), len(steps) - 1)
    if not steps or target == index:
        return program
    steps.insert(target, steps.pop(index))
    return Program(program.name, tuple(steps))


def toggled_step(program: Program, index: int) -> Program:
    """Step ``index`` a linear move if it was a joint move, and back (its own
    speed dropped: the two are in different units); a wait stays."""
    steps = list(program.steps)
    if not 0 <= index < len(steps) or steps[index].is_wait:
        return program
    step = steps[index]
    steps[index] = Step("linear" if step.move == "joint" else "joint", step.to)
    return Program(program.name, tuple(steps))


def with_changed_step(program: Program, index: int, step: Step) -> Program:
    """Step ``index`` replaced by ``step``."""
    steps = list(program.steps)
    if 0 <= index < len(steps):
        steps[index] = step
    return Program(program.name, tuple(steps))


def renamed_program(programs: tuple[Program, ...], old: str, new: str) -> tuple[Program, ...]:
    """``programs`` with program ``old`` called ``new``, in its place;
    :class:`DhsimError` if ``new`` is taken or empty (other checks: the
    robot's, when the programs are replaced)."""
    if not new.strip():
        raise DhsimError("a program needs a non-empty name")
    if new != old and any(p.name == new for p in programs):
        raise DhsimError(f"there is a program named {printable(shortened(new))!r} already")
    return tuple(Program(new, p.steps) if p.name == old else p for p in programs)


def new_program_name(programs: tuple[Program, ...]) -> str:
    """``program1``, ``program2``...: the first not taken."""
    names = {p.name for p in programs}
    number = 1
    while f"program{number}" in names:
        number += 1
    return f"program{number}"


def with_program(programs: tuple[Program, ...], program: Program) -> tuple[Program, ...]:
    """``programs`` with ``program`` in place of the one of its name (added last if new)."""
    names = [p.name for p in programs]
    if program.name in names:
        return tuple(program if p.name == program.name else p for p in programs)
    return (*programs, program)

"""The robot file's ``[programs]`` table: each program an array of steps,
each step an inline table (:mod:`dhsim_tui.core.model.program` says what
they mean)::

    [programs]
    demo = [
      { move = "joint", to = "qr" },
      { move = "linear", to = "ready", speed = 250 },
      { move = "joint", to = [0, 45, -90, 0, 45, 0], speed = 50 },
      { wait = 0.5 },
    ]

:func:`programs_from_data` checks every step's keys, spelling and types,
naming the program, the step (from 1) and the field; what needs the robot (a
pose name, the number of joint values, the limits, a speed's range) is
checked when the robot is built (:func:`~dhsim_tui.core.model.program.check_programs`).
:func:`programs_to_data` is the table written for a robot's programs.
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping
from typing import Any

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.program import MOVES, Program, Step, step_where
from dhsim_tui.core.model.text import printable, shortened
from dhsim_tui.core.model.validation import check_name_length, check_number, check_text

#: the keys a step may have: a move's, then a wait's
MOVE_KEYS = ("move", "to", "speed")
WAIT_KEYS = ("wait",)
STEP_KEYS = MOVE_KEYS + WAIT_KEYS
#: how a step is written, for messages
STEP_FORMS = (
    '{ move = "joint" or "linear", to = <pose name or joint values> } or { wait = <seconds> }'
)


def program_where(name: str) -> str:
    """``programs.demo``, as messages name a program."""
    return f"programs.{printable(shortened(name))}"


def _kind(value: object) -> str:
    """What a wrong value is, for messages."""
    if isinstance(value, str):
        return f"the text {printable(shortened(value))!r}"
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if isinstance(value, int | float):
        return f"the number {value:g}"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, Mapping):
        return "a table"
    return type(value).__name__


def _check_step_keys(table: Mapping[str, Any], program: str, number: int) -> None:
    for key in table:
        if key not in STEP_KEYS:
            close = difflib.get_close_matches(key, STEP_KEYS, n=1)
            hint = f"did you mean {close[0]!r}?" if close else f"allowed: {', '.join(STEP_KEYS)}"
            where = step_where(program, number, printable(shortened(key)))
            raise DhsimError(f"{where}: unknown key ({hint})")


def _move(value: object, where: str) -> str:
    if value in MOVES:
        return value  # type: ignore[return-value]
    hint = ""
    if isinstance(value, str):
        close = difflib.get_close_matches(value, MOVES, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        if value == "wait":
            hint = " (a wait is written { wait = <seconds> })"
    moves = " or ".join(repr(move) for move in MOVES)
    raise DhsimError(f"{where}: {_kind(value)} is not a move; a move is {moves}{hint}")


def _target(value: object, where: str) -> str | tuple[float, ...]:
    if isinstance(value, str):
        return value
    if isinstance(value, list):
        return tuple(check_number(v, f"{where}[{i}]") for i, v in enumerate(value, start=1))
    raise DhsimError(
        f"{where}: expected a pose name in quotes or a list of joint values, got {_kind(value)}"
    )


def step_from_data(data: object, program: str, number: int) -> Step:
    """One step of a program as the file writes it, checked for its keys and
    their types (:data:`STEP_FORMS`)."""
    if not isinstance(data, Mapping):
        raise DhsimError(
            f"{step_where(program, number)}: expected a step, {STEP_FORMS}; got {_kind(data)}"
        )
    _check_step_keys(data, program, number)
    if "wait" in data:
        other = next((key for key in data if key != "wait"), None)
        if other is not None:
            raise DhsimError(
                f"{step_where(program, number, other)}: a wait has no {other!r}; "
                "a step is a move or a wait, not both"
            )
        seconds = check_number(data["wait"], step_where(program, number, "wait"))
        return Step(move="wait", seconds=seconds)
    for key in ("move", "to"):
        if key not in data:
            raise DhsimError(f"{step_where(program, number, key)}: missing; a step is {STEP_FORMS}")
    move = _move(data["move"], step_where(program, number, "move"))
    target = _target(data["to"], step_where(program, number, "to"))
    speed = None
    if "speed" in data:
        speed = check_number(data["speed"], step_where(program, number, "speed"))
    return Step(move=move, to=target, speed=speed)


def programs_from_data(data: object) -> tuple[Program, ...]:
    """The ``[programs]`` table as programs, in file order."""
    if not isinstance(data, Mapping):
        raise DhsimError(
            "programs: expected a table of programs, written [programs], "
            f"each an array of steps; got {_kind(data)}"
        )
    programs = []
    for name, steps in data.items():
        where = program_where(name)
        check_text(name, where, "a program name")
        check_name_length(name, where, "a program name")
        if not isinstance(steps, list):
            raise DhsimError(
                f"{where}: expected an array of steps, like "
                f'[{{ move = "joint", to = "qr" }}, {{ wait = 0.5 }}]; got {_kind(steps)}'
            )
        programs.append(
            Program(
                name=name,
                steps=tuple(step_from_data(s, name, i) for i, s in enumerate(steps, start=1)),
            )
        )
    return tuple(programs)


def step_to_data(step: Step) -> dict[str, Any]:
    """A step as the file writes it (a default speed left out)."""
    if step.is_wait:
        return {"wait": float(step.seconds)}
    data: dict[str, Any] = {"move": step.move}
    data["to"] = step.to if isinstance(step.to, str) else [float(v) for v in step.to or ()]
    if step.speed is not None:
        data["speed"] = float(step.speed)
    return data


def programs_to_data(programs: tuple[Program, ...]) -> dict[str, list[dict[str, Any]]]:
    """The ``[programs]`` table for ``programs``."""
    return {program.name: [step_to_data(step) for step in program.steps] for program in programs}

"""What an import gives: the robot, remarks for the user, and comment lines
for the top of its robot file. A leaf shared by the URDF and CSV importers,
with :func:`shortened` for the file text their messages quote."""

from __future__ import annotations

from dataclasses import dataclass

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.text import printable, shortened


@dataclass(frozen=True)
class ImportResult:
    """The robot, and one-line remarks for the user (what was checked, what is odd)."""

    robot: Robot
    notes: tuple[str, ...] = ()
    #: comment lines for the top of the robot file (where it came from, joint names)
    header: tuple[str, ...] = ()


def quoted(text: str, limit: int = 200) -> str:
    """``repr`` of :func:`shortened` text: how a message names a file's word."""
    return repr(shortened(text, limit))


def check_choice(value: str, allowed: tuple[str, ...], what: str, source: str) -> None:
    if value not in allowed:
        raise DhsimError(
            printable(f"{source}: {what} {quoted(value, 60)} is not one of {', '.join(allowed)}")
        )

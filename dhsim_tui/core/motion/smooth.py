"""Smooth joint-space motion: a quintic blend (zero velocity and acceleration
at both ends), sampled at whatever rate the screen draws."""

from __future__ import annotations

from collections.abc import Sequence

#: seconds a move takes (about one second: quick, yet slow enough to follow)
DURATION = 1.0


def quintic(fraction: float) -> float:
    """0 -> 0, 1 -> 1, with zero first and second derivatives at both ends."""
    t = min(max(fraction, 0.0), 1.0)
    return t * t * t * (10.0 + t * (-15.0 + 6.0 * t))


def interpolate(
    start: Sequence[float], goal: Sequence[float], fraction: float
) -> tuple[float, ...]:
    s = quintic(fraction)
    return tuple(a + (b - a) * s for a, b in zip(start, goal, strict=True))


class SmoothMove:
    """A move from ``start`` to ``goal`` begun at ``began`` (seconds, any
    clock), over ``duration`` (:data:`DURATION`): :meth:`at` gives the joints
    at a time."""

    def __init__(
        self,
        start: Sequence[float],
        goal: Sequence[float],
        began: float,
        duration: float | None = None,
    ) -> None:
        self.start = tuple(start)
        self.goal = tuple(goal)
        self.began = began
        self.duration = DURATION if duration is None else duration

    def at(self, now: float) -> tuple[tuple[float, ...], bool]:
        """The joints at ``now``, and whether the move is over (then exactly ``goal``)."""
        fraction = (now - self.began) / self.duration
        if fraction >= 1:
            return self.goal, True
        return interpolate(self.start, self.goal, fraction), False

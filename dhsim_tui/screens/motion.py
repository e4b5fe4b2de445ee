"""Smooth moves for the control screen: a quintic joint-space move over about a
second, drawn at the screen's frame rate; any key stops it where it is."""

from __future__ import annotations

import time

from dhsim_tui.core.motion import DURATION, interpolate


class SmoothMotion:
    """Mixed into the control screen, which has ``q``, ``animate`` and ``say``."""

    _animation = None

    def _go_to(self, goal: tuple[float, ...], message: str) -> None:
        """Straight to ``goal``, or a quintic move over about a second when
        motion is on; any key interrupts it where it is."""
        self._stop_motion()
        self.say(message)
        if not self.animate or goal == self.q:
            self.q = goal
            return
        start, began = self.q, time.monotonic()

        def tick() -> None:
            fraction = (time.monotonic() - began) / DURATION
            self.q = interpolate(start, goal, fraction) if fraction < 1 else goal
            if fraction >= 1:
                self._stop_motion()

        self._animation = self.set_interval(1 / 30, tick)

    def _stop_motion(self) -> bool:
        if self._animation is None:
            return False
        self._animation.stop()
        self._animation = None
        return True

    @property
    def moving(self) -> bool:
        return self._animation is not None

    def on_key(self) -> None:
        if self._stop_motion():
            self.say("stopped")

    def action_toggle_motion(self) -> None:
        self.animate = not self.animate
        self.say("smooth motion on" if self.animate else "smooth motion off")

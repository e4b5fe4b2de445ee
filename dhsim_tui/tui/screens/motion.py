"""Smooth moves for the control screen: a quintic joint-space move over about a
second, drawn at the screen's frame rate.

Only what moves the arm stops a move where it is: a joint or Cartesian step,
home, the next pose, the next IK branch, typing a value, and escape.
Switching the view, the read-out, help and the like leave it running. Whether motion is on shows in
the footer ("m Motion on" / "m Motion off") for as long as the screen is up.
"""

from __future__ import annotations

import time

from dhsim_tui.core.motion.smooth import DURATION, interpolate


class SmoothMotion:
    """Mixed into the control screen, which has ``q``, ``animate``, ``say``,
    ``set_interval`` and ``refresh_bindings``."""

    _animation = None
    #: where the move under way ends (None when none is under way)
    motion_goal: tuple[float, ...] | None = None

    def _go_to(self, goal: tuple[float, ...], message: str) -> None:
        """Straight to ``goal``, or a quintic move over about a second when
        motion is on; a key that moves the arm interrupts it where it is."""
        self._stop_motion()
        self.say(message)
        if not self.animate or goal == self.q:
            self.q = goal
            return
        start, began = self.q, time.monotonic()
        self.motion_goal = goal

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
        self.motion_goal = None
        return True

    def _interrupt(self) -> None:
        """A key that moves the arm: stop a move where it is, and say so (the
        key's own action may say something else right after)."""
        if self._stop_motion():
            self.say("stopped")

    @property
    def moving(self) -> bool:
        return self._animation is not None

    def action_stop(self) -> None:
        """escape: stop a smooth move (nothing else)."""
        self._interrupt()

    def action_toggle_motion(self, _shown_as_on: int = 0) -> None:
        """``m``: the parameter only tells the footer's two labels apart."""
        self.animate = not self.animate
        self.app.animate = self.animate  # a new control screen (after the editor) keeps it
        self.refresh_bindings()
        self.say(
            "smooth motion on: h, p and b move over a second; escape stops"
            if self.animate
            else "smooth motion off: h, p and b jump"
        )

"""How long the control screen stays busy after a burst of keys (a benchmark, not a test).

    python bench/control_burst.py [--keys 500] [--rate 0] [--size 80x24] [--robot puma560]

Drives the app headlessly and posts ``--keys`` presses of ``right`` into its
queue the way a terminal's input thread does, either all at once
(``--rate 0``, a key held down over a slow link, then delivered together) or
at ``--rate`` keys a second (auto-repeat). Every frame Textual hands to the
terminal is timed (the app's ``_display`` hook; the frame is also turned into
terminal segments so that cost counts). The settle time is from the moment
the last key was posted to the last frame drawn; the target is 0.3 s for 500
keys (issue 8). It then checks that no key was lost: the joint moved by
exactly ``--keys`` steps (or stopped on its limit).
"""

from __future__ import annotations

import argparse
import asyncio
import time

from textual import events

from dhsim_tui.core import load_robot
from dhsim_tui.core.motion.jog import set_joint, step_size
from dhsim_tui.tui.app import DhsimApp

#: the app counts as settled when no frame has been drawn for this long
QUIET = 1.0


async def burst(
    robot_name: str, size: tuple[int, int], keys: int, rate: float, step_level: int
) -> tuple[float, int, int, tuple[float, ...], tuple[float, ...]]:
    """(settle seconds, frames drawn after the last key, redraws of the pose,
    q reached, q expected)."""
    robot, path = load_robot(robot_name)
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=size) as pilot:
        screen = app.screen
        await pilot.press(*["left_square_bracket"] * 5, *["right_square_bracket"] * step_level)
        await pilot.pause()
        frames: list[float] = []
        original = app._display

        def display(screen_, renderable) -> None:
            original(screen_, renderable)
            if renderable is not None:
                list(renderable.render_segments(app.console))
                frames.append(time.perf_counter())

        app._display = display  # type: ignore[method-assign]
        expected = screen.q
        for _ in range(keys):  # what every key should add up to
            expected = set_joint(
                robot, expected, 0, expected[0] + step_size(robot, 0, screen.step_level)
            ).q
        gap = 1 / rate if rate else 0.0
        redraws = screen.redraws
        last_key = time.perf_counter()
        for i in range(keys):
            app.post_message(events.Key("right", None))
            last_key = time.perf_counter()
            if gap and i < keys - 1:
                await asyncio.sleep(gap)
        while True:
            await asyncio.sleep(0.05)
            now = time.perf_counter()
            if now - (frames[-1] if frames else last_key) > QUIET:
                break
        after = [t for t in frames if t >= last_key]
        settle = (after[-1] - last_key) if after else 0.0
        return settle, len(after), screen.redraws - redraws, screen.q, expected


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--keys", type=int, default=500)
    parser.add_argument("--rate", type=float, default=0.0, help="keys a second; 0: all at once")
    parser.add_argument("--size", default="80x24")
    parser.add_argument("--robot", default="puma560")
    parser.add_argument(
        "--step-level", type=int, default=0, help="0 is the smallest step (0.1 deg / 0.1 mm)"
    )
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    settle, frames, redraws, q, expected = asyncio.run(
        burst(args.robot, (width, height), args.keys, args.rate, args.step_level)
    )
    how = f"at {args.rate:g}/s" if args.rate else "all at once"
    print(f"{args.robot} at {width}x{height}: {args.keys} presses of right, {how}")
    print(f"  settled {settle * 1000:6.0f} ms after the last key   (target 300 ms)")
    print(f"  frames drawn after the last key: {frames}; the pose was computed {redraws} times")
    lost = "none" if q == expected else f"LOST: joint 1 is {q[0]!r}, expected {expected[0]!r}"
    print(f"  keys lost: {lost}")


if __name__ == "__main__":
    main()

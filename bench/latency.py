"""Key-press-to-frame latency of the control screen (a benchmark, not a test).

    python bench/latency.py [--presses 200] [--size 160x48] [--robot puma560]
                            [--renderer plotext|braille] [--json]

Drives the app headlessly, sends ``right`` the way Pilot does (a Key event
through the driver), and times until the screen's next update has been
composed: the app's ``_display`` hook is where Textual hands a finished
frame to the terminal (headless, it writes nothing; we also turn the frame
into terminal segments so that cost is counted). ``pilot.press`` + ``pause``
would measure ~80 ms of sleeping instead. Also reports time to first frame
and peak memory for a real ``dhsim`` start.

When a key is pressed (``--phase``): ``random`` (the default) waits a random
0-50 ms after the app has settled, so keys land at any point of Textual's
frame clock, as a person's do; ``after-frame`` presses the key just after a
frame was drawn, the worst moment (Pilot's ``pause`` draws one, and Textual
then holds the next frame until 1/60 s after it). Figures before 2026-11-25
were measured the ``after-frame`` way.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import random
import statistics
import subprocess
import sys
import time

from textual import events

from dhsim_tui.core import load_robot
from dhsim_tui.tui.app import DhsimApp


async def settle(pilot, phase: str, rng: random.Random) -> None:
    """Wait until the app is idle (Pilot draws a frame then); at a random
    phase, a further 0-50 ms (three frames at 60 Hz)."""
    await pilot.pause()
    if phase == "random":
        await asyncio.sleep(rng.uniform(0.0, 0.05))


async def measure(
    robot_name: str,
    size: tuple[int, int],
    presses: int,
    renderer: str,
    playing: bool = False,
    phase: str = "random",
) -> list[float]:
    robot, path = load_robot(robot_name)
    app = DhsimApp(robot, path, renderer, animate=False)
    samples: list[float] = []
    async with app.run_test(size=size) as pilot:
        await pilot.pause()
        frame = asyncio.Event()
        original = app._display

        def display(screen, renderable) -> None:
            original(screen, renderable)
            if renderable is not None:
                list(renderable.render_segments(app.console))
                frame.set()

        app._display = display  # type: ignore[method-assign]
        rng = random.Random(1)
        if playing:
            return await _during_playback(app, pilot, frame, presses, phase, rng)
        step_keys = ("right", "left")  # back and forth: never stopped by a limit
        for i in range(presses):
            await settle(pilot, phase, rng)
            frame.clear()
            key = step_keys[(i // 20) % 2]
            start = time.perf_counter()
            app.post_message(events.Key(key, None))
            await asyncio.wait_for(frame.wait(), 5)
            samples.append(time.perf_counter() - start)
            if i == 0:  # the measured frames really are the key's effect
                assert app.screen.q[0] == robot.home[0] + 1.0, app.screen.q
    return samples


async def _during_playback(
    app, pilot, frame: asyncio.Event, presses: int, phase: str, rng: random.Random
) -> list[float]:
    """``tab`` (the next view) while the robot's first program plays, over and
    over: from the key to the first frame that shows the view it selected."""
    from dhsim_tui.tui.widgets.views_panel import ViewsPanel

    views = app.screen.query_one(ViewsPanel)
    await pilot.press("g", "space")
    samples = []
    for _ in range(presses):
        player = app.screen._programs
        if not player.playing:  # at the end: again from the start
            app.screen.q = app.robot.home
            await pilot.press("space")
        await settle(pilot, phase, rng)
        expected = (views.selected + 1) % len(views.views)
        start = time.perf_counter()
        app.post_message(events.Key("tab", None))
        while True:
            frame.clear()
            await asyncio.wait_for(frame.wait(), 5)
            if views.selected == expected:
                break
        samples.append(time.perf_counter() - start)
    return samples


def first_frame_and_memory(
    robot_name: str, size: tuple[int, int], renderer: str
) -> tuple[float, float]:
    """Start a fresh interpreter, run the app headless until its first frame."""
    script = f"""
import asyncio, resource, time
t0 = time.perf_counter()
import dhsim_tui.cli.main  # what the dhsim command loads before the app
from dhsim_tui.core import load_robot
from dhsim_tui.tui.app import DhsimApp
async def main():
    robot, path = load_robot({robot_name!r})
    app = DhsimApp(robot, path, {renderer!r})
    done = asyncio.Event()
    async with app.run_test(size={size!r}) as pilot:
        original = app._display
        def display(screen, renderable):
            original(screen, renderable)
            if renderable is not None:
                done.set()
        app._display = display
        await asyncio.wait_for(done.wait(), 10)
        first = time.perf_counter() - t0
        await pilot.press("right", "right")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(first, peak)
asyncio.run(main())
"""
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    ).stdout.split()
    return float(out[0]), float(out[1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--presses", type=int, default=200)
    parser.add_argument("--size", default="160x48")
    parser.add_argument("--robot", default="puma560")
    parser.add_argument("--renderer", default="plotext", choices=("plotext", "braille"))
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument(
        "--during-playback",
        action="store_true",
        help="press tab while the robot's first program plays (g, space)",
    )
    parser.add_argument(
        "--phase",
        default="random",
        choices=("random", "after-frame"),
        help="press each key at a random moment, or just after a frame (the worst)",
    )
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    samples = asyncio.run(
        measure(
            args.robot,
            (width, height),
            args.presses,
            args.renderer,
            args.during_playback,
            args.phase,
        )
    )
    ms = sorted(s * 1000 for s in samples)
    p95 = ms[min(len(ms) - 1, round(0.95 * (len(ms) - 1)))]
    first, peak = first_frame_and_memory(args.robot, (width, height), args.renderer)
    median, views = statistics.median(ms), "four" if width >= 120 and height >= 36 else "one"
    if args.json:
        print(
            json.dumps(
                {
                    "robot": args.robot,
                    "size": f"{width}x{height}",
                    "renderer": args.renderer,
                    "views_shown": views,
                    "presses": len(ms),
                    "phase": args.phase,
                    "during_playback": args.during_playback,
                    "median_ms": round(median, 2),
                    "p95_ms": round(p95, 2),
                    "first_frame_s": round(first, 3),
                    "peak_memory_mb": round(peak, 1),
                }
            )
        )
        return
    print(
        f"{args.robot} at {width}x{height}, {views} {args.renderer} view(s), "
        f"{len(ms)} presses of {'tab while playing' if args.during_playback else 'right/left'}"
        f" ({args.phase} phase)"
    )
    print(f"  key -> composed frame   median {median:6.1f} ms   p95 {p95:6.1f} ms")
    print(f"  time to first frame    {first * 1000:6.0f} ms   (target 500 ms)")
    print(f"  peak memory            {peak:6.0f} MB   (target 150 MB)")


if __name__ == "__main__":
    main()

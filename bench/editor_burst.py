"""How long the editor stays busy after a burst of keys (a benchmark, not a test).

    python bench/editor_burst.py [--keys 300] [--key t] [--size 80x24] [--robot puma560]

Opens the editor headlessly, posts ``--keys`` key events at once (as a
terminal delivers a burst: no pause between them), then watches the frames
the app hands to the terminal (its ``_display`` hook; the frame is turned
into terminal segments so that cost is counted). The settle time is from the
last key posted to the last frame, once no frame has come for a second.
Target (issue 8): <= 0.5 s for 300 ``t`` presses at 80x24.
"""

from __future__ import annotations

import argparse
import asyncio
import time

from textual import events

from dhsim_tui.core import load_robot
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.editor import EditorScreen

QUIET = 1.0  # seconds without a frame that count as settled
TARGET = 0.5


async def settle_time(robot_name: str, size: tuple[int, int], keys: int, key: str) -> float:
    robot, path = load_robot(robot_name)
    app = DhsimApp(robot, path, start="edit", animate=False)
    async with app.run_test(size=size) as pilot:
        await pilot.pause()
        await pilot.pause(0.3)
        editor = app.screen
        assert isinstance(editor, EditorScreen), editor
        frames: list[float] = []
        original = app._display

        def display(screen, renderable) -> None:
            original(screen, renderable)
            if renderable is not None:
                list(renderable.render_segments(app.console))
                frames.append(time.perf_counter())

        app._display = display  # type: ignore[method-assign]
        character = key if len(key) == 1 else None
        for _ in range(keys):
            app.post_message(events.Key(key, character))
        last_key = time.perf_counter()
        while True:
            await asyncio.sleep(0.05)
            now = time.perf_counter()
            last = frames[-1] if frames else last_key
            if now - last >= QUIET and app._message_queue.empty():
                break
            if now - last_key > 60:
                raise TimeoutError("the editor never settled")
        if key == "t":  # every press really was applied
            assert editor.robot.joints[0].is_revolute == (keys % 2 == 0), "keys were lost"
        return frames[-1] - last_key if frames else 0.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--keys", type=int, default=300)
    parser.add_argument("--key", default="t")
    parser.add_argument("--size", default="80x24")
    parser.add_argument("--robot", default="puma560")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    width, height = (int(n) for n in args.size.split("x"))
    results = [
        asyncio.run(settle_time(args.robot, (width, height), args.keys, args.key))
        for _ in range(args.runs)
    ]
    worst = max(results)
    print(
        f"{args.keys} x {args.key!r} on {args.robot} at {args.size}: settled "
        + ", ".join(f"{r:.3f}" for r in results)
        + f" s after the last key (worst {worst:.3f} s, target <= {TARGET} s: "
        + ("met" if worst <= TARGET else "NOT met")
        + ")"
    )


if __name__ == "__main__":
    main()

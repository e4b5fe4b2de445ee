"""A mouse drag across a joint's bar: how long after the last motion event
the screen has settled on the value under the pointer (a benchmark, not a
test; issue 16's target: 50 ms).

    python bench/mouse.py [--drags 20] [--events 30] [--size 80x24] [--json]

Each drag is a button press on the bar, ``--events`` motion reports along
it delivered back to back (as a terminal hands over a quick drag in one
read), and the release; the clock runs from the last motion report to the
frame that shows the joint at its final value (Textual's ``_display``,
with the frame turned into terminal segments).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import time

from textual.events import MouseDown, MouseMove, MouseUp

from dhsim_tui.core import load_robot
from dhsim_tui.core.motion.jog import snapped
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.widgets.joint_row import BAR_START, JointRow, bar_value


def _event(kind, row: JointRow, x: int, button: int = 1):
    region = row.region  # the screen takes events in its own coordinates
    return kind(
        widget=row,
        x=region.x + x,
        y=region.y,
        delta_x=0,
        delta_y=0,
        button=button,
        shift=False,
        meta=False,
        ctrl=False,
        screen_x=region.x + x,
        screen_y=region.y,
    )


async def measure(drags: int, events: int, size: tuple[int, int]) -> list[float]:
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    samples: list[float] = []
    async with app.run_test(size=size) as pilot:
        await pilot.pause()
        screen = app.screen
        row = next(iter(screen.query(JointRow)))
        width = max(row._bar_width(), 5)
        original = app._display
        settled: list[float] = []
        final = [None]

        def display(target, renderable) -> None:
            original(target, renderable)
            if renderable is not None:
                list(renderable.render_segments(app.console))
                if screen.q[0] == final[0] and not screen._dirty:
                    settled.append(time.perf_counter())

        app._display = display  # type: ignore[method-assign]
        for drag in range(drags):
            forward = drag % 2 == 0
            columns = [
                BAR_START + 1 + (k * (width - 3)) // max(events - 1, 1) for k in range(events)
            ]
            if not forward:
                columns.reverse()
            final[0] = snapped(
                robot, 0, bar_value(robot.joints[0], columns[-1] - BAR_START, width), 1
            )
            await pilot.pause()
            settled.clear()
            screen._forward_event(_event(MouseDown, row, columns[0]))
            for column in columns:
                screen._forward_event(_event(MouseMove, row, column))
            start = time.perf_counter()
            screen._forward_event(_event(MouseUp, row, columns[-1]))
            deadline = start + 5
            while not settled and time.perf_counter() < deadline:
                await asyncio.sleep(0.001)
            if not settled:
                raise RuntimeError("the drag never settled on its final value")
            samples.append(settled[0] - start)
    return samples


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--drags", type=int, default=20)
    parser.add_argument("--events", type=int, default=30)
    parser.add_argument("--size", default="80x24")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    samples = asyncio.run(measure(args.drags, args.events, size))
    ms = sorted(1000 * s for s in samples)
    result = {
        "size": args.size,
        "drags": args.drags,
        "events_per_drag": args.events,
        "settle_median_ms": round(statistics.median(ms), 2),
        "settle_max_ms": round(ms[-1], 2),
    }
    if args.json:
        print(json.dumps(result))
    else:
        print(
            f"drag of {args.events} motion events at {args.size}: settled "
            f"{result['settle_median_ms']} ms after the last (median), "
            f"{result['settle_max_ms']} ms at most"
        )


if __name__ == "__main__":
    main()

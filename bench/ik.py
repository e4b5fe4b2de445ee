"""Inverse-kinematics speed (a benchmark, not a test).

    python bench/ik.py [--count N] [--json]

For the Puma 560 and the Panda, on targets made by FK of random joints within
the limits (seeded):

* a solve from a start near the answer (each joint off by about 5°, no
  restarts), as when following a moving target;
* a solve from home with ``restarts=30``, as ``dhsim ik`` calls it, and how
  many of those reachable targets it reached (every one, it should be);
* one Cartesian jog step (``jog.cartesian_move``: a 1 mm step along X from
  the current joints, as the control screen does), 100 in a row.

Medians and 95th percentiles. Targets: near <= 150 us; from home median
<= 1 ms, p95 <= 5 ms; a jog step <= 0.3 ms.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np

from dhsim_tui.core import load_robot
from dhsim_tui.core.ik.numerical import solve
from dhsim_tui.core.motion.jog import cartesian_move, move_pose

START = {
    "puma560": (-20.0, 50.0, -170.0, 10.0, 40.0, 0.0),
    "panda": (0.0, -17.19, 0.0, -126.05, 0.0, 114.59, 45.0),
}
#: as cli.py's IK_RESTARTS
RESTARTS = 30


def stats(samples: list[float], unit: float = 1e6) -> dict:
    ordered = sorted(samples)
    return {
        "median": statistics.median(ordered) * unit,
        "p95": ordered[min(len(ordered) - 1, int(0.95 * len(ordered)))] * unit,
    }


def bench(name: str, count: int) -> dict:
    robot, _ = load_robot(name)
    rng = np.random.default_rng(7)
    near, cold, solved = [], [], 0
    for k in range(count):
        q = rng.uniform(robot.lower, robot.upper)
        target = robot.kinematics.pose(q)
        start = np.clip(q + rng.normal(0, 5, robot.dof), robot.lower, robot.upper)
        start = tuple(start.tolist())
        t = time.perf_counter()
        solve(robot, target, start)
        near.append(time.perf_counter() - t)
        t = time.perf_counter()
        solved += solve(robot, target, robot.home, restarts=RESTARTS, seed=k).success
        cold.append(time.perf_counter() - t)
    q = START[name]
    commanded = robot.kinematics.pose(q)
    steps = []
    for _ in range(100):
        commanded = move_pose(commanded, 0, 1.0)
        t = time.perf_counter()
        move = cartesian_move(robot, q, commanded)
        steps.append(time.perf_counter() - t)
        q = move.q
    return {
        "near_us": stats(near),
        "home_ms": stats(cold, 1e3),
        "solved_percent": solved / count * 100,
        "jog_step_ms": stats(steps, 1e3),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=300, help="targets per robot")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    results = {name: bench(name, args.count) for name in START}
    if args.json:
        print(json.dumps(results, indent=2))
        return
    print(
        f"{'':10}{'solve, near':>22}{'solve, home, restarts=30':>28}{'solved':>9}{'jog step':>20}"
    )
    print(f"{'robot':10}{'median / p95':>22}{'median / p95':>28}{'':>9}{'median / p95':>20}")
    for name, r in results.items():
        near, home, jog = r["near_us"], r["home_ms"], r["jog_step_ms"]
        print(
            f"{name:10}{near['median']:>10.0f} / {near['p95']:>4.0f} us"
            f"{home['median']:>14.2f} / {home['p95']:>5.2f} ms"
            f"{r['solved_percent']:>8.1f}%"
            f"{jog['median']:>9.3f} / {jog['p95']:.3f} ms"
        )
    print("targets: near <= 150 us; home median <= 1 ms, p95 <= 5 ms; jog step <= 0.3 ms")


if __name__ == "__main__":
    main()

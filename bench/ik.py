"""Inverse-kinematics speed (a benchmark, not a test).

    python bench/ik.py

For the Puma 560 and the Panda: the median time of one IK solve for targets
made by FK of random joints (a) from a start near the answer, as when
following a moving target, and (b) from home with seeded random restarts, as
`dhsim ik` does; and of one Cartesian jog step on the control screen (a 1 mm
step along X, solved from the current joints). Targets: a solve <= 1 ms, a jog
step <= 2 ms.
"""

from __future__ import annotations

import statistics
import time

import numpy as np

from dhsim_tui.core import load_robot
from dhsim_tui.core.ik import solve
from dhsim_tui.core.jog import cartesian_move, move_pose

START = {
    "puma560": (-20.0, 50.0, -170.0, 10.0, 40.0, 0.0),
    "panda": (0.0, -17.19, 0.0, -126.05, 0.0, 114.59, 45.0),
}


def median_ms(samples: list[float]) -> float:
    return statistics.median(samples) * 1e3


def bench(name: str, count: int = 300) -> tuple[float, float, float, float]:
    robot, _ = load_robot(name)
    rng = np.random.default_rng(7)
    near, cold, solved = [], [], 0
    for k in range(count):
        q = rng.uniform(robot.lower, robot.upper)
        target = robot.kinematics.pose(q)
        start = np.clip(q + rng.normal(0, 5, robot.dof), robot.lower, robot.upper)
        t = time.perf_counter()
        solve(robot, target, start)
        near.append(time.perf_counter() - t)
        t = time.perf_counter()
        solved += solve(robot, target, restarts=20, seed=k).success
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
    return median_ms(near), median_ms(cold), solved / count * 100, median_ms(steps)


def main() -> None:
    print(
        f"{'robot':<10}{'solve, near':>14}{'solve, home+restarts':>23}{'solved':>9}{'jog step':>11}"
    )
    for name in ("puma560", "panda"):
        near, cold, rate, step = bench(name)
        print(f"{name:<10}{near:>11.2f} ms{cold:>20.2f} ms{rate:>8.1f}%{step:>8.2f} ms")


if __name__ == "__main__":
    main()

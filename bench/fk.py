"""Forward-kinematics speed on the Puma 560 (a benchmark, not a test).

    python bench/fk.py

Prints the median time of one end-effector pose, of one pose with every
frame (what the views draw), and of a batch of 100,000 joint vectors; then of
the world Jacobian and the manipulability (both compiled per robot, like FK).
Targets: <= 10 us, <= 20 us, <= 50 ms, <= 6 us and <= 12 us; filling arrays
given with ``out=``: the pose <= 2 us, the Jacobian <= 3 us and a batch of
100,000 Panda joint vectors <= 15 ms.
"""

from __future__ import annotations

import statistics
import timeit

import numpy as np

from dhsim_tui.core import load_robot
from dhsim_tui.core.analysis.jacobian import COMPILE_AFTER, jacobian, manipulability


def median_seconds(fn, number: int, repeat: int = 15) -> float:
    return statistics.median(timeit.repeat(fn, number=number, repeat=repeat)) / number


def main() -> None:
    robot, _ = load_robot("puma560")
    kin = robot.kinematics
    q = (0.0, 30.0, 45.0, 60.0, 90.0, 0.0)
    qs = np.random.default_rng(1).uniform(robot.lower, robot.upper, size=(100_000, 6))
    kin.batch(qs)  # warm up
    for _ in range(COMPILE_AFTER):  # past the stepwise start: the compiled paths
        jacobian(robot, q)
        kin.pose(q)
        kin.frames(q)
    panda, _ = load_robot("panda")
    panda_qs = np.random.default_rng(1).uniform(panda.lower, panda.upper, size=(100_000, 7))
    pose, jac, poses = np.empty((4, 4)), np.empty((6, 6)), np.empty((100_000, 4, 4))
    panda.kinematics.batch(panda_qs, out=poses)
    rows = [
        (
            "single pose, end effector (state)",
            median_seconds(lambda: kin.state(q), 20_000),
            "us",
            10,
        ),
        ("single pose, 4x4 matrix (pose)", median_seconds(lambda: kin.pose(q), 20_000), "us", None),
        ("  the same into out=", median_seconds(lambda: kin.pose(q, out=pose), 20_000), "us", 2),
        (
            "single pose, all frames (frames)",
            median_seconds(lambda: kin.frames(q), 20_000),
            "us",
            20,
        ),
        ("batch of 100,000 (batch)", median_seconds(lambda: kin.batch(qs), 1, repeat=9), "ms", 50),
        (
            "  Panda's, into out=",
            median_seconds(lambda: panda.kinematics.batch(panda_qs, out=poses), 1, repeat=21),
            "ms",
            15,
        ),
        ("Jacobian (jacobian)", median_seconds(lambda: jacobian(robot, q), 20_000), "us", 6),
        (
            "  the same into out=",
            median_seconds(lambda: jacobian(robot, q, out=jac), 20_000),
            "us",
            3,
        ),
        (
            "manipulability (manipulability)",
            median_seconds(lambda: manipulability(robot, q), 20_000),
            "us",
            12,
        ),
    ]
    print(f"{'Puma 560 forward kinematics':<36}{'median':>10}   target")
    for label, seconds, unit, target in rows:
        value = seconds * (1e6 if unit == "us" else 1e3)
        goal = f"<= {target} {unit}" if target else ""
        print(f"{label:<36}{value:>7.2f} {unit}   {goal}")


if __name__ == "__main__":
    main()

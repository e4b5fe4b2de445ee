"""Every-solution IK speed (a benchmark, not a test).

    python bench/ik_all.py [--count N] [--json]

The median and 95th percentile time of one ``all_solutions`` call (each
target's fastest of 5 runs) for targets made by FK of random joints within
limits: the closed forms (Puma
560, IRB 140, UR5 — whose ±360° joints give each solution several turns,
reported once, at the turn nearest the start — and the Stanford arm), the
closed-form step alone (each analytic arm), and the numerical
search (Panda, a few targets: it is slow). Target: the analytic Puma
<= 60 us.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import time

import numpy as np

from dhsim_tui.core import load_robot
from dhsim_tui.core.ik import analytic as ik_analytic
from dhsim_tui.core.ik.solutions import all_solutions

ANALYTIC = ("puma560", "irb140", "ur5", "stanford")
NUMERICAL = ("panda",)


def stats(samples: list[float]) -> dict:
    ordered = sorted(samples)
    return {
        "median_us": statistics.median(ordered) * 1e6,
        "p95_us": ordered[min(len(ordered) - 1, int(0.95 * len(ordered)))] * 1e6,
    }


def timed(call, targets, repeat: int = 5) -> tuple[dict, float]:
    """Each target's fastest of ``repeat`` runs (another process's time slice
    is not the code's): median and p95 over the targets, and the mean count
    of solutions."""
    call(targets[0])  # warm: detection, the compiled chain
    samples, counts = [math.inf] * len(targets), []
    for round_ in range(repeat):
        for i, target in enumerate(targets):
            t = time.perf_counter()
            found = call(target)
            samples[i] = min(samples[i], time.perf_counter() - t)
            if round_ == 0:
                counts.append(len(found.solutions) if hasattr(found, "solutions") else len(found))
    return stats(samples), statistics.mean(counts)


def bench(name: str, count: int) -> dict:
    robot, _ = load_robot(name)
    rng = np.random.default_rng(7)
    targets = [
        robot.kinematics.pose(q) for q in rng.uniform(robot.lower, robot.upper, (count, robot.dof))
    ]
    result, mean = timed(lambda t: all_solutions(robot, t), targets)
    out = {"all_solutions": result, "mean_solutions": mean}
    geometry = ik_analytic.detect(robot)
    if geometry is not None:
        closed, _ = timed(lambda t: ik_analytic.solve(robot, geometry, t, robot.home)[0], targets)
        out["closed_form_only"] = closed
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=500, help="targets per analytic robot")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    results = {name: bench(name, args.count) for name in ANALYTIC}
    results.update({name: bench(name, max(3, args.count // 100)) for name in NUMERICAL})
    if args.json:
        print(json.dumps(results, indent=2))
        return
    print(
        f"{'robot':10}{'all_solutions median / p95':>32}{'solutions':>11}{'closed form alone':>22}"
    )
    for name, r in results.items():
        a = r["all_solutions"]
        closed = r.get("closed_form_only")
        alone = f"{closed['median_us']:>12.0f} us" if closed else f"{'-':>15}"
        print(
            f"{name:10}{a['median_us']:>17.0f} / {a['p95_us']:>7.0f} us"
            f"{r['mean_solutions']:>11.1f}{alone:>22}"
        )
    print("target: the analytic Puma 560 <= 60 us (median)")


if __name__ == "__main__":
    main()

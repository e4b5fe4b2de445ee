"""Numerical IK speed per solve, row by row (a benchmark, not a test).

    python bench/ik_speed.py [--count N] [--repeat R] [--json] [--dump FILE] [--rows ROW ...]

Targets are made by FK of seeded random joint values within the limits, so
every one is reachable. The rows:

* ``panda home``: ``solve(robot, T, robot.home, restarts=30)``, as ``dhsim ik``;
* ``panda near`` / ``puma near``: from a start with each joint about 5° off
  the answer, ``solve(robot, T, near, max_iter=40)``, as a Cartesian jog calls it;
* ``puma home``: as ``panda home``, for the Puma 560.

Each row gives the median and 95th percentile time of one solve (µs; with
``--repeat`` each target's time is its fastest of R runs) and its success:
the share of targets solved *and* checked independently (the answer within
the limits, and ``robot.kinematics.pose`` of it on the target to the
solver's tolerances). ``--dump`` writes every answer (q, success) to a JSON
file, to compare one version of the solver with another on the same targets.
Needs no other process. The machine is usually shared: ``--repeat 3`` and a
few runs give steadier figures.

Targets: panda home median <= 160 us, p95 <= 314 us; panda near <= 58 us;
puma near <= 46 us.
"""

from __future__ import annotations

import argparse
import functools
import json
import statistics
import time

import numpy as np

from dhsim_tui.core import load_robot, reach
from dhsim_tui.core.ik.numerical import solve
from dhsim_tui.core.ik.numerical_problem import ORIENTATION_TOL, POSITION_TOL
from dhsim_tui.core.ik.rotation import rotation_error

#: as cli.kinematics.IK_RESTARTS
RESTARTS = 30
#: as motion.jog's Cartesian jog
JOG_ITER = 40
#: how far each joint of a nearby start is off the answer (degrees, one sigma)
NEAR_DEG = 5.0
ROWS = (
    ("panda home", "panda", "home"),
    ("panda near", "panda", "near"),
    ("puma near", "puma560", "near"),
    ("puma home", "puma560", "home"),
)


def targets(robot, count: int) -> list[tuple[np.ndarray, np.ndarray, tuple[float, ...]]]:
    """(answer q, target pose, nearby start) per target, seeded."""
    rng = np.random.default_rng(7)
    out = []
    for _ in range(count):
        q = rng.uniform(robot.lower, robot.upper)
        near = np.clip(q + rng.normal(0.0, NEAR_DEG, robot.dof), robot.lower, robot.upper)
        out.append((q, robot.kinematics.pose(q), tuple(near.tolist())))
    return out


def verified(robot, target: np.ndarray, result) -> bool:
    """The solver says it succeeded, and an independent FK agrees."""
    if not result.success:
        return False
    q = np.array(result.q)
    if np.any(q < np.array(robot.lower)) or np.any(q > np.array(robot.upper)):
        return False
    pose = robot.kinematics.pose(result.q)
    position = np.linalg.norm(pose[:3, 3] - target[:3, 3])
    turn = np.linalg.norm(rotation_error(target[:3, :3], pose[:3, :3]))
    return position <= 2 * POSITION_TOL * reach(robot) and turn <= 2 * ORIENTATION_TOL


def run_row(robot, cases, mode: str, repeat: int) -> tuple[dict, list]:
    times, answers, good = [], [], 0
    for _, target, near in cases:
        if mode == "home":
            call = functools.partial(solve, robot, target, robot.home, restarts=RESTARTS)
        else:
            call = functools.partial(solve, robot, target, near, max_iter=JOG_ITER)
        best = float("inf")
        for _ in range(repeat):
            t = time.perf_counter()
            result = call()
            best = min(best, time.perf_counter() - t)
        times.append(best * 1e6)
        ok = verified(robot, target, result)
        ok = bool(ok)
        good += ok
        answers.append({"success": bool(result.success), "verified": ok, "q": list(result.q)})
    ordered = sorted(times)
    summary = {
        "median_us": statistics.median(ordered),
        "p95_us": ordered[min(len(ordered) - 1, int(0.95 * len(ordered)))],
        "success_percent": 100.0 * good / len(cases),
        "count": len(cases),
    }
    return summary, answers


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=500, help="targets per arm")
    parser.add_argument("--repeat", type=int, default=1, help="runs per target (fastest kept)")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")
    parser.add_argument("--dump", metavar="FILE", help="write every answer to FILE (JSON)")
    parser.add_argument("--rows", nargs="*", help="only these rows (e.g. 'panda home')")
    args = parser.parse_args()
    robots, cases, summary, dump = {}, {}, {}, {}
    for label, name, mode in ROWS:
        if args.rows and label not in args.rows:
            continue
        if name not in robots:
            robots[name] = load_robot(name)[0]
            cases[name] = targets(robots[name], args.count)
            for _, target, near in cases[name][:40]:  # warm up: compile the descents
                solve(robots[name], target, near, max_iter=JOG_ITER)
        summary[label], dump[label] = run_row(robots[name], cases[name], mode, args.repeat)
    if args.dump:
        with open(args.dump, "w") as f:
            json.dump(dump, f)
    if args.json:
        print(json.dumps(summary, indent=2))
        return
    print(f"{'row':12}{'median':>10}{'p95':>10}{'success':>10}")
    for label, r in summary.items():
        print(
            f"{label:12}{r['median_us']:>8.0f}us{r['p95_us']:>8.0f}us{r['success_percent']:>9.1f}%"
        )
    print("targets: panda home <= 160 / 314 us; panda near <= 58 us; puma near <= 46 us")


if __name__ == "__main__":
    main()

"""Programs: how long ``dhsim run`` takes (a benchmark, not a test).

    python bench/run.py [--repeat N]

* ``dhsim run puma560 demo`` at 100 Hz as a whole process (Python's start,
  the imports, loading the robot, sampling, the path check, the report):
  the median wall-clock time of N runs, and the CPU time the process took.
  Target: <= 0.5 s.
* A 60-second linear-heavy program on the Puma 560 (linear moves around the
  nominal pose, a short wait now and then) at 100 Hz, in-process: sampling
  with IK at every sample of every linear move, then the path check, then
  the CSV text. Target: sampling and check <= 2 s.

The machine may be shared: wall-clock times then include waiting for a
CPU, the CPU times do not.
"""

from __future__ import annotations

import argparse
import resource
import statistics
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

from dhsim_tui.core import load_robot
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.motion.path_check import check_path
from dhsim_tui.core.motion.trajectory import sample
from dhsim_tui.core.motion.trajectory_csv import csv_text

DHSIM = Path(sys.executable).with_name("dhsim")
#: the linear-heavy program's waypoints: bent elbow and wrist, well inside the limits
WAYPOINTS = (
    (0.0, 45.0, -180.0, 0.0, 45.0, 0.0),
    (0.0, 45.0, -135.0, 0.0, 45.0, 0.0),
    (-30.0, 40.0, -150.0, 0.0, 50.0, 0.0),
    (25.0, 55.0, -165.0, 15.0, 40.0, 20.0),
    (10.0, 35.0, -140.0, -10.0, 55.0, -15.0),
)
LENGTH = 60.0


def _cpu_children() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def whole_process(repeat: int) -> tuple[float, float, int]:
    """Median wall-clock and CPU seconds of ``dhsim run puma560 demo``, and its status."""
    walls, cpus, status = [], [], 0
    for _ in range(repeat):
        cpu = _cpu_children()
        began = time.perf_counter()
        done = subprocess.run([str(DHSIM), "run", "puma560", "demo"], capture_output=True)
        walls.append(time.perf_counter() - began)
        cpus.append(_cpu_children() - cpu)
        status = done.returncode
    return statistics.median(walls), statistics.median(cpus), status


def linear_heavy(robot):
    """Linear moves between WAYPOINTS (100 mm/s and 200 mm/s in turn), a 0.2 s
    wait after every fourth, round and round until the program lasts LENGTH s."""
    cycle = []
    for i, q in enumerate(WAYPOINTS[1:] + WAYPOINTS[:1]):
        cycle.append(Step("linear", q, speed=100.0 if i % 2 else 200.0))
        if i % 4 == 3:
            cycle.append(Step("wait", seconds=0.2))
    steps = [Step("joint", WAYPOINTS[0])]
    once = sample(replace(robot, programs=()), Program("cycle", (*steps, *cycle)), 10.0)
    lengths = [span.duration for span in once.spans[1:]]
    total = once.spans[0].duration
    while total < LENGTH:
        i = (len(steps) - 1) % len(cycle)
        steps.append(cycle[i])
        total += lengths[i]
    return Program("linear", tuple(steps))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7, help="runs of the whole process")
    args = parser.parse_args()

    wall, cpu, status = whole_process(args.repeat)
    print(f"{'dhsim run puma560 demo (100 Hz), whole process':<52}")
    print(f"  {'median wall clock':<48}{wall:>7.3f} s   <= 0.5 s")
    print(f"  {'median CPU (user + system)':<48}{cpu:>7.3f} s   (exit status {status})")

    robot, _ = load_robot("puma560")
    program = linear_heavy(robot)
    robot = replace(robot, programs=(program,))
    cpu = time.process_time()
    began = time.perf_counter()
    trajectory = sample(robot, program, 100.0)
    sampled = time.perf_counter()
    problems = check_path(trajectory)
    checked = time.perf_counter()
    text = csv_text(trajectory)
    written = time.perf_counter()
    cpu = time.process_time() - cpu
    linear = int((trajectory.move == "linear").sum())
    print(
        f"{'a linear-heavy program':<52}\n  {trajectory.duration:.1f} s, "
        f"{len(program.steps)} steps, {len(trajectory.time)} samples at 100 Hz, "
        f"{linear} of them in linear moves (IK each), {len(problems)} problems"
    )
    print(f"  {'sampling (IK at every linear sample)':<48}{sampled - began:>7.3f} s")
    print(f"  {'path check':<48}{checked - sampled:>7.3f} s")
    print(f"  {'sampling + check':<48}{checked - began:>7.3f} s   <= 2 s")
    print(f"  {f'CSV text ({len(text) / 1e6:.1f} MB)':<48}{written - checked:>7.3f} s")
    print(f"  {'CPU for all three':<48}{cpu:>7.3f} s")


if __name__ == "__main__":
    main()

"""``dhsim draw`` as a user runs it: the whole process, start to file
(a benchmark, not a test; issue 16's target: 1 s for every view as an SVG).

    python bench/draw.py [--runs 9] [--robot puma560] [--json]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--robot", default="puma560")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    dhsim = Path(sys.executable).parent / "dhsim"
    results = {}
    with tempfile.TemporaryDirectory() as folder:
        for suffix in ("svg", "txt"):
            times = []
            for run in range(args.runs):
                out = Path(folder) / f"{run}.{suffix}"
                start = time.perf_counter()
                subprocess.run(
                    [str(dhsim), "draw", args.robot, "--view", "all", "-o", str(out)],
                    check=True,
                    capture_output=True,
                )
                times.append(time.perf_counter() - start)
            results[suffix] = {
                "median_s": round(statistics.median(times), 3),
                "max_s": round(max(times), 3),
            }
    if args.json:
        print(json.dumps(results))
    else:
        for suffix, figures in results.items():
            print(
                f"dhsim draw {args.robot} --view all -o x.{suffix}: "
                f"median {figures['median_s']} s, at most {figures['max_s']} s"
            )


if __name__ == "__main__":
    main()

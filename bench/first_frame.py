"""Time to the simulator's first frame, one source tree against another, side
by side (a benchmark, not a test; issue 27's target: 0.5 s on an idle machine).

    python bench/first_frame.py [--runs 15] [--size 80x24] [--robot puma560]
                                [--bytecode] [--json] [TREE ...]

Each TREE is a folder holding a ``dhsim_tui`` package (default: this one);
``git archive HEAD | tar -x -C /tmp/old`` makes one of the last commit. The
runs alternate between the trees, so that a machine that gets busier or
quieter weighs on each alike. A run is a fresh interpreter, timed from its
start, through ``dhsim_tui.cli.main`` (what the ``dhsim`` command loads) and
the app, to the first frame Textual composes headless (``bench/latency.py``
measures it the same way). Also counts the modules of the closed-form IK
and its generated code loaded by then.

Without ``--bytecode`` Python compiles every module at each start (this
machine's environment sets ``PYTHONDONTWRITEBYTECODE=1``, as a source tree is
run); with it, each tree's bytecode is written once, under a folder of its
own in /tmp, as ``pip install .`` does.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

SCRIPT = """
import asyncio, sys, time
t0 = time.perf_counter()
import dhsim_tui, dhsim_tui.cli.main  # what the dhsim command loads before the app
from dhsim_tui.core import load_robot
from dhsim_tui.tui.app import DhsimApp
async def main():
    robot, path = load_robot({robot!r})
    app = DhsimApp(robot, path, "plotext")
    done = asyncio.Event()
    async with app.run_test(size={size!r}):
        original = app._display
        def display(screen, renderable):
            original(screen, renderable)
            if renderable is not None:
                done.set()
        app._display = display
        await asyncio.wait_for(done.wait(), 30)
        first = time.perf_counter() - t0
        closed = [m for m in sys.modules if m.startswith("dhsim_tui.core.ik.")
                  and m.rsplit(".", 1)[1] in {closed!r}]
    print(first, len(closed))
asyncio.run(main())
"""
#: the closed forms' modules (ik.analytic and what it imports) and the IK's
#: generated code (step_codegen, codegen_fold)
CLOSED_FORMS = (
    "step_codegen",
    "codegen_fold",
    "analytic",
    "geometry",
    "right_angle_wrist",
    "wrist",
    "parallel",
    "planar",
    "subproblems",
    "vectors",
    "labels",
)


def run(tree: Path, robot: str, size: tuple[int, int], bytecode: Path | None) -> tuple[float, int]:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    if bytecode is not None:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = str(bytecode)
    script = SCRIPT.format(robot=robot, size=size, closed=sorted(CLOSED_FORMS))
    script += f"assert dhsim_tui.__file__.startswith({str(tree)!r})\n"
    out = subprocess.run(  # from /: ``-c`` puts the working folder first on the path
        [sys.executable, "-c", script], capture_output=True, text=True, check=True, env=env, cwd="/"
    ).stdout.split()
    return float(out[0]), int(out[1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("trees", nargs="*", type=Path)
    parser.add_argument("--runs", type=int, default=15)
    parser.add_argument("--size", default="80x24")
    parser.add_argument("--robot", default="puma560")
    parser.add_argument("--bytecode", action="store_true", help="bytecode written once per tree")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    trees = [tree.resolve() for tree in args.trees] or [Path(__file__).resolve().parents[1]]
    size = tuple(int(v) for v in args.size.split("x"))
    times: dict[Path, list[float]] = {tree: [] for tree in trees}
    closed: dict[Path, int] = {}
    with tempfile.TemporaryDirectory() as folder:
        caches = {
            tree: Path(folder) / str(i) if args.bytecode else None for i, tree in enumerate(trees)
        }
        if args.bytecode:  # write each tree's bytecode before timing
            for tree in trees:
                run(tree, args.robot, size, caches[tree])
        for _ in range(args.runs):
            for tree in trees:
                first, closed[tree] = run(tree, args.robot, size, caches[tree])
                times[tree].append(first)
    results = {
        str(tree): {
            "median_s": round(statistics.median(t), 3),
            "min_s": round(min(t), 3),
            "max_s": round(max(t), 3),
            "closed_form_modules": closed[tree],
        }
        for tree, t in times.items()
    }
    if args.json:
        print(json.dumps({"size": args.size, "bytecode": args.bytecode, "trees": results}))
        return
    how = "bytecode written once" if args.bytecode else "compiled at every start"
    print(f"first frame, {args.robot} at {args.size}, {args.runs} runs each ({how}):")
    for tree, figures in results.items():
        print(
            f"  {tree}: median {figures['median_s']} s "
            f"({figures['min_s']}-{figures['max_s']} s), "
            f"{figures['closed_form_modules']} closed-form modules loaded"
        )


if __name__ == "__main__":
    main()

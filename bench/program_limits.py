"""Programs at the limits: how fast a program too long is refused and how
much memory the longest accepted ones take (a benchmark, not a test).

    python bench/program_limits.py [--skip-long]

* **Refusals**, in-process: loading a robot file whose program would take
  more than the hour (a linear move at 1e-3 mm/s was 829 MB before issue 26,
  1e-4 mm/s 5.7 GB), or has a speed under the floors (5e-324: a division by
  zero before). Each is refused while the file is read. Target: ≤ 0.2 s each.
* **The longest accepted programs**, each ``dhsim run`` as a whole process
  with ``--csv``: its peak resident memory (``ru_maxrss`` of the child) and
  wall time. A wait of nearly an hour, a joint move of nearly an hour, a
  linear move of nearly an hour (IK at every sample: slow, skipped with
  ``--skip-long``), and a 32-joint arm waiting nearly an hour. Target: ≤ 300 MB.
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.model.errors import DhsimError

DHSIM = Path(sys.executable).with_name("dhsim")
PUMA = Path(load_robot("puma560")[1])


def puma_with(programs: str) -> str:
    """The bundled Puma 560's file with ``programs`` as its [programs] table."""
    text = PUMA.read_text(encoding="utf-8")
    return re.sub(r"\[programs\].*?\n\]\n", programs, text, flags=re.S)


UP = '{ move = "linear", to = [0, 45, -135, 0, 45, 0], speed = '
REFUSED = {
    "linear move at 1e-3 mm/s": UP + "1e-3 }",
    "linear move at 1e-4 mm/s": UP + "1e-4 }",
    "linear move at 5e-324 mm/s": UP + "5e-324 }",
    "joint move at 5e-324 %": '{ move = "joint", to = "qn", speed = 5e-324 }',
    "waits of 3,000 + 700 s": "{ wait = 3000 }, { wait = 700 }",
}

LONG = {
    "wait of 3,599 s": "{ wait = 3599 }",
    "joint move of 3,333 s": '{ move = "joint", to = "qn", speed = 0.06 }',
    "linear move of 3,308 s": '{ move = "joint", to = "qn" }, '
    '{ move = "linear", to = [0, 45, -135, 0, 45, 0], speed = 0.1 }',
}


def snake(step: str) -> str:
    """A 32-joint arm (the most a robot file may have) with ``step``, and a
    pose ``far`` (every joint at 30 degrees)."""
    rows = "".join(
        f'\n[[joints]]\ntype = "revolute"\ntheta = 0.0\nd = 0.0\na = 10.0\n'
        f"alpha = {90.0 if i % 2 else 0.0}\nmin = -170.0\nmax = 170.0\n"
        for i in range(32)
    )
    far = ", ".join(["30.0"] * 32)
    head = f'name = "snake"\nunits = "mm"\n[poses]\nfar = [{far}]\n[programs]\np = [ {step} ]\n'
    return head + rows


def refusals(folder: Path) -> None:
    print("refusals (in-process, loading the file):")
    for what, step in REFUSED.items():
        path = folder / "refused.toml"
        path.write_text(puma_with(f"[programs]\np = [ {step} ]\n"), encoding="utf-8")
        began = time.perf_counter()
        try:
            load_robot(str(path))
        except DhsimError as exc:
            took = time.perf_counter() - began
            print(f"  {what}: refused in {took * 1000:.1f} ms: {str(exc)[-90:]}")
        else:
            print(f"  {what}: NOT refused")


def long_programs(folder: Path, skip_long: bool) -> None:
    print("the longest accepted programs (dhsim run --csv, a whole process each):")
    cases = [(what, puma_with(f"[programs]\np = [ {step} ]\n")) for what, step in LONG.items()]
    cases.append(("32 joints waiting 3,599 s", snake("{ wait = 3599 }")))
    cases.append(
        (
            "32 joints, a joint move of 3,333 s",
            snake('{ move = "joint", to = "far", speed = 0.01 }'),
        )
    )
    for what, text in cases:
        if skip_long and what.startswith("linear"):
            continue
        path = folder / "long.toml"
        path.write_text(text, encoding="utf-8")
        # each in its own process, so ru_maxrss is this run's alone
        code = (
            "import resource, subprocess, sys; "
            "subprocess.run(sys.argv[1:], capture_output=True); "
            "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)"
        )
        command = [str(DHSIM), "run", str(path), "p", "--csv", str(folder / "out.csv"), "--force"]
        began = time.perf_counter()
        done = subprocess.run(
            [sys.executable, "-c", code, *command], capture_output=True, text=True, check=True
        )
        took = time.perf_counter() - began
        rows = sum(1 for _ in (folder / "out.csv").open(encoding="utf-8")) - 2
        print(f"  {what}: {int(done.stdout) / 1024:.0f} MB peak, {took:.1f} s, {rows:,} CSV rows")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--skip-long", action="store_true", help="skip the hour of IK")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        refusals(folder)
        long_programs(folder, args.skip_long)


if __name__ == "__main__":
    main()

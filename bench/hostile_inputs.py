"""Hostile files: how long a refusal takes (a benchmark, not a test).

    python bench/hostile_inputs.py [--runs 3] [--only TEXT] [--json]

Builds the files of ``tests/cli/test_hostile_files.py`` (robot files whose
one key or table header has 100,000 dotted parts), of
``tests/cli/test_hostile_counts.py`` (25,000 table headers of 16 parts,
40,000 poses, an 800 KB multi-line string) and of
``tests/core/test_import_limits.py`` and ``tests/core/test_urdf.py``
(CSV and URDF files built to waste time and memory) in a temporary folder,
and times each refusal in a fresh interpreter, as the tests measure its
memory:

* a robot file: ``dhsim check FILE`` (``cli.main.main``), opening it as the
  simulator and the editor do (``load_with_stamp``), and saving the Puma 560
  over it (a save reads the file it replaces). Target: <= 0.2 s each (the
  issue's bound; tomllib took 42 s on the first file).
* an import: ``import_file(FILE)``. Target: <= 1 s (<= 0.5 s for the first
  bad cell of a long CSV); a careless reader took 15 s and 718 MB.
* memory, for both: the growth of the peak resident size (``ru_maxrss``)
  over the step. Target: <= 100 MB.
* a command line of 30,000 unknown options (``tests/cli/test_hostile_cli.py``):
  ``cli.main.main``. Target: <= 0.2 s (argparse took 61 s and printed 150 KB).

Prints the median wall-clock time of N runs, the median CPU time (the
machine may be shared: wall-clock time then includes waiting for a CPU, CPU
time does not) and the largest memory growth of the N runs. The tests check
the outcome (refused, in one line, in little memory); only this script
looks at the clock.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from dhsim_tui.core.files.tomlparse import MAX_KEY_PARTS
from dhsim_tui.core.interop.csv_import import MAX_CSV_BYTES, MAX_POSES

ROOT = Path(__file__).resolve().parents[1]
ROBOT_SECONDS = 0.2
IMPORT_SECONDS = 1.0
MEGABYTES = 100.0

ROBOT_CHILD = """
import contextlib, io, json, resource, sys, time
from pathlib import Path
from dhsim_tui.cli.main import main
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.files.robotfile import RobotFileError, load_with_stamp, save

def rss():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux

with contextlib.redirect_stdout(io.StringIO()):
    main(["check", "puma560"])  # warm: whatever loads on first use is loaded
puma, _ = load_robot("puma560")
path = Path(sys.argv[1])

def check():
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = main(["check", str(path)])
    return "refused" if code == 2 and len(err.getvalue().strip().splitlines()) == 1 else "CHECKED"

def opened():
    try:
        load_with_stamp(path)
    except RobotFileError:
        return "refused"
    return "LOADED"

def saved():
    save(puma, path)
    return "saved"

steps = []
for step, call in (("check", check), ("open", opened), ("save over", saved)):
    before = rss()
    wall, cpu = time.perf_counter(), time.process_time()
    outcome = call()
    steps.append({
        "step": step, "outcome": outcome,
        "seconds": time.perf_counter() - wall, "cpu": time.process_time() - cpu,
        "megabytes": (rss() - before) / 1024,
    })
print(json.dumps(steps))
"""

CLI_CHILD = """
import contextlib, io, json, resource, sys, time
from dhsim_tui.cli.main import main

argv = ["fk", "puma560", *(f"--option{i}" for i in range(30_000))]
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
wall, cpu = time.perf_counter(), time.process_time()
err = io.StringIO()
with contextlib.redirect_stderr(err):
    code = main(argv)
short = code == 2 and len(err.getvalue()) < 300
print(json.dumps([{
    "step": "parse", "outcome": "refused" if short else "LONG MESSAGE",
    "seconds": time.perf_counter() - wall, "cpu": time.process_time() - cpu,
    "megabytes": (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) / 1024,
}]))
"""

IMPORT_CHILD = """
import json, resource, sys, time
from dhsim_tui.core.interop.importer import import_file
from dhsim_tui.core.model.errors import DhsimError

before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
wall, cpu = time.perf_counter(), time.process_time()
try:
    import_file(sys.argv[1])
    outcome = "IMPORTED"
except DhsimError as exc:
    message = str(exc)
    outcome = "refused" if "\\n" not in message and len(message) < 400 else "LONG MESSAGE"
print(json.dumps([{
    "step": "import", "outcome": outcome,
    "seconds": time.perf_counter() - wall, "cpu": time.process_time() - cpu,
    "megabytes": (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) / 1024,
}]))
"""


# -- the files (as the tests build them) -------------------------------------------------

PARTS = 100_000
ROBOT_FILES = {
    "key.toml": 'name = "n"\n' + ".".join(["a"] * PARTS) + " = 1\n",
    "header.toml": 'name = "n"\n[' + ".".join(["a"] * PARTS) + "]\n",
    "array-header.toml": 'name = "n"\n[[' + ".".join(["a"] * PARTS) + "]]\n",
    # test_hostile_counts.py's: counts no robot needs, each file under 1 MB
    "wide-headers.toml": 'name = "n"\n'
    + "".join(f"[h{i}" + ".a" * 15 + "]\n" for i in range(25_000)),
    "poses.toml": 'name = "n"\n[poses]\n'
    + "".join(f"p{i} = [0]\n" for i in range(40_000))
    + "[[joints]]\ntheta = 0\nd = 0\na = 100\nalpha = 0\n",
    "string.toml": 'name = """' + ("x" * 70 + "\n") * 11_000 + '"""\n',
}
assert PARTS > MAX_KEY_PARTS


def _chain_of(links: int, origin: str = "0.1 0 0") -> str:
    declared = "".join(f'<link name="l{i}"/>' for i in range(links))
    joints = "".join(
        f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
        f'<origin xyz="{origin}"/><axis xyz="0 0 1"/><limit lower="-1" upper="1"/></joint>'
        for i in range(1, links)
    )
    return f'<robot name="big">{declared}{joints}</robot>'


def _entity_bomb() -> str:
    entities = '<!ENTITY a "aaaaaaaaaa">' + "".join(
        f'<!ENTITY {b} "&{a};&{a};&{a};&{a};&{a};&{a};&{a};&{a};&{a};&{a};">'
        for a, b in zip("abcdefgh", "bcdefghi", strict=True)
    )
    return f'<?xml version="1.0"?>\n<!DOCTYPE robot [{entities}]>\n<robot name="&i;"/>'


def _sparse(path: Path, size: int) -> None:
    with path.open("wb") as handle:
        handle.truncate(size)  # sparse: its size is what counts


CSV_HEAD = "theta,d,a,alpha\n"
#: test_import_limits.py's hostile CSV lines (each one row of the table)
CSV_LINES = {
    "csv: 10,001 named poses": "".join(f'# pose "p{i}" = 0\n' for i in range(MAX_POSES + 1)),
    "csv: a pose of 100,001 values": '# pose "wide" = ' + "0, " * 100_000 + "0\n" + CSV_HEAD,
    "csv: base_xyz of 100,001 values": "# base_xyz = " + "1, " * 100_000 + "1\n",
    "csv: a 150,000-character cell": CSV_HEAD + "0,0," + "1" * 150_000 + ",0\n",
    "csv: a 50,000-digit number": CSV_HEAD + "0,0," + "7" * 50_000 + ",0\n",
    "csv: a 50,000-character bad cell": CSV_HEAD + "0,0,0,0\n0,0," + "x" * 50_000 + ",0\n",
    "csv: a 50,000-character type": "type,theta,d,a,alpha\n" + "Q" * 50_000 + ",0,0,0,0\n",
    "csv: a 50,000-character column": "theta,d,a,alpha," + "z" * 50_000 + "\n",
    "csv: a 50,000-character unit": "theta (" + "g" * 50_000 + "),d,a,alpha\n0,0,0,0\n",
    "csv: a 50,000-character pose name": '# pose "' + "n" * 50_000 + '" = x\n' + CSV_HEAD,
    "csv: a 50,000-character base_z": "# base_z = " + "f" * 50_000 + "\n" + CSV_HEAD + "0,0,0,0\n",
    "csv: a 50,000-character units": "# units = " + "u" * 50_000 + "\n" + CSV_HEAD + "0,0,0,0\n",
    "csv: a 5,000-character pose name": '# pose "'
    + "p" * 5_000
    + '" = 1, 2\n'
    + CSV_HEAD
    + "0,0,0,0\n",
}


@dataclass(frozen=True)
class Case:
    name: str
    file: str
    build: Callable[[Path], None]
    seconds: float
    child: str = IMPORT_CHILD


def _text(text: str) -> Callable[[Path], None]:
    return lambda path: path.write_text(text, encoding="utf-8")


def cases() -> list[Case]:
    robot = [
        Case(name, name, _text(text), ROBOT_SECONDS, ROBOT_CHILD)
        for name, text in ROBOT_FILES.items()
    ]
    rows = (MAX_CSV_BYTES - 100) // 8
    imports = [
        Case(
            "csv: 1,000,000 rows (8 MB)",
            "million.csv",
            _text(CSV_HEAD + "0,0,0,0\n" * 1_000_000),
            IMPORT_SECONDS,
        ),
        Case(
            f"csv: {rows:,} rows, just under the cap",
            "long.csv",
            _text(CSV_HEAD + "0,0,0,0\n" * rows),
            IMPORT_SECONDS,
        ),
        Case(
            "csv: a bad cell, then 200,000 rows",
            "bad-cell.csv",
            _text(CSV_HEAD + "0,0,x,0\n" + "0,0,0,0\n" * 200_000),
            0.5,
        ),
        *(
            Case(name, f"line{i}.csv", _text(text), IMPORT_SECONDS)
            for i, (name, text) in enumerate(CSV_LINES.items())
        ),
        Case("urdf: 10,000 links", "links.urdf", _text(_chain_of(10_000)), IMPORT_SECONDS),
        Case(
            "urdf: 50 MB (sparse)", "fifty.urdf", lambda p: _sparse(p, 50_000_000), IMPORT_SECONDS
        ),
        Case(
            "urdf: 900,000 elements",
            "nodes.urdf",
            _text('<robot name="r"><link name="a">' + "<b/>" * 900_000 + "</link></robot>"),
            IMPORT_SECONDS,
        ),
        Case(
            "urdf: 350,000 attributes",
            "attributes.urdf",
            _text(
                '<robot name="r"><link name="a" '
                + " ".join(f'a{i}=""' for i in range(350_000))
                + "/></robot>"
            ),
            IMPORT_SECONDS,
        ),
        Case(
            "urdf: nested 300,000 deep",
            "deep.urdf",
            _text('<robot name="r">' + "<a>" * 300_000 + "</a>" * 300_000 + "</robot>"),
            IMPORT_SECONDS,
        ),
        Case(
            "urdf: 899 moving joints, nan origins",
            "joints.urdf",
            _text(_chain_of(900, "nan 0 0")),
            IMPORT_SECONDS,
        ),
        Case("urdf: entity bomb (10**9 a's)", "bomb.urdf", _text(_entity_bomb()), IMPORT_SECONDS),
    ]
    cli = [Case("cli: 30,000 unknown options", "none", lambda path: None, ROBOT_SECONDS, CLI_CHILD)]
    return robot + imports + cli


# -- measuring ---------------------------------------------------------------------------


def run_once(case: Case, folder: Path) -> list[dict]:
    """Build the case's file afresh (a save replaces it) and refuse it in a new interpreter."""
    path = folder / case.file
    case.build(path)
    done = subprocess.run(
        [sys.executable, "-c", case.child, str(path)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=False,
    )
    if done.returncode != 0:
        raise SystemExit(f"{case.name}: the child failed:\n{done.stderr[-2000:]}")
    return json.loads(done.stdout)


def measure(case: Case, folder: Path, runs: int) -> list[dict]:
    """One row per step: median wall and CPU seconds, largest growth, outcome, verdict."""
    by_run = [run_once(case, folder) for _ in range(runs)]
    rows = []
    for index, first in enumerate(by_run[0]):
        steps = [run[index] for run in by_run]
        seconds = statistics.median(s["seconds"] for s in steps)
        megabytes = max(s["megabytes"] for s in steps)
        outcomes = sorted({s["outcome"] for s in steps})
        expected = "saved" if first["step"] == "save over" else "refused"
        met = seconds <= case.seconds and megabytes <= MEGABYTES and outcomes == [expected]
        rows.append(
            {
                "case": case.name
                if case.child in (IMPORT_CHILD, CLI_CHILD)
                else f"{case.name}: {first['step']}",
                "outcome": "/".join(outcomes),
                "seconds": round(seconds, 4),
                "cpu": round(statistics.median(s["cpu"] for s in steps), 4),
                "megabytes": round(megabytes, 1),
                "target_seconds": case.seconds,
                "target_megabytes": MEGABYTES,
                "met": met,
            }
        )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="fresh interpreters per case")
    parser.add_argument("--only", default="", help="the cases whose name holds this text")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    rows = []
    if not args.json:
        print(
            f"{'case':<44}{'outcome':>9}{'wall s':>9}{'CPU s':>8}{'MB':>7}{'target':>16}  verdict"
        )
    with tempfile.TemporaryDirectory(prefix="dhsim-hostile-") as folder:
        for case in (c for c in cases() if args.only in c.name):
            measured = measure(case, Path(folder), args.runs)
            rows.extend(measured)
            if not args.json:
                for row in measured:
                    _print_row(row)
    if args.json:
        print(json.dumps(rows, indent=1))
        return
    missed = [row["case"] for row in rows if not row["met"]]
    print(f"\n{len(rows) - len(missed)} of {len(rows)} targets met (median of {args.runs} runs)")
    for name in missed:
        print(f"  NOT met: {name}")


def _print_row(row: dict) -> None:
    target = f"{row['target_seconds']:g} s, {row['target_megabytes']:g} MB"
    print(
        f"{row['case']:<44}{row['outcome']:>9}{row['seconds']:>9.3f}{row['cpu']:>8.3f}"
        f"{row['megabytes']:>7.1f}{target:>16}  {'met' if row['met'] else 'NOT met'}",
        flush=True,
    )


if __name__ == "__main__":
    main()

"""A key-and-mouse monkey for the real ``dhsim`` in a pseudo-terminal.

    python bench/monkey.py [--sequences 1000] [--seed 1] [--per-process 25] [--json]
    python bench/monkey.py --palette-bursts 100

Each sequence is a burst of 10-60 random events, keys and xterm SGR mouse
reports (clicks, double clicks, drags, the wheel, anywhere on the screen),
0-50 ms apart, typed into the simulator or the editor of a copy of a robot
file; then ``escape`` until the screen is back where it started. The same
process takes ``--per-process`` sequences, and then is asked to quit (any
unsaved change discarded). After every process:

* nothing on the screen or in the bytes written is a traceback;
* it answered (its screen still changes when keys come) and quit when asked;
* the robot file is a valid robot file and no temporary file is left.

``--palette-bursts N`` runs the fault campaign's crash N times: ``ctrl+p``
and then, 0-50 ms later, ``s``, ``x``, backspace or ``escape`` (or another
``ctrl+p``), in the editor. ``tests/pty/test_monkey.py`` runs a short campaign of
both; this script is the long one, whose figures the README gives.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import json
import os
import random
import shutil
import signal
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))

from pty_screen import PtyScreen  # noqa: E402

from dhsim_tui.core import load, load_robot  # noqa: E402
from dhsim_tui.core.model.errors import DhsimError  # noqa: E402

#: the keys a sequence draws from: the simulator's and the editor's, and typing
KEYS = [
    "\x1b[A", "\x1b[B", "\x1b[C", "\x1b[D", "\x1b[1;2C", "\x1b[1;2D",
    "[", "]", "\r", "\t", "\x1b", "\x7f", "h", "p", "v", "c", "f", "b", "m", "z", "F",
    "x", "1", "2", "3", "4", "+", "-", "0", "a", "d", "w", "s", "W", "P", "?", "e",
    "t", "S", "\x10", "\x13", "\x1a", "\x19", "\x0f", "5", ".", ",", "q",
    "g", "R", "L", " ", "n", "l", "\x1b[1;5A", "\x1b[1;5B",  # programs
]  # fmt: skip
#: what a burst answers a dialog's question with
TEXT = list("0123456789.-, abcxyz")
#: sizes a process runs at (columns, rows)
SIZES = [(80, 24), (120, 36), (100, 30)]


@dataclass
class Report:
    sequences: int = 0
    events: int = 0
    mouse_events: int = 0
    processes: int = 0
    tracebacks: list[str] = field(default_factory=list)
    hangs: list[str] = field(default_factory=list)
    damaged: list[str] = field(default_factory=list)
    seconds: float = 0.0

    @property
    def clean(self) -> bool:
        return not (self.tracebacks or self.hangs or self.damaged)

    def as_dict(self) -> dict:
        return {
            "sequences": self.sequences,
            "events": self.events,
            "mouse_events": self.mouse_events,
            "processes": self.processes,
            "tracebacks": len(self.tracebacks),
            "hangs": len(self.hangs),
            "damaged_files": len(self.damaged),
            "seconds": round(self.seconds, 1),
        }


def _mouse(rng: random.Random, size: tuple[int, int]) -> list[str]:
    """One gesture as xterm SGR reports (1-based columns and rows)."""
    cols, rows = size
    x, y = rng.randint(1, cols), rng.randint(1, rows)
    kind = rng.choice(["click", "click", "double", "drag", "wheel_up", "wheel_down", "right"])
    if kind in ("wheel_up", "wheel_down"):
        return [f"\x1b[<{64 if kind == 'wheel_up' else 65};{x};{y}M"] * rng.randint(1, 4)
    if kind == "right":
        return [f"\x1b[<2;{x};{y}M", f"\x1b[<2;{x};{y}m"]
    press, release = f"\x1b[<0;{x};{y}M", f"\x1b[<0;{x};{y}m"
    if kind == "click":
        return [press, release]
    if kind == "double":
        return [press, release, press, release]
    path = []
    for _ in range(rng.randint(2, 12)):
        x = min(cols, max(1, x + rng.randint(-3, 3)))
        y = min(rows, max(1, y + rng.randint(-1, 1)))
        path.append(f"\x1b[<32;{x};{y}M")
    return [press, *path, f"\x1b[<0;{x};{y}m"]


def _sequence(rng: random.Random, size: tuple[int, int]) -> list[tuple[str, bool]]:
    """(bytes to send, is it a mouse report) for one burst."""
    out: list[tuple[str, bool]] = []
    for _ in range(rng.randint(10, 60)):
        roll = rng.random()
        if roll < 0.35:
            out.extend((report, True) for report in _mouse(rng, size))
        elif roll < 0.45:
            out.append((rng.choice(TEXT), False))
        else:
            out.append((rng.choice(KEYS), False))
    return out


#: the last events written, with when (s since the process started), for a hang's report
SENT: collections.deque[tuple[float, str]] = collections.deque(maxlen=120)


def _write(screen: PtyScreen, data: str) -> bool:
    SENT.append((time.monotonic(), data))
    try:
        screen.proc.write(data.encode())
        return True
    except OSError:
        return False


def _traceback(screen: PtyScreen) -> str | None:
    text = screen.screen_text()
    raw = screen.raw_bytes().decode("utf-8", "replace")
    for where in (text, raw):
        for word in ("Traceback", "Error: ", "locals ─"):
            if word in where:
                at = where.index(word)
                return where[max(0, at - 300) : at + 300]
    return None


#: how long (s) dhsim may take to answer a key, quit, or start before the
#: monkey calls it hung; the tests pass their own HANG (a busy machine must
#: not make a hang of a slow answer)
PATIENCE = 4.0


def _responds(screen: PtyScreen, patience: float = PATIENCE) -> bool:
    """The app still answers keys: one of ``?`` (help) and ``escape`` (out
    of a dialog, or leaving the editor, which asks) changes the screen,
    whatever state the burst left it in."""
    time.sleep(0.3)
    for key in ("?", "\x1b", "?", "\x1b", "\x1b"):
        before = screen.screen_text()
        _write(screen, key)
        deadline = time.monotonic() + patience
        while time.monotonic() < deadline:
            if not screen.proc.isalive() or screen.screen_text() != before:
                for _ in range(2):
                    _write(screen, "\x1b")
                    time.sleep(0.1)
                return True
            time.sleep(0.05)
    return False


def _stacks(screen: PtyScreen) -> str:
    """What a hung dhsim was doing: its screen, and every thread's stack
    (SIGABRT, which faulthandler answers: PYTHONFAULTHANDLER is set)."""
    shown = screen.screen_text()
    if screen.proc.isalive():
        with contextlib.suppress(OSError):
            os.kill(screen.proc.pid, signal.SIGABRT)
        time.sleep(1.0)
    tail = bytes(screen.raw[-6000:]).decode("utf-8", "replace")
    start = SENT[0][0] if SENT else 0.0
    sent = " ".join(f"{at - start:.2f}:{data!r}" for at, data in SENT)
    return f"{shown}\n-- the last events sent:\n{sent}\n-- the last bytes it wrote:\n{tail}"


def _quit(screen: PtyScreen, patience: float = PATIENCE) -> bool:
    """escape out of everything, ctrl+q, discard: True once it has exited."""
    for _ in range(6):
        if not screen.proc.isalive():
            return True
        for data in ("\x1b", "\x1b", "\x1b", "\x11"):
            _write(screen, data)
            time.sleep(0.15)
        time.sleep(0.4)
        text = screen.screen_text()
        if "discard" in text.lower():
            _write(screen, "d")
            time.sleep(0.5)
    deadline = time.monotonic() + patience + 1
    while screen.proc.isalive() and time.monotonic() < deadline:
        time.sleep(0.05)
    return not screen.proc.isalive()


def _check_folder(folder: Path, report: Report, what: str) -> None:
    for file in folder.rglob("*"):
        if file.name.endswith(".tmp"):
            report.damaged.append(f"{what}: temporary file left: {file}")
        if file.suffix == ".toml" and "recovery" not in file.parts:
            try:
                load(file)
            except DhsimError as exc:
                report.damaged.append(f"{what}: {file.name} no longer loads: {exc}")


def run_monkey(
    sequences: int,
    seed: int = 1,
    per_process: int = 25,
    log=lambda line: None,
    patience: float = PATIENCE,
) -> Report:
    rng = random.Random(seed)
    report = Report()
    start = time.monotonic()
    robot_file = load_robot("puma560")[1]
    done = 0
    logged: set[str] = set()
    while done < sequences:
        folder = Path(tempfile.mkdtemp(prefix="dhsim-monkey-"))
        (folder / "robots").mkdir()
        shutil.copy(robot_file, folder / "robots" / "arm.toml")
        size = rng.choice(SIZES)
        args = rng.choice([["robots/arm.toml"], ["edit", "robots/arm.toml"], []])
        env = {"DHSIM_RECOVERY_DIR": str(folder / "recovery"), "PYTHONFAULTHANDLER": "1"}
        env.update(rng.choice([{}, {"TERM": "xterm"}, {"NO_COLOR": "1"}, {"LC_ALL": "C"}]))
        what = f"process {report.processes + 1} ({' '.join(args) or 'dhsim'}, {size}, {env})"
        screen = PtyScreen(args, size=size, env=env, cwd=folder)
        report.processes += 1
        try:
            screen.wait_for(
                lambda text: "Th1" in text or "theta" in text, timeout=max(30, patience)
            )
            for _ in range(min(per_process, sequences - done)):
                for data, mouse in _sequence(rng, size):
                    if not _write(screen, data):
                        break
                    report.events += 1
                    report.mouse_events += mouse
                    time.sleep(rng.uniform(0, 0.05))
                done += 1
                report.sequences += 1
                time.sleep(0.3)
                found = _traceback(screen)
                if found:
                    report.tracebacks.append(f"{what}: {found}")
                    break
                if not screen.proc.isalive():
                    break  # it quit (q answered "discard"): a new process
                if not _responds(screen, patience):
                    report.hangs.append(f"{what}: no redraw after a key:\n{_stacks(screen)}")
                    break
            if screen.proc.isalive() and not _quit(screen, patience):
                report.hangs.append(f"{what}: did not quit when asked:\n{_stacks(screen)}")
            found = _traceback(screen)
            if found and f"{what}: {found}" not in report.tracebacks:
                report.tracebacks.append(f"{what}: {found}")
        finally:
            screen.close()
            _check_folder(folder, report, what)
            for crash in sorted(folder.glob("crash-*.txt")):  # the traceback dhsim kept
                report.tracebacks.append(f"{what}: {crash.name}:\n{crash.read_text()}")
            shutil.rmtree(folder, ignore_errors=True)
        for line in report.tracebacks + report.hangs + report.damaged:
            if line not in logged:  # as soon as it is found: a long run may be stopped
                logged.add(line)
                log(f"-- {line}")
        log(f"{done}/{sequences} sequences, {report.events} events, {len(report.tracebacks)} "
            f"tracebacks, {len(report.hangs)} hangs, {len(report.damaged)} damaged")  # fmt: skip
    report.seconds = time.monotonic() - start
    return report


def palette_bursts(
    runs: int, seed: int = 2, log=lambda line: None, patience: float = PATIENCE
) -> Report:
    """ctrl+p and, 0-50 ms later, another key, in the editor; ``runs`` times."""
    rng = random.Random(seed)
    report = Report()
    start = time.monotonic()
    robot_file = load_robot("puma560")[1]
    folder = Path(tempfile.mkdtemp(prefix="dhsim-palette-"))
    shutil.copy(robot_file, folder / "arm.toml")
    screen = None
    try:
        for run in range(runs):
            if screen is None or not screen.proc.isalive():
                if screen is not None:
                    screen.close()
                screen = PtyScreen(
                    ["edit", "arm.toml"],
                    size=(80, 24),
                    env={"DHSIM_RECOVERY_DIR": str(folder / "recovery")},
                    cwd=folder,
                )
                report.processes += 1
                screen.wait_for("theta", timeout=max(30, patience))
            follow = rng.choice(["s", "x", "\x7f", "\x1b", "\x10", "\x1b\x10"])
            _write(screen, "\x10")
            time.sleep(rng.uniform(0, 0.05))
            _write(screen, follow)
            report.events += 2
            report.sequences += 1
            time.sleep(0.25)
            found = _traceback(screen)
            if found:
                report.tracebacks.append(f"burst {run + 1} ({follow!r}): {found}")
                screen.close()
                screen = None
                continue
            for _ in range(3):
                _write(screen, "\x1b")
                time.sleep(0.08)
            if not _responds(screen, patience):
                report.hangs.append(f"burst {run + 1}: no redraw after a key")
            log(f"{run + 1}/{runs} bursts, {len(report.tracebacks)} tracebacks")
        if screen is not None and screen.proc.isalive() and not _quit(screen, patience):
            report.hangs.append("did not quit when asked")
    finally:
        if screen is not None:
            screen.close()
        _check_folder(folder, report, "palette bursts")
        shutil.rmtree(folder, ignore_errors=True)
    report.seconds = time.monotonic() - start
    return report


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sequences", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--per-process", type=int, default=25)
    parser.add_argument("--palette-bursts", type=int, default=0)
    parser.add_argument("--patience", type=float, default=PATIENCE, help="seconds before a hang")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    log = (lambda line: None) if args.json else (lambda line: print(line, flush=True))
    if args.palette_bursts:
        report = palette_bursts(args.palette_bursts, args.seed, log, args.patience)
    else:
        report = run_monkey(args.sequences, args.seed, args.per_process, log, args.patience)
    if args.json:
        print(json.dumps(report.as_dict()))
    else:
        print(json.dumps(report.as_dict(), indent=2))
        for line in report.tracebacks + report.hangs + report.damaged:
            print("--", line)
    sys.exit(0 if report.clean else 1)


if __name__ == "__main__":
    main()

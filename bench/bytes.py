"""Bytes written to the terminal per joint step (a benchmark, not a test).

    python bench/bytes.py [--size 80x24] [--presses 40] [--term xterm-256color]
                          [--env K=V ...] [--robot puma560] [--json]

Spawns the real ``dhsim`` (the console script beside this interpreter) in a
pseudo-terminal of the given size (default: 80x24, then 160x48) with
TERM=xterm-256color, waits for the first frame to settle, then presses
``right`` (one joint step of the selected joint) ``--presses`` times, going
back with ``left`` after every 20 so no limit is hit, and lets the output
settle after each key. Every byte read from the terminal after a key counts
for that step.

The breakdown splits the bytes by kind (SGR colour/attribute codes, cursor
moves including newlines, other control sequences such as synchronized-update
markers, printable text in UTF-8) and by where they land on the screen: the
views (right of the side panel), the side panel (joints, pose, status), the
footer (last row). A cursor move ``ESC[y;xH`` sets where the following bytes
land, up to the next move (Textual writes one move per widget per line).

The colour system follows the environment, as it would for a user: with
TERM=xterm-256color and no COLORTERM, Rich uses 256 colours. Pass
``--env COLORTERM=truecolor`` for 24-bit colour, ``--term xterm`` for 16.
COLORTERM is not inherited from the shell running the bench, so the figures
don't depend on it.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import select
import shutil
import statistics
import sys
import threading
import time
from pathlib import Path

import pyte
from ptyprocess import PtyProcess

#: output counts as settled when nothing more arrived for this long
QUIET = 0.3
#: how long to wait for the first frame / for a key's output at most
FIRST_TIMEOUT = 20.0
KEY_TIMEOUT = 5.0
KEYS = {"right": b"\x1b[C", "left": b"\x1b[D"}

SGR = re.compile(rb"\x1b\[[0-9;:]*m")
MOVE = re.compile(rb"\x1b\[(\d*)(?:;(\d*))?H")
CURSOR = re.compile(rb"\x1b\[\d*(?:;\d*)?[HfABCDEFGd]|\n|\r")
OTHER = re.compile(
    rb"\x1b\[[?<>=!]?[0-9;:]*[ -/]*[@-~]|\x1b[@-Z\\-_]|\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)"
)
TOKEN = re.compile(SGR.pattern + b"|" + CURSOR.pattern + b"|" + OTHER.pattern)


def dhsim_command() -> str:
    beside = Path(sys.executable).parent / "dhsim"
    if beside.exists():
        return str(beside)
    found = shutil.which("dhsim")
    if found is None:
        raise SystemExit("the dhsim console script is not installed (pip install -e .)")
    return found


class Terminal:
    """``dhsim`` in a pseudo-terminal; a thread reads everything it writes."""

    def __init__(self, args: list[str], size: tuple[int, int], env: dict[str, str]) -> None:
        columns, rows = size
        full_env = dict(os.environ)
        full_env.pop("COLORTERM", None)
        full_env.pop("TEXTUAL_ALLOW_SIGNALS", None)
        full_env.update({"COLUMNS": str(columns), "LINES": str(rows)})
        full_env.update(env)
        self.screen = pyte.Screen(columns, rows)
        self._stream = pyte.ByteStream(self.screen)
        self._lock = threading.Lock()
        self.raw = bytearray()
        self.last_read = time.monotonic()
        self._stop = threading.Event()
        self.proc = PtyProcess.spawn(
            [dhsim_command(), *args], env=full_env, dimensions=(rows, columns)
        )
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        while not self._stop.is_set():
            try:
                ready, _, _ = select.select([self.proc.fd], [], [], 0.02)
                if not ready:
                    continue
                data = self.proc.read(65536)
            except (EOFError, OSError, ValueError):
                return
            with self._lock:
                self.raw.extend(data)
                self._stream.feed(data)
                self.last_read = time.monotonic()

    def size_read(self) -> int:
        with self._lock:
            return len(self.raw)

    def settle(self, since: int, timeout: float) -> None:
        """Wait until bytes beyond ``since`` arrived and then nothing for QUIET."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            with self._lock:
                grown, last = len(self.raw) > since, self.last_read
            if grown and time.monotonic() - last >= QUIET:
                return
            time.sleep(0.01)
        if not self.proc.isalive():
            raise SystemExit(f"dhsim exited; the screen:\n{self.text()}")

    def text(self) -> str:
        with self._lock:
            return "\n".join(line.rstrip() for line in self.screen.display)

    def send(self, key: str) -> None:
        self.proc.write(KEYS[key])

    def close(self) -> None:
        self._stop.set()
        if self.proc.isalive():
            self.proc.write(b"\x11")  # ctrl+q
            deadline = time.monotonic() + 3
            while self.proc.isalive() and time.monotonic() < deadline:
                time.sleep(0.05)
            if self.proc.isalive():
                self.proc.terminate(force=True)
        self._reader.join(timeout=2)
        if not self.proc.closed:
            self.proc.close(force=True)


def split_column(screen_text: str, columns: int) -> int:
    """The first column of the views: the second box corner on the top row."""
    top = screen_text.splitlines()[0] if screen_text else ""
    corners = [i for i, ch in enumerate(top) if ch == "╭"]
    if len(corners) >= 2:
        return corners[1]
    return 44 if columns >= 120 else 38


def breakdown(data: bytes, split: int, rows: int) -> dict[str, int]:
    """Bytes of ``data`` by kind and by screen area (see the module's docstring)."""
    out = {"sgr": 0, "cursor": 0, "other": 0, "text": 0, "views": 0, "side": 0, "footer": 0}
    area = "side"
    position = 0

    def count(chunk: bytes, kind: str) -> None:
        out[kind] += len(chunk)
        if kind != "other":
            out[area] += len(chunk)

    for match in TOKEN.finditer(data):
        if match.start() > position:
            count(data[position : match.start()], "text")
        token = match.group(0)
        move = MOVE.fullmatch(token)
        if move:
            y = int(move.group(1) or 1) - 1
            x = int(move.group(2) or 1) - 1
            area = "footer" if y >= rows - 1 else "views" if x >= split else "side"
        if SGR.fullmatch(token):
            count(token, "sgr")
        elif CURSOR.fullmatch(token):
            count(token, "cursor")
        else:
            count(token, "other")
        position = match.end()
    if position < len(data):
        count(data[position:], "text")
    return out


def measure(
    size: tuple[int, int], presses: int, term: str, env: dict[str, str], robot: str
) -> dict:
    columns, rows = size
    terminal = Terminal([robot], size, {"TERM": term, **env})
    try:
        deadline = time.monotonic() + FIRST_TIMEOUT
        while "Th1" not in terminal.text() and "d1" not in terminal.text():
            if time.monotonic() > deadline or not terminal.proc.isalive():
                raise SystemExit(f"no control screen after {FIRST_TIMEOUT} s:\n{terminal.text()}")
            time.sleep(0.05)
        terminal.settle(0, FIRST_TIMEOUT)
        first = terminal.text()
        first_bytes = terminal.size_read()
        split = split_column(first, columns)
        steps: list[bytes] = []
        for i in range(presses):
            before = terminal.size_read()
            terminal.send("right" if (i // 20) % 2 == 0 else "left")
            terminal.settle(before, KEY_TIMEOUT)
            with terminal._lock:
                steps.append(bytes(terminal.raw[before:]))
        last = terminal.text()
    finally:
        terminal.close()
    sizes = [len(step) for step in steps]
    parts = [breakdown(step, split, rows) for step in steps]
    mean_parts = {k: round(statistics.fmean(p[k] for p in parts), 1) for k in parts[0]}
    return {
        "size": f"{columns}x{rows}",
        "term": term,
        "env": env,
        "presses": presses,
        "first_frame_bytes": first_bytes,
        "split_column": split,
        "median": statistics.median(sizes),
        "mean": round(statistics.fmean(sizes), 1),
        "max": max(sizes),
        "min": min(sizes),
        "breakdown_mean": mean_parts,
        "screen_after": last,
    }


def parse_size(text: str) -> tuple[int, int]:
    columns, rows = text.lower().split("x")
    return int(columns), int(rows)


def report(result: dict) -> str:
    b = result["breakdown_mean"]
    total = max(result["mean"], 1)
    lines = [
        f"{result['size']} TERM={result['term']}"
        + "".join(f" {k}={v}" for k, v in result["env"].items())
        + f", {result['presses']} steps (first frame {result['first_frame_bytes']} B)",
        f"  bytes per step: median {result['median']:.0f}  mean {result['mean']:.0f}"
        f"  max {result['max']}  min {result['min']}",
        "  by kind (mean): "
        + ", ".join(
            f"{name} {b[key]:.0f} ({b[key] / total:.0%})"
            for key, name in (
                ("sgr", "SGR codes"),
                ("cursor", "cursor moves"),
                ("other", "other sequences"),
                ("text", "printable text"),
            )
        ),
        f"  by area (mean): views {b['views']:.0f}, side panel {b['side']:.0f}, "
        f"footer {b['footer']:.0f} (views from column {result['split_column']})",
    ]
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", action="append", type=parse_size, help="COLSxROWS (repeatable)")
    parser.add_argument("--presses", type=int, default=40)
    parser.add_argument("--term", default="xterm-256color")
    parser.add_argument("--env", action="append", default=[], metavar="K=V")
    parser.add_argument("--robot", default="puma560")
    parser.add_argument("--json", action="store_true", help="one JSON object")
    parser.add_argument("--screen", action="store_true", help="print the last screen too")
    args = parser.parse_args()
    env = dict(item.split("=", 1) for item in args.env)
    sizes = args.size or [(80, 24), (160, 48)]
    results = [measure(size, args.presses, args.term, env, args.robot) for size in sizes]
    if args.json:
        for result in results:
            del result["screen_after"]
        print(json.dumps({"results": results}))
        return
    for result in results:
        print(report(result))
        if args.screen:
            print(result["screen_after"])


if __name__ == "__main__":
    main()

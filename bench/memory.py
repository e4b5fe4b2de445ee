"""Memory: the editor's undo history, and a long mixed session of the real
``dhsim`` (a benchmark, not a test).

    python bench/memory.py [--minutes 10] [--size 100x30] [--unfixed]
    python bench/memory.py --minutes 1          # a quick check
    python bench/memory.py --minutes 0          # the edits alone
    python bench/memory.py --no-edits           # the session alone

**Edits.** 3,000 edits of a 32-joint robot through the core, as the editor
makes them: each edit is pushed on the undo history and previewed (the new
robot's frames at home, as the editor draws it). Prints this process's
resident memory before and after, and the growth per edit. Target: <= 100 MB
RSS after the 3,000 edits (it was 205 MB when each undo step kept compiled
kinematics).

**Session.** The installed ``dhsim`` on the Puma 560 in a pseudo-terminal
(tests/pty_screen.py), driven for ``--minutes`` (10 by default) by rounds of
mixed use paced as a person types: joint jogging, ``c`` to Cartesian
jogging and back, ``g`` to the program panel (a step recorded and deleted)
and back, the views (``tab``, ``z``, ``x``, zoom, orbit), a read-out, a
named pose and home, the help and the editor (entered and left, nothing
kept). Each step waits for the screen to show it (the footer of the mode, the
help, the editor), so a lost key fails the bench rather than skewing it.
Prints dhsim's RSS (``/proc/<pid>/status``) after its first frame, every
minute and at the end, with its peak and the mode switches (``c``/``g``)
made. Target: <= 100 MB at the end of 10 minutes. Two Textual 8.2.8 leaks
made it grow without end (docs/upstream/textual-footer-leak.md): the footer
kept its keys on every mode switch (0.3-0.65 MB each: 306 switches took it
from 69 to 184 MB; dhsim_tui/tui/widgets/footer.py), and the views panel's
watcher of the app's theme kept every views panel, with its screen, after
each trip to the editor (views_panel.py). ``--unfixed`` runs dhsim with both
workarounds undone, to measure what they save.
"""

from __future__ import annotations

import argparse
import gc
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))

from pty_screen import PtyScreen  # noqa: E402

from dhsim_tui.core.model.editing import History, new_robot, set_joint_field  # noqa: E402

EDITS = 3000
JOINTS = 32
TARGET_MB = 100.0

#: keys as a terminal sends them
RIGHT, LEFT, UP, DOWN = "\x1b[C", "\x1b[D", "\x1b[A", "\x1b[B"
SHIFT_RIGHT, SHIFT_LEFT = "\x1b[1;2C", "\x1b[1;2D"
DELETE, ESCAPE, TAB = "\x1b[3~", "\x1b", "\t"
#: a person's pause between steps (s): pacing, not a wait for anything
THINK = 0.15

#: dhsim with both workarounds undone: Textual's footer recompose back, and
#: the views panel watching the app's theme (the two leaks, to measure them)
UNFIXED = """
import sys
from textual.widgets import Footer
from dhsim_tui.tui.widgets.footer import KeysFooter
from dhsim_tui.tui.widgets.views_panel import ViewsPanel
KeysFooter.recompose = Footer.recompose
mounted = ViewsPanel.on_mount
def on_mount(self):
    mounted(self)
    self.app.theme_changed_signal.unsubscribe(self)
    self.watch(self.app, "theme", self._restyle, init=False)
ViewsPanel.on_mount = on_mount
from dhsim_tui.cli.main import main
sys.exit(main())
"""


def rss_mb(pid: int | str = "self", field: str = "VmRSS") -> float:
    """Resident set size now (or ``VmHWM``, its peak), Linux /proc, in MB."""
    with open(f"/proc/{pid}/status", encoding="ascii") as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024.0
    raise RuntimeError(f"no {field} in /proc/{pid}/status")


# -- the edits --------------------------------------------------------------------
def edits() -> None:
    history = History(new_robot(joints=JOINTS))
    history.current.kinematics.frames(history.current.home)
    gc.collect()
    before = rss_mb()
    started = time.perf_counter()
    for step in range(EDITS):
        robot = history.current
        index = step % JOINTS
        history.push(set_joint_field(robot, index, "a", robot.joints[index].a + 0.5))
        history.current.kinematics.frames(history.current.home)
    elapsed = time.perf_counter() - started
    gc.collect()
    after = rss_mb()
    verdict = "ok" if after <= TARGET_MB else "OVER TARGET"
    print(f"{EDITS} edits of a {JOINTS}-joint robot, {elapsed / EDITS * 1e3:.2f} ms per edit")
    print(f"RSS {before:.1f} MB -> {after:.1f} MB (target <= {TARGET_MB:.0f} MB): {verdict}")
    print(f"growth {(after - before) * 1024 / EDITS:.2f} KiB per undo step")


# -- the session ------------------------------------------------------------------
def footer(text: str) -> str:
    return text.rstrip("\n").rsplit("\n", 1)[-1]


class Session:
    """One dhsim in a pseudo-terminal and the steps of a round of use."""

    def __init__(self, screen: PtyScreen) -> None:
        self.screen = screen
        self.switches = 0
        self.keys = 0

    def send(self, *keys: str) -> None:
        self.screen.send(*keys)
        self.keys += len(keys)

    def shows(self, check, what: str) -> None:
        """Wait until the screen shows ``what`` (``check`` on its text)."""
        try:
            self.screen.wait_for(check)
        except AssertionError as error:
            raise SystemExit(f"dhsim did not show {what}:\n{error}") from None
        if "Traceback" in self.screen.screen_text():
            raise SystemExit(f"a traceback on the screen:\n{self.screen.screen_text()}")
        time.sleep(THINK)

    def mode(self, key: str, footer_has: str) -> None:
        """A mode switch (``c`` or ``g``): wait for the footer of the new mode."""
        self.send(key)
        self.switches += 1
        self.shows(lambda text: footer_has in footer(text), f"the footer with {footer_has!r}")

    def joints_footer(self) -> None:
        self.shows(lambda text: "↑↓ Joint" in footer(text), "the joints' footer")

    def round(self) -> None:
        self.joints_footer()
        # joint jogging
        for keys in ([RIGHT] * 4, [DOWN], [LEFT] * 3, [SHIFT_RIGHT], [UP], [SHIFT_LEFT]):
            self.send(*keys)
        self.joints_footer()
        # Cartesian jogging and back
        self.mode("c", "c Joints")
        for keys in ([RIGHT] * 3, [DOWN], [LEFT] * 3, [DOWN], [RIGHT], [UP, UP]):
            self.send(*keys)
        self.mode("c", "c Cartesian")
        # the program panel: a step recorded and deleted, and back
        self.mode("g", "↑↓ Step")
        self.send("R")
        self.send(DELETE)
        self.mode("g", "↑↓ Joint")
        # the views, a read-out, a pose and home
        for key in (TAB, "z", "z", "x", "x", "x", "+", "-", "0", "a", "d", "w", "s", TAB, "v"):
            self.send(key)
        self.send("p")
        self.send("h")
        self.joints_footer()
        # the help, and back
        self.send("?")
        self.shows(lambda text: "escape closes" in text, "the help")
        self.send(ESCAPE)
        self.shows(lambda text: "escape closes" not in text, "the help closed")
        # the editor, and back (nothing kept)
        self.send("e")
        self.shows(lambda text: "esc Back" in footer(text), "the editor")
        self.send(ESCAPE)
        self.shows(
            lambda text: "Unsaved changes" in text or "↑↓ Joint" in footer(text),
            "the way back from the editor",
        )
        if "Unsaved changes" in self.screen.screen_text():
            self.send("d")
        self.joints_footer()


def session(minutes: float, size: tuple[int, int], unfixed: bool) -> None:
    folder = tempfile.mkdtemp(prefix="dhsim-memory-")
    command = [sys.executable, "-c", UNFIXED] if unfixed else None
    env = {"DHSIM_RECOVERY_DIR": str(Path(folder) / "recovery")}
    with PtyScreen(["puma560"], size=size, env=env, cwd=folder, command=command) as screen:
        run = Session(screen)
        run.joints_footer()
        pid = screen.pid
        start_rss = rss_mb(pid)
        started = time.monotonic()
        kind = "workarounds undone (--unfixed)" if unfixed else "as installed"
        print(f"session: dhsim puma560 at {size[0]}x{size[1]}, {kind}, {minutes:g} min")
        print(f"  0.0 min  RSS {start_rss:6.1f} MB  (after the first frame)")
        rounds = 0
        next_report = 60.0
        warm: tuple[float, float, int] | None = None  # (minutes, MB, switches) at 1 min
        while (elapsed := time.monotonic() - started) < minutes * 60:
            run.round()
            rounds += 1
            if elapsed >= next_report:
                rss = rss_mb(pid)
                print(
                    f"  {elapsed / 60:.1f} min  RSS {rss:6.1f} MB  "
                    f"{run.switches} mode switches, {rounds} rounds"
                )
                if warm is None:
                    warm = (elapsed / 60, rss, run.switches)
                next_report += 60.0
        elapsed = time.monotonic() - started
        end_rss = rss_mb(pid)
        peak = rss_mb(pid, "VmHWM")
        run.send("q")
        verdict = "ok" if end_rss <= TARGET_MB else "OVER TARGET"
        print(
            f"{elapsed / 60:.1f} min, {rounds} rounds, {run.keys} keys, "
            f"{run.switches} mode switches (c, g)"
        )
        print(
            f"RSS {start_rss:.1f} MB -> {end_rss:.1f} MB, peak {peak:.1f} MB "
            f"(target <= {TARGET_MB:.0f} MB at the end): {verdict}"
        )
        if warm is not None and run.switches > warm[2]:
            since, rss, switches = warm
            growth = end_rss - rss
            print(
                f"after the first minute (warm-up): {growth:+.1f} MB in "
                f"{elapsed / 60 - since:.1f} min, "
                f"{growth * 1024 / (run.switches - switches):.1f} KiB per mode switch"
            )


def size_arg(text: str) -> tuple[int, int]:
    columns, rows = text.lower().split("x")
    return int(columns), int(rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--minutes", type=float, default=10.0, help="session length (0: none)")
    parser.add_argument("--size", type=size_arg, default=(100, 30), help="COLUMNSxROWS")
    parser.add_argument(
        "--unfixed", action="store_true", help="the footer and views workarounds undone"
    )
    parser.add_argument("--no-edits", action="store_true", help="skip the 3,000 edits")
    args = parser.parse_args()
    if not args.no_edits:
        edits()
    if args.minutes > 0:
        session(args.minutes, args.size, args.unfixed)


if __name__ == "__main__":
    main()

"""Editor memory (a benchmark, not a test).

    python bench/memory.py

3,000 edits of a 32-joint robot through the core, as the editor makes them:
each edit is pushed on the undo history and previewed (the new robot's
frames at home, as the editor draws it). Prints the process's resident memory
before and after, and the growth per edit. Target: <= 100 MB RSS after the
3,000 edits (it was 205 MB when each undo step kept compiled kinematics).
"""

from __future__ import annotations

import gc
import time

from dhsim_tui.core.model.editing import History, new_robot, set_joint_field

EDITS = 3000
JOINTS = 32
TARGET_MB = 100.0


def rss_mb() -> float:
    """Resident set size now (Linux /proc), in MB."""
    with open("/proc/self/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    raise RuntimeError("no VmRSS in /proc/self/status")


def main() -> None:
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


if __name__ == "__main__":
    main()

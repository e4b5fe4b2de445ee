"""A short run of the key-and-mouse monkey (bench/monkey.py has the long
one): random keys and xterm mouse reports into the real dhsim, and the
fault campaign's palette bursts; no traceback, no hang, no damaged file."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))

from monkey import palette_bursts, run_monkey
from waiting import HANG


def test_random_keys_and_mouse_reports_never_crash_hang_or_damage_a_file():
    report = run_monkey(sequences=6, seed=11, per_process=3, patience=HANG)
    assert report.sequences == 6 and report.mouse_events > 50
    assert report.clean, report.tracebacks + report.hangs + report.damaged


def test_keys_right_after_ctrl_p_never_put_a_traceback_on_screen():
    report = palette_bursts(20, seed=5, patience=HANG)
    assert report.sequences == 20
    assert report.clean, report.tracebacks + report.hangs + report.damaged

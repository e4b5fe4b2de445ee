"""What the screens show, compared with stored SVG snapshots.

Update on purpose with ``pytest tests/test_snapshots.py --snapshot-update``
and look at the result (``snapshot_report.html`` shows the differences).
"""

from __future__ import annotations

from pathlib import Path

APP = Path(__file__).parent / "apps" / "control_app.py"
MOVE = (
    "down",
    "right_square_bracket",
    "right_square_bracket",
    "right",
    "right",
    "down",
    "left",
    "left",
    "left",
)


def test_control_80x24_home(snap_compare):
    assert snap_compare(APP, terminal_size=(80, 24))


def test_control_80x24_moved_side_view(snap_compare):
    assert snap_compare(APP, press=(*MOVE, "3"), terminal_size=(80, 24))


def test_control_160x48_moved(snap_compare):
    assert snap_compare(APP, press=MOVE, terminal_size=(160, 48))


def test_control_rpy_and_matrix_readouts(snap_compare):
    assert snap_compare(APP, press=(*MOVE, "v", "v"), terminal_size=(80, 24))


def test_help_80x24(snap_compare):
    assert snap_compare(APP, press=("question_mark",), terminal_size=(80, 24))


def test_value_entry_with_an_error(snap_compare):
    assert snap_compare(
        APP, press=("enter", "ctrl+u", "9", "9", "9", "enter"), terminal_size=(80, 24)
    )


def test_too_small(snap_compare):
    assert snap_compare(APP, terminal_size=(50, 14))


EDITOR = Path(__file__).parent / "apps" / "editor_app.py"


def test_editor_80x24(snap_compare):
    assert snap_compare(EDITOR, press=("down", "right", "right"), terminal_size=(80, 24))


def test_editor_160x48(snap_compare):
    assert snap_compare(EDITOR, press=("down", "right", "right"), terminal_size=(160, 48))


def test_editor_rejected_value(snap_compare):
    keys = ("right", "right", "enter", "ctrl+u", "2", "0", "0", "enter")
    assert snap_compare(EDITOR, press=keys, terminal_size=(80, 24))


def test_control_cartesian_mode(snap_compare):
    assert snap_compare(APP, press=("p", "p", "c", "down", "down"), terminal_size=(80, 24))

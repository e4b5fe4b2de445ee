"""What the screens show, compared with stored SVG snapshots.

Update on purpose with ``pytest tests/tui/test_snapshots.py --snapshot-update``
and look at the result (``snapshot_report.html`` shows the differences).
"""

from __future__ import annotations

from pathlib import Path

from pilot_helpers import press, started

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


def keys(*pressed: str):
    """What to do before the picture is taken: wait for the app to start,
    press the keys and wait until they are handled and drawn (Pilot's own
    ``press=`` guesses from CPU time, which a loaded machine fools)."""

    async def run_before(pilot) -> None:
        await started(pilot)
        await press(pilot, *pressed)

    return run_before


def test_control_80x24_home(snap_compare):
    assert snap_compare(APP, run_before=keys(), terminal_size=(80, 24))


def test_control_80x24_moved_side_view(snap_compare):
    assert snap_compare(APP, run_before=keys(*MOVE, "3"), terminal_size=(80, 24))


def test_control_160x48_moved(snap_compare):
    assert snap_compare(APP, run_before=keys(*MOVE), terminal_size=(160, 48))


def test_control_rpy_and_matrix_readouts(snap_compare):
    assert snap_compare(APP, run_before=keys(*MOVE, "v", "v"), terminal_size=(80, 24))


def test_help_80x24(snap_compare):
    assert snap_compare(APP, run_before=keys("question_mark"), terminal_size=(80, 24))


def test_value_entry_with_an_error(snap_compare):
    assert snap_compare(
        APP, run_before=keys("enter", "ctrl+u", "9", "9", "9", "enter"), terminal_size=(80, 24)
    )


def test_too_small(snap_compare):
    assert snap_compare(APP, run_before=keys(), terminal_size=(50, 14))


EDITOR = Path(__file__).parent / "apps" / "editor_app.py"


def test_editor_80x24(snap_compare):
    assert snap_compare(EDITOR, run_before=keys("down", "right", "right"), terminal_size=(80, 24))


def test_editor_160x48(snap_compare):
    assert snap_compare(EDITOR, run_before=keys("down", "right", "right"), terminal_size=(160, 48))


def test_editor_rejected_value(snap_compare):
    typed = ("right", "right", "enter", "ctrl+u", "2", "0", "0", "enter")
    assert snap_compare(EDITOR, run_before=keys(*typed), terminal_size=(80, 24))


def test_control_cartesian_mode(snap_compare):
    assert snap_compare(APP, run_before=keys("p", "p", "c", "down", "down"), terminal_size=(80, 24))


def test_control_program_panel(snap_compare):
    """g: the Puma's demo program, its steps and the one selected (issue 19)."""
    assert snap_compare(APP, run_before=keys("g", "down"), terminal_size=(80, 24))


def test_control_program_plot(snap_compare):
    """t on the program panel: the demo's joints and tool speed against time."""
    assert snap_compare(APP, run_before=keys("g", "t"), terminal_size=(100, 30))


# -- the views in every mode a terminal can ask for ---------------------------------


def _puma(**kwargs):
    from rich.color import ColorSystem

    from dhsim_tui.core import load_robot
    from dhsim_tui.tui.app import DhsimApp

    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False, **kwargs)
    app.console._color_system = ColorSystem.TRUECOLOR  # unless a test says otherwise
    return app


def test_views_120x36_four_views(snap_compare):
    assert snap_compare(APP, run_before=keys(*MOVE), terminal_size=(120, 36))


def test_views_3d_maximised_and_orbited(snap_compare):
    assert snap_compare(APP, run_before=keys(*MOVE, "4", "z", "d", "w"), terminal_size=(120, 36))


def test_views_over_the_work_area(snap_compare):
    """The views open fitted to the arm (the other snapshots); 0: the work area."""
    assert snap_compare(APP, run_before=keys(*MOVE, "0"), terminal_size=(120, 36))


def test_views_with_the_base_and_tool_frames_only(snap_compare):
    assert snap_compare(APP, run_before=keys(*MOVE, "x"), terminal_size=(120, 36))


def test_control_200x60_every_read_out(snap_compare):
    assert snap_compare(APP, run_before=keys(*MOVE), terminal_size=(200, 60))


def test_views_zoomed(snap_compare):
    assert snap_compare(APP, run_before=keys(*MOVE, "plus", "plus"), terminal_size=(120, 36))


def test_views_16_colours(snap_compare):
    from rich.color import ColorSystem

    app = _puma()
    app.console._color_system = ColorSystem.STANDARD  # as TERM=xterm gets
    assert snap_compare(app, run_before=keys(*MOVE), terminal_size=(120, 36))


def test_views_256_colours(snap_compare):
    from rich.color import ColorSystem

    app = _puma()
    app.console._color_system = ColorSystem.EIGHT_BIT  # as TERM=xterm-256color gets
    assert snap_compare(app, run_before=keys(*MOVE), terminal_size=(120, 36))


def test_views_no_color(snap_compare, monkeypatch):
    monkeypatch.setenv("NO_COLOR", "1")
    assert snap_compare(_puma(), run_before=keys(*MOVE), terminal_size=(120, 36))


def test_views_ansi_theme(snap_compare):
    app = _puma()

    async def ansi(pilot):
        pilot.app.theme = "dhsim-ansi"
        await keys(*MOVE)(pilot)

    assert snap_compare(app, run_before=ansi, terminal_size=(120, 36))


def test_views_ascii(snap_compare):
    assert snap_compare(_puma(ascii=True), run_before=keys(*MOVE), terminal_size=(120, 36))

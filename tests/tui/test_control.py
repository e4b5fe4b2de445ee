"""The control screen, driven with Pilot as a person would drive it."""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest
from pilot_helpers import press, until

from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.screens.value_entry import ValueEntry
from dhsim_tui.tui.widgets.arm_view import ArmView
from dhsim_tui.tui.widgets.joint_panel import JointPanel
from dhsim_tui.tui.widgets.pose_panel import PosePanel
from dhsim_tui.tui.widgets.views_panel import ViewsPanel
from tui.conftest import control


def pose_numbers(app: DhsimApp) -> dict[str, float]:
    """The pose panel's numbers as a person reads them off the screen."""
    text = str(app.screen.query_one(PosePanel).render())
    return {name: float(value) for name, value in re.findall(r"(\w+)\s+(-?\d+\.\d+)", text)}


async def test_right_left_and_shift_step_the_selected_joint(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "right", "shift+right")
        assert control(app).q == (12.0, 0, 0, 0, 0, 0)
        await press(pilot, "down", "left", "shift+left")
        assert control(app).q == (12.0, -11.0, 0, 0, 0, 0)


async def test_up_down_select_and_wrap(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "up")
        assert control(app).query_one(JointPanel).selected == 5
        await press(pilot, "down", "down")
        assert control(app).query_one(JointPanel).selected == 1
        rows = app.screen.query("JointRow")
        assert rows[1].has_class("-selected") and not rows[0].has_class("-selected")


async def test_step_size_ladder_changes_the_step_and_is_shown(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right_square_bracket", "right")
        assert control(app).q[0] == 5.0
        assert "step 5 deg" in str(app.screen.query_one("#joints").border_subtitle)
        for _ in range(6):  # past the top of the ladder it stays at 45
            await press(pilot, "right_square_bracket")
        await press(pilot, "right")
        assert control(app).q[0] == 50.0
        for _ in range(6):
            await press(pilot, "left_square_bracket")
        await press(pilot, "left")
        assert control(app).q[0] == pytest.approx(49.9)


async def test_prismatic_steps_use_the_robots_unit(control_app):
    app = control_app("stanford")
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "down", "down", "right", "right_square_bracket", "right")
        assert control(app).q[2] == pytest.approx(304.8 + 1 + 10)
        assert "step 10 mm" in str(app.screen.query_one("#joints").border_subtitle)


async def test_stepping_stops_at_the_limit_and_says_so(status, control_app):
    app = control_app()  # joint 1: -160..160
    async with app.run_test(size=(80, 24)) as pilot:
        for _ in range(3):
            await press(pilot, "right_square_bracket")  # 45 deg steps
        for _ in range(5):
            await press(pilot, "right")
        assert control(app).q[0] == 160.0
        assert "Th1 is at its max limit, 160 deg" in status(app)
        row = str(app.screen.query("JointRow")[0].render())
        assert "▶" in row.split("├")[1]  # the bar shows the limit
        await press(pilot, "left")
        assert control(app).q[0] == 115.0
        assert status(app) == ""


async def test_enter_sets_an_exact_value(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "down", "enter")
        assert isinstance(app.screen, ValueEntry)
        await press(pilot, "ctrl+u", *"12.5", "enter")
        assert isinstance(app.screen, ControlScreen)
        assert control(app).q[1] == 12.5


@pytest.mark.parametrize(
    ("typed", "message"),
    [
        ("abc", "'abc' is not a number"),
        ("", "type a number"),
        ("nan", "NaN"),
        ("inf", "out of range"),
        ("1e400", "out of range"),
        ("300", "300 is outside Th2's limits -45..225 deg"),
    ],
)
async def test_enter_rejects_bad_values_and_changes_nothing(typed, message, control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "down", "enter", "ctrl+u", *typed, "enter")
        await until(  # the refusal is shown once the key has been handled
            pilot,
            lambda: (
                isinstance(app.screen, ValueEntry) and str(app.screen.query_one("#error").render())
            ),
            "the refusal",
        )
        assert isinstance(app.screen, ValueEntry)
        assert message in str(app.screen.query_one("#error").render())
        assert app.screen.query_one("Input").value == typed  # kept, to be fixed
        await press(pilot, "escape")
        assert isinstance(app.screen, ControlScreen)
        assert control(app).q == app.robot.home


async def test_home_key_and_h_send_every_joint_home(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "down", "right", "right")
        assert control(app).q != app.robot.home
        await press(pilot, "h")
        assert control(app).q == app.robot.home
        await press(pilot, "right")
        await press(pilot, "home")
        assert control(app).q == app.robot.home


async def test_p_cycles_the_named_poses(status, control_app):
    app = control_app()
    robot = app.robot
    async with app.run_test(size=(80, 24)) as pilot:
        seen = []
        for _ in range(5):
            await press(pilot, "p")
            seen.append(control(app).q)
        assert seen == [robot.pose(n) for n in ("qz", "qr", "qs", "qn", "qz")]
        assert "pose qz (1/4)" in status(app)


async def test_p_is_disabled_for_a_robot_without_poses(control_app):
    app = control_app("irb140")
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "p")
        assert control(app).q[0] == 1.0
        assert control(app).check_action("next_pose", ()) is None


async def test_v_cycles_oat_rpy_and_matrix(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        panel = app.screen.query_one(PosePanel)
        assert {"O", "A", "T"} <= set(pose_numbers(app))
        await press(pilot, "v")
        assert {"roll", "pitch", "yaw"} <= set(pose_numbers(app))
        await press(pilot, "v")
        text = str(panel.render())
        assert "431.80" in text and "0.0000" in text and "1.0000" in text
        await press(pilot, "v")
        assert {"O", "A", "T"} <= set(pose_numbers(app))


@pytest.mark.parametrize(
    "q", [(0, 30, 45, 60, 90, 0), (30, 30, 30, 30, 30, 30), (0, 90, 0, 45, 0, 60)]
)
async def test_screen_numbers_equal_dhsim_fk(q, control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        for index, value in enumerate(q):
            if index:
                await press(pilot, "down")
            await press(pilot, "enter", "ctrl+u", *str(value), "enter")
        assert control(app).q == tuple(float(v) for v in q)
        shown = pose_numbers(app)
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "dhsim_tui",
            "fk",
            "puma560",
            "--q",
            ",".join(map(str, q)),
            "--json",
        ],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    fk = json.loads(out)
    for name, value in zip("XYZ", fk["xyz"], strict=True):
        assert shown[name] == round(value, 2) + 0.0
    for name, value in zip("OAT", fk["oat"], strict=True):
        assert shown[name] == round(value, 2) + 0.0


async def test_resize_keeps_joints_step_and_view(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right", "right_square_bracket", "3")
        before = (
            control(app).q,
            control(app).step_level,
            control(app).query_one(ViewsPanel).selected,
        )
        await pilot.resize_terminal(160, 48)
        await until(pilot, lambda: app.screen.has_class("-wide"), "the wide layout")
        await until(
            pilot, lambda: all(v.display for v in app.screen.query(ArmView)), "all four views"
        )
        await pilot.resize_terminal(80, 24)
        await until(pilot, lambda: not app.screen.has_class("-wide"), "the narrow layout")
        await until(
            pilot, lambda: sum(v.display for v in app.screen.query(ArmView)) == 1, "one view"
        )
        assert (
            control(app).q,
            control(app).step_level,
            control(app).query_one(ViewsPanel).selected,
        ) == before
        shown = [v.view.key for v in app.screen.query(ArmView) if v.display]
        assert shown == ["side"]


async def test_tab_and_number_keys_switch_views_at_80x24(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:

        def shown():
            return [v.view.key for v in app.screen.query(ArmView) if v.display]

        assert shown() == ["front"]
        await press(pilot, "tab")
        assert shown() == ["side"]
        await press(pilot, "1")
        assert shown() == ["top"]


async def test_too_small_terminal_shows_a_message(control_app):
    app = control_app()
    async with app.run_test(size=(40, 12)) as pilot:
        await until(pilot, lambda: app.screen.has_class("-too-small"), "the too-small layout")
        assert "Terminal too small: 40×12" in str(app.screen.query_one("#too-small").render())
        await pilot.resize_terminal(80, 24)
        await until(pilot, lambda: not app.screen.has_class("-too-small"), "the usual layout")


async def test_help_lists_keys_and_closes(screen_text, control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "question_mark")
        assert isinstance(app.screen, HelpScreen)
        text = " ".join(screen_text(app).split())
        for words in (
            "select a joint",
            "step the selected joint",
            "exact value",
            "home",
            "qz, qr, qs, qn",
            "4×4",
        ):
            assert words in text
        await press(pilot, "escape")
        assert isinstance(app.screen, ControlScreen)


async def test_q_quits(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "q")
    assert app.return_code == 0


async def test_views_redraw_when_a_joint_moves(control_app):
    app = control_app()
    async with app.run_test(size=(160, 48)) as pilot:
        top = app.screen.query_one("#view-top", ArmView)
        await until(pilot, lambda: top.picture is not None, "the top view drawn")
        before = top.picture.lines
        await press(pilot, "right_square_bracket", "right_square_bracket", "right")
        assert top.picture.lines != before


async def test_braille_renderer_draws_the_arm_without_axes(control_app):
    app = control_app(renderer="braille")
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "right")
        await pilot.pause()
        view = app.screen.query_one("#view-front", ArmView)
        assert view.scene is not None
        text = view.picture.text()
        assert "◆" in text and "┤" not in text  # the tool, and no plotext axes


async def test_every_bundled_robot_opens_and_steps(bundled):
    app = DhsimApp(bundled, None, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        for _ in range(bundled.dof):
            await press(pilot, "right", "down")
        await press(pilot, "h")
        assert control(app).q == bundled.home


async def test_rows_scroll_to_keep_the_selected_joint_in_view():
    from dhsim_tui.core import Joint, Robot

    robot = Robot("long arm", tuple(Joint(a=50.0) for _ in range(20)))
    app = DhsimApp(robot, None, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "up")  # wraps to joint 20
        panel = app.screen.query_one("#joints")
        row = app.screen.query("JointRow")[19]
        await until(pilot, lambda: panel.region.contains_region(row.region), "joint 20 in view")
        assert panel.scroll_y > 0
        await press(pilot, "down")  # back to joint 1
        await until(pilot, lambda: panel.scroll_y == 0, "joint 1 in view")


async def test_metre_robots_show_enough_decimals(control_app):
    app = control_app("planar2")
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "enter", "ctrl+u", *"10", "enter")
        assert isinstance(app.screen, ControlScreen)
        assert "1.96962 m" in str(app.screen.query_one("#pose").render())

"""The mouse, as the seed's sliders were used (issue 16): click, drag and the
wheel on the joints, the Cartesian rows, the views and the editor's table.
Pilot's mouse events here; xterm's SGR mouse reports to a real dhsim in a
pseudo-terminal at the end."""

from __future__ import annotations

import pytest
from pilot_helpers import press, settled
from pty_screen import PtyScreen
from textual.coordinate import Coordinate
from textual.events import MouseMove, MouseScrollDown, MouseScrollUp
from waiting import until

from dhsim_tui.core import load_robot
from dhsim_tui.core.motion.jog import snapped
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.widgets.arm_view import ArmView
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel
from dhsim_tui.tui.widgets.joint_panel import JointPanel
from dhsim_tui.tui.widgets.joint_row import BAR_START, JointRow, bar_value
from dhsim_tui.tui.widgets.views_panel import ViewsPanel


def make_app(start: str = "control") -> DhsimApp:
    robot, path = load_robot("puma560")
    return DhsimApp(robot, path, animate=False, start=start)


def rows(app) -> list[JointRow]:
    return list(app.screen.query(JointRow))


async def started(pilot) -> None:
    """The app's first screen is up, ready and drawn: the simulator, or the editor."""
    app = pilot.app
    kind = EditorScreen if app.start == "edit" else ControlScreen
    await until(pilot, lambda: isinstance(app.screen, kind) and app.screen._ready, kind.__name__)
    await handled(pilot)


async def handled(pilot) -> None:
    """Wait until the app has handled what it was sent and drawn what changed."""
    await until(pilot, lambda: settled(pilot.app), "the events handled and drawn")


async def click(pilot, widget, offset, double: bool = False) -> None:
    await (pilot.double_click if double else pilot.click)(widget, offset=offset)
    await handled(pilot)


async def wheel(pilot, widget, offset, up: bool = True, times: int = 1) -> None:
    for _ in range(times):
        await pilot._post_mouse_events([MouseScrollUp if up else MouseScrollDown], widget, offset)
    await handled(pilot)


async def drag(pilot, widget, start, path) -> None:
    await pilot.mouse_down(widget, offset=start)
    for point in path:
        await pilot._post_mouse_events([MouseMove], widget, offset=point, button=1)
    await pilot.mouse_up(widget, offset=path[-1])
    await handled(pilot)


# -- the joints ---------------------------------------------------------------------------


async def test_a_click_on_a_joint_selects_it():
    app = make_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        before = app.screen.q
        await click(pilot, rows(app)[3], (2, 0))  # on the label
        assert app.screen.query_one(JointPanel).selected == 3
        assert app.screen.q == before  # a click on the label moves nothing
        assert rows(app)[3].has_class("-selected")


@pytest.mark.parametrize("column", [0, 3, 7, 11])
async def test_a_click_on_the_bar_sets_the_value_there_rounded_to_the_step(column):
    app = make_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        row = rows(app)[1]
        width = max(row._bar_width(), 5)
        await click(pilot, row, (BAR_START + column, 0))
        screen = app.screen
        joint = app.robot.joints[1]
        # independent of the widget: the bar's ends are the limits, cells evenly between
        inner = width - 2
        cell = min(inner - 1, max(0, column - 1))
        raw = joint.min + (joint.max - joint.min) * cell / (inner - 1)
        step = 1.0  # the default step
        expected = min(max(round(raw / step) * step, joint.min), joint.max)
        assert screen.query_one(JointPanel).selected == 1
        assert screen.q[1] == pytest.approx(expected)
        assert screen.q[1] == snapped(app.robot, 1, bar_value(joint, column, width), 1)


async def test_a_drag_along_the_bar_follows_the_pointer_within_the_limits():
    app = make_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        row = rows(app)[2]
        joint = app.robot.joints[2]
        width = max(row._bar_width(), 5)
        await drag(pilot, row, (BAR_START + 5, 0), [(BAR_START + 7, 0), (BAR_START + 9, 0)])
        middle = app.screen.q[2]
        assert joint.min < middle < joint.max
        # past the bar's end: the limit, never beyond
        await drag(pilot, row, (BAR_START + 3, 0), [(BAR_START + width + 6, 0)])
        assert app.screen.q[2] == joint.max
        await drag(pilot, row, (BAR_START + 3, 0), [(0, 0)])
        assert app.screen.q[2] == joint.min
        assert "limit" in str(app.screen.query_one("#status").render())


async def test_the_wheel_over_a_joint_steps_it_and_selects_it():
    app = make_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "right_square_bracket", "right_square_bracket")  # 15-degree steps
        home = app.screen.q[4]
        await wheel(pilot, rows(app)[4], (3, 0), up=True, times=2)
        assert app.screen.query_one(JointPanel).selected == 4
        assert app.screen.q[4] == pytest.approx(home + 30.0)
        await wheel(pilot, rows(app)[4], (3, 0), up=False)
        assert app.screen.q[4] == pytest.approx(home + 15.0)


async def test_a_click_on_a_joint_in_cartesian_mode_goes_back_to_the_joints():
    app = make_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "c")
        assert app.screen.cartesian
        await click(pilot, rows(app)[0], (2, 0))
        assert not app.screen.cartesian and app.screen.query_one(JointPanel).selected == 0


async def test_cartesian_rows_take_a_click_and_the_wheel():
    app = make_app()
    async with app.run_test(size=(80, 30)) as pilot:
        await started(pilot)
        await press(pilot, "p", "c")  # a pose away from the singular home
        panel = app.screen.query_one("#cartesian")
        await click(pilot, panel, (3, 2))  # the Z row
        assert app.screen.query_one(CartesianPanel).row == 2
        z = app.robot.kinematics.position(app.screen.q)[2]
        await wheel(pilot, panel, (3, 2), up=True)
        assert app.robot.kinematics.position(app.screen.q)[2] == pytest.approx(z + 1.0, abs=1e-6)


# -- the views ---------------------------------------------------------------------------


async def test_a_click_selects_a_view_and_a_double_click_maximises_it():
    app = make_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        side = app.screen.query_one("#view-side", ArmView)
        await click(pilot, side, (10, 5))
        assert panel.selected == 2 and side.has_class("-selected")
        assert not panel.maximised
        await click(pilot, side, (10, 5), double=True)
        assert panel.maximised and app.screen.has_class("-max")
        assert side.size.width > 100  # the whole screen
        await click(pilot, side, (10, 5), double=True)
        assert not panel.maximised


async def test_the_wheel_over_a_view_zooms():
    app = make_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        front = app.screen.query_one("#view-front", ArmView)
        await wheel(pilot, front, (20, 8), up=True, times=2)
        assert panel.zoom == pytest.approx(1.5**2)
        await wheel(pilot, front, (20, 8), up=False)
        assert panel.zoom == pytest.approx(1.5)
        assert "zoom 1.5x" in str(front.border_subtitle)


async def test_a_drag_in_the_3d_view_orbits_it_and_elsewhere_does_not():
    app = make_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        iso = app.screen.query_one("#view-iso", ArmView)
        start = panel.orbit
        await drag(pilot, iso, (20, 10), [(24, 10), (28, 11)])
        # grab the scene: 8 columns right turns it 24 degrees, a row down tips it 6
        assert panel.orbit.azimuth == pytest.approx(start.azimuth - 24.0)
        assert panel.orbit.elevation == pytest.approx(start.elevation + 6.0)
        turned = panel.orbit
        await drag(pilot, "#view-front", (20, 10), [(30, 12)])
        assert panel.orbit == turned


# -- the editor ----------------------------------------------------------------------------


async def test_in_the_editor_a_click_selects_a_cell_and_a_double_click_edits_it():
    app = make_app(start="edit")
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        table = app.screen.query_one("#joints-table")
        # the cell of joint 2's "a": find its place from the table itself
        cell = table._get_cell_region(Coordinate(1, 4))  # in the table's content
        inset = table.content_region.offset - table.region.offset  # its border
        offset = (inset.x + cell.x + 1, inset.y + cell.y)
        await click(pilot, table, offset)
        editor = app.screen
        assert table.cursor_coordinate == (1, 4)
        assert app.screen is editor  # no dialog: a click only selects
        await click(pilot, table, offset)  # a second, slow click: still no dialog
        assert app.screen is editor
        await click(pilot, table, offset, double=True)
        await until(pilot, lambda: app.screen is not editor, "the value dialog for that cell")
        await handled(pilot)
        assert "a" in str(app.screen.query_one("Label").render())


# -- a real terminal -----------------------------------------------------------------------


def _sgr(button: int, column: int, row: int, press: bool = True) -> str:
    return f"\x1b[<{button};{column};{row}{'M' if press else 'm'}"


def test_xterm_mouse_reports_drive_a_real_dhsim():
    """SGR mouse reports (what xterm, tmux, iTerm and others send) reach the
    joints and views of the real program: a click, a drag and the wheel."""
    with PtyScreen([], size=(80, 24)) as screen:
        screen.wait_for("Th6")
        lines = screen.screen_text().splitlines()
        th3 = next(i for i, line in enumerate(lines) if "Th3" in line) + 1
        screen.send(_sgr(0, 4, th3), _sgr(0, 4, th3, press=False))
        screen.wait_for(lambda text: "▶ Th3" in text)
        th4 = th3 + 1
        # press on the bar's left end, drag to its far left: joint 4 at its minimum
        screen.send(_sgr(0, 14, th4), _sgr(32, 11, th4), _sgr(32, 9, th4), _sgr(0, 9, th4, False))
        screen.wait_for(lambda text: "-110.00°" in text)
        # the wheel up twice over Th6: two one-degree steps
        th6 = th3 + 3
        screen.send(_sgr(64, 4, th6), _sgr(64, 4, th6))
        screen.wait_for(lambda text: "2.00°" in text)
        # and over the view: zoom
        screen.send(_sgr(64, 60, 12))
        screen.wait_for(lambda text: "zoom 1.5x" in text)
        assert "Traceback" not in screen.screen_text()
        screen.send("q")
        assert screen.wait_exit() == 0

"""The views panel as a user meets it: four views from 120x36, one scale,
z to maximise, + - 0 to zoom, 4 and a d w s for the 3-D view, a legend that
never wraps, and the axis colours in every colour depth."""

from __future__ import annotations

import pytest
from pilot_helpers import press, started, until
from rich.color import ColorSystem
from rich.console import Console
from rich.segment import Segment

from dhsim_tui.core import load_robot
from dhsim_tui.render.picture import CELL_ROLES
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.widgets.arm_view import ArmView
from dhsim_tui.tui.widgets.view_style import role_styles
from dhsim_tui.tui.widgets.views_panel import ViewsPanel


def views(app) -> list[ArmView]:
    return list(app.screen.query(ArmView))


def per_column(view: ArmView) -> float:
    """Robot units per column (two braille dots), whatever the y labels' width."""
    picture = view.picture
    return 2 * (picture.xlim[1] - picture.xlim[0]) / (2 * picture.canvas[2] - 1)


async def test_four_views_in_a_grid_at_one_scale_from_120x36(control_app):
    app = control_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        await press(pilot, "0")  # the work area (the views open fitted to the arm)
        await pilot.pause()
        shown = [v for v in views(app) if v.display and v.size.area]
        assert [v.view.key for v in shown] == ["top", "front", "side", "iso"]
        sizes = {v.size for v in shown}
        assert len(sizes) == 1  # a 2x2 grid of equal views
        assert shown[3].border_title.startswith("3-D")
        scales = [per_column(v) for v in shown[:3]]
        assert max(scales) == pytest.approx(min(scales))  # 100 mm: as many columns in each
        # the work area: reach + 30 each side, floor at -h
        area = shown[0].scene.bounds
        xlim, ylim = shown[0].picture.xlim, shown[0].picture.ylim
        assert (
            xlim[0] <= area[0] and xlim[1] >= area[1] and ylim[0] <= area[2] and ylim[1] >= area[3]
        )


async def test_one_view_at_80x24_and_tab_cycles_all_four(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        seen = []
        for _ in range(4):
            shown = [v.view.key for v in views(app) if v.display and v.size.area]
            seen.append(shown)
            await press(pilot, "tab")
        assert seen == [["front"], ["side"], ["iso"], ["top"]]
        await press(pilot, "4")
        assert [v.view.key for v in views(app) if v.display and v.size.area] == ["iso"]


async def test_z_maximises_the_selected_view_and_restores_it(control_app):
    app = control_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        front = app.screen.query_one("#view-front", ArmView)
        before = front.size
        await press(pilot, "z")
        await pilot.pause()
        assert front.size.width > 2 * before.width - 10 and front.size.height > before.height
        assert not app.screen.query_one("#side-panel").display
        assert [v.view.key for v in views(app) if v.display and v.size.area] == ["front"]
        await press(pilot, "z")
        await pilot.pause()
        assert front.size == before


async def test_zoom_about_the_arm_and_back_to_the_work_area(control_app):
    app = control_app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        await press(pilot, "0")  # the work area (the views open fitted to the arm)
        await pilot.pause()
        front = app.screen.query_one("#view-front", ArmView)
        whole = per_column(front)
        default_xlim = front.picture.xlim
        await press(pilot, "plus", "plus")
        await pilot.pause()
        # a regular scale (a tick every k rows) shows up to 1.25 times more,
        # at zoom 1 as zoomed: the zoom is 2.25 within that
        assert whole / 1.5**2 / 1.25 <= per_column(front) <= 1.25 * whole / 1.5**2
        panel = app.screen.query_one(ViewsPanel)
        centre = panel._zoom_centre
        xlim = front.picture.xlim
        assert xlim[0] < centre[0] < xlim[1]  # about the arm
        assert "zoom 2.25x" in str(front.border_subtitle)
        await press(pilot, "minus")
        await pilot.pause()
        assert whole / 1.5 / 1.25 <= per_column(front) <= 1.25 * whole / 1.5
        await press(pilot, "0")
        await pilot.pause()
        assert per_column(front) == pytest.approx(whole)
        assert front.picture.xlim == pytest.approx(default_xlim)
        assert "zoom" not in str(front.border_subtitle)


async def test_orbit_keys_turn_the_3d_view(control_app):
    app = control_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "d")  # shows the 3-D view and turns it
        await pilot.pause()
        iso = app.screen.query_one("#view-iso", ArmView)
        assert iso.display and iso.size.area
        assert "az 60° el 35°" in str(iso.border_subtitle)
        before = iso.picture.lines
        await press(pilot, "w", "w")
        await pilot.pause()
        assert "az 60° el 65°" in str(iso.border_subtitle)
        assert iso.picture.lines != before


@pytest.mark.parametrize("size", [(80, 24), (120, 36), (200, 60)])
async def test_the_legend_and_views_fill_the_panel_without_wrapping(size, control_app):
    app = control_app()
    async with app.run_test(size=size) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        legend = panel.query_one(".legend")
        if legend.display:
            assert legend.size.height == 1
            assert len(legend.render().plain) <= legend.size.width  # never wrapped or cut
        shown = [v for v in views(app) if v.display and v.size.area]
        area = sum(v.outer_size.area for v in shown) + (
            legend.outer_size.area if legend.display else 0
        )
        assert area == panel.size.area  # no dead space in the panel
        side = app.screen.query_one("#side-panel")
        used = sum(child.outer_size.height for child in side.children if child.display)
        assert used == side.size.height


def _sgr(style, system: str) -> str:
    console = Console(color_system=system, force_terminal=True, width=10)
    return console._render_buffer([Segment("━", style)])


@pytest.mark.parametrize(
    ("system", "codes"),
    [
        ("standard", ("91", "92", "94")),  # the ANSI bright red, green, blue
        ("256", ("38;5;167", "38;5;71", "38;5;69")),
        ("truecolor", ("38;2;215;95;95", "38;2;95;175;95", "38;2;95;135;255")),
    ],
)
def test_axes_are_red_green_blue_in_every_colour_depth(system, codes):
    styles = dict(zip(CELL_ROLES, role_styles(system), strict=True))
    for role, code in zip("xyz", codes, strict=True):
        assert f"\x1b[{code}m" in _sgr(styles[role], system) or f";{code}m" in _sgr(
            styles[role], system
        ), (role, _sgr(styles[role], system))
    if system == "standard":  # nothing else in the scene uses those three
        others = {_sgr(styles[role], system) for role in CELL_ROLES if role not in ("x", "y", "z")}
        for code in codes:
            assert not any(f"[{code}m" in text or f";{code}m" in text for text in others)
    # blue is really blue: its blue channel leads
    colour = styles["z"].color.get_truecolor()
    assert colour.blue > 1.5 * max(colour.red, colour.green)


def test_without_colour_the_tool_stands_out():
    styles = dict(zip(CELL_ROLES, role_styles(None, mono=True), strict=True))
    assert styles["tool"].reverse and styles["tool"].bold
    assert ColorSystem  # the mono styles carry no colour at all
    assert all(style.color is None for style in styles.values())


async def test_the_ansi_theme_hands_the_terminal_its_own_colours():
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False, theme="ansi")
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        front = app.screen.query_one("#view-front", ArmView)
        styles = front._styles
        for role, name in (("x", "bright_red"), ("y", "bright_green"), ("z", "bright_blue")):
            colour = styles[CELL_ROLES.index(role)].color
            assert colour.is_system_defined and colour.name == name
        app.theme = "dhsim-dark"  # and back: real blue again
        z = CELL_ROLES.index("z")
        await until(
            pilot,
            lambda: front._styles is None or not front._styles[z].color.is_system_defined,
            "the views restyled",
        )
        front.render_line(0)
        assert not front._styles[CELL_ROLES.index("z")].color.is_system_defined


@pytest.mark.parametrize("size", [(80, 24), (120, 36), (160, 48)])
async def test_the_editors_preview_shows_the_legend_only_when_it_fits(size):
    """The legend is shown when it names at least the links, the joints and
    the tool on its one line (the editor's preview has room for it at 80
    columns too, since it sits under the joints table), and is never
    wrapped or cut."""
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False, start="edit")
    async with app.run_test(size=size) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        legend = panel.query_one(".legend")
        essentials = len("━ links  ● joint  ◆ tool")
        fits = panel.size.width - 2 >= essentials
        assert legend.display == fits
        if fits:
            text = legend.render().plain
            assert text.startswith("━ links  ● joint  ◆ tool")
            assert len(text) <= legend.size.width


def test_a_theme_that_does_not_exist_gets_one_line(capsys):
    from dhsim_tui.cli.main import main

    assert main(["--theme", "bogus"]) == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'bogus'" in err and "ansi" in err and "Traceback" not in err

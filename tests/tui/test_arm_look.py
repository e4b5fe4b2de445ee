"""See the arm (issue 16): heavy links over the frames, joints marked by type,
frames that can be thinned, a faint floor, one colour for the links and one
legend that tells the truth. Scene and render level; no app."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from conftest import reference_frames
from pilot_helpers import press, started
from rich.color import Color as RichColor
from rich.color import ColorSystem

from dhsim_tui.core import bundled_names, load_robot
from dhsim_tui.render.picture import CELL_ROLES, NO_ROLE, ROLE_INDEX, Look
from dhsim_tui.render.plotext_picture import PlotextPainter
from dhsim_tui.scene import build_wireframe, project
from dhsim_tui.scene.figure import least_size
from dhsim_tui.scene.framing import fitted, framing_of
from dhsim_tui.scene.oblique import Orbit, project_oblique
from dhsim_tui.scene.projection import FRONT, SIDE, TOP, VIEWS, Polyline, ViewScene, limits_at
from dhsim_tui.scene.raster import QUADRANTS, rasterize
from dhsim_tui.tui.colour import THEMES, sixteen
from dhsim_tui.tui.widgets.legend import legend_items, pack
from dhsim_tui.tui.widgets.view_style import PALETTES, role_styles

BUNDLED = bundled_names()
#: quadrant pixels of each block glyph: upper left, upper right, lower left, lower right
QUAD_BITS = {glyph: bits for bits, glyph in enumerate(QUADRANTS)}


def _scene(name: str, view, q=None, frames: str = "all"):
    robot, _ = load_robot(name)
    wire = build_wireframe(robot, robot.kinematics.frames(robot.home if q is None else q))
    scene = project_oblique(wire, Orbit(), frames) if view.is_3d else project(wire, view, frames)
    return wire, scene


def _raster_fitted(scene: ViewScene, wire, cols: int, rows: int):
    framing = fitted(scene, cols, rows, least_size(wire))
    return rasterize(scene, cols, rows, limits_at(framing.centre, framing.per_dot, cols, rows))


# -- the links --------------------------------------------------------------------------


def test_a_link_is_a_solid_bar_two_dots_wide_whichever_way_it_runs():
    """Across: one cell wide (two of a braille cell's dots); up and down: half
    a cell deep (also two dots). Drawn in quadrant blocks, not braille."""
    nan = float("nan")
    across = Polyline((-8.0, 8.0), (0.0, 0.0), "link")
    up = Polyline((5.0, 5.0), (-8.0, 8.0), "link")
    scene = ViewScene(None, (across, up), (nan, nan), (-10, 10, -10, 10))
    raster = rasterize(scene, 40, 20, ((-10.0, 10.0), (-10.0, 10.0)))
    link = raster.palette.index("link")
    glyphs = {ch for y, line in enumerate(raster.lines) for x, ch in enumerate(line)
              if raster.colours[y, x] == link}  # fmt: skip
    assert glyphs and glyphs <= set(QUADRANTS[1:])  # blocks only, never a braille dot
    # the vertical bar: every row it crosses has two quadrant columns filled
    pixels: dict[int, set[int]] = {}
    for y, line in enumerate(raster.lines):
        for x, ch in enumerate(line):
            if raster.colours[y, x] == link and ch in QUAD_BITS and x > 24:
                bits = QUAD_BITS[ch]
                for half in (0, 1):  # upper, lower half of the cell
                    for side in (0, 1):
                        if bits & (1 << (2 * half + side)):
                            pixels.setdefault(2 * y + half, set()).add(2 * x + side)
    widths = [len(columns) for columns in pixels.values()]
    assert widths and min(widths) >= 2


@pytest.mark.parametrize("view", VIEWS, ids=lambda v: v.key)
def test_the_links_are_drawn_over_the_frames_floor_and_grid(view):
    """Wherever a link passes, its cell shows the link: never an axis, the
    floor or the grid drawn after it."""
    wire, scene = _scene("puma560", view, q=(10.0, 30.0, -60.0, 20.0, 40.0, 0.0))
    raster = _raster_fitted(scene, wire, 50, 20)
    (link,) = [line for line in scene.lines if line.role == "link"]
    sx = (2 * 50 - 1) / (raster.xlim[1] - raster.xlim[0])
    sy = (4 * 20 - 1) / (raster.ylim[1] - raster.ylim[0])
    marks = {raster.palette.index(role) for role in ("revolute", "prismatic", "tool")}
    checked = 0
    for (x0, x1), (y0, y1) in zip(
        zip(link.xs, link.xs[1:], strict=False),
        zip(link.ys, link.ys[1:], strict=False),
        strict=True,
    ):
        for t in np.linspace(0.25, 0.75, 5):
            x, y = x0 + t * (x1 - x0), y0 + t * (y1 - y0)
            col = round((x - raster.xlim[0]) * sx) // 2
            row = round((raster.ylim[1] - y) * sy) // 4
            if 0 <= col < 50 and 0 <= row < 20 and math.hypot(x1 - x0, y1 - y0) > 0:
                role = raster.colours[row, col]
                assert role == raster.palette.index("link") or role in marks, (row, col)
                checked += 1
    assert checked > 5


def test_the_links_colour_is_theirs_alone_in_every_palette():
    for name, palette in PALETTES.items():
        others = {colour for role, colour in palette.items() if role != "link"}
        assert palette["link"] not in others, name
        # nor anything the scene draws with a colour of its own in full colour
        assert palette["link"] not in ("bright_red", "bright_green", "bright_blue")
    # and no theme's chrome is the links' colour (nor, in 16 colours, becomes it)
    link16 = RichColor.parse(PALETTES["standard"]["link"]).downgrade(ColorSystem.STANDARD)
    for theme in THEMES.values():
        for field in ("primary", "secondary", "accent", "warning", "error", "success"):
            value = getattr(theme, field)
            if value is None:
                continue
            if value.startswith("ansi_"):  # the terminal's own palette, by name
                reserved = ("red", "green", "blue", "bright_yellow")
                assert not value.endswith(reserved), (theme.name, field, value)
                continue
            assert value.lower() != PALETTES["truecolor"]["link"], (theme.name, field)
            chrome = sixteen(RichColor.parse(value)).downgrade(ColorSystem.STANDARD)
            assert chrome.number != link16.number, (theme.name, field, value)
            assert chrome.number not in (1, 2, 4, 9, 10, 12), (theme.name, field, value)


def test_sixteen_colours_keep_red_green_blue_and_bright_yellow_for_the_scene():
    for number in range(16):
        colour = sixteen(RichColor.from_ansi(number))
        kept = number in (9, 10, 11, 12)  # the axes' and the links' own
        assert (colour.number == number) == (kept or number not in (1, 2, 4)), number
    for triplet in ("rgb(255,85,85)", "rgb(85,255,85)", "rgb(85,85,255)", "rgb(255,255,85)"):
        assert sixteen(RichColor.parse(triplet)) == RichColor.parse(triplet)
    # a crimson error, a green toast, a blue cursor, a yellow warning: none stays
    for other in ("#d7306f", "#4EBF71", "#0178D4", "#ffd75f", "red", "green", "blue"):
        number = sixteen(RichColor.parse(other)).downgrade(ColorSystem.STANDARD).number
        assert number not in (1, 2, 4, 9, 10, 11, 12), other


# -- the joints ---------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["puma560", "puma560_modified", "stanford", "cobra600", "gantry"])
def test_every_joint_is_marked_where_its_axis_is_by_its_type(name, rng):
    """Joint i turns about (slides along) z of frame i-1 in standard D-H and
    of frame i in modified: the mark is at that origin, from an independent FK."""
    robot, _ = load_robot(name)
    q = rng.uniform(robot.lower, robot.upper)
    wire = build_wireframe(robot, robot.kinematics.frames(q))
    frames = reference_frames(robot, q)
    first = 0 if robot.convention == "standard" else 1
    expected = frames[first : first + robot.dof, :3, 3]
    np.testing.assert_allclose(wire.joints, expected, atol=1e-9 * max(1.0, np.abs(expected).max()))
    scene = project(wire, FRONT)
    marks = [mark for mark in scene.marks if mark.role != "tool"]
    assert [mark.role for mark in marks] == [joint.type for joint in robot.joints]
    np.testing.assert_allclose(
        [(m.x, m.y) for m in marks], expected[:, [0, 2]], atol=1e-9 * np.abs(expected).max()
    )
    assert scene.marks[-1].role == "tool"  # drawn last: on top of every joint


def test_a_prismatic_joint_shows_a_square_and_a_revolute_one_a_dot():
    wire, scene = _scene("stanford", FRONT, q=(20.0, -30.0, 600.0, 0.0, 40.0, 0.0))
    text = "".join(_raster_fitted(scene, wire, 60, 24).lines)
    assert "■" in text and "●" in text and "◆" in text


# -- the frames --------------------------------------------------------------------------


@pytest.mark.parametrize(("mode", "count"), [("all", 7), ("ends", 2), ("none", 0)])
def test_x_draws_every_frame_the_base_and_tool_or_none(mode, count):
    wire, scene = _scene("puma560", FRONT, frames=mode)
    assert list(wire.shown_frames(mode)) == ([0, 6] if mode == "ends" else list(range(count)))
    for role in ("x", "y", "z"):
        lines = [line for line in scene.lines if line.role == role]
        strokes = 0 if not lines else sum(1 for v in lines[0].xs if math.isnan(v)) + 1
        assert strokes == count
    assert len(scene.tips) == 3 * count
    assert any(line.role == "link" for line in scene.lines)  # the arm stays whatever the frames


def test_frame_axes_are_shorter_than_the_links_and_thin():
    """Axes 6% of the reach (the Puma's links are about a third of it each)."""
    wire, _ = _scene("puma560", FRONT)
    lengths = np.linalg.norm(wire.axes - wire.origins[:, None, :], axis=2)
    links = np.linalg.norm(np.diff(wire.links, axis=0), axis=1)
    assert lengths.min() < 0.25 * links.max()
    styles = dict(zip(CELL_ROLES, role_styles("256"), strict=True))
    assert not any(styles[role].bold for role in "xyz")


# -- the floor -------------------------------------------------------------------------


def test_the_3d_grid_is_sparse_and_no_line_lies_on_the_outline():
    wire, scene = _scene("puma560", VIEWS[3])
    raster = rasterize(scene, 100, 30)
    grid = raster.palette.index("grid")
    dots = sum(
        bin(ord(ch) - 0x2800).count("1")
        for y, line in enumerate(raster.lines)
        for x, ch in enumerate(line)
        if raster.colours[y, x] == grid and ch >= "\u2800"
    )
    cells = int((raster.colours == grid).sum())
    assert cells and dots / cells < 1.6  # every fourth dot: light, never solid runs
    area = wire.area
    step = scene.grid_step
    inner = [k * step for k in range(-100, 101) if area.xmin < k * step < area.xmax]
    assert all(not math.isclose(v, area.xmin) and not math.isclose(v, area.xmax) for v in inner)


def test_the_floor_and_grid_are_fainter_than_the_links():
    """In every colour depth, the floor's and grid's grey is darker than the
    links' colour (on a dark background): never louder than the arm."""

    def brightness(style) -> float:
        red, green, blue = style.color.get_truecolor()
        return 0.2126 * red + 0.7152 * green + 0.0722 * blue

    for system in ("truecolor", "256", "standard"):
        styles = dict(zip(CELL_ROLES, role_styles(system), strict=True))
        for faint in ("grid", "floor", "shadow"):
            assert brightness(styles[faint]) < brightness(styles["link"]), (system, faint)
    mono = dict(zip(CELL_ROLES, role_styles(None, mono=True), strict=True))
    assert mono["link"].bold and mono["grid"].dim and mono["floor"].bold is not True


def test_the_3d_view_draws_the_links_shadow_on_the_floor():
    wire, scene = _scene("puma560", VIEWS[3], q=(30.0, 40.0, -60.0, 0.0, 0.0, 0.0))
    (shadow,) = [line for line in scene.lines if line.role == "shadow"]
    assert len(shadow.xs) == len(wire.links)
    np.testing.assert_allclose(wire.shadow[:, :2], wire.links[:, :2])
    assert np.all(wire.shadow[:, 2] == wire.floor_z)


# -- the legend ---------------------------------------------------------------------------


@pytest.mark.parametrize("system", ["truecolor", "256", "standard"])
def test_the_legend_shows_each_role_in_its_real_colour_and_glyph(system):
    styles = dict(zip(CELL_ROLES, role_styles(system), strict=True))
    items = legend_items(
        ascii=False, mono=False, styles=styles, joint_types=("revolute", "prismatic")
    )
    text = pack(items, 200)
    drawn = {"━": "link", "●": "revolute", "■": "prismatic", "◆": "tool", "┄": "floor"}
    for glyph, role in drawn.items():
        at = text.plain.index(glyph)
        spans = [span for span in text.spans if span.start <= at < span.end]
        assert spans and spans[-1].style == styles[role], (glyph, spans)
    # and the glyphs are the ones the views draw
    wire, scene = _scene("stanford", FRONT)
    raster_text = "".join(_raster_fitted(scene, wire, 60, 24).lines)
    for glyph in ("●", "■", "◆"):
        assert glyph in raster_text


def test_a_narrow_legend_keeps_the_arm_first_and_never_wraps():
    styles = dict(zip(CELL_ROLES, role_styles("256"), strict=True))
    items = legend_items(ascii=False, mono=False, styles=styles)
    for width in (24, 40, 60, 80):
        text = pack(items, width)
        assert text.cell_len <= width or width < 24
        assert text.plain.startswith("━ links  ● joint  ◆ tool")


# -- views in every mode ------------------------------------------------------------------


@pytest.mark.parametrize("view", [TOP, FRONT, SIDE], ids=lambda v: v.key)
def test_mono_pictures_carry_the_arm_in_blocks_and_no_letter_runs(view):
    _, scene = _scene("puma560", view, q=(10.0, 30.0, -60.0, 20.0, 40.0, 0.0))
    framing = framing_of(scene.bounds, 50, 20)
    picture = PlotextPainter().draw(scene, 60, 24, framing, Look(mono=True))
    links = picture.roles == ROLE_INDEX["link"]
    assert links.any()
    for line in picture.lines:
        for a, b in itertools.pairwise(line):
            assert not (a == b and a in "xyz"), line
    assert NO_ROLE in picture.roles


def test_no_nan_reaches_the_marks_of_a_scene_off_the_picture():
    _, scene = _scene("puma560", FRONT)
    raster = rasterize(scene, 10, 5, ((1e6, 2e6), (1e6, 2e6)))  # nothing on the picture
    assert all(set(line) == {" "} for line in raster.lines)


@pytest.mark.parametrize("name", BUNDLED)
def test_every_bundled_robot_draws_links_in_every_view(name):
    robot, _ = load_robot(name)
    wire = build_wireframe(robot, robot.kinematics.frames(robot.home))
    for view in VIEWS:
        scene = project_oblique(wire, Orbit()) if view.is_3d else project(wire, view)
        raster = _raster_fitted(scene, wire, 40, 16)
        link = raster.palette.index("link")
        if (
            np.ptp(
                wire.links[:, [view.right, view.up]] if not view.is_3d else wire.links, axis=0
            ).max()
            > 0
        ):
            assert (raster.colours == link).any(), (name, view.key)


async def test_x_cycles_the_frames_and_the_legend_and_captions_say_which():
    from dhsim_tui.tui.app import DhsimApp
    from dhsim_tui.tui.widgets.arm_view import ArmView
    from dhsim_tui.tui.widgets.views_panel import ViewsPanel

    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False)
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        panel = app.screen.query_one(ViewsPanel)
        front = app.screen.query_one("#view-front", ArmView)
        legend = panel.query_one(".legend")

        def axis_cells() -> int:
            roles = front.picture.roles
            return int(sum((roles == ROLE_INDEX[r]).sum() for r in "xyz"))

        # the views open close up, fitted to the arm: the axes of every frame show
        every = axis_cells()
        assert "frames: all (x)" in str(legend.render())
        await press(pilot, "x")
        await pilot.pause()
        assert panel.frames == "ends" and 0 < axis_cells() < every
        assert "frames: base+tool" in str(legend.render())
        assert "frames: base+tool" in str(front.border_subtitle)
        await press(pilot, "x")
        await pilot.pause()
        assert panel.frames == "none" and axis_cells() == 0
        assert (front.picture.roles == ROLE_INDEX["link"]).any()  # the arm stays
        await press(pilot, "x")
        await pilot.pause()
        assert panel.frames == "all" and axis_cells() == every

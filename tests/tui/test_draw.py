"""Pictures for a lab report (issue 16): ``dhsim draw`` and the simulator's
"Save picture". The SVG's links are checked against an independent FK
through the drawing's own tick labels."""

from __future__ import annotations

import itertools
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from conftest import reference_frames
from pilot_helpers import palette_searching, press, started, until

from dhsim_tui.cli.main import main
from dhsim_tui.core import load_robot
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.palette import SAVE_PICTURE, DhsimPalette

SVG = "{http://www.w3.org/2000/svg}"
Q = (10.0, 45.0, -45.0, 20.0, 30.0, 40.0)


def draw(tmp_path, capsys, *args: str) -> tuple[int, str, str]:
    status = main(["draw", *args])
    out, err = capsys.readouterr()
    return status, out, err


def _number(text: str | None) -> float | None:
    try:
        return float(text or "")
    except ValueError:
        return None


def test_an_svg_of_every_view_draws_the_links_where_an_independent_fk_puts_them(tmp_path, capsys):
    out = tmp_path / "puma.svg"
    status, stdout, _ = draw(
        tmp_path, capsys, "puma560", "--q", ",".join(map(str, Q)), "-o", str(out)
    )
    assert status == 0 and f"wrote {out}" in stdout
    root = ET.parse(out).getroot()  # well-formed XML
    assert root.tag == f"{SVG}svg"
    captions = [el.text for el in root.iter(f"{SVG}text")]
    for caption in ("Top  X→ Y↑", "Front  X→ Z↑", "Side  Y→ Z↑", "3-D"):
        assert caption in captions
    robot, _ = load_robot("puma560")
    origins = reference_frames(robot, Q)[: robot.dof + 1, :3, 3]
    # the front view: its x tick labels give pixels -> mm across, its y labels up
    texts = [
        (_number(el.text), float(el.get("x")), float(el.get("y")), el.get("text-anchor"))
        for el in root.iter(f"{SVG}text")
    ]
    texts = [(v, x, y, a) for v, x, y, a in texts if v is not None]
    front_x = [(v, x) for v, x, y, a in texts if a == "middle" and 400 < y < 450 and x > 600]
    front_y = [(v, y) for v, x, y, a in texts if a == "end" and x > 600 and y < 450]
    (v0, p0), (v1, p1) = front_x[0], front_x[-1]
    (w0, q0), (w1, q1) = front_y[0], front_y[-1]
    to_mm_x = lambda px: v0 + (px - p0) * (v1 - v0) / (p1 - p0)  # noqa: E731
    to_mm_z = lambda py: w0 + (py + 3.5 - q0) * (w1 - w0) / (q1 - q0)  # labels sit 3.5 px low  # noqa: E731
    links = [el for el in root.iter(f"{SVG}line") if el.get("stroke") == "#ff7f0e"]
    front = [el for el in links if float(el.get("x1")) > 600 and float(el.get("y1")) < 450]
    assert len(front) == robot.dof  # one segment a link, frame 0 to frame 6
    tolerance = 2.0 * abs((v1 - v0) / (p1 - p0))  # two pixels, in mm
    for segment, (start, end) in zip(front, itertools.pairwise(origins), strict=True):
        got = [
            (to_mm_x(float(segment.get("x1"))), to_mm_z(float(segment.get("y1")))),
            (to_mm_x(float(segment.get("x2"))), to_mm_z(float(segment.get("y2")))),
        ]
        np.testing.assert_allclose(got, [start[[0, 2]], end[[0, 2]]], atol=tolerance)
    # the joints and the tool are marked: six circles, one diamond a view
    assert len(list(root.iter(f"{SVG}circle"))) >= 4 * robot.dof
    assert len(list(root.iter(f"{SVG}polygon"))) >= 4


def test_a_prismatic_joint_is_a_square_in_the_svg(tmp_path, capsys):
    out = tmp_path / "stanford.svg"
    status, _, _ = draw(tmp_path, capsys, "stanford", "--view", "front", "-o", str(out))
    assert status == 0
    root = ET.parse(out).getroot()
    squares = [el for el in root.iter(f"{SVG}rect") if el.get("width") == "10"]
    assert len(squares) >= 2  # the joint and the legend's


def test_text_goes_to_stdout_without_colour_when_it_is_not_a_terminal(tmp_path, capsys):
    status, out, _ = draw(tmp_path, capsys, "puma560", "--view", "front", "--size", "80x24")
    assert status == 0
    assert "\x1b" not in out
    lines = out.rstrip("\n").split("\n")
    assert lines[0].startswith("Front") and len(lines) <= 24
    assert max(len(line) for line in lines) <= 80
    assert "█" in out or "▀" in out or "▄" in out  # the links
    assert "◆" in out


def test_a_txt_file_holds_the_four_views(tmp_path, capsys):
    out = tmp_path / "views.txt"
    status, _, _ = draw(tmp_path, capsys, "puma560", "--fit", "-o", str(out))
    assert status == 0
    text = out.read_text(encoding="utf-8")
    for caption in ("Top", "Front", "Side", "3-D"):
        assert caption in text
    assert "\x1b" not in text


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["--view", "back"], "invalid choice: 'back'"),
        (["--size", "big"], "expected WIDTHxHEIGHT"),
        (["--size", "10x10", "-o", "x.svg"], "200 to 8000 pixels"),
        (["--size", "20x5"], "columns and rows"),
        (["-o", "x.png"], "ends in .svg (a drawing) or .txt"),
        (["-o", ""], "the file name is empty"),
        (["--q", "1,2"], "--q"),
        (["--q", "0,0,0,0,0,0", "--pose", "qr"], "either --q or --pose"),
        (["--pose", "nope"], "nope"),
        (["--orbit", "45"], "AZIMUTH,ELEVATION"),
        (["--orbit", "45,100"], "-90 to 90"),
        (["--frames", "some"], "invalid choice: 'some'"),
    ],
)
def test_bad_arguments_get_one_line_and_exit_2(tmp_path, capsys, monkeypatch, args, says):
    monkeypatch.chdir(tmp_path)
    status, _, err = draw(tmp_path, capsys, "puma560", *args)
    assert status == 2
    assert says in err and err.count("\n") == 1 and "Traceback" not in err
    assert not list(tmp_path.iterdir())  # nothing written


def test_an_existing_file_is_kept_unless_forced(tmp_path, capsys):
    out = tmp_path / "a.svg"
    out.write_text("mine")
    status, _, err = draw(tmp_path, capsys, "puma560", "-o", str(out))
    assert status == 2 and "already exists" in err and out.read_text() == "mine"
    status, _, _ = draw(tmp_path, capsys, "puma560", "-o", str(out), "--force")
    assert status == 0 and out.read_text().startswith("<svg")


def test_draw_needs_no_terminal_and_no_textual(tmp_path):
    """Run as a command: no terminal, and the UI library is never loaded."""
    import subprocess
    import sys

    code = (
        "import sys; from dhsim_tui.cli.main import main; "
        f"status = main(['draw', 'puma560', '-o', {str(tmp_path / 'p.svg')!r}]); "
        "assert 'textual' not in sys.modules, 'textual loaded'; sys.exit(status)"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], stdin=subprocess.DEVNULL, capture_output=True, text=True
    )
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "p.svg").stat().st_size > 1000


# -- the simulator's "Save picture" ---------------------------------------------------------


def _app() -> DhsimApp:
    robot, path = load_robot("puma560")
    return DhsimApp(robot, path, animate=False)


async def test_i_saves_the_screen_as_an_svg_in_the_working_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    app = _app()
    async with app.run_test(size=(120, 36)) as pilot:
        await started(pilot)
        await press(pilot, "i")
        await pilot.pause()
        (picture,) = list(tmp_path.glob("dhsim-Puma_560-*.svg"))
        root = ET.parse(picture).getroot()
        assert root.tag == f"{SVG}svg"
        assert "Th1" in picture.read_text(encoding="utf-8")  # what the screen showed
        status = str(app.screen.query_one("#status").render())
        assert status.startswith("picture saved: ") and status.endswith(f"/{picture.name}")
        await press(pilot, "i")  # again in the same second: a new name, nothing replaced
        await pilot.pause()
        assert len(list(tmp_path.glob("dhsim-Puma_560-*.svg"))) == 2


@pytest.mark.parametrize("size", [(120, 36), (80, 24)])
async def test_a_long_path_is_shortened_in_the_middle_never_at_its_end(size, tmp_path, monkeypatch):
    deep = tmp_path.joinpath(*(f"a-rather-long-folder-name-{n}" for n in range(4)))
    deep.mkdir(parents=True)
    monkeypatch.chdir(deep)
    app = _app()
    async with app.run_test(size=size) as pilot:
        await started(pilot)
        await press(pilot, "i")
        await pilot.pause()
        (picture,) = list(deep.glob("dhsim-Puma_560-*.svg"))
        status = app.screen.query_one("#status")
        said = str(status.render())
        head, _, path = said.partition("picture saved: ")
        assert not head and path.endswith(f"/{picture.name}") and " … " in path
        head = path.split(" … ")[0]
        assert head and str(deep).startswith(head)  # the start of the path, then its end
        # the whole message is on the screen: no line of it cut
        lines = status.render_lines(status.region.reset_offset)
        shown = "".join(strip.text for strip in lines).replace(" ", "")
        assert said.replace(" ", "").replace("\n", "") in shown


async def test_a_picture_that_cannot_be_written_says_why(tmp_path, monkeypatch):
    gone = tmp_path / "gone"
    gone.mkdir()
    monkeypatch.chdir(gone)
    gone.rmdir()  # the working folder was removed under us
    app = _app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await press(pilot, "i")
        await pilot.pause()
        status = app.screen.query_one("#status")
        assert "picture not saved" in str(status.render()) and status.has_class("-error")


@pytest.mark.parametrize("query", ["scree", "plot", "picture"])
async def test_the_palette_finds_save_picture(query, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    app = _app()
    async with app.run_test(size=(100, 30)) as pilot:
        await started(pilot)
        await press(pilot, "ctrl+p")
        await pilot.pause()
        assert isinstance(app.screen, DhsimPalette)
        await press(pilot, *query)

        def shown() -> list[str]:
            return [
                str(option.prompt) for option in app.screen.query("CommandList").first().options
            ]

        await until(pilot, lambda: shown() and not palette_searching(app), "the palette's search")
        assert SAVE_PICTURE in shown()[0]
        await press(pilot, "enter")
        await until(pilot, lambda: list(tmp_path.glob("dhsim-*.svg")), "the picture saved")


def test_every_screenshot_mode_differs(request):
    """The README's mode pictures: each terminal mode's file is its own."""
    folder = Path(request.config.rootpath) / "screenshots"
    modes = [
        "views-120x36.svg",
        "views-16-colours-120x36.svg",
        "views-256-colours-120x36.svg",
        "views-no-color-120x36.svg",
        "views-ascii-120x36.svg",
        "views-ansi-theme-120x36.svg",
    ]
    contents = [(folder / name).read_bytes() for name in modes]
    assert len(set(contents)) == len(modes)
    # and the 16-colour picture holds only the 16 colours of its palette
    sixteen = (folder / "views-16-colours-120x36.svg").read_text()
    truecolour = (folder / "views-120x36.svg").read_text()
    assert len(set(re.findall(r"fill: (#[0-9a-f]{6})", sixteen))) <= 16
    assert len(set(re.findall(r"fill: (#[0-9a-f]{6})", truecolour))) > 16

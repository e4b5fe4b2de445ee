"""``dhsim draw``: the views of a robot as a picture for a report, without a
terminal.

    dhsim draw ROBOT [--q V,...|--pose NAME] [--view top|front|side|3d|all]
                     [--size WxH] [--fit] [--frames all|ends|none]
                     [--orbit AZ,EL] [-o FILE.svg|FILE.txt] [--force]

An ``.svg`` is a vector drawing (white page, the views with their ticks, a
legend); a ``.txt`` the views as the simulator draws them, in plain text.
Without ``-o`` the text goes to standard output, coloured only when that is
a terminal (and NO_COLOR is not set). ``--size`` is in pixels for an SVG and
in columns and rows for text. A thin shell over the scene and render layers.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from dhsim_tui.cli.kinematics import joint_values, parse_values
from dhsim_tui.core.files.atomicfile import write_file
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.text import counted, printable
from dhsim_tui.core.model.validation import fmt
from dhsim_tui.scene.figure import (
    VIEW_NAMES,
    figure_framings,
    least_size,
    view_scenes,
    wireframe_at,
)
from dhsim_tui.scene.oblique import ISOMETRIC_ELEVATION, Orbit
from dhsim_tui.scene.projection import VIEWS
from dhsim_tui.scene.wireframe import FRAME_MODES

#: what --view takes
VIEW_CHOICES = (*VIEW_NAMES, "all")
#: default sizes: SVG in pixels, text in columns × rows (one view, all four)
SVG_SIZES = {"one": (720, 560), "all": (1200, 900)}
TEXT_SIZES = {"one": (80, 24), "all": (120, 48)}
#: the sizes --size accepts
SVG_RANGE = (200, 8000)
TEXT_RANGE = ((40, 12), (1000, 1000))
#: the suffixes -o knows
SUFFIXES = (".svg", ".txt")


def parse_size(text: str) -> tuple[int, int]:
    """``"800x600"`` -> (800, 600), or a DhsimError saying what is wrong."""
    parts = text.lower().split("x")
    if len(parts) != 2 or not all(p.strip().isascii() and p.strip().isdigit() for p in parts):
        raise DhsimError(f"--size {printable(text)}: expected WIDTHxHEIGHT, e.g. 800x600")
    return int(parts[0]), int(parts[1])


def parse_orbit(text: str) -> Orbit:
    values = parse_values(text, "--orbit")
    if len(values) != 2:
        raise DhsimError(
            f"--orbit: expected AZIMUTH,ELEVATION in degrees, got {counted(len(values), 'value')}"
        )
    azimuth, elevation = values
    if not -90 <= elevation <= 90:
        raise DhsimError(f"--orbit: the elevation must be -90 to 90 degrees, got {fmt(elevation)}")
    return Orbit().turned(azimuth - Orbit().azimuth, elevation - ISOMETRIC_ELEVATION)


def _check_size(size: tuple[int, int], svg: bool) -> None:
    width, height = size
    if svg:
        low, high = SVG_RANGE
        if not (low <= width <= high and low <= height <= high):
            raise DhsimError(f"--size {width}x{height}: an SVG is {low} to {high} pixels each way")
    else:
        (min_w, min_h), (max_w, max_h) = TEXT_RANGE
        if not (min_w <= width <= max_w and min_h <= height <= max_h):
            raise DhsimError(
                f"--size {width}x{height}: text is {min_w}x{min_h} to {max_w}x{max_h} "
                "columns and rows"
            )


def _caption(view, ascii: bool) -> str:
    if view.is_3d:
        return view.title
    right, up = view.axis_names
    arrows = ("> ", "^") if ascii else ("→ ", "↑")
    return f"{view.title}  {right}{arrows[0]}{up}{arrows[1]}"


def _wants_colour(stream) -> bool:
    try:
        return stream.isatty() and not os.environ.get("NO_COLOR")
    except (AttributeError, ValueError, OSError):
        return False


def cmd_draw(args: argparse.Namespace) -> int:
    out = args.output
    suffix = Path(out).suffix.lower() if out else ".txt"
    if out is not None and not out:
        raise DhsimError("-o: the file name is empty; give a name ending in .svg or .txt")
    if suffix not in SUFFIXES:
        raise DhsimError(
            printable(f"-o {out}: a picture's name ends in .svg (a drawing) or .txt (text)")
        )
    svg = suffix == ".svg"
    which = "all" if args.view == "all" else "one"
    size = parse_size(args.size) if args.size else (SVG_SIZES if svg else TEXT_SIZES)[which]
    _check_size(size, svg)
    orbit = parse_orbit(args.orbit) if args.orbit else Orbit()
    robot, _ = load_robot(args.robot)
    q = joint_values(robot, args.q, args.pose)
    views = VIEWS if args.view == "all" else (VIEW_NAMES[args.view],)
    wire = wireframe_at(robot, q)
    scenes = view_scenes(wire, views, args.frames, orbit)
    ascii = not svg and _ascii_output(out)
    captions = [_caption(view, ascii) for view in views]
    if svg:
        from dhsim_tui.render.svg import layout, svg_figure

        panels = layout(scenes, captions, size)
        canvases = [panel.canvas for panel in panels]
        framings = figure_framings(scenes, canvases, fit=args.fit, least=least_size(wire))
        values = ", ".join(fmt(round(v, 6)) for v in q)
        title = printable(f"{robot.name}   q = {values}   ({robot.units}, deg)")
        text = svg_figure(panels, framings, size, title, {joint.type for joint in robot.joints})
    else:
        from dhsim_tui.render.text_figure import canvas, text_figure

        cells = size if len(views) == 1 else ((size[0] - 1) // 2, (size[1] - 1) // 2 - 1)
        canvases = [
            canvas(scene, cells[0], cells[1] - (1 if len(views) == 1 else 0)) for scene in scenes
        ]
        framings = figure_framings(scenes, canvases, fit=args.fit, least=least_size(wire))
        colour = out is None and _wants_colour(sys.stdout)
        text = text_figure(scenes, captions, framings, size, ascii=ascii, colour=colour)
    if out is None:
        sys.stdout.write(text)
        return 0
    write_file(out, text.encode("utf-8"), overwrite=args.force)
    print(printable(f"wrote {out}"))
    return 0


def _ascii_output(out: str | None) -> bool:
    """Text for a terminal whose locale is not UTF-8 is 7-bit ASCII; a file is UTF-8."""
    if out is not None:
        return False
    from dhsim_tui.terminal.locale_env import original_environ, wants_ascii

    return wants_ascii(original_environ())


def subparsers(parser_class: type[argparse.ArgumentParser]) -> dict[str, argparse.ArgumentParser]:
    draw = parser_class(
        prog="dhsim draw",
        description="Draw a robot's views as an SVG or text picture (no terminal needed).",
    )
    draw.add_argument("robot", help="a robot file or a bundled robot's name")
    draw.add_argument("--q", help="joint values, comma-separated (default: home)")
    draw.add_argument("--pose", help="a named pose of the robot")
    draw.add_argument(
        "--view", choices=VIEW_CHOICES, default="all", help="which view (default all)"
    )
    draw.add_argument("--size", help="WIDTHxHEIGHT: pixels for .svg, columns x rows for text")
    draw.add_argument("--fit", action="store_true", help="fit each view to the arm (as F does)")
    draw.add_argument(
        "--frames", choices=FRAME_MODES, default="all", help="frame axes drawn (as x cycles)"
    )
    draw.add_argument("--orbit", help="AZIMUTH,ELEVATION of the 3-D view (default 45,35.26)")
    draw.add_argument(
        "-o", "--output", metavar="FILE", help="FILE.svg or FILE.txt (default: text on stdout)"
    )
    draw.add_argument("--force", action="store_true", help="replace FILE if it exists")
    draw.set_defaults(func=cmd_draw)
    return {"draw": draw}

"""What each scene role looks like in a given terminal.

Frame axes are x red, y green, z blue in every colour depth, chosen per
depth rather than left to a conversion: in truecolor and 256 colours a
readable real blue (Textual's default ANSI theme made z purple, colour 135),
and in 16 colours the terminal's own bright red, green and blue (given as
the very RGB values rich's 16-colour palette holds, so rich maps them back
exactly: the ANSI-to-truecolor filter never sees an ANSI colour). Nothing
else in the scene is red, green or blue. With an ANSI theme, plain ANSI
colour names, so the terminal's palette decides. With NO_COLOR, letters at
the axis tips tell the axes apart and the tool is bold and reversed.

The workspace cloud, when shown, is a dark grey behind everything (dim as
well where that grey is the floor's), and dim without colour.
"""

from __future__ import annotations

from rich.style import Style

from dhsim_tui.render.picture import CELL_ROLES, Look
from dhsim_tui.terminal import ascii_mode

#: role -> colour, per colour system (rich's names for them)
PALETTES: dict[str, dict[str, str]] = {
    "truecolor": {
        "x": "#ff4f4f",
        "y": "#33cc33",
        "z": "#4f86ff",
        "tool": "#ff55ff",
        "pedestal": "#c8a000",
        "floor": "#8a8a8a",
        "floor_hit": "#ffd700",
        "grid": "#5f5f5f",
        "axes": "#9e9e9e",
        "cloud": "#4a4a4a",
    },
    "256": {
        "x": "color(196)",
        "y": "color(40)",
        "z": "color(33)",
        "tool": "color(201)",
        "pedestal": "color(178)",
        "floor": "color(245)",
        "floor_hit": "color(220)",
        "grid": "color(240)",
        "axes": "color(247)",
        "cloud": "color(238)",
    },
    # exactly rich's STANDARD_PALETTE entries 9, 10, 12, 13, 3, 8, 11, 8, 7
    "standard": {
        "x": "rgb(255,85,85)",
        "y": "rgb(85,255,85)",
        "z": "rgb(85,85,255)",
        "tool": "rgb(255,85,255)",
        "pedestal": "rgb(170,85,0)",
        "floor": "rgb(85,85,85)",
        "floor_hit": "rgb(255,255,85)",
        "grid": "rgb(85,85,85)",
        "axes": "rgb(170,170,170)",
        "cloud": "rgb(85,85,85)",
    },
    # an ANSI theme: the terminal's own palette
    "ansi": {
        "x": "bright_red",
        "y": "bright_green",
        "z": "bright_blue",
        "tool": "bright_magenta",
        "pedestal": "yellow",
        "floor": "bright_black",
        "floor_hit": "bright_yellow",
        "grid": "bright_black",
        "axes": "white",
        "cloud": "bright_black",
    },
}
#: drawn bold whatever the colours
BOLD = {"tool", "floor_hit"}
#: drawn dim in the palettes where their grey is the floor's (16 colours, an
#: ANSI theme): the workspace cloud stays behind the arm and the floor
DIM = {"cloud"}
DIM_PALETTES = ("standard", "ansi")


def palette_name(color_system: str | None, ansi_theme: bool) -> str:
    if ansi_theme:
        return "ansi"
    if color_system in ("truecolor", "256"):
        return color_system
    return "standard"


def role_styles(color_system: str | None, *, ansi_theme: bool = False, mono: bool = False):
    """A style per cell role (indexed like ``CELL_ROLES``)."""
    if mono or color_system is None:
        return [
            Style(bold=True, reverse=True)
            if role == "tool"
            else Style(bold=True)
            if role == "floor_hit"
            else Style(dim=True)
            if role in ("grid", "axes", "cloud")
            else Style()
            for role in CELL_ROLES
        ]
    name = palette_name(color_system, ansi_theme)
    colours = PALETTES[name]
    dim = DIM if name in DIM_PALETTES else set()
    return [
        Style(color=colours.get(role), bold=role in BOLD, dim=True if role in dim else None)
        if role in colours
        else Style()
        for role in CELL_ROLES
    ]


def look_of(app) -> Look:
    """How ``app``'s terminal wants the views: 7-bit ASCII, and whether it
    has colour at all (NO_COLOR, or a terminal without colours)."""
    return Look(
        ascii=ascii_mode(app),
        mono=bool(app.no_color) or app.console.color_system is None,
    )

"""What each scene role looks like in a given terminal.

The arm comes first: its links are the one orange (bright yellow in 16
colours) in the app, drawn with a heavy pen over everything but the joints
(white or the text colour, bold: ``●`` revolute, ``■`` prismatic) and the
tool (magenta ``◆``). Frame axes are x red, y green, z blue in every colour
depth, thin and a little softer than the links; nothing else on screen is
red, green or blue in 16 colours (``dhsim_tui.tui.colour`` keeps the chrome off
them). The floor, its grid and the links' shadow are dark greys, dimmer
than the arm.

Colours are chosen per depth rather than left to a conversion: in truecolor
and 256 colours the xterm-256 colours themselves, and in 16 colours the very
RGB values rich's 16-colour palette holds, so rich maps them back exactly
(the ANSI-to-truecolor filter never sees an ANSI colour). With an ANSI
theme, plain ANSI colour names, so the terminal's palette decides. With
NO_COLOR no colour at all: the links and joints bold, the frame axes, floor
and grid dim, letters at the axis tips, the tool bold and reversed.
"""

from __future__ import annotations

from rich.style import Style

from dhsim_tui.render.picture import CELL_ROLES, Look
from dhsim_tui.terminal.charset import ascii_mode

#: role -> colour, per colour system (rich's names for them); a role missing
#: from a palette (the joints) is drawn in the text's own colour, bold
PALETTES: dict[str, dict[str, str]] = {
    "truecolor": {
        "x": "#d75f5f",
        "y": "#5faf5f",
        "z": "#5f87ff",
        "link": "#ff8700",
        "tool": "#ff5fff",
        "pedestal": "#808080",
        "floor": "#6c6c6c",
        "floor_hit": "#ffd700",
        "grid": "#4e4e4e",
        "shadow": "#585858",
        "trail": "#5fafaf",
        "axes": "#9e9e9e",
        "cloud": "#444444",
    },
    "256": {
        "x": "color(167)",
        "y": "color(71)",
        "z": "color(69)",
        "link": "color(208)",
        "tool": "color(207)",
        "pedestal": "color(244)",
        "floor": "color(242)",
        "floor_hit": "color(220)",
        "grid": "color(239)",
        "shadow": "color(240)",
        "trail": "color(73)",
        "axes": "color(247)",
        "cloud": "color(238)",
    },
    # exactly rich's STANDARD_PALETTE entries: bright red, green, blue for the
    # axes alone; bright yellow for the links alone
    "standard": {
        "x": "rgb(255,85,85)",
        "y": "rgb(85,255,85)",
        "z": "rgb(85,85,255)",
        "link": "rgb(255,255,85)",
        "tool": "rgb(255,85,255)",
        "pedestal": "rgb(170,170,170)",
        "floor": "rgb(85,85,85)",
        "floor_hit": "rgb(170,0,170)",
        "grid": "rgb(85,85,85)",
        "shadow": "rgb(85,85,85)",
        "trail": "rgb(0,170,170)",
        "axes": "rgb(170,170,170)",
        "cloud": "rgb(85,85,85)",
    },
    # an ANSI theme: the terminal's own palette
    "ansi": {
        "x": "bright_red",
        "y": "bright_green",
        "z": "bright_blue",
        "link": "bright_yellow",
        "tool": "bright_magenta",
        "pedestal": "white",
        "floor": "bright_black",
        "floor_hit": "magenta",
        "grid": "bright_black",
        "shadow": "bright_black",
        "trail": "cyan",
        "axes": "white",
        "cloud": "bright_black",
    },
}
#: drawn bold whatever the colours
BOLD = {"tool", "floor_hit", "revolute", "prismatic"}
#: drawn dim in the palettes where their grey is the floor's (16 colours, an
#: ANSI theme): the grid and the workspace cloud stay behind the arm and the floor
DIM = {"cloud", "grid"}
DIM_PALETTES = ("standard", "ansi")
#: without colour: what is bold (the arm) and what is dim (everything behind it)
MONO_BOLD = {"link", "pedestal", "revolute", "prismatic", "floor_hit"}
MONO_DIM = {"x", "y", "z", "grid", "shadow", "axes", "cloud"}


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
            if role in MONO_BOLD
            else Style(dim=True)
            if role in MONO_DIM
            else Style()
            for role in CELL_ROLES
        ]
    name = palette_name(color_system, ansi_theme)
    colours = PALETTES[name]
    dim = DIM if name in DIM_PALETTES else set()
    return [
        Style(
            color=colours.get(role),
            bold=True if role in BOLD else None,
            dim=True if role in dim else None,
        )
        for role in CELL_ROLES
    ]


def look_of(app) -> Look:
    """How ``app``'s terminal wants the views: 7-bit ASCII, and whether it
    has colour at all (NO_COLOR, or a terminal without colours)."""
    return Look(
        ascii=ascii_mode(app),
        mono=bool(app.no_color) or app.console.color_system is None,
    )

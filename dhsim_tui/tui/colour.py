"""Colour that keeps its promises: dhsim's themes and two last nets.

* **Themes.** dhsim's chrome (borders, titles, the footer's keys, cursors) is
  teal and cyan, never orange, red, green or blue: orange is the arm's links
  alone, red, green and blue the frame axes' (``widgets.view_style``). The
  themes are Textual's own with those colours changed.
* **16 colours** (``TERM=xterm``, ``screen``): :class:`SixteenColours` moves
  every colour that would come out as ANSI red, green or blue (bright or
  not), or bright yellow, to another of the sixteen, unless it is one of
  the frame axes' own three or the links' yellow. Nothing but the axes is
  red, green or blue, and nothing but the links bright yellow, whatever a
  widget asked for (an error, a success toast, a blue cursor, a warning).
* **NO_COLOR** (any value): :class:`NoColour` writes no colour at all, only
  attributes: what stood out by its background (a cursor, a selection, a
  highlighted key) is reversed, and faint text is dim. Textual's own
  NO_COLOR filter turns colours grey, still as 256-colour codes.
"""

from __future__ import annotations

from functools import lru_cache

from rich.color import Color as RichColor
from rich.color import ColorType
from rich.segment import Segment
from rich.style import Style
from rich.terminal_theme import DEFAULT_TERMINAL_THEME
from textual.color import Color
from textual.filter import LineFilter, Monochrome, NoColor
from textual.theme import BUILTIN_THEMES, Theme

#: dhsim's chrome colours (dark and light themes)
TEAL = "#1f9faa"
CYAN = "#4fd1dc"
DEEP_TEAL = "#0b6f78"
#: errors: a crimson in full colour (16 colours make it magenta)
CRIMSON = "#d7306f"


def _variant(base: str, name: str, **colours: str) -> Theme:
    theme = BUILTIN_THEMES[base]
    fields = {
        key: getattr(theme, key)
        for key in (
            "primary",
            "secondary",
            "warning",
            "error",
            "success",
            "accent",
            "foreground",
            "background",
            "surface",
            "panel",
            "boost",
            "dark",
            "luminosity_spread",
            "text_alpha",
            "ansi",
        )
    }
    variables = dict(theme.variables)
    variables.update(colours.pop("variables", {}))  # type: ignore[arg-type]
    fields.update(colours)
    return Theme(name=name, variables=variables, **fields)


THEMES: dict[str, Theme] = {
    "dark": _variant(
        "textual-dark",
        "dhsim-dark",
        primary=TEAL,
        secondary=DEEP_TEAL,
        accent=CYAN,
        success=CYAN,
        warning="#ffd75f",
        error=CRIMSON,
    ),
    "light": _variant(
        "textual-light",
        "dhsim-light",
        primary=DEEP_TEAL,
        secondary=TEAL,
        accent=DEEP_TEAL,
        success=DEEP_TEAL,
        warning="#af8700",
        error=CRIMSON,
        variables={"footer-key-foreground": DEEP_TEAL},
    ),
    "ansi": _variant(
        "ansi-dark",
        "dhsim-ansi",
        primary="ansi_cyan",
        secondary="ansi_cyan",
        accent="ansi_bright_cyan",
        success="ansi_cyan",
        warning="ansi_yellow",
        error="ansi_magenta",
        variables={
            "input-selection-background": "ansi_bright_cyan",
            "screen-selection-background": "ansi_bright_cyan",
        },
    ),
}
#: the themes --theme offers, by short names, and the Textual theme each is
THEME_NAMES = {short: theme.name for short, theme in THEMES.items()}


# -- 16 colours ---------------------------------------------------------------------
#: ANSI red, green and blue and their bright forms (the axes'), and bright
#: yellow (the links')
_RESERVED_NUMBERS = frozenset({1, 2, 4, 9, 10, 12, 11})
#: the colours the scene keeps for itself in 16 colours, as view_style gives
#: them: the axes' exact palette triplets (or ANSI numbers) and the links'
KEPT_TRIPLETS = frozenset({(255, 85, 85), (85, 255, 85), (85, 85, 255), (255, 255, 85)})
KEPT_NUMBERS = frozenset({9, 10, 12, 11})
#: where each reserved colour goes instead: magenta for red (errors,
#: limits), cyan for green (success) and blue (cursors, the primary
#: colour), yellow for bright yellow (warnings)
_INSTEAD = {1: 5, 9: 5, 2: 6, 10: 14, 4: 6, 12: 14, 11: 3}


def _standard_number(color: RichColor) -> int | None:
    """The colour as one of the sixteen (None: the terminal's default)."""
    if color.type == ColorType.DEFAULT:
        return None
    if color.type == ColorType.STANDARD:
        return color.number
    standard = color.downgrade(_STANDARD)
    return standard.number


_STANDARD = RichColor.parse("red").system  # ColorSystem.STANDARD


@lru_cache(4096)
def sixteen(color: RichColor | None) -> RichColor | None:
    """``color`` as one of the sixteen, never red, green, blue or bright
    yellow unless it is an axis's or the links' own (given as its exact
    palette triplet or ANSI number)."""
    if color is None or color.type == ColorType.DEFAULT:
        return color
    if color.triplet is not None and tuple(color.triplet) in KEPT_TRIPLETS:
        return color
    if color.type == ColorType.STANDARD and color.number in KEPT_NUMBERS:
        return color
    number = _standard_number(color)
    if number is None or number not in _RESERVED_NUMBERS:
        return color
    return RichColor.from_ansi(_INSTEAD[number])


@lru_cache(4096)
def sixteen_style(style: Style) -> Style:
    color, bgcolor = sixteen(style.color), sixteen(style.bgcolor)
    if color is style.color and bgcolor is style.bgcolor:
        return style
    return style + Style.from_color(color, bgcolor)


class SixteenColours(LineFilter):
    """In 16 colours, no red, green or blue but the axes' (see the module)."""

    def __init__(self, app, enabled: bool = True) -> None:
        super().__init__(enabled)
        self._app = app

    def apply(self, segments: list[Segment], background: Color) -> list[Segment]:
        if self._app.console.color_system != "standard":
            return segments
        return [
            Segment(text, None if style is None else sixteen_style(style), control)
            for text, style, control in segments
        ]


# -- NO_COLOR ------------------------------------------------------------------------
#: a background this much lighter or darker (0..1 luminance) than the theme's
#: marks something out (a cursor, a selection): reversed without colour
HIGHLIGHT = 0.18
#: text this close to its background in luminance was faint: dim without colour
FAINT = 0.45


def _luminance(color: RichColor) -> float:
    red, green, blue = color.get_truecolor(DEFAULT_TERMINAL_THEME)
    return (0.2126 * red + 0.7152 * green + 0.0722 * blue) / 255


@lru_cache(4096)
def no_colour_style(style: Style, base: float) -> Style:
    """``style`` without colour; ``base`` is the theme background's luminance."""
    reverse = None
    background_set = style.bgcolor is not None and style.bgcolor.type != ColorType.DEFAULT
    if background_set and abs(_luminance(style.bgcolor) - base) > HIGHLIGHT:
        reverse = True
    dim = None
    if style.color is not None and style.color.type != ColorType.DEFAULT and not reverse:
        background = (
            _luminance(style.bgcolor)
            if style.bgcolor is not None and style.bgcolor.type != ColorType.DEFAULT
            else base
        )
        if abs(_luminance(style.color) - background) < FAINT:
            dim = True
    plain = style.without_color  # attributes, links and Textual's meta kept
    if reverse or dim:
        plain += Style(reverse=reverse, dim=dim)
    return plain


@lru_cache(64)
def _theme_background(name: str | None) -> float:
    """The luminance of a theme's background (black for the terminal's own)."""
    try:
        return Color.parse(name).brightness if name else 0.0
    except Exception:  # "ansi_default": the terminal's, assumed dark
        return 0.0


class NoColour(LineFilter):
    """No colour codes at all: attributes only (see the module)."""

    def __init__(self, app, enabled: bool = True) -> None:
        super().__init__(enabled)
        self._app = app

    def apply(self, segments: list[Segment], background: Color) -> list[Segment]:
        luminance = _theme_background(self._app.current_theme.background)
        return [
            Segment(text, None if style is None else no_colour_style(style, luminance), control)
            for text, style, control in segments
        ]


def install_filters(app) -> None:
    """The app's line filters: NO_COLOR's ours instead of Textual's, and the
    16-colour net (which acts only while the console has 16 colours)."""
    filters = app._filters
    if app.no_color:
        filters[:] = [f for f in filters if not isinstance(f, Monochrome | NoColor)]
        filters.append(NoColour(app))
    filters.append(SixteenColours(app))


def install_colours(app, theme: str) -> None:
    """dhsim's themes registered on ``app`` and ``theme`` (one of
    ``THEME_NAMES``) chosen, then its line filters (:func:`install_filters`)."""
    for registered in THEMES.values():
        app.register_theme(registered)
    install_filters(app)
    app.theme = THEME_NAMES[theme]

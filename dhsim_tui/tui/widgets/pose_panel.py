"""The pose panel: world XYZ and the orientation read-out, fixed-width numbers.

Few bytes per key press (``bench/bytes.py`` counts them): the panel keeps
what it shows and, on a new pose, repaints only the lines that changed, each
only up to its last changed column (the title and subtitle only when they
change: setting a border title repaints the whole widget).
"""

from __future__ import annotations

from rich.cells import cell_len
from rich.text import Text
from textual.geometry import Region
from textual.widget import Widget

from dhsim_tui.core.analysis.jacobian import Dexterity
from dhsim_tui.core.model.kinematics import EndEffector
from dhsim_tui.core.model.robot import LENGTH_DECIMALS
from dhsim_tui.tui.widgets.joint_row import ascii_mode, changed_extent

READOUTS = ("oat", "rpy", "matrix")
#: every read-out at once: what a tall side panel shows (v then has nothing to switch)
ALL_READOUTS = "all"
#: the key that switches the read-out, named where it acts (the footer has no room)
READOUT_KEY = "v: next read-out"
READOUT_TITLES = {
    "oat": "XYZ / OAT",
    "rpy": "XYZ / roll pitch yaw",
    "matrix": "4×4 transform",
    ALL_READOUTS: "XYZ / OAT / roll pitch yaw / 4×4",
}
READOUT_TITLES_ASCII = {
    **READOUT_TITLES,
    "matrix": "4x4 transform",
    ALL_READOUTS: "XYZ / OAT / roll pitch yaw / 4x4",
}


#: labels are right-aligned in this many columns, one more than the longest
#: ("pitch"), so no label touches the panel's border
LABEL_WIDTH = 6


def _number(value: float, decimals: int = 2, width: int = 10) -> str:
    return f"{round(value, decimals) + 0.0:{width}.{decimals}f}"


def pose_text(
    pose: EndEffector, readout: str, units: str, ascii: bool = False, compact: bool = False
) -> Text:
    """The read-out as text; pure so tests can compare it with ``dhsim fk``.
    ``ascii``: "deg" for the degree sign, "x" for the multiplication sign.
    ``compact``: XYZ on one line and the angles on the next (OAT and RPY;
    for a short screen where the program panel shares the side)."""
    degree = "deg" if ascii else "°"
    text = Text()
    if compact and readout in ("oat", "rpy"):
        decimals = LENGTH_DECIMALS[units]
        for i, (name, value) in enumerate(zip("XYZ", pose.xyz, strict=True)):
            text.append(f"{name} " if i == 0 else f" {name} ", style="bold")
            text.append(_number(value, decimals, 8))
        text.append(f" {units}\n")
        names = ("O", "A", "T") if readout == "oat" else ("R", "P", "Y")
        angles = pose.oat if readout == "oat" else pose.rpy
        for i, (name, value) in enumerate(zip(names, angles, strict=True)):
            text.append(f"{name} " if i == 0 else f" {name} ", style="bold")
            text.append(_number(value, 2, 7))
        text.append(f" {degree}")  # once, as the unit of the line above: fits "deg" too
        return text
    if readout == ALL_READOUTS:
        text.append_text(pose_text(pose, "oat", units, ascii))
        angles = pose_text(pose, "rpy", units, ascii).split("\n", allow_blank=True)[3:]
        for line in angles:
            text.append("\n")
            text.append_text(line)
        text.append("\n")
        text.append_text(pose_text(pose, "matrix", units, ascii))
        return text
    if readout == "matrix":
        for row in pose.matrix:
            text.append("".join(_number(v, 4, 8) for v in row[:3]) + _number(row[3], 2, 11) + "\n")
        times = "x" if ascii else "×"
        text.append(f"  rotation (3{times}3) | position ({units})", style="dim")
        return text
    for name, value in zip("XYZ", pose.xyz, strict=True):
        text.append(f"{name:>{LABEL_WIDTH}} ", style="bold")
        text.append(f"{_number(value, LENGTH_DECIMALS[units], 11)} {units}\n")
    names = ("O", "A", "T") if readout == "oat" else ("roll", "pitch", "yaw")
    angles = pose.oat if readout == "oat" else pose.rpy
    for i, (name, value) in enumerate(zip(names, angles, strict=True)):
        text.append(f"{name:>{LABEL_WIDTH}} ", style="bold")
        text.append(f"{_number(value)}{degree}" + ("\n" if i < 2 else ""))
    return text


class TextPanel(Widget):
    """A panel that shows one Text and repaints only the lines that change."""

    def __init__(
        self,
        *children: Widget,
        name: str | None = None,
        id: str | None = None,
        classes: str | None = None,
    ) -> None:
        super().__init__(*children, name=name, id=id, classes=classes)
        self._text = Text()

    def render(self) -> Text:
        return self._text


class PosePanel(TextPanel):
    """Shows what the screen hands it; computes nothing itself."""

    DEFAULT_CSS = """
    PosePanel { height: 10; }
    """

    _titles: tuple[str, str] | None = None
    _branch = ""
    _grows = False
    _last: tuple | None = None  # what it was last handed, to show again when resized
    #: fewer lines than this inside: the compact read-out (two lines)
    FULL_LINES = 8

    @property
    def compact(self) -> bool:
        """Laid out shorter than the full read-out needs (a short screen with
        the program panel): XYZ and the angles on a line each."""
        return 0 < self.size.height < self.FULL_LINES  # (the size inside the border)

    def on_resize(self) -> None:
        if self._last is not None:
            self.show(*self._last)

    def show(
        self,
        pose: EndEffector,
        readout: str,
        units: str,
        dexterity: Dexterity | None = None,
        warnings: tuple[str, ...] = (),
        branch: str = "",
    ) -> None:
        """``branch``: which of the arm's solutions for this tool pose it is in
        (``b``), shown under the rest (the panel grows to fit it), or "".
        Plain text, never markup."""
        self._last = (pose, readout, units, dexterity, warnings, branch)
        ascii = ascii_mode(self)
        title = (READOUT_TITLES_ASCII if ascii else READOUT_TITLES)[readout]
        subtitle = "" if readout == ALL_READOUTS else READOUT_KEY
        # a border title repaints the whole panel: set only when it changes
        if self._titles != (title, subtitle):
            self._titles = (title, subtitle)
            self.border_title = title
            self.border_subtitle = subtitle
        text = pose_text(pose, readout, units, ascii, compact=self.compact)
        text.append("\n")
        text.append_text(health_text(dexterity, warnings, ascii))
        if branch:
            text.append("\n")
            text.append(branch, style="bold")
        grows = bool(branch) or readout == ALL_READOUTS
        if (branch, grows) != (self._branch, self._grows):  # lines more (wrapped), or back
            self._branch, self._grows = branch, grows
            self.styles.height = "auto" if grows else None
            self.refresh(layout=True)
        refresh_changed_lines(self, self._text, text)
        self._text = text


def refresh_changed_lines(widget: Widget, old: Text, new: Text) -> None:
    """Repaint the lines of ``widget`` (which renders ``new`` from now on) that
    differ from ``old``, each up to its last changed column; everything when
    the number of lines changed or the widget isn't on screen yet."""
    old_lines = old.split("\n", allow_blank=True)
    new_lines = new.split("\n", allow_blank=True)
    width = widget.content_size.width if widget.is_mounted else 0
    if (
        width <= 0
        or len(old_lines) != len(new_lines)
        or not old.plain
        # a line that wraps moves the lines after it: no line-by-line repaint
        or any(cell_len(line.plain) > width for line in (*old_lines, *new_lines))
    ):
        widget.refresh()
        return
    for y, (before, after) in enumerate(zip(old_lines, new_lines, strict=True)):
        extent = changed_extent(before, after)
        if extent is not None:
            widget.refresh(Region(0, y, min(extent, width), 1))


def health_text(
    dexterity: Dexterity | None, warnings: tuple[str, ...], ascii: bool = False
) -> Text:
    """Manipulability (warning colour near a singularity) and the floor check."""
    text = Text()
    if dexterity is not None:
        mu = "mu" if ascii else "μ"
        text.append(f"{mu:>{LABEL_WIDTH}} ", style="bold")
        style = "bold red" if dexterity.singular else "yellow" if dexterity.near_singular else ""
        note = (
            "  singular"
            if dexterity.singular
            else "  near singular"
            if (dexterity.near_singular)
            else ""
        )
        text.append(f"{dexterity.manipulability:10.4f}{note}", style=style)
    text.append("\n")
    if warnings:
        warning = "  ! " if ascii else "  ⚠ "
        text.append(warning + "; ".join(warnings), style="bold red")
    return text

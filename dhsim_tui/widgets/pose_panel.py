"""The pose panel: world XYZ and the orientation read-out, fixed-width numbers."""

from __future__ import annotations

from rich.text import Text
from textual.widgets import Static

from dhsim_tui.core.jacobian import Dexterity
from dhsim_tui.core.kinematics import EndEffector
from dhsim_tui.core.model import LENGTH_DECIMALS

READOUTS = ("oat", "rpy", "matrix")
#: the key that switches the read-out, named where it acts (the footer has no room)
READOUT_KEY = "v: next read-out"
READOUT_TITLES = {"oat": "XYZ / OAT", "rpy": "XYZ / roll pitch yaw", "matrix": "4×4 transform"}


#: labels are right-aligned in this many columns, one more than the longest
#: ("pitch"), so no label touches the panel's border
LABEL_WIDTH = 6


def _number(value: float, decimals: int = 2, width: int = 10) -> str:
    return f"{round(value, decimals) + 0.0:{width}.{decimals}f}"


def pose_text(pose: EndEffector, readout: str, units: str) -> Text:
    """The read-out as text; pure so tests can compare it with ``dhsim fk``."""
    text = Text()
    if readout == "matrix":
        for row in pose.matrix:
            text.append("".join(_number(v, 4, 8) for v in row[:3]) + _number(row[3], 2, 11) + "\n")
        text.append(f"  rotation (3×3) | position ({units})", style="dim")
        return text
    for name, value in zip("XYZ", pose.xyz, strict=True):
        text.append(f"{name:>{LABEL_WIDTH}} ", style="bold")
        text.append(f"{_number(value, LENGTH_DECIMALS[units], 11)} {units}\n")
    names = ("O", "A", "T") if readout == "oat" else ("roll", "pitch", "yaw")
    angles = pose.oat if readout == "oat" else pose.rpy
    for i, (name, value) in enumerate(zip(names, angles, strict=True)):
        text.append(f"{name:>{LABEL_WIDTH}} ", style="bold")
        text.append(f"{_number(value)}°" + ("\n" if i < 2 else ""))
    return text


class PosePanel(Static):
    """Shows what the screen hands it; computes nothing itself."""

    DEFAULT_CSS = """
    PosePanel { height: 10; }
    """

    def show(
        self,
        pose: EndEffector,
        readout: str,
        units: str,
        dexterity: Dexterity | None = None,
        warnings: tuple[str, ...] = (),
    ) -> None:
        self.border_title = READOUT_TITLES[readout]
        self.border_subtitle = READOUT_KEY
        text = pose_text(pose, readout, units)
        text.append("\n")
        text.append_text(health_text(dexterity, warnings))
        self.update(text, layout=False)


def health_text(dexterity: Dexterity | None, warnings: tuple[str, ...]) -> Text:
    """Manipulability (warning colour near a singularity) and the floor check."""
    text = Text()
    if dexterity is not None:
        text.append(f"{'μ':>{LABEL_WIDTH}} ", style="bold")
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
        text.append("  ⚠ " + "; ".join(warnings), style="bold red")
    return text

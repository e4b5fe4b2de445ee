"""The views' legend: each mark in its real colour and glyph, on one line.

The items are packed in order of importance (the arm, then its frames, then
the floor) and the line takes as many as fit its width: at 80 columns it
names the links, joints, tool and which frames are drawn; from 120 columns
the rest too. A legend never wraps and is never cut.
"""

from __future__ import annotations

from rich.style import Style
from rich.text import Text

from dhsim_tui.scene.wireframe import FRAME_MODE_NAMES

#: the workspace cloud's glyph: ASCII, without colour, with colour
CLOUD_GLYPHS = (".", "·", "⢕")
#: the frame modes as the legend names them (x cycles them)
FRAMES_SHORT = {"all": "all", "ends": "base+tool", "none": "none"}
#: the space between two items
GAP = "  "
#: the items the legend must show to be shown at all: links, joints, tool
#: (one more when the arm has both kinds of joint)
ESSENTIAL = 3


def legend_items(
    *,
    ascii: bool,
    mono: bool,
    styles: dict[str, Style],
    joint_types: tuple[str, ...] = ("revolute",),
    pedestal: bool = False,
    frames: str = "all",
    cloud: bool = False,
    trail: bool = False,
) -> list[Text]:
    """The legend's items, most important first."""
    kinds = set(joint_types)

    def item(glyph: str, role: str | None, words: str) -> Text:
        text = Text()
        text.append(glyph, styles.get(role, Style()) if role and not ascii else Style())
        text.append(f" {words}")
        return text

    link, floor = ("#", "_") if ascii else ("━", "┄")
    revolute, prismatic, tool = ("O", "=", "@") if ascii else ("●", "■", "◆")
    items = [item(link, "link", "links")]
    if kinds == {"prismatic"}:
        items.append(item(prismatic, "prismatic", "joint"))
    elif "prismatic" in kinds:
        items.append(item(revolute, "revolute", "revolute"))
        items.append(item(prismatic, "prismatic", "prismatic"))
    else:
        items.append(item(revolute, "revolute", "joint"))
    items.append(item(tool, "tool", "tool"))
    if cloud:  # just asked for (W): named before the rest
        glyph = CLOUD_GLYPHS[0 if ascii else 1 if mono else 2]
        items.append(item(glyph, "cloud", "workspace"))
    if trail:  # a program played: the tool's path
        items.append(item(":" if ascii else "┈", "trail", "path"))
    items.append(Text(f"frames: {FRAMES_SHORT[frames]} (x)"))
    if frames != "none":
        if ascii or mono:
            items.append(Text("axes x y z at their tips" if mono else "axes x y z"))
        else:
            axes = Text("axes")
            for role in ("x", "y", "z"):
                axes.append(" ")
                axes.append("─", styles.get(role, Style()))
                axes.append(role)
            items.append(axes)
    items.append(item(floor, "floor", "floor"))
    if pedestal:
        items.append(item("H" if ascii else "┃", "pedestal", "pedestal"))
    return items


def pack(items: list[Text], width: int) -> Text:
    """The items, in order, that fit in ``width`` cells: each one that would
    not fit is left out (the first always stays: the caller hides a legend
    too narrow for it)."""
    text = Text()
    for entry in items:
        if not text.cell_len:
            text.append_text(entry)
        elif text.cell_len + len(GAP) + entry.cell_len <= width:
            text.append(GAP)
            text.append_text(entry)
    return text


def frames_caption(frames: str) -> str:
    """What the help and palette call a frame mode."""
    return FRAME_MODE_NAMES[frames]


def legend_line(
    look,
    styles: dict[str, Style],
    joint_types: tuple[str, ...],
    pedestal: bool,
    frames: str,
    cloud: bool,
    width: int,
    trail: bool = False,
) -> tuple[Text, bool]:
    """The legend packed into ``width`` columns, and whether it is too
    cramped to show (it would not name the links, the joints and the tool):
    one line or nothing, never wrapped or cut."""
    items = legend_items(
        ascii=look.ascii,
        mono=look.mono,
        styles=styles,
        joint_types=joint_types or ("revolute",),
        pedestal=pedestal,
        frames=frames,
        cloud=cloud,
        trail=trail,
    )
    kinds = len(set(joint_types)) if joint_types else 1
    essential = pack(items[: ESSENTIAL + kinds - 1], 10**6).cell_len
    return pack(items, width), essential > width

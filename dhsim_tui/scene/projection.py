"""Orthographic views of a wireframe and limits that keep both axes at one scale."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dhsim_tui.scene.wireframe import Wireframe

AXIS_COLOURS = ("red", "green", "blue")


@dataclass(frozen=True)
class View:
    """A projection: which world axis runs right and which runs up."""

    key: str
    title: str
    right: int  # 0 = X, 1 = Y, 2 = Z
    up: int

    @property
    def caption(self) -> str:
        return f"{self.title}  {'XYZ'[self.right]}→ {'XYZ'[self.up]}↑  ({VIEW_KEYS[self.key]})"


VIEW_KEYS = {"top": "1", "front": "2", "side": "3"}
VIEWS: tuple[View, ...] = (
    View("top", "Top", 0, 1),
    View("front", "Front", 0, 2),
    View("side", "Side", 1, 2),
)


@dataclass(frozen=True)
class Polyline:
    """Points joined in order; a NaN point lifts the pen (starts a new stroke)."""

    xs: tuple[float, ...]
    ys: tuple[float, ...]
    colour: str


@dataclass(frozen=True)
class ViewScene:
    """One view ready to draw: 2-D polylines in draw order, the end effector,
    and the region that must stay visible (the seed's work area)."""

    view: View
    lines: tuple[Polyline, ...]
    end_effector: tuple[float, float]
    bounds: tuple[float, float, float, float]  # xmin, xmax, ymin, ymax
    units: str = ""


def _line(points: np.ndarray, view: View, colour: str) -> Polyline:
    return Polyline(
        tuple(points[:, view.right].tolist()), tuple(points[:, view.up].tolist()), colour
    )


def project(wire: Wireframe, view: View) -> ViewScene:
    area = wire.area
    names = "xyz"
    xmin, xmax = area.limits(names[view.right])
    ymin, ymax = area.limits(names[view.up])
    lines: list[Polyline] = []
    if view.up == 2:  # the floor, seen edge-on in the front and side views
        floor = "red" if wire.below_floor else "gray"  # something went through the floor
        lines.append(Polyline((xmin, xmax), (wire.floor_z, wire.floor_z), floor))
    if wire.pedestal is not None and view.up == 2:
        lines.append(_line(wire.pedestal, view, "yellow"))
    lines.append(_line(wire.links, view, "default"))
    gap = np.full((len(wire.origins), 1, 3), np.nan)
    for k, colour in enumerate(AXIS_COLOURS):
        # every frame's k-th axis as one polyline, segments separated by NaN
        strokes = np.concatenate([wire.origins[:, None, :], wire.axes[:, k : k + 1, :], gap], 1)
        lines.append(_line(strokes.reshape(-1, 3)[:-1], view, colour))
    ee = (float(wire.end_effector[view.right]), float(wire.end_effector[view.up]))
    return ViewScene(view, tuple(lines), ee, (xmin, xmax, ymin, ymax), wire.units)


def equal_scale_limits(
    bounds: tuple[float, float, float, float],
    cols: int,
    rows: int,
    dots: tuple[int, int] = (2, 4),
) -> tuple[tuple[float, float], tuple[float, float]]:
    """Axis limits showing ``bounds`` with the same length per dot on both axes.

    A terminal cell is about twice as tall as wide, and a braille cell has
    2×4 dots, so its dots are square: equal units per dot means a 100 mm
    link looks 100 mm long whichever way it points. The bounds are centred
    and the shorter side widened.
    """
    xmin, xmax, ymin, ymax = bounds
    nx = max(cols * dots[0] - 1, 1)
    ny = max(rows * dots[1] - 1, 1)
    per_dot = max((xmax - xmin) / nx, (ymax - ymin) / ny)
    if per_dot <= 0:
        per_dot = 1.0
    cx, cy = (xmin + xmax) / 2, (ymin + ymax) / 2
    half_x, half_y = per_dot * nx / 2, per_dot * ny / 2
    return (cx - half_x, cx + half_x), (cy - half_y, cy + half_y)

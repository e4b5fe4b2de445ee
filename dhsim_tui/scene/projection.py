"""Orthographic views of a wireframe and limits that keep both axes at one scale.

Lines carry a *role* ("x", "link", "floor", ...), not a colour: what a role
looks like depends on the terminal (colours, monochrome, ASCII) and is the
widgets' business.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dhsim_tui.scene.wireframe import Wireframe

#: the roles of a frame's three axes, in order
AXIS_ROLES = ("x", "y", "z")
#: every role a scene line or mark can have, in drawing order (later ones on
#: top): the floor and its grid, the links' shadow on it, the frame axes,
#: the pedestal and links over them, and the joints and tool over the links
ROLES = (
    "grid",
    "floor",
    "floor_hit",
    "shadow",
    "trail",
    "x",
    "y",
    "z",
    "pedestal",
    "link",
    "revolute",
    "prismatic",
    "tool",
)
#: the roles drawn as a mark (one glyph at a point) rather than a line
MARK_ROLES = ("revolute", "prismatic", "tool")


@dataclass(frozen=True)
class View:
    """A projection: which world axis runs right and which runs up
    (``right`` and ``up`` are -1 for the 3-D view, which orbits)."""

    key: str
    title: str
    right: int  # 0 = X, 1 = Y, 2 = Z
    up: int

    @property
    def is_3d(self) -> bool:
        return self.right < 0

    @property
    def axis_names(self) -> tuple[str, str]:
        """What the horizontal and vertical axes of the picture measure."""
        if self.is_3d:
            return ("", "")
        return ("XYZ"[self.right], "XYZ"[self.up])

    @property
    def caption(self) -> str:
        if self.is_3d:
            return f"{self.title}  ({self.number})"
        right, up = self.axis_names
        return f"{self.title}  {right}→ {up}↑  ({self.number})"

    @property
    def number(self) -> str:
        """The key that selects the view."""
        return VIEW_KEYS[self.key]


VIEW_KEYS = {"top": "1", "front": "2", "side": "3", "iso": "4"}
TOP = View("top", "Top", 0, 1)
FRONT = View("front", "Front", 0, 2)
SIDE = View("side", "Side", 1, 2)
ISO = View("iso", "3-D", -1, -1)
#: the orthographic views (one scale for all of them)
ORTHO_VIEWS: tuple[View, ...] = (TOP, FRONT, SIDE)
#: every view, in the order of their keys 1-4
VIEWS: tuple[View, ...] = (*ORTHO_VIEWS, ISO)


@dataclass(frozen=True)
class Polyline:
    """Points joined in order; a NaN point lifts the pen (starts a new stroke)."""

    xs: tuple[float, ...]
    ys: tuple[float, ...]
    role: str

    @property
    def colour(self) -> str:  # the name older code and tests use
        return self.role


@dataclass(frozen=True)
class Mark:
    """One glyph at a point: a joint (``revolute`` or ``prismatic``) or the tool."""

    x: float
    y: float
    role: str


@dataclass(frozen=True)
class Tip:
    """The end of one frame axis: where a letter can name it without colour."""

    x: float
    y: float
    role: str  # "x", "y" or "z"


@dataclass(frozen=True)
class ViewScene:
    """One view ready to draw: 2-D polylines in draw order, the end effector,
    the axis tips, and the region that must stay visible (the seed's work
    area; for the 3-D view a region that holds it from every direction)."""

    view: View
    lines: tuple[Polyline, ...]
    end_effector: tuple[float, float]
    bounds: tuple[float, float, float, float]  # xmin, xmax, ymin, ymax
    units: str = ""
    tips: tuple[Tip, ...] = ()
    #: the arm's own extent (links and frame origins): what zooming centres on
    arm_bounds: tuple[float, float, float, float] | None = None
    #: spacing of the floor grid (3-D view), in the robot's unit
    grid_step: float | None = None
    #: the joints and the tool, drawn over everything (the tool last)
    marks: tuple[Mark, ...] = ()
    #: what F fits the view to: the links, tool, joints and the axes drawn,
    #: and the program's path (``path_bounds``) when one is drawn
    fit_bounds: tuple[float, float, float, float] | None = None
    #: the program's path drawn (the trail), or None
    path_bounds: tuple[float, float, float, float] | None = None


def extent(xs: np.ndarray, ys: np.ndarray) -> tuple[float, float, float, float]:
    """Bounding box of the finite points (xmin, xmax, ymin, ymax)."""
    ok = np.isfinite(xs) & np.isfinite(ys)
    if not ok.any():
        return (0.0, 0.0, 0.0, 0.0)
    return (
        float(xs[ok].min()),
        float(xs[ok].max()),
        float(ys[ok].min()),
        float(ys[ok].max()),
    )


def wire_lines(
    wire: Wireframe, to_2d, floor: list[Polyline], frames: str = "all"
) -> tuple[tuple[Polyline, ...], tuple[Tip, ...], tuple[float, float], tuple, tuple, tuple]:
    """The wireframe's lines through a projection ``to_2d((m, 3)) -> (xs, ys)``:
    the given floor lines, pedestal, the axes of the frames ``frames`` shows
    (``FRAME_MODES``) and the links over them; the axis tips, the end
    effector, the arm's extent, the joints' and the tool's marks and what
    ``F`` fits (links, joints, tool, the axes drawn and the program's path),
    in the projection's plane."""

    def line(points: np.ndarray, role: str) -> Polyline:
        xs, ys = to_2d(points)
        return Polyline(tuple(xs.tolist()), tuple(ys.tolist()), role)

    lines = list(floor)
    shown = wire.shown_frames(frames)
    origins, ends = wire.origins[shown], wire.axes[shown]
    gap = np.full((len(origins), 1, 3), np.nan)
    tips: list[Tip] = []
    for k, role in enumerate(AXIS_ROLES):
        if not len(origins):
            break
        # every shown frame's k-th axis as one polyline, segments separated by NaN
        strokes = np.concatenate([origins[:, None, :], ends[:, k : k + 1, :], gap], 1)
        lines.append(line(strokes.reshape(-1, 3)[:-1], role))
        ends_x, ends_y = to_2d(ends[:, k, :])
        tips.extend(Tip(float(x), float(y), role) for x, y in zip(ends_x, ends_y, strict=True))
    if wire.pedestal is not None:  # the arm's structure goes over its frames
        lines.append(line(wire.pedestal, "pedestal"))
    lines.append(line(wire.links, "link"))
    marks: list[Mark] = []
    if wire.joints is not None and len(wire.joints):
        jx, jy = to_2d(wire.joints)
        marks.extend(
            Mark(float(x), float(y), kind)
            for x, y, kind in zip(jx.tolist(), jy.tolist(), wire.joint_types, strict=True)
        )
    ex, ey = to_2d(wire.end_effector[None, :])
    marks.append(Mark(float(ex[0]), float(ey[0]), "tool"))
    arm_x, arm_y = to_2d(np.vstack([wire.links, wire.origins]))
    fit_x, fit_y = to_2d(np.vstack([wire.links, wire.end_effector[None, :], *ends, *_path(wire)]))
    return (
        tuple(lines),
        tuple(tips),
        (float(ex[0]), float(ey[0])),
        extent(arm_x, arm_y),
        tuple(marks),
        extent(fit_x, fit_y),
    )


def _path(wire: Wireframe) -> list[np.ndarray]:
    """The program's path drawn (the trail's points), as a list of none or one."""
    return [wire.trail] if wire.trail is not None and len(wire.trail) > 1 else []


def path_extent(wire: Wireframe, to_2d) -> tuple[float, float, float, float] | None:
    """The extent of the program's path drawn, in the projection's plane, or None."""
    path = _path(wire)
    return extent(*to_2d(path[0])) if path else None


def project(wire: Wireframe, view: View, frames: str = "all") -> ViewScene:
    """An orthographic view (top, front or side) of the wireframe, with the
    axes of the frames ``frames`` shows."""
    if view.is_3d:
        raise ValueError("the 3-D view orbits: use scene.oblique.project_oblique")
    area = wire.area
    names = "xyz"
    xmin, xmax = area.limits(names[view.right])
    ymin, ymax = area.limits(names[view.up])
    floor: list[Polyline] = []
    if view.up == 2:  # the floor, seen edge-on in the front and side views
        role = "floor_hit" if wire.below_floor else "floor"  # something went through it
        floor.append(Polyline((xmin, xmax), (wire.floor_z, wire.floor_z), role))

    def to_2d(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return points[:, view.right], points[:, view.up]

    if wire.trail is not None and len(wire.trail) > 1:  # a program's path, under the arm
        xs, ys = to_2d(wire.trail)
        floor.append(Polyline(tuple(xs.tolist()), tuple(ys.tolist()), "trail"))
    lines, tips, ee, arm, marks, fit = wire_lines(wire, to_2d, floor, frames)
    if view.up != 2:  # the pedestal stands straight up: a point from above
        lines = tuple(line for line in lines if line.role != "pedestal")
    return ViewScene(
        view,
        lines,
        ee,
        (xmin, xmax, ymin, ymax),
        wire.units,
        tips,
        arm,
        marks=marks,
        fit_bounds=fit,
        path_bounds=path_extent(wire, to_2d),
    )


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
    return limits_at(((xmin + xmax) / 2, (ymin + ymax) / 2), per_dot, cols, rows, dots)


def per_dot_needed(
    bounds: tuple[float, float, float, float], cols: int, rows: int, dots=(2, 4)
) -> float:
    """The smallest length per dot that fits ``bounds`` in cols × rows cells."""
    xmin, xmax, ymin, ymax = bounds
    nx = max(cols * dots[0] - 1, 1)
    ny = max(rows * dots[1] - 1, 1)
    return max((xmax - xmin) / nx, (ymax - ymin) / ny)


def limits_at(
    centre: tuple[float, float], per_dot: float, cols: int, rows: int, dots=(2, 4)
) -> tuple[tuple[float, float], tuple[float, float]]:
    """Limits of a cols × rows picture centred on ``centre`` at ``per_dot``."""
    nx = max(cols * dots[0] - 1, 1)
    ny = max(rows * dots[1] - 1, 1)
    per_dot = per_dot if per_dot > 0 else 1.0
    cx, cy = centre
    half_x, half_y = per_dot * nx / 2, per_dot * ny / 2
    return (cx - half_x, cx + half_x), (cy - half_y, cy + half_y)


#: the room F leaves round the arm, a fraction of its size on every side
FIT_MARGIN = 0.05


def fit_framing_bounds(
    bounds: tuple[float, float, float, float], least: float
) -> tuple[float, float, float, float]:
    """``bounds`` grown by ``FIT_MARGIN`` of their larger side on every side,
    and to at least ``least`` across both ways (an arm seen end-on is a point)."""
    xmin, xmax, ymin, ymax = bounds
    size = max(xmax - xmin, ymax - ymin, least)
    pad = FIT_MARGIN * size
    cx, cy = (xmin + xmax) / 2, (ymin + ymax) / 2
    half_x = max(xmax - xmin, least) / 2 + pad
    half_y = max(ymax - ymin, least) / 2 + pad
    return (cx - half_x, cx + half_x, cy - half_y, cy + half_y)


def holds(
    bounds: tuple[float, float, float, float],
    centre: tuple[float, float],
    per_dot: float,
    cols: int,
    rows: int,
) -> bool:
    """Whether the picture at ``centre`` and ``per_dot`` shows all of ``bounds``."""
    (x0, x1), (y0, y1) = limits_at(centre, per_dot, cols, rows)
    xmin, xmax, ymin, ymax = bounds
    return x0 <= xmin and xmax <= x1 and y0 <= ymin and ymax <= y1

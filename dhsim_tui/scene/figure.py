"""The views of a robot at given joint values, ready to draw: what the
simulator shows, for ``dhsim draw`` (no terminal)."""

from __future__ import annotations

from collections.abc import Sequence

from dhsim_tui.core.model.robot import Robot
from dhsim_tui.scene.framing import Framing, fitted, work_area_framings
from dhsim_tui.scene.oblique import Orbit, project_oblique
from dhsim_tui.scene.projection import VIEWS, View, ViewScene, project
from dhsim_tui.scene.wireframe import Wireframe, build_wireframe

#: the names ``dhsim draw --view`` takes, and the views they are
VIEW_NAMES = {"top": VIEWS[0], "front": VIEWS[1], "side": VIEWS[2], "3d": VIEWS[3]}


def wireframe_at(robot: Robot, q: Sequence[float]) -> Wireframe:
    return build_wireframe(robot, robot.kinematics.frames(q))


def view_scenes(
    wire: Wireframe,
    views: Sequence[View] = VIEWS,
    frames: str = "all",
    orbit: Orbit | None = None,
) -> list[ViewScene]:
    """Each view of the wireframe, with the axes of the frames ``frames``
    shows; the 3-D one from ``orbit`` (default: isometric)."""
    orbit = orbit or Orbit()
    return [
        project_oblique(wire, orbit, frames) if view.is_3d else project(wire, view, frames)
        for view in views
    ]


def figure_framings(
    scenes: Sequence[ViewScene],
    canvases: Sequence[tuple[int, int]],
    *,
    fit: bool = False,
    least: float = 1.0,
) -> list[Framing]:
    """The framings the simulator would give these views on canvases of
    (columns, rows) braille cells: the work area's, or each fitted to the arm."""
    if fit:
        return [
            fitted(scene, cols, rows, least)
            for scene, (cols, rows) in zip(scenes, canvases, strict=True)
        ]
    return work_area_framings(scenes, canvases)


def least_size(wire: Wireframe) -> float:
    """The smallest picture a fitted view makes: a fiftieth of the work area
    (an arm folded to a point, or seen end-on)."""
    area = wire.area
    return max(area.xmax - area.xmin, area.zmax - area.zmin) / 50

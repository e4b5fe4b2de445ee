"""The scene layer: turns world frames into what the views draw (projected
polylines, colours, limits with equal scale). numpy only, no UI."""

from dhsim_tui.scene.projection import VIEWS, View, ViewScene, equal_scale_limits, project
from dhsim_tui.scene.wireframe import Wireframe, axis_length, build_wireframe

__all__ = [
    "VIEWS",
    "View",
    "ViewScene",
    "Wireframe",
    "axis_length",
    "build_wireframe",
    "equal_scale_limits",
    "project",
]

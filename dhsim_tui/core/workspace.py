"""The seed's work area and the robot's reach (reference §3)."""

from __future__ import annotations

from dataclasses import dataclass

from dhsim_tui.core.model import Robot

#: the seed's margin around the reach, in millimetres
WORK_AREA_MARGIN_MM = 30.0


def link_length(joint) -> float:
    """The largest length a link can have: |a| plus |d|, with a prismatic
    joint's d at the largest magnitude its range allows."""
    if joint.is_revolute:
        return abs(joint.a) + abs(joint.d)
    return abs(joint.a) + max(abs(joint.min), abs(joint.max))


def reach(robot: Robot) -> float:
    """Sum of the largest link lengths plus the tool's length (robot units)."""
    return sum(link_length(j) for j in robot.joints) + robot.tool.length


@dataclass(frozen=True)
class WorkArea:
    """An axis-aligned box in world coordinates (robot units)."""

    xmin: float
    xmax: float
    ymin: float
    ymax: float
    zmin: float
    zmax: float

    def limits(self, axis: str) -> tuple[float, float]:
        return (getattr(self, f"{axis}min"), getattr(self, f"{axis}max"))


def work_area(robot: Robot) -> WorkArea:
    """Centred on frame 0 (the world origin unless base_xyz moves it); floor
    at -base_height; sides and ceiling at reach + 30 mm from frame 0."""
    side = reach(robot) + robot.mm(WORK_AREA_MARGIN_MM)
    x, y, z = robot.base_xyz
    floor = -robot.base_height
    bottom = floor if z >= floor else z - side  # a frame 0 under the floor: the arm hangs
    return WorkArea(x - side, x + side, y - side, y + side, bottom, z + side)

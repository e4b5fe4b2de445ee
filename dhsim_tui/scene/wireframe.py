"""The arm in 3-D: links, joints, pedestal, floor, the links' shadow on the
floor and each joint frame's axes."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.analysis.workspace import WorkArea, reach, work_area
from dhsim_tui.core.model.robot import Robot

#: a frame's axes are this fraction of the robot's reach long: short enough
#: that the links, not the frames, are what the eye follows
AXIS_FRACTION = 0.06
#: each earlier frame at the same origin makes the next one's axes this much longer
SHARED_ORIGIN_GROWTH = 0.5
#: which frames' axes are drawn (``x`` cycles them): every frame, frame 0 and
#: the last one (the tool's when it has one), or none
FRAME_MODES = ("all", "ends", "none")
#: how each mode is named on screen
FRAME_MODE_NAMES = {"all": "every frame", "ends": "base and tool", "none": "none"}


def axis_length(robot: Robot) -> float:
    """Axis length scaled to the arm (the seed's fixed size was lost on big arms)."""
    size = reach(robot)
    return AXIS_FRACTION * size if size > 0 else robot.mm(50.0)


@dataclass(frozen=True)
class Wireframe:
    """Everything drawn, in world coordinates (robot units).

    ``axes[i, k]`` is the end of frame i's k-th axis (x, y, z) and
    ``origins[i]`` its start; frames are 0..n, then the tool if it has one.
    ``joints[j]`` is where joint j + 1's axis is marked (the origin of the
    frame it turns or slides along: frame j in standard D-H, frame j + 1 in
    modified) and ``joint_types[j]`` says what it is.
    """

    links: np.ndarray  # (m, 3) polyline through frame origins, base to tool
    origins: np.ndarray  # (f, 3)
    axes: np.ndarray  # (f, 3, 3)
    end_effector: np.ndarray  # (3,)
    pedestal: np.ndarray | None  # (2, 3) floor to frame 0, when frame 0 is above the floor
    floor_z: float
    area: WorkArea
    below_floor: tuple[int, ...]  # frames whose origin is under the floor
    units: str = "mm"
    joints: np.ndarray | None = None  # (n, 3)
    joint_types: tuple[str, ...] = ()
    #: the links dropped straight down onto the floor (the 3-D view's depth cue)
    shadow: np.ndarray | None = None
    #: the tool's path (a program played): world points, drawn under the arm
    trail: np.ndarray | None = None

    @property
    def warnings(self) -> tuple[str, ...]:
        """What the pose panel flags: frames that went through the floor."""
        if not self.below_floor:
            return ()
        return (f"below the floor: frame {', '.join(str(i) for i in self.below_floor)}",)

    def shown_frames(self, mode: str) -> np.ndarray:
        """The indices (into ``origins`` and ``axes``) of the frames ``mode`` draws."""
        count = len(self.origins)
        if mode == "none" or count == 0:
            return np.empty(0, dtype=np.int64)
        if mode == "ends":
            return np.unique(np.array([0, count - 1], dtype=np.int64))
        return np.arange(count)


def build_wireframe(robot: Robot, frames: np.ndarray, trail: np.ndarray | None = None) -> Wireframe:
    """``frames`` is Kinematics.frames(q): (n + 2, 4, 4), frames 0..n and the
    tool; ``trail`` the tool's path to draw (world points), if any."""
    origins = frames[:, :3, 3]
    n = robot.dof
    drawn = frames if not robot.tool.is_identity else frames[: n + 1]
    drawn_origins = drawn[:, :3, 3]
    length = axis_length(robot)
    tolerance = 1e-6 * max(length, 1e-12)
    # how many earlier frames share each frame's origin
    gaps = np.abs(drawn_origins[:, None, :] - drawn_origins[None, :, :]).max(axis=2)
    shared = np.tril(gaps < tolerance, k=-1).sum(axis=1)
    scale = length * (1.0 + SHARED_ORIGIN_GROWTH * shared)
    # columns of each rotation are the axes; ends = origin + scale * axis
    axes = drawn_origins[:, None, :] + scale[:, None, None] * drawn[:, :3, :3].transpose(0, 2, 1)
    floor_z = -robot.base_height
    pedestal = None
    x, y, z = origins[0]
    if z > floor_z + tolerance:
        pedestal = np.array([[x, y, floor_z], [x, y, z]])
    links = origins if not robot.tool.is_identity else origins[: n + 1]
    below = tuple(int(i) for i in np.nonzero(origins[: n + 1, 2] < floor_z - tolerance)[0])
    # joint i + 1 turns about (slides along) z of frame i (standard) or i + 1 (modified)
    first = 0 if robot.convention == "standard" else 1
    joints = origins[first : first + n].copy()
    shadow = links.copy()
    shadow[:, 2] = floor_z
    return Wireframe(
        links=links,
        origins=drawn_origins,
        axes=axes,
        end_effector=origins[-1],
        pedestal=pedestal,
        floor_z=floor_z,
        area=work_area(robot),
        below_floor=below,
        units=robot.units,
        joints=joints,
        joint_types=tuple(joint.type for joint in robot.joints),
        shadow=shadow,
        trail=None if trail is None else np.asarray(trail, dtype=float).reshape(-1, 3),
    )

"""The seed's work area and the robot's reach (reference §3), and the
workspace: a cloud of tool positions from random joint vectors, summarised."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, replace

import numpy as np

from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.kinematics import robot_base
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


# -- the workspace: where the tool can go ------------------------------------------

#: how many random joint vectors make a workspace cloud by default
DEFAULT_SAMPLES = 20_000
#: the most samples a caller may ask for (10 million: about 2 s and no more
#: memory than one chunk when only the summary is wanted)
MAX_SAMPLES = 10_000_000
#: joint vectors drawn and put through batch FK at a time: a worker thread can
#: stop (or let the event loop run) between chunks
SAMPLE_CHUNK = 16_384


def check_sample_count(n: object) -> int:
    """``n`` as a whole number of samples in 1..MAX_SAMPLES, or a DhsimError."""
    if isinstance(n, bool) or not isinstance(n, int | np.integer):
        raise DhsimError(f"the number of samples must be a whole number, got {n!r}")
    if not 1 <= n <= MAX_SAMPLES:
        raise DhsimError(f"the number of samples must be 1 to {MAX_SAMPLES:,}, got {n}")
    return int(n)


def joint_samples(
    robot: Robot, n: int = DEFAULT_SAMPLES, seed: int = 0, chunk: int = SAMPLE_CHUNK
) -> Iterator[np.ndarray]:
    """``n`` joint vectors drawn uniformly within every joint's limits, in
    chunks of at most ``chunk`` rows (k, dof). The same ``seed`` gives the same
    vectors whatever the chunk size (the generator's stream is read in order)."""
    n = check_sample_count(n)
    if chunk < 1:
        raise DhsimError(f"chunk must be at least 1, got {chunk}")
    rng = np.random.default_rng(seed)
    low, high = np.array(robot.lower, dtype=float), np.array(robot.upper, dtype=float)
    for start in range(0, n, chunk):
        yield rng.uniform(low, high, size=(min(chunk, n - start), robot.dof))


def position_chunks(
    robot: Robot, n: int = DEFAULT_SAMPLES, seed: int = 0, chunk: int = SAMPLE_CHUNK
) -> Iterator[np.ndarray]:
    """The tool positions (world, robot units) of :func:`joint_samples`, chunk
    by chunk, each (k, 3): a worker thread may stop between two chunks."""
    kinematics = robot.kinematics
    for qs in joint_samples(robot, n, seed, chunk):
        yield np.ascontiguousarray(kinematics.batch(qs)[:, :3, 3])


def sample_positions(robot: Robot, n: int = DEFAULT_SAMPLES, seed: int = 0) -> np.ndarray:
    """(n, 3) tool positions (world, robot units) for ``n`` joint vectors drawn
    uniformly within the limits, by batch FK: a cloud of the workspace.
    Repeatable: the same robot, n and seed give the same points."""
    return np.concatenate(list(position_chunks(robot, n, seed)))


@dataclass(frozen=True)
class WorkspaceSummary:
    """The extent of a cloud of tool positions (world coordinates, robot units).

    ``reach_reached`` is the largest distance from frame 0's origin; it never
    exceeds ``reach_bound`` (:func:`reach`). ``horizontal_radius`` is the
    largest distance from the vertical line through frame 0's origin."""

    count: int
    units: str
    origin: tuple[float, float, float]  # frame 0's origin
    xyz_min: tuple[float, float, float]
    xyz_max: tuple[float, float, float]
    reach_reached: float
    reach_bound: float
    horizontal_radius: float

    @property
    def z_range(self) -> tuple[float, float]:
        return (self.xyz_min[2], self.xyz_max[2])

    def contains(self, points: np.ndarray, tolerance: float = 0.0) -> bool:
        """True when every point lies in the bounding box (within ``tolerance``)."""
        pts = np.asarray(points, dtype=float).reshape(-1, 3)
        return bool(
            np.all(pts >= np.array(self.xyz_min) - tolerance)
            and np.all(pts <= np.array(self.xyz_max) + tolerance)
        )

    def merged(self, other: WorkspaceSummary) -> WorkspaceSummary:
        """The summary of both clouds together (same robot)."""
        return replace(
            self,
            count=self.count + other.count,
            xyz_min=_triple(np.minimum(self.xyz_min, other.xyz_min)),
            xyz_max=_triple(np.maximum(self.xyz_max, other.xyz_max)),
            reach_reached=max(self.reach_reached, other.reach_reached),
            horizontal_radius=max(self.horizontal_radius, other.horizontal_radius),
        )

    def as_dict(self) -> dict:
        """Plain numbers and lists (for JSON)."""
        return {
            "units": self.units,
            "samples": self.count,
            "origin": list(self.origin),
            "min": list(self.xyz_min),
            "max": list(self.xyz_max),
            "z_range": list(self.z_range),
            "reach": self.reach_reached,
            "reach_bound": self.reach_bound,
            "horizontal_radius": self.horizontal_radius,
        }


def _triple(values) -> tuple[float, float, float]:
    x, y, z = (float(v) for v in values)
    return (x, y, z)


def frame0_origin(robot: Robot) -> np.ndarray:
    """Frame 0's origin in world coordinates (base_xyz, or the world origin)."""
    return robot_base(robot)[:3, 3].copy()


def workspace_summary(robot: Robot, points: np.ndarray) -> WorkspaceSummary:
    """Bounding box, reach reached (and its bound) and horizontal radius of a
    cloud of tool positions (n, 3), n >= 1."""
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    if len(pts) == 0:
        raise DhsimError("a workspace summary needs at least one point")
    origin = frame0_origin(robot)
    offsets = pts - origin
    return WorkspaceSummary(
        count=len(pts),
        units=robot.units,
        origin=_triple(origin),
        xyz_min=_triple(pts.min(axis=0)),
        xyz_max=_triple(pts.max(axis=0)),
        reach_reached=float(np.sqrt((offsets**2).sum(axis=1)).max()),
        reach_bound=float(reach(robot)),
        horizontal_radius=float(np.hypot(offsets[:, 0], offsets[:, 1]).max()),
    )


def sample_summary(robot: Robot, n: int = DEFAULT_SAMPLES, seed: int = 0) -> WorkspaceSummary:
    """``workspace_summary(robot, sample_positions(robot, n, seed))``, chunk by
    chunk: millions of samples without holding them all."""
    summary: WorkspaceSummary | None = None
    for points in position_chunks(robot, n, seed):
        part = workspace_summary(robot, points)
        summary = part if summary is None else summary.merged(part)
    assert summary is not None  # n >= 1
    return summary

"""The seed's work area and the robot's reach (kinematics
reference section 3: the world frame and work area), the length
the solvers measure against (:func:`length_scale`), and the workspace: a
cloud of tool positions from random joint vectors, summarised."""

from __future__ import annotations

import functools
from collections.abc import Iterator
from dataclasses import dataclass, replace

import numpy as np

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics import robot_base
from dhsim_tui.core.model.robot import Robot

#: the seed's margin around the reach, in millimetres
WORK_AREA_MARGIN_MM = 30.0


def link_length(joint) -> float:
    """The largest length a link can have: |a| plus |d|, with a prismatic
    joint's d at the largest magnitude its range allows."""
    if joint.is_revolute:
        return abs(joint.a) + abs(joint.d)
    return abs(joint.a) + max(abs(joint.min), abs(joint.max))


def reach(robot: Robot) -> float:
    """Sum of the largest link lengths plus the tool's length (robot units):
    the seed's bound on the reach, and the scale the solvers measure errors
    against. No pose comes further; most arms fall well short of it (the
    Puma 560: 1034 mm against its real 877 mm). :func:`arm_reach` is the
    reach itself."""
    return sum(link_length(j) for j in robot.joints) + robot.tool.length


def length_scale(robot: Robot) -> float:
    """The arm's characteristic length (its reach), to make lengths dimensionless."""
    return reach(robot) or 1.0


#: joint vectors sampled to start the search for the reach, and how many of
#: the farthest are then pushed further by local ascent
REACH_SAMPLES = 4096
REACH_STARTS = 8
REACH_ITERATIONS = 40
#: a start stops when a round gains less than this share of its distance
REACH_TOLERANCE = 1e-12


def _distances(robot: Robot, qs: np.ndarray, origin: np.ndarray) -> np.ndarray:
    points = robot.kinematics.batch(qs)[:, :3, 3]
    return np.sqrt(((points - origin) ** 2).sum(axis=1))


def _ascend(robot: Robot, q: np.ndarray, origin: np.ndarray, scale: float) -> float:
    """Push ``q`` to a local maximum of the tool's distance from ``origin``
    within the limits; that distance. Newton steps on the distance (its
    gradient and Hessian by central differences, one batch of FK a round),
    the Hessian made negative definite where it is not, so each step goes
    uphill, then a line search over halving steps, kept within the limits.
    Joint values are measured in steps of 30 degrees or 0.3 of the reach
    bound, so the two kinds of joint weigh alike."""
    low, high = np.array(robot.lower, dtype=float), np.array(robot.upper, dtype=float)
    n = len(q)
    unit = np.where([j.is_revolute for j in robot.joints], 30.0, 0.3 * scale)
    x, lo, hi = q / unit, low / unit, high / unit
    h = 1e-3
    eye = np.eye(n) * h
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    tries = 0.5 ** np.arange(20)

    def distance(points: np.ndarray) -> np.ndarray:
        return _distances(robot, points * unit, origin)

    best = float(distance(x[None, :])[0])
    for _ in range(REACH_ITERATIONS):
        # the distance at x, x +- h e_i and x +- h e_i +- h e_j: one batch
        around = [x + eye[i] for i in range(n)] + [x - eye[i] for i in range(n)]
        for i, j in pairs:
            around += [x + eye[i] + eye[j], x - eye[i] - eye[j]]
        values = distance(np.clip(np.array(around), lo - h, hi + h))
        up, down = values[:n], values[n : 2 * n]
        gradient = (up - down) / (2 * h)
        hessian = np.diag((up - 2 * best + down) / h**2)
        for k, (i, j) in enumerate(pairs):
            both = values[2 * n + 2 * k] + values[2 * n + 2 * k + 1]
            hessian[i, j] = hessian[j, i] = (
                both - up[i] - down[i] - up[j] - down[j] + 2 * best
            ) / (2 * h**2)
        # a joint on a stop that pulls outward stays there
        free = ~(((x <= lo) & (gradient < 0)) | ((x >= hi) & (gradient > 0)))
        if not free.any() or not np.abs(gradient[free]).max() > 1e-12 * best:
            break
        curvature, vectors = np.linalg.eigh(-hessian[np.ix_(free, free)])
        floor = max(1e-3 * np.abs(curvature).max(), 1e-9 * best, 1e-12)
        inverse = (vectors / np.maximum(curvature, floor)) @ vectors.T
        direction = np.zeros(n)
        direction[free] = inverse @ gradient[free]
        longest = np.abs(direction).max()
        if longest > 1.0:  # at most a whole unit (30 degrees) at once
            direction /= longest
        candidates = np.clip(x[None, :] + tries[:, None] * direction[None, :], lo, hi)
        found = distance(candidates)
        k = int(np.argmax(found))
        if found[k] <= best * (1 + REACH_TOLERANCE):
            best = max(best, float(found[k]))
            break
        x, best = candidates[k], float(found[k])
    return best


#: arms with at most this many joints also try every corner of their limits
#: box (2**n joint vectors) as starts
CORNER_JOINTS = 8


@functools.lru_cache(maxsize=64)
def arm_reach(robot: Robot) -> float:
    """The arm's reach: the largest distance of the tool from frame 0's
    origin within the joint limits (robot units).

    Found the way a person would: the farthest of ``REACH_SAMPLES`` joint
    vectors drawn within the limits (and every corner of the limits box, for
    arms of up to :data:`CORNER_JOINTS` joints: a stop often decides) are each pushed further by
    local ascent, which converges on the maximum near it. The same arm in
    either D-H convention gives the same reach; a sampled workspace never
    exceeds it. Repeatable: the samples are seeded."""
    origin = frame0_origin(robot)
    low, high = np.array(robot.lower, dtype=float), np.array(robot.upper, dtype=float)
    rng = np.random.default_rng(0)
    qs = np.vstack([rng.uniform(low, high, size=(REACH_SAMPLES, robot.dof)), low, high])
    if robot.dof <= CORNER_JOINTS:  # every corner of the limits box, where stops decide
        corners = np.meshgrid(*zip(low, high, strict=True), indexing="ij")
        qs = np.vstack([qs, np.stack(corners, axis=-1).reshape(-1, robot.dof)])
    qs = np.vstack([qs, np.array(robot.home, dtype=float)])
    distances = _distances(robot, qs, origin)
    scale = max(reach(robot), 1e-12)
    best = float(distances.max())
    for index in np.argsort(distances)[::-1][:REACH_STARTS]:
        best = max(best, _ascend(robot, qs[index].copy(), origin, scale))
    return best


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
    at -base_height; sides and ceiling at the arm's reach + 30 mm from frame
    0. The seed's reach was the sum of the link lengths (:func:`reach`), a
    bound most arms fall well short of; the arm's own reach
    (:func:`arm_reach`) frames it tighter and the same in either convention."""
    side = arm_reach(robot) + robot.mm(WORK_AREA_MARGIN_MM)
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
    exceeds ``reach`` (:func:`arm_reach`), nor ``reach_bound`` (:func:`reach`).
    ``horizontal_radius`` is the largest distance from the vertical line
    through frame 0's origin."""

    count: int
    units: str
    origin: tuple[float, float, float]  # frame 0's origin
    xyz_min: tuple[float, float, float]
    xyz_max: tuple[float, float, float]
    reach_reached: float
    reach_bound: float
    horizontal_radius: float
    reach: float = 0.0

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
            "reach": self.reach,
            "reach_reached": self.reach_reached,
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
        reach=arm_reach(robot),
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

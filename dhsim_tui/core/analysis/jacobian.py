"""The geometric Jacobian in world coordinates and the measures built on it.

Column i is the end effector's velocity (linear over angular) per unit speed
of joint i: a revolute joint turning about axis z through origin o gives
(z × (p − o), z) per radian; a prismatic one sliding along z gives (z, 0) per
unit length. Standard D-H joint i moves about frame i−1's z; modified D-H
joint i about frame i's own z.

Like forward kinematics (see kinematics.py), the Jacobian is compiled per
robot into one straight-line Python function: the solvers' :func:`kernel` by
:mod:`dhsim_tui.core.analysis.jacobian_codegen`, :func:`jacobian`'s by the
chain's own writer (:func:`_compile_plain`: the codegen's operations, so the
same numbers, packed straight into an array). Until a robot has asked for
it :data:`COMPILE_AFTER` times it is read off the frames instead
(:func:`jacobian_from_frames`, the same operations again), which spares the
editor a compile per edit. The manipulability's written-out Cholesky
factorisation is in :mod:`dhsim_tui.core.analysis.cholesky`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.analysis.cholesky import root_gram_det
from dhsim_tui.core.analysis.jacobian_codegen import compile_jacobian
from dhsim_tui.core.analysis.workspace import length_scale
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics import COMPILE_AFTER, as_floats, start_state
from dhsim_tui.core.model.kinematics_batch import check_out
from dhsim_tui.core.model.kinematics_codegen import (
    ChainWriter,
    Term,
    Value,
    negated,
    packer,
    product,
    signed,
    text,
    total,
)
from dhsim_tui.core.model.robot import Joint, Robot

_F64 = np.dtype(np.float64)
_ndarray = np.ndarray
_empty = np.empty
#: the arm counts as singular when its normalised manipulability drops below this
SINGULAR_THRESHOLD = 1e-3
#: warn from this value on
NEAR_SINGULAR = 0.02


def jacobian_from_frames(
    robot: Robot, frames: np.ndarray, out: np.ndarray | None = None
) -> np.ndarray:
    """6×n Jacobian from Kinematics.frames(q) (frames 0..n and the tool), in
    ``out`` (a float64 6×n array) when given."""
    n = robot.dof
    offset = 0 if robot.convention == "standard" else 1
    axes = frames[offset : offset + n, :3, 2]  # (n, 3) joint axes in world
    origins = frames[offset : offset + n, :3, 3]
    lever = frames[-1, :3, 3] - origins
    revolute = np.array([j.is_revolute for j in robot.joints])
    if out is not None:
        check_out(out, (6, n))
    jac = np.zeros((6, n)) if out is None else out
    # axes × lever, written out (np.cross costs more than the rest together)
    ax, ay, az = axes.T
    lx, ly, lz = lever.T
    jac[0] = np.where(revolute, ay * lz - az * ly, ax)
    jac[1] = np.where(revolute, az * lx - ax * lz, ay)
    jac[2] = np.where(revolute, ax * ly - ay * lx, az)
    jac[3:] = np.where(revolute, axes.T, 0.0)
    return jac


# -- the compiled Jacobian, cached on the robot --------------------------------------


class _Compiled:
    """A robot's compiled Jacobians, built on demand, and how often it was asked."""

    __slots__ = ("calls", "kernel", "measure", "plain", "shape")

    def __init__(self, dof: int) -> None:
        self.calls = 0
        self.shape = (6, dof)
        self.plain: Callable | None = None
        self.kernel: Callable | None = None
        self.measure: tuple | None = None


def _compiled(robot: Robot) -> _Compiled:
    cached = robot.__dict__.get("_jacobian_compiled")
    if cached is None:
        cached = _Compiled(robot.dof)
        object.__setattr__(robot, "_jacobian_compiled", cached)
    return cached


def _compile_plain(robot: Robot) -> Callable:
    """``f(q, o)``: the world Jacobian packed into ``o`` (a C-contiguous float64
    6×n array), written by the chain's :class:`ChainWriter` with the operations
    of jacobian_codegen's plain Jacobian, so the same numbers, but no copies,
    and nothing the Jacobian does not need (often the last joint's turn)."""
    tool = None if robot.tool.is_identity else robot.kinematics.tool
    writer = ChainWriter(robot, tool, start_state(robot))
    standard = robot.convention == "standard"
    axes = []  # each joint's axis and a point on it: z and origin of frame i-1 (or i)
    for i in range(robot.dof):
        if standard:
            axes.append([writer.state[name] for name in ("z0", "z1", "z2", "p0", "p1", "p2")])
        writer.joint(i)
        if not standard:
            axes.append([writer.state[name] for name in ("z0", "z1", "z2", "p0", "p1", "p2")])
    writer.tool()
    end = [writer.state[name] for name in ("p0", "p1", "p2")]
    columns = [_column(writer, joint, axes[i], end, i == 0) for i, joint in enumerate(robot.joints)]
    flat = ", ".join(column[row] for row in range(6) for column in columns)
    return writer.compile([f"_pack(o, 0, {flat})"], {"_pack": packer(6 * robot.dof)})


def _column(
    writer: ChainWriter, joint: Joint, axis: list[Value], end: list[Value], first: bool
) -> list[str]:
    """A joint's column: (z, 0) for a prismatic joint, (z × (p - o), z) for a
    revolute one. Joint 1's axis and origin are constants: as jacobian_codegen
    does, a zero origin makes no difference and a zero or unit term of the
    cross product is left out or not multiplied."""
    z = axis[:3]
    if not joint.is_revolute:
        return [*(text(v) for v in z), "0.0", "0.0", "0.0"]
    lever = [
        p if first and o == 0.0 else writer.bind(total(signed(p), negated(signed(o))))
        for p, o in zip(end, axis[3:], strict=True)
    ]

    def term(c: Value, value: Value) -> Term | None:
        return None if first and c == 0.0 else product(c, value)  # (±1: no product)

    def difference(a: Term | None, b: Term | None) -> Term:
        if a is None or b is None:
            return 0.0 if a is None and b is None else a if b is None else negated(b)
        return total(a, negated(b))

    (ax, ay, az), (lx, ly, lz) = z, lever
    cross = [
        difference(term(ay, lz), term(az, ly)),
        difference(term(az, lx), term(ax, lz)),
        difference(term(ax, ly), term(ay, lx)),
    ]
    return [*(text(writer.bind(t)) for t in cross), *(text(v) for v in z)]


def kernel(robot: Robot) -> Callable:
    """The robot's compiled ``f(q) -> (state, normalised flat Jacobian)``, for
    solvers that run it many times (compiled on first use)."""
    cached = _compiled(robot)
    if cached.kernel is None:
        cached.kernel = compile_jacobian(robot, normalise=True, with_state=True)
    return cached.kernel


def _bad_q(robot: Robot, exc: Exception) -> DhsimError:
    return DhsimError(f"expected {robot.dof} joint values for {robot.name!r}: {exc}")


def jacobian(robot: Robot, q: Sequence[float], out: np.ndarray | None = None) -> np.ndarray:
    """The world-frame geometric Jacobian at joint values q (deg / robot units),
    6×n, in ``out`` (a float64 6×n array, returned) when given."""
    try:
        cached = robot._jacobian_compiled
    except AttributeError:
        cached = _compiled(robot)
    if q.__class__ is _ndarray:
        q = as_floats(q)
    if out is None:
        out = _empty(cached.shape)
    elif out.__class__ is not _ndarray or out.shape != cached.shape or out.dtype is not _F64:
        check_out(out, cached.shape)
    plain = cached.plain
    if plain is None:
        cached.calls += 1
        if cached.calls < COMPILE_AFTER:
            return jacobian_from_frames(robot, robot.kinematics.frames(q), out)
        plain = cached.plain = _compile_plain(robot)
    try:
        plain(q, out)
    except (ValueError, TypeError) as exc:  # (an out not C-contiguous: through a new one)
        if not out.flags.writeable:
            raise DhsimError("out must be a writable array") from None
        if out.flags.c_contiguous:
            raise _bad_q(robot, exc) from None
        out[...] = jacobian(robot, q)
    return out


def task_rank(robot: Robot) -> int:
    """The rank the arm has in general (largest over a few sample poses)."""
    cached = getattr(robot, "_task_rank", None)
    if cached is None:
        cached = max(np.linalg.matrix_rank(j, tol=1e-6) for j in _sample_jacobians(robot))
        object.__setattr__(robot, "_task_rank", int(cached))
    return cached


def _sample_jacobians(robot: Robot) -> list[np.ndarray]:
    """Normalised Jacobians at a few seeded random poses within the limits,
    for the facts that hold in general (rank, which directions can move)."""
    cached = getattr(robot, "_sample_jacobians", None)
    if cached is None:
        rng = np.random.default_rng(0)
        samples = rng.uniform(robot.lower, robot.upper, size=(8, robot.dof))
        cached = [normalised(robot, jacobian(robot, q)) for q in samples]
        object.__setattr__(robot, "_sample_jacobians", cached)
    return cached


def normalised(robot: Robot, jac: np.ndarray) -> np.ndarray:
    """Dimensionless Jacobian: linear rows per reach, prismatic columns per reach
    (so a gantry and an arm of any size and unit compare)."""
    scale = length_scale(robot)
    out = jac.copy()
    out[:3] /= scale
    prismatic = [i for i, j in enumerate(robot.joints) if not j.is_revolute]
    out[:, prismatic] *= scale
    return out


def controllable_rows(robot: Robot) -> np.ndarray:
    """Which of (x, y, z, rx, ry, rz) the arm can move at all (a SCARA cannot
    tilt, a planar arm cannot leave its plane): rows of the Jacobian that are
    not zero at every sample pose."""
    cached = getattr(robot, "_controllable_rows", None)
    if cached is None:
        size = np.max([np.abs(j).max(axis=1) for j in _sample_jacobians(robot)], axis=0)
        cached = size > 1e-9
        object.__setattr__(robot, "_controllable_rows", cached)
    return cached


@dataclass(frozen=True)
class Dexterity:
    """How well the arm can move here. Both measures use the normalised
    Jacobian and the rank the arm has (a SCARA or planar arm is not
    'singular' merely for having fewer than six joints)."""

    manipulability: float  # Yoshikawa: product of the top-rank singular values
    condition: float  # sigma_max / sigma_rank (inf when singular)
    rank: int

    @property
    def singular(self) -> bool:
        return self.manipulability < SINGULAR_THRESHOLD

    @property
    def near_singular(self) -> bool:
        return self.manipulability < NEAR_SINGULAR


def _measured_rows(robot: Robot) -> tuple[np.ndarray, int]:
    """The rows the dexterity measures and the rank it takes."""
    rows = controllable_rows(robot)
    if robot.dof < rows.sum():
        # fewer joints than directions it can move in (a planar arm: x, y and
        # the turn): it positions the tool, so measure how well it positions
        rows = rows.copy()
        rows[3:] = False
        return rows, min(robot.dof, int(rows.sum()))
    return rows, task_rank(robot)


def dexterity(
    robot: Robot, q: Sequence[float] | None = None, *, jac: np.ndarray | None = None
) -> Dexterity:
    if jac is None:
        jac = jacobian(robot, q if q is not None else robot.home)
    jac = normalised(robot, jac)
    rows, rank = _measured_rows(robot)
    sigma = np.linalg.svd(jac[rows], compute_uv=False)[:rank]
    if len(sigma) < rank:
        sigma = np.concatenate([sigma, np.zeros(rank - len(sigma))])
    manip = float(np.prod(sigma))
    condition = float(sigma[0] / sigma[-1]) if sigma[-1] > 1e-12 else float("inf")
    return Dexterity(manip, condition, rank)


# -- manipulability without numpy's per-call overhead -----------------------------


def _measure_plan(robot: Robot) -> tuple:
    """The measured row indices, and whether the measure is sqrt det of a Gram
    matrix (not when the rank is below both sides: then it needs the singular
    values)."""
    cached = _compiled(robot)
    if cached.measure is None:
        rows, rank = _measured_rows(robot)
        picked = tuple(int(r) for r in np.flatnonzero(rows))
        cached.measure = (picked, bool(rank == min(len(picked), robot.dof)))
    return cached.measure


def manipulability(
    robot: Robot, q: Sequence[float] | None = None, *, jac: np.ndarray | None = None
) -> float:
    """``dexterity(robot, q).manipulability`` (Yoshikawa's sqrt det(J Jᵀ) on the
    normalised Jacobian's measured rows) without the singular values: sqrt det
    of the smaller Gram matrix by a written-out Cholesky factorisation, on the
    compiled Jacobian."""
    picked, exact = _measure_plan(robot)
    if not exact:
        return dexterity(robot, q, jac=jac).manipulability
    n = robot.dof
    if jac is None:
        try:
            flat = kernel(robot)(q if q is not None else robot.home)[1]
        except (ValueError, TypeError) as exc:
            raise _bad_q(robot, exc) from None
        if len(picked) < 6:
            flat = [v for r in picked for v in flat[r * n : r * n + n]]
    else:
        flat = normalised(robot, np.asarray(jac, dtype=float))[list(picked)].ravel().tolist()
    return root_gram_det(len(picked), n)(flat)

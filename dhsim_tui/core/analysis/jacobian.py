"""The geometric Jacobian in world coordinates and the measures built on it.

Column i is the end effector's velocity (linear over angular) per unit speed
of joint i: a revolute joint turning about axis z through origin o gives
(z × (p − o), z) per radian; a prismatic one sliding along z gives (z, 0) per
unit length. Standard D-H joint i moves about frame i−1's z; modified D-H
joint i about frame i's own z.

Like forward kinematics (see kinematics.py), the Jacobian is compiled per
robot into one straight-line Python function: the chain's own lines, each
joint's axis and origin kept as it passes, the cross products written out at
the end, constants folded (the first joint's axis is a constant). Until a
robot has asked for it :data:`COMPILE_AFTER` times it is read off the frames
instead (:func:`jacobian_from_frames`, the same operations, so the same
numbers), which spares the editor a compile per edit.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.analysis.workspace import reach
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics import (
    COMPILE_AFTER,
    _constant_lines,
    _joint_lines,
    _start,
    _step,
)
from dhsim_tui.core.model.robot import Robot

#: the arm counts as singular when its normalised manipulability drops below this
SINGULAR_THRESHOLD = 1e-3
#: warn from this value on
NEAR_SINGULAR = 0.02

_STATE = "x0, x1, x2, y0, y1, y2, z0, z1, z2, p0, p1, p2"


def jacobian_from_frames(robot: Robot, frames: np.ndarray) -> np.ndarray:
    """6×n Jacobian from Kinematics.frames(q) (frames 0..n and the tool)."""
    n = robot.dof
    offset = 0 if robot.convention == "standard" else 1
    axes = frames[offset : offset + n, :3, 2]  # (n, 3) joint axes in world
    origins = frames[offset : offset + n, :3, 3]
    lever = frames[-1, :3, 3] - origins
    revolute = np.array([j.is_revolute for j in robot.joints])
    jac = np.zeros((6, n))
    # axes × lever, written out (np.cross costs more than the rest together)
    ax, ay, az = axes.T
    lx, ly, lz = lever.T
    jac[0] = np.where(revolute, ay * lz - az * ly, ax)
    jac[1] = np.where(revolute, az * lx - ax * lz, ay)
    jac[2] = np.where(revolute, ax * ly - ay * lx, az)
    jac[3:] = np.where(revolute, axes.T, 0.0)
    return jac


# -- the compiled Jacobian ---------------------------------------------------------


def _term(coefficient: float | str, name: str) -> str | None:
    """``coefficient * name`` with 0 and ±1 folded (None for a zero)."""
    if isinstance(coefficient, str):
        return f"{coefficient}*{name}"
    if coefficient == 0.0:
        return None
    if coefficient == 1.0:
        return name
    if coefficient == -1.0:
        return f"-{name}"
    return f"{coefficient!r}*{name}"


def _difference(first: str | None, second: str | None) -> str:
    if first is None and second is None:
        return "0.0"
    if second is None:
        return str(first)
    if first is None:
        return f"-({second})"
    return f"{first} - {second}"


def _value(v: float | str) -> str:
    return v if isinstance(v, str) else repr(float(v))


def _first_axis(robot: Robot) -> tuple[float, ...]:
    """Joint 1's axis and origin (6 floats): constants, whatever q is. Standard
    D-H: frame 0's z and origin; modified: frame 1's, whose z and (for a
    revolute joint) origin the joint's own turn leaves alone. Computed by the
    chain's own lines, so the same bits as at run time."""
    state = _start(robot)
    if robot.convention != "standard":
        state = _step(tuple(_joint_lines(robot, 0, "qi")))(state, 0.0)
    return tuple(state[6:12])


def jacobian_source(robot: Robot, *, normalise: bool = False, with_state: bool = False) -> str:
    """The Python source of the robot's compiled Jacobian ``f(q)``.

    It returns the 6×n Jacobian as a flat row-major list; ``with_state`` also
    returns the end effector's 12-float state (as ``Kinematics.state``) first.
    ``normalise`` gives :func:`normalised`'s dimensionless Jacobian instead
    (linear rows per reach, prismatic columns per reach)."""
    n = robot.dof
    standard = robot.convention == "standard"
    tool = None if robot.tool.is_identity else robot.kinematics.tool
    body = [f"{_STATE} = {', '.join(repr(float(v)) for v in _start(robot))}"]
    body.append(f"{', '.join(f'q{i}' for i in range(n))}, = q")
    axes: list[tuple] = []

    def capture(i: int) -> tuple:
        if i == 0:
            return _first_axis(robot)
        body.append(f"u{i}x, u{i}y, u{i}z, o{i}x, o{i}y, o{i}z = z0, z1, z2, p0, p1, p2")
        return tuple(f"{k}{i}{c}" for k in "uo" for c in "xyz")

    for i in range(n):
        if standard:
            axes.append(capture(i))
        body += _joint_lines(robot, i)
        if not standard:
            axes.append(capture(i))
    if tool is not None:
        body += _constant_lines(tool)
    inverse = 1.0 / length_scale(robot) if normalise else 1.0
    columns = []
    for i, joint in enumerate(robot.joints):
        ax, ay, az, ox, oy, oz = axes[i]
        if not joint.is_revolute:  # (z, 0): per unit length, or per reach (× reach / reach)
            columns.append([_value(ax), _value(ay), _value(az), "0.0", "0.0", "0.0"])
            continue
        for k, (p, o) in enumerate(zip(("p0", "p1", "p2"), (ox, oy, oz), strict=True)):
            lever = f"{p} - {_value(o)}" if o != 0.0 else p
            if inverse != 1.0:
                lever = f"({lever})*{inverse!r}"
            body.append(f"l{k} = {lever}")
        columns.append(
            [
                _difference(_term(ay, "l2"), _term(az, "l1")),
                _difference(_term(az, "l0"), _term(ax, "l2")),
                _difference(_term(ax, "l1"), _term(ay, "l0")),
                _value(ax),
                _value(ay),
                _value(az),
            ]
        )
        # the lever's names are reused: keep this column's values before the next
        names = [f"c{i}_{r}" for r in range(3)]
        body.append(f"{', '.join(names)} = {', '.join(columns[-1][:3])}")
        columns[-1][:3] = names
    flat = ", ".join(columns[c][r] for r in range(6) for c in range(n))
    body.append(f"return ({_STATE}), [{flat}]" if with_state else f"return [{flat}]")
    return "def jacobian(q):\n" + "".join(f"    {line}\n" for line in body)


def compile_jacobian(robot: Robot, *, normalise: bool = False, with_state: bool = False):
    """:func:`jacobian_source` compiled: ``f(q) -> flat list`` (or ``(state, flat)``)."""
    source = jacobian_source(robot, normalise=normalise, with_state=with_state)
    namespace: dict = {"_cos": math.cos, "_sin": math.sin}
    exec(compile(source, f"<dhsim jacobian: {robot.name}>", "exec"), namespace)
    return namespace["jacobian"]


class _Compiled:
    """A robot's compiled Jacobians, built on demand, and how often it was asked."""

    __slots__ = ("calls", "kernel", "measure", "plain")

    def __init__(self) -> None:
        self.calls = 0
        self.plain: Callable | None = None
        self.kernel: Callable | None = None
        self.measure: tuple | None = None


def _compiled(robot: Robot) -> _Compiled:
    cached = robot.__dict__.get("_jacobian_compiled")
    if cached is None:
        cached = _Compiled()
        object.__setattr__(robot, "_jacobian_compiled", cached)
    return cached


def kernel(robot: Robot) -> Callable:
    """The robot's compiled ``f(q) -> (state, normalised flat Jacobian)``, for
    solvers that run it many times (compiled on first use)."""
    cached = _compiled(robot)
    if cached.kernel is None:
        cached.kernel = compile_jacobian(robot, normalise=True, with_state=True)
    return cached.kernel


def _bad_q(robot: Robot, exc: Exception) -> DhsimError:
    return DhsimError(f"expected {robot.dof} joint values for {robot.name!r}: {exc}")


def jacobian(robot: Robot, q: Sequence[float]) -> np.ndarray:
    """The world-frame geometric Jacobian at joint values q (deg / robot units)."""
    cached = _compiled(robot)
    if cached.plain is None:
        cached.calls += 1
        if cached.calls < COMPILE_AFTER:
            return jacobian_from_frames(robot, robot.kinematics.frames(q))
        cached.plain = compile_jacobian(robot)
    try:
        flat = cached.plain(q)
    except (ValueError, TypeError) as exc:
        raise _bad_q(robot, exc) from None
    return np.fromiter(flat, float, 6 * robot.dof).reshape(6, robot.dof)


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


def length_scale(robot: Robot) -> float:
    """The arm's characteristic length (its reach), to make lengths dimensionless."""
    return reach(robot) or 1.0


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


def _gram_cholesky_lines(m: int, n: int, damped: bool) -> tuple[list[str], int]:
    """Straight-line Cholesky factor L of the smaller Gram matrix of a flat m×n
    ``jac`` (JᵀJ when n <= m, else JJᵀ), plus ``lam`` on its diagonal when
    ``damped``: lines defining ``L{i}_{j}``, and the matrix's side."""
    names = [[f"j{r}_{c}" for c in range(n)] for r in range(m)]
    lines = [f"{', '.join(name for row in names for name in row)}, = jac"] if m and n else []
    side = min(m, n)

    def gram(i: int, j: int) -> str:
        if n <= m:
            return " + ".join(f"{names[r][i]}*{names[r][j]}" for r in range(m))
        return " + ".join(f"{names[i][c]}*{names[j][c]}" for c in range(n))

    for i in range(side):
        for j in range(i + 1):
            value = gram(i, j) + (" + lam" if damped and i == j else "")
            value += "".join(f" - L{i}_{t}*L{j}_{t}" for t in range(j))
            if i == j:
                lines.append(f"L{i}_{i} = _sqrt({value})")
            else:
                lines.append(f"L{i}_{j} = ({value}) / L{j}_{j}")
    return lines, side


def _generated(name: str, lines: list[str], arguments: str) -> Callable:
    source = f"def {name}({arguments}):\n" + "".join(f"    {line}\n" for line in lines)
    namespace: dict = {"_sqrt": math.sqrt}
    exec(compile(source, f"<dhsim {name}>", "exec"), namespace)
    return namespace[name]


@functools.lru_cache(maxsize=64)
def root_gram_det(m: int, n: int) -> Callable:
    """``f(jac) -> sqrt det`` of the smaller Gram matrix of a flat m×n ``jac``:
    the product of its singular values, 0.0 when it is singular."""
    lines, side = _gram_cholesky_lines(m, n, damped=False)
    guarded = []
    for line in lines:  # a pivot that is not positive: singular (or rounding of it)
        if line.startswith("L") and "_sqrt(" in line:
            head, value = line.split(" = _sqrt(", 1)
            guarded += [f"d = {value[:-1]}", "if d <= 0.0: return 0.0", f"{head} = _sqrt(d)"]
        else:
            guarded.append(line)
    guarded.append("return " + ("*".join(f"L{i}_{i}" for i in range(side)) or "1.0"))
    return _generated("root_gram_det", guarded, "jac")


@functools.lru_cache(maxsize=64)
def damped_solver(m: int, n: int) -> Callable:
    """``f(jac, e, lam) -> dx``: the damped least-squares step
    ``(JᵀJ + lam·I)⁻¹ Jᵀ e = Jᵀ (JJᵀ + lam·I)⁻¹ e`` for a flat m×n ``jac``, by a
    Cholesky factorisation of the smaller of the two, written out in full (no
    numpy call: at this size its per-call overhead is most of the cost). Raises
    ValueError or ZeroDivisionError when the matrix is not positive definite."""
    lines, side = _gram_cholesky_lines(m, n, damped=True)
    arguments = "jac, e, lam"
    if not side:  # no row to solve for (or no joint): no step
        return _generated("damped_solver", [f"return {[0.0] * n!r}"], arguments)
    lines.append(f"{', '.join(f'e{r}' for r in range(m))}, = e")
    if n <= m:  # right-hand side Jᵀe
        rhs = [" + ".join(f"j{r}_{c}*e{r}" for r in range(m)) for c in range(n)]
    else:
        rhs = [f"e{r}" for r in range(m)]
    for i in range(side):  # L z = rhs
        value = f"({rhs[i]})" + "".join(f" - L{i}_{t}*z{t}" for t in range(i))
        lines.append(f"z{i} = ({value}) / L{i}_{i}")
    for i in reversed(range(side)):  # Lᵀ y = z
        value = f"z{i}" + "".join(f" - L{t}_{i}*y{t}" for t in range(i + 1, side))
        lines.append(f"y{i} = ({value}) / L{i}_{i}")
    if n <= m:
        lines.append(f"return [{', '.join(f'y{c}' for c in range(n))}]")
    else:  # dx = Jᵀ y
        back = [" + ".join(f"j{r}_{c}*y{r}" for r in range(m)) for c in range(n)]
        lines.append(f"return [{', '.join(back)}]")
    return _generated("damped_solver", lines, arguments)


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

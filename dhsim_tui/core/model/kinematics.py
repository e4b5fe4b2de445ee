"""Forward kinematics for standard and modified D-H chains (reference §1).

A chain is a product of 4×4 transforms, but most of their entries are
constants: alpha is fixed, and 0° or ±90° more often than not. So
:class:`Kinematics` writes, once per robot, a straight-line Python function
with those constants folded in and no loop or numpy call; it computes one
pose in a few microseconds, about four times faster than a loop of 4×4
products. Rotations are carried as their three columns (x, y, z axes), so a
rotation about z touches only x and y, and one about x only y and z.
A vectorised version of the same recurrence does many joint vectors at once.
The tests check both against the plain matrix product of the reference.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.orientation import (
    base_transform,
    cos_sin,
    oat_from_matrix,
    rpy_from_matrix,
    rpy_matrix,
)

if TYPE_CHECKING:
    from dhsim_tui.core.model.robot import Robot

_DEG = math.pi / 180.0
#: batch FK works on slices this long so its arrays stay in the CPU cache
_CHUNK = 16384
_AXES = ("x", "y", "z")


@dataclass(frozen=True)
class EndEffector:
    """What the pose panel and ``dhsim fk`` show: world XYZ, OAT and RPY."""

    matrix: np.ndarray
    xyz: tuple[float, float, float]
    oat: tuple[float, float, float]
    rpy: tuple[float, float, float]


def read_out(matrix: np.ndarray) -> EndEffector:
    """XYZ, OAT and RPY of a world transform."""
    r = matrix[:3, :3]
    xyz = (float(matrix[0, 3]), float(matrix[1, 3]), float(matrix[2, 3]))
    return EndEffector(matrix, xyz, oat_from_matrix(r), rpy_from_matrix(r))


def _rotate(first: str, second: str, c: str, s: str) -> str:
    """Columns (u, v) -> (c·u + s·v, c·v - s·u): a rotation about the third axis."""
    new_u = ", ".join(f"{c}*{first}{k} + {s}*{second}{k}" for k in range(3))
    new_v = ", ".join(f"{c}*{second}{k} - {s}*{first}{k}" for k in range(3))
    names = (
        ", ".join(f"{first}{k}" for k in range(3))
        + ", "
        + ", ".join(f"{second}{k}" for k in range(3))
    )
    return f"{names} = {new_u}, {new_v}"


def _rotate_const(first: str, second: str, deg: float) -> list[str]:
    c, s = cos_sin(deg)
    if (c, s) == (1.0, 0.0):
        return []
    if c == 0.0:  # ±90°: a swap with a sign
        names = [f"{first}{k}" for k in range(3)] + [f"{second}{k}" for k in range(3)]
        pos = "" if s > 0 else "-"
        neg = "-" if s > 0 else ""
        values = [f"{pos}{second}{k}" for k in range(3)] + [f"{neg}{first}{k}" for k in range(3)]
        return [f"{', '.join(names)} = {', '.join(values)}"]
    return [_rotate(first, second, repr(c), repr(s))]


def _translate(axis: str, amount: str) -> list[str]:
    if amount in ("0.0", "-0.0"):
        return []
    return [f"p{k} += {amount}*{axis}{k}" for k in range(3)]


def _joint_lines(robot: Robot, index: int, q: str = "") -> list[str]:
    """Joint ``index``'s transform as lines on the state; its variable is ``q``."""
    joint = robot.joints[index]
    q = q or f"q{index}"
    if joint.offset:  # the D-H variable is the joint value plus the offset
        q = f"({q} + {float(joint.offset)!r})"
    if joint.is_revolute:
        rot_z = [f"c = _cos({q}*{_DEG!r}); s = _sin({q}*{_DEG!r})", _rotate("x", "y", "c", "s")]
        move_d = _translate("z", repr(float(joint.d)))
    else:
        rot_z = _rotate_const("x", "y", joint.theta)
        move_d = _translate("z", q)
    move_a = _translate("x", repr(float(joint.a)))
    rot_x = _rotate_const("y", "z", joint.alpha)
    if robot.convention == "standard":  # Rz(theta) Tz(d) Tx(a) Rx(alpha)
        return rot_z + move_d + move_a + rot_x
    return rot_x + move_a + rot_z + move_d  # Rx(alpha) Tx(a) Rz(theta) Tz(d)


def _constant_lines(matrix: np.ndarray) -> list[str]:
    """Post-multiply by a constant transform (the tool)."""
    r, t = matrix[:3, :3].tolist(), matrix[:3, 3].tolist()
    lines = [
        f"p{k} += " + " + ".join(f"{t[j]!r}*{_AXES[j]}{k}" for j in range(3)) for k in range(3)
    ]
    cols = []
    for col in range(3):
        for k in range(3):
            cols.append(" + ".join(f"{r[j][col]!r}*{_AXES[j]}{k}" for j in range(3)))
    names = ", ".join(f"{a}{k}" for a in _AXES for k in range(3))
    return [*lines, f"{names} = {', '.join(cols)}"]


def robot_base(robot: Robot) -> np.ndarray:
    """Frame 0 in world coordinates (4×4)."""
    return base_transform(robot.base_z, robot.base_x, robot.base_xyz, robot.base_rpy)


def _start(robot: Robot) -> tuple[float, ...]:
    """The chain's starting state: frame 0's axes (columns) then its origin."""
    base = robot_base(robot)
    return (*(float(v) for v in base[:3, :3].T.reshape(-1)), *(float(v) for v in base[:3, 3]))


_STATE = "(x0, x1, x2, y0, y1, y2, z0, z1, z2, p0, p1, p2)"
#: the same state as the rows of a 4×4 homogeneous transform
_MATRIX = "(x0, y0, z0, p0, x1, y1, z1, p1, x2, y2, z2, p2, 0.0, 0.0, 0.0, 1.0)"


def _compile(robot: Robot, tool: np.ndarray | None, record: bool) -> Callable:
    """Write and compile ``f(q)`` for this robot; ``record`` returns every frame."""
    start = [repr(float(v)) for v in _start(robot)]
    body = [f"{_STATE[1:-1]} = {', '.join(start)}"]
    qs = ", ".join(f"q{i}" for i in range(robot.dof))
    body.append(f"{qs}, = q")
    if record:
        body.append(f"out = list({_MATRIX})")
    for i in range(robot.dof):
        body += _joint_lines(robot, i)
        if record:
            body.append(f"out += {_MATRIX}")
    if tool is not None:
        body += _constant_lines(tool)
    body.append(f"out += {_MATRIX}" if record else f"return {_STATE}")
    if record:
        body.append("return out")
    source = "def chain(q):\n" + "\n".join(f"    {line}" for line in body) + "\n"
    namespace: dict = {"_cos": math.cos, "_sin": math.sin}
    exec(compile(source, f"<dhsim chain: {robot.name}>", "exec"), namespace)
    return namespace["chain"]


#: a chain is compiled whole after this many calls; until then it runs as a
#: sequence of per-joint steps (cached by their text), so an edit in the editor
#: costs one small compile instead of a whole chain's (~10 ms for 32 joints)
COMPILE_AFTER = 32


@functools.lru_cache(maxsize=512)
def _step(lines: tuple[str, ...]) -> Callable:
    """``step(state, qi) -> state``: the chain's lines for one joint (or the
    tool), the same operations in the same order, so the same bits."""
    body = "".join(f"    {line}\n" for line in lines)
    source = f"def step(state, qi):\n    {_STATE[1:-1]} = state\n{body}    return {_STATE}\n"
    namespace: dict = {"_cos": math.cos, "_sin": math.sin}
    exec(compile(source, "<dhsim joint>", "exec"), namespace)
    return namespace["step"]


def _matrix(s: tuple[float, ...]) -> list[float]:
    """The state's 4×4 rows, flat (as ``_MATRIX``)."""
    return [
        s[0],
        s[3],
        s[6],
        s[9],
        s[1],
        s[4],
        s[7],
        s[10],
        s[2],
        s[5],
        s[8],
        s[11],
        0.0,
        0.0,
        0.0,
        1.0,
    ]


def _stepwise(robot: Robot, tool: np.ndarray | None, record: bool) -> Callable:
    """The chain of :func:`_compile` as a loop over cached per-joint steps."""
    start = _start(robot)
    steps = [_step(tuple(_joint_lines(robot, i, "qi"))) for i in range(robot.dof)]
    if tool is not None:
        steps.append(_step(tuple(_constant_lines(tool))))
    dof = robot.dof

    def chain(q):
        values = tuple(q)
        if len(values) != dof:
            raise ValueError(f"got {len(values)}")
        state = start
        out = _matrix(state) if record else None
        for step, value in zip(steps, values + (None,) * (len(steps) - dof), strict=True):
            state = step(state, value)
            if record:
                out += _matrix(state)
        if not record:
            return state
        if tool is None:
            out += _matrix(state)  # the tool frame is the last joint's
        return out

    return chain


class Kinematics:
    """Forward kinematics of one robot. Joint values are in the robot's units:
    degrees for revolute joints, the length unit for prismatic ones.

    Limits are not checked here (use :meth:`Robot.check_q`), so a study may
    look at any configuration.
    """

    def __init__(self, robot: Robot) -> None:
        self.robot = robot
        self.dof = robot.dof
        self.base = robot_base(robot)
        self.tool = np.eye(4)
        self.tool[:3, :3] = rpy_matrix(*robot.tool.rpy)
        self.tool[:3, 3] = robot.tool.xyz
        self._tool = None if robot.tool.is_identity else self.tool
        # [pose chain, frames chain] and how often each ran
        self._chains = [_stepwise(robot, self._tool, False), _stepwise(robot, self._tool, True)]
        self._calls = [0, 0]

    def _call(self, record: bool, q: Sequence[float]):
        calls = self._calls[record] = self._calls[record] + 1
        if calls == COMPILE_AFTER:  # in use: worth the whole compile
            self._chains[record] = _compile(self.robot, self._tool, record)
        try:
            return self._chains[record](q)
        except (ValueError, TypeError) as exc:
            raise DhsimError(
                f"expected {self.dof} joint values for {self.robot.name!r}: {exc}"
            ) from None

    def state(self, q: Sequence[float]) -> tuple[float, ...]:
        """The end effector as 12 floats (x, y, z axes then origin): the fast path."""
        return self._call(False, q)

    def state_function(self) -> Callable[[Sequence[float]], tuple[float, ...]]:
        """:meth:`state` as the compiled function itself (compiled now if it
        was not yet), for a loop over many joint vectors: no call count and
        no wrapping of errors (a wrong count of values raises ValueError)."""
        if self._calls[False] < COMPILE_AFTER:
            self._calls[False] = COMPILE_AFTER
            self._chains[False] = _compile(self.robot, self._tool, False)
        return self._chains[False]

    def position(self, q: Sequence[float]) -> tuple[float, float, float]:
        """The end effector's world XYZ."""
        s = self._call(False, q)
        return (s[9], s[10], s[11])

    def pose(self, q: Sequence[float]) -> np.ndarray:
        """The end effector's 4×4 world transform ``B · T1 ··· Tn · Tool``."""
        x0, x1, x2, y0, y1, y2, z0, z1, z2, p0, p1, p2 = self._call(False, q)
        return np.array(
            ((x0, y0, z0, p0), (x1, y1, z1, p1), (x2, y2, z2, p2), (0.0, 0.0, 0.0, 1.0))
        )

    def frames(self, q: Sequence[float]) -> np.ndarray:
        """World transforms of frames 0..n and the tool: shape (n + 2, 4, 4)."""
        flat = self._call(True, q)
        return np.fromiter(flat, float, len(flat)).reshape(-1, 4, 4)

    def end_effector(self, q: Sequence[float]) -> EndEffector:
        return read_out(self.pose(q))

    def batch(self, qs: np.ndarray) -> np.ndarray:
        """End-effector transforms for many joint vectors: (N, n) -> (N, 4, 4).

        The same recurrence as :meth:`pose`, on (3, N) arrays updated in place
        (numpy's float64 sin and cos are the slow part, so each angle costs a
        single tan, see :func:`_batch_cos_sin`).
        """
        qs = np.asarray(qs, dtype=float)
        if qs.ndim != 2 or qs.shape[1] != self.dof:
            raise DhsimError(f"expected an array of shape (N, {self.dof}), got {qs.shape}")
        count = qs.shape[0]
        out = np.zeros((4, 4, count))  # transposed result: out[row, col, sample]
        out[3, 3] = 1.0
        for start in range(0, count, _CHUNK):
            self._batch_chunk(qs[start : start + _CHUNK], out[:, :, start : start + _CHUNK])
        result = out.transpose(2, 0, 1)
        return result if self.robot.tool.is_identity else result @ self.tool

    def _batch_chunk(self, qs: np.ndarray, out: np.ndarray) -> None:
        count = qs.shape[0]
        axes = [np.repeat(self.base[:3, k : k + 1], count, axis=1) for k in range(3)]
        p = out[:3, 3]
        p[...] = self.base[:3, 3:4]
        scratch = np.empty((3, count))
        standard = self.robot.convention == "standard"
        for i, joint in enumerate(self.robot.joints):
            variable = qs[:, i] + joint.offset if joint.offset else qs[:, i]
            if joint.is_revolute:
                rot_z, d = _batch_cos_sin(variable * _DEG), joint.d
            else:
                rot_z, d = cos_sin(joint.theta), variable
            if not standard:
                _batch_rotate(axes, 1, 2, cos_sin(joint.alpha), scratch)
                _batch_translate(p, axes[0], joint.a, scratch)
            _batch_rotate(axes, 0, 1, rot_z, scratch)
            _batch_translate(p, axes[2], d, scratch)
            if standard:
                _batch_translate(p, axes[0], joint.a, scratch)
                _batch_rotate(axes, 1, 2, cos_sin(joint.alpha), scratch)
        for k in range(3):
            out[:3, k] = axes[k]


def _batch_cos_sin(rad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin from one tan of the half angle (to a few ulp; 2-3× faster)."""
    t = np.tan(rad * 0.5)
    t2 = t * t
    inv = 1.0 / (1.0 + t2)
    np.multiply(t, 2.0, out=t)
    t *= inv
    np.subtract(1.0, t2, out=t2)
    t2 *= inv
    return (t2, t)


def _batch_rotate(axes: list[np.ndarray], u: int, v: int, cs: tuple, scratch: np.ndarray) -> None:
    """(axes[u], axes[v]) <- (c·u + s·v, c·v - s·u), in place; 0/±1 cost no products."""
    c, s = cs
    first, second = axes[u], axes[v]
    if isinstance(c, float):
        if (c, s) == (1.0, 0.0):
            return
        if c == 0.0:  # ±90°: swap, negating one
            np.negative(first if s > 0 else second, out=first if s > 0 else second)
            axes[u], axes[v] = second, first
            return
    np.multiply(first, c, out=scratch)
    scratch += np.multiply(second, s)
    second *= c
    first *= s
    second -= first
    first[...] = scratch


def _batch_translate(
    p: np.ndarray, axis: np.ndarray, amount: float | np.ndarray, scratch: np.ndarray
) -> None:
    if isinstance(amount, float) and amount == 0.0:
        return
    np.multiply(axis, amount, out=scratch)
    p += scratch

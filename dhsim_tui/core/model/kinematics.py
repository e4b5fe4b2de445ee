"""Forward kinematics for standard and modified D-H chains (kinematics
reference section 1, the D-H conventions).

A chain is a product of 4×4 transforms, but most of their entries are
constants: alpha is fixed, and 0° or ±90° more often than not. So
:class:`Kinematics` writes, once per robot, a straight-line Python function
with those constants folded in and no loop or numpy call; it computes one
pose in a couple of microseconds, several times faster than a loop of 4×4
products. Rotations are carried as their three columns (x, y, z axes), so a
rotation about z touches only x and y, and one about x only y and z.
The function is written on named values, each entry computed once by the
same floating-point operations as a run of the chain's lines below, so the
same bits (:mod:`dhsim_tui.core.model.kinematics_codegen`); it packs the
pose and the frames straight into a numpy array, the caller's when given
(``out=``). A vectorised version of the same recurrence does many joint
vectors at once (:mod:`dhsim_tui.core.model.kinematics_batch`).
The tests check them all against the plain matrix product of the reference.
"""

from __future__ import annotations

import functools
import math
import operator
import weakref
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.kinematics_batch import BatchKinematics, check_out
from dhsim_tui.core.model.kinematics_codegen import NAMES, ROWS, chain_function, packer
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


# -- the chain as lines of code on the state x0..z2 p0..p2 (the per-joint steps
# below and the Jacobian's code in analysis/jacobian_codegen.py) -----------------


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


def joint_transform_lines(robot: Robot, index: int, q: str = "") -> list[str]:
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


def constant_transform_lines(matrix: np.ndarray) -> list[str]:
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


def start_state(robot: Robot) -> tuple[float, ...]:
    """The chain's starting state: frame 0's axes (columns) then its origin."""
    base = robot_base(robot)
    return (*(float(v) for v in base[:3, :3].T.reshape(-1)), *(float(v) for v in base[:3, 3]))


_STATE = f"({', '.join(NAMES)})"


def _compile(robot: Robot, tool: np.ndarray | None, record: bool) -> Callable:
    """The chain compiled whole (see :mod:`~dhsim_tui.core.model.kinematics_codegen`)."""
    return chain_function(robot, tool, start_state(robot), record)


#: a chain is compiled whole after this many calls; until then it runs as a
#: sequence of per-joint steps (cached by their text), so an edit in the editor
#: costs one small compile instead of a whole chain's (~10 ms for 32 joints)
COMPILE_AFTER = 32


@functools.lru_cache(maxsize=512)
def compile_step(lines: tuple[str, ...]) -> Callable:
    """``step(state, qi) -> state``: the chain's lines for one joint (or the
    tool), the same operations in the same order, so the same bits."""
    body = "".join(f"    {line}\n" for line in lines)
    source = f"def step(state, qi):\n    {_STATE[1:-1]} = state\n{body}    return {_STATE}\n"
    namespace: dict = {"_cos": math.cos, "_sin": math.sin}
    exec(compile(source, "<dhsim joint>", "exec"), namespace)
    return namespace["step"]


_ROW_ITEMS = operator.itemgetter(*(NAMES.index(name) for name in ROWS))


def _matrix(state: tuple[float, ...]) -> list[float]:
    """The state's 4×4 rows, flat."""
    return [*_ROW_ITEMS(state), 0.0, 0.0, 0.0, 1.0]


def _stepwise(robot: Robot, tool: np.ndarray | None, record: bool) -> Callable:
    """The chain of :func:`_compile` as a loop over cached per-joint steps."""
    start = start_state(robot)
    steps = [compile_step(tuple(joint_transform_lines(robot, i, "qi"))) for i in range(robot.dof)]
    if tool is not None:
        steps.append(compile_step(tuple(constant_transform_lines(tool))))
    dof = robot.dof
    pack = packer(16 * (dof + 2) if record else 16)

    def chain(q, o=None):
        values = tuple(q)
        if len(values) != dof:
            raise ValueError(f"got {len(values)}")
        state = start
        out = _matrix(state) if record else None
        for step, value in zip(steps, values + (None,) * (len(steps) - dof), strict=True):
            state = step(state, value)
            if record:
                out += _matrix(state)
        if record and tool is None:
            out += _matrix(state)  # the tool frame is the last joint's
        if o is not None:
            pack(o, 0, *(out if record else _matrix(state)))
            return None
        return out if record else state

    return chain


_ndarray = np.ndarray
_empty = np.empty
_F64 = np.dtype(np.float64)
_POSE = (4, 4)


def as_floats(q: np.ndarray) -> Sequence[float]:
    """A float64 vector as a list (numpy scalars are slow in Python arithmetic)."""
    return q.tolist() if q.ndim == 1 and q.dtype == _F64 else q


class Kinematics:
    """Forward kinematics of one robot. Joint values are in the robot's units:
    degrees for revolute joints, the length unit for prismatic ones.

    Limits are not checked here (use :meth:`Robot.check_q`), so a study may
    look at any configuration. ``out=`` takes a float64 array of the result's
    shape to fill and return, instead of a new one.
    """

    def __init__(self, robot: Robot) -> None:
        self.robot = robot
        self.dof = robot.dof
        self.base = robot_base(robot)
        self.tool = np.eye(4)
        self.tool[:3, :3] = rpy_matrix(*robot.tool.rpy)
        self.tool[:3, 3] = robot.tool.xyz
        self._tool = None if robot.tool.is_identity else self.tool
        self._frames_shape = (robot.dof + 2, 4, 4)
        # chain(q, o=None) of the end effector and of every frame: stepwise
        # (counting calls) until compiled
        self._pose_chain = self._warming(False)
        self._frames_chain = self._warming(True)
        self._batch = BatchKinematics(robot, self.base, self._tool)

    def _warming(self, record: bool) -> Callable:
        """The stepwise chain, which compiles the whole one on its
        :data:`COMPILE_AFTER`-th call and puts it in its own place."""
        stepwise = _stepwise(self.robot, self._tool, record)
        robot, tool, owner = self.robot, self._tool, weakref.ref(self)
        calls = 0

        def chain(q, o=None):
            nonlocal calls
            calls += 1
            if calls < COMPILE_AFTER:
                return stepwise(q, o)
            compiled = _compile(robot, tool, record)
            kinematics = owner()
            if kinematics is not None:  # in use: worth the whole compile
                setattr(kinematics, "_frames_chain" if record else "_pose_chain", compiled)
            return compiled(q, o)

        chain.warming = True
        return chain

    def _bad_q(self, exc: Exception) -> DhsimError:
        return DhsimError(f"expected {self.dof} joint values for {self.robot.name!r}: {exc}")

    def _refill(self, exc: Exception, method: Callable, q, out: np.ndarray) -> np.ndarray:
        """After packing into ``out`` failed: an ``out`` that is not C-contiguous
        gets a new array's values; else the joint values were wrong."""
        if not out.flags.writeable:
            raise DhsimError("out must be a writable array") from None
        if out.flags.c_contiguous:
            raise self._bad_q(exc) from None
        out[...] = method(q)
        return out

    def state(self, q: Sequence[float]) -> tuple[float, ...]:
        """The end effector as 12 floats (x, y, z axes then origin): the fast path."""
        if q.__class__ is _ndarray:
            q = as_floats(q)
        try:
            return self._pose_chain(q)
        except (ValueError, TypeError) as exc:
            raise self._bad_q(exc) from None

    def state_function(self) -> Callable[[Sequence[float]], tuple[float, ...]]:
        """:meth:`state` as the compiled function itself (compiled now if it
        was not yet), for a loop over many joint vectors: no call count and
        no wrapping of errors (a wrong count of values raises ValueError)."""
        if getattr(self._pose_chain, "warming", False):
            self._pose_chain = _compile(self.robot, self._tool, False)
        return self._pose_chain

    def position(self, q: Sequence[float]) -> tuple[float, float, float]:
        """The end effector's world XYZ."""
        if q.__class__ is _ndarray:
            q = as_floats(q)
        try:
            s = self._pose_chain(q)
        except (ValueError, TypeError) as exc:
            raise self._bad_q(exc) from None
        return (s[9], s[10], s[11])

    def pose(self, q: Sequence[float], out: np.ndarray | None = None) -> np.ndarray:
        """The end effector's 4×4 world transform ``B · T1 ··· Tn · Tool``."""
        if q.__class__ is _ndarray:
            q = as_floats(q)
        if out is None:
            out = _empty(_POSE)
        elif out.__class__ is not _ndarray or out.shape != _POSE or out.dtype is not _F64:
            check_out(out, _POSE)
        try:
            self._pose_chain(q, out)
        except (ValueError, TypeError) as exc:
            return self._refill(exc, self.pose, q, out)
        return out

    def frames(self, q: Sequence[float], out: np.ndarray | None = None) -> np.ndarray:
        """World transforms of frames 0..n and the tool: shape (n + 2, 4, 4)."""
        if q.__class__ is _ndarray:
            q = as_floats(q)
        shape = self._frames_shape
        if out is None:
            out = _empty(shape)
        elif out.__class__ is not _ndarray or out.shape != shape or out.dtype is not _F64:
            check_out(out, shape)
        try:
            self._frames_chain(q, out)
        except (ValueError, TypeError) as exc:
            return self._refill(exc, self.frames, q, out)
        return out

    def end_effector(self, q: Sequence[float]) -> EndEffector:
        return read_out(self.pose(q))

    def batch(self, qs: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """End-effector transforms for many joint vectors: (N, n) -> (N, 4, 4).
        ``out``: any float64 (N, 4, 4) array; for a robot without a tool the
        transpose of a (4, 4, N) one, like the new result, is filled fastest.
        See :mod:`~dhsim_tui.core.model.kinematics_batch`."""
        return self._batch(qs, out)

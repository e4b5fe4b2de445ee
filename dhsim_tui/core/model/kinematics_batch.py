"""Forward kinematics of many joint vectors at once (``Kinematics.batch``).

The recurrence of :mod:`dhsim_tui.core.model.kinematics` on (3, k) arrays, one
chunk of k joint vectors at a time so they stay in the CPU cache: the chain's
frame is carried as three axes and an origin, updated in place; numpy's
float64 sin and cos are the slow part, so each angle costs a single tan
(:func:`_cos_sin`). The arrays a chunk needs are allocated once and kept
(:class:`BatchKinematics` lives on the robot's ``Kinematics``), so a call
allocates only its result, or nothing when given ``out=``. The same
operations in the same order as before they were kept, so the same bits.
"""

from __future__ import annotations

import math
import threading

import numpy as np

from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.orientation import cos_sin

_DEG = math.pi / 180.0
#: joint vectors per chunk, so its arrays stay in the CPU cache (kept: about
#: 2.9 MB, 5 MB with a tool)
CHUNK = 16384
#: rows padded by this many values, so no two start a power of two bytes apart
#: (which would map the 16 values of one transform to one set of the cache)
_PAD = 8
_LAST_ROW = np.array([0.0, 0.0, 0.0, 1.0])


class _Scratch:
    """A chunk's arrays for up to ``size`` joint vectors: six (3, k) arrays
    (three axes, the origin, two spare), four (k,) ones for the angles and,
    when the result is not filled directly (a tool), a (4, 4, k) stage."""

    __slots__ = ("pool", "size", "stage", "trig", "views")

    def __init__(self, size: int) -> None:
        self.size = size
        self.pool = np.empty((6, 3 * size + _PAD))
        self.trig = np.empty((4, size + _PAD))
        self.stage: np.ndarray | None = None
        self.views: dict[tuple, tuple] = {}

    def arrays(self, k: int, strided: bool, staged: bool) -> tuple[list, list, np.ndarray | None]:
        """Views for a chunk of ``k`` vectors. The stage is (4, 4, k): from a
        (4, 4, size) array when the batch runs over several chunks (so its
        (k, 4, 4) transpose is strided like the result's always was, and
        ``@ tool`` takes the same loop), else from a (4, 4, k) one (padded
        but for one vector, for the same reason)."""
        key = (k, strided, staged)
        views = self.views.get(key)
        if views is None:
            if len(self.views) > 8:
                self.views.clear()
            stage = None
            if staged:
                if self.stage is None:
                    self.stage = np.empty(16 * (self.size + _PAD))
                row = self.size + _PAD if strided else k + (_PAD if k > 1 else 0)
                stage = self.stage[: 16 * row].reshape(4, 4, row)[:, :, :k]
            pool = [line[: 3 * k].reshape(3, k) for line in self.pool]
            views = self.views[key] = (pool, [line[:k] for line in self.trig], stage)
        return views


class BatchKinematics:
    """Batch FK of one robot, reusing its chunk arrays from call to call (a
    second thread asking meanwhile gets arrays of its own)."""

    def __init__(self, robot, base: np.ndarray, tool: np.ndarray | None) -> None:
        self.robot = robot
        self.base = base
        self.tool = tool
        self._scratch: _Scratch | None = None
        self._lock = threading.Lock()

    def __call__(self, qs, out: np.ndarray | None = None) -> np.ndarray:
        dof = self.robot.dof
        qs = np.asarray(qs, dtype=float)
        if qs.ndim != 2 or qs.shape[1] != dof:
            raise DhsimError(f"expected an array of shape (N, {dof}), got {qs.shape}")
        count = qs.shape[0]
        if out is not None:
            check_out(out, (count, 4, 4))
            if np.may_share_memory(out, qs):
                raise DhsimError("out must not share memory with the joint values")
            result = out
        elif self.tool is None:  # the transposed (4, 4, N) array, as it always was
            result = np.empty((4, 4, count)).transpose(2, 0, 1)
        else:
            result = np.empty((count, 4, 4))
        if count == 0:
            return result
        size = min(count, CHUNK)
        if self._lock.acquire(blocking=False):
            try:
                scratch = self._scratch
                if scratch is None or scratch.size < size:
                    scratch = self._scratch = _Scratch(size)
                self._run(qs, result, scratch)
            finally:
                self._lock.release()
        else:  # in use by another thread
            self._run(qs, result, _Scratch(size))
        return result

    def _run(self, qs: np.ndarray, result: np.ndarray, scratch: _Scratch) -> None:
        count = qs.shape[0]
        strided = count > CHUNK
        # without a tool, straight into a result laid out (4, 4, N) like the
        # new one (so its rows are the chunk's), else first into the stage
        direct = self.tool is None and result.strides[0] == result.itemsize
        for start in range(0, count, CHUNK):
            chunk = qs[start : start + CHUNK]
            pool, trig, stage = scratch.arrays(chunk.shape[0], strided, not direct)
            axes, origin = self._chunk(chunk, list(pool), trig)
            into = result[start : start + CHUNK]
            frame = into.transpose(1, 2, 0) if direct else stage
            for k in range(3):
                frame[:3, k] = axes[k]
            frame[:3, 3] = origin
            frame[3] = _LAST_ROW[:, None]
            if self.tool is not None:
                np.matmul(stage.transpose(2, 0, 1), self.tool, out=into)
            elif frame is stage:
                into[...] = stage.transpose(2, 0, 1)

    def _chunk(self, qs: np.ndarray, pool: list, trig: list) -> tuple[list, np.ndarray]:
        """The chain on one chunk: its three axes and origin, each (3, k)."""
        axes, origin, spare = pool[:3], pool[3], pool[4:]
        for k in range(3):
            axes[k][...] = self.base[:3, k : k + 1]
        origin[...] = self.base[:3, 3:4]
        standard = self.robot.convention == "standard"
        for i, joint in enumerate(self.robot.joints):
            variable = qs[:, i]
            if joint.offset:
                variable = np.add(variable, joint.offset, trig[0])
            if joint.is_revolute:
                rot_z, d = _cos_sin(variable, trig), joint.d
            else:
                rot_z, d = cos_sin(joint.theta), variable
            if not standard:
                _rotate(axes, 1, 2, cos_sin(joint.alpha), spare)
                _translate(origin, axes[0], joint.a, spare[0])
            _rotate(axes, 0, 1, rot_z, spare)
            _translate(origin, axes[2], d, spare[0])
            if standard:
                _translate(origin, axes[0], joint.a, spare[0])
                _rotate(axes, 1, 2, cos_sin(joint.alpha), spare)
        return axes, origin


def check_out(out: object, shape: tuple[int, ...]) -> None:
    """A DhsimError unless ``out`` is a writable float64 array of ``shape``."""
    if not isinstance(out, np.ndarray):
        raise DhsimError(f"out must be a float64 array of shape {shape}, got {type(out).__name__}")
    if out.shape != shape or out.dtype != np.float64:
        raise DhsimError(
            f"out must be a float64 array of shape {shape}, got {out.dtype} {out.shape}"
        )
    if not out.flags.writeable:
        raise DhsimError("out must be a writable array")


def _cos_sin(variable: np.ndarray, trig: list) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin of ``variable`` degrees from one tan of the half angle (to a
    few ulp; 2-3× faster than numpy's), in ``trig``'s arrays."""
    rad, t, t2, inv = trig
    np.multiply(variable, _DEG, rad)
    np.multiply(rad, 0.5, rad)
    np.tan(rad, t)
    np.multiply(t, t, t2)
    np.add(t2, 1.0, inv)
    np.divide(1.0, inv, inv)
    t *= 2.0
    t *= inv
    np.subtract(1.0, t2, t2)
    t2 *= inv
    return (t2, t)


def _rotate(axes: list, u: int, v: int, cs: tuple, spare: list) -> None:
    """(axes[u], axes[v]) <- (c·u + s·v, c·v - s·u); 0/±1 cost no products.
    The new u goes to a spare array and the old one becomes the spare."""
    c, s = cs
    first, second = axes[u], axes[v]
    if isinstance(c, float):
        if (c, s) == (1.0, 0.0):
            return
        if c == 0.0:  # ±90°: swap, negating one
            negative = first if s > 0 else second
            np.negative(negative, negative)
            axes[u], axes[v] = second, first
            return
    new, product = spare
    np.multiply(first, c, new)
    np.multiply(second, s, product)
    new += product
    second *= c
    np.multiply(first, s, product)
    second -= product
    axes[u], spare[0] = new, first


def _translate(origin: np.ndarray, axis: np.ndarray, amount, product: np.ndarray) -> None:
    if isinstance(amount, float) and amount == 0.0:
        return
    np.multiply(axis, amount, product)
    origin += product

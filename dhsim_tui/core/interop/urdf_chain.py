"""The serial chain a URDF gives (:class:`UrdfChain` of :class:`UrdfJoint`):
the URDF's own kinematics, a fixed transform and a motion per joint, with
its forward kinematics and its joints' axis lines at zero; and the URDF's
roll, pitch, yaw rotation (:func:`rpy_matrix`).
:func:`dhsim_tui.core.interop.urdf.read_chain` reads one from a file.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.model.errors import DhsimError


def frozen_matrix(values: np.ndarray) -> np.ndarray:
    """``values`` as a read-only float array."""
    array = np.array(values, dtype=float)
    array.setflags(write=False)
    return array


@dataclass(frozen=True, eq=False)
class UrdfJoint:
    """One joint on the chain, as the URDF gives it.

    ``origin`` (4×4) places the joint frame in the parent link's frame;
    ``axis`` is a unit vector in the joint frame. ``kind`` is ``"revolute"``
    (``continuous`` tells a continuous joint), ``"prismatic"`` or
    ``"fixed"``; ``lower``/``upper`` are radians or metres (0 for a fixed
    joint). The arrays are read-only.
    """

    name: str
    kind: str
    origin: np.ndarray
    axis: np.ndarray
    lower: float
    upper: float
    continuous: bool = False

    @property
    def moves(self) -> bool:
        return self.kind != "fixed"

    def motion(self, q: float) -> np.ndarray:
        """The joint's motion (4×4) in its own frame at value ``q``."""
        m = np.eye(4)
        if self.kind == "revolute":
            m[:3, :3] = _rotation(self.axis, q)
        elif self.kind == "prismatic":
            m[:3, 3] = q * self.axis
        return m

    def transform(self, q: float) -> np.ndarray:
        """Child link in parent link: ``origin @ motion(q)``."""
        return self.origin @ self.motion(q)


@dataclass(frozen=True, eq=False)
class UrdfChain:
    """The joints from link ``base`` to link ``tip``, in order, fixed ones included."""

    base: str
    tip: str
    joints: tuple[UrdfJoint, ...]
    name: str = ""  # the <robot name="..."> attribute
    #: the text of the file's first
    #: :data:`~dhsim_tui.core.interop.urdf_xml.DHSIM_COMMENT` comment, or None
    stored: str | None = None

    @property
    def moving(self) -> tuple[UrdfJoint, ...]:
        """The joints that move (revolute, continuous, prismatic), in order."""
        return tuple(j for j in self.joints if j.moves)

    def _values(self, q: object) -> np.ndarray:
        values = np.asarray(q, dtype=float).reshape(-1)
        if not np.all(np.isfinite(values)):
            raise DhsimError("joint values must be finite numbers")
        count = len(self.moving)
        if values.shape != (count,):
            raise DhsimError(
                f"expected {count} joint values, one per moving joint, got {values.size}"
            )
        return values

    def fk(self, q: object) -> np.ndarray:
        """The tip link's pose (4×4) in the base link's frame; ``q`` holds one
        value per moving joint, radians or metres. Limits are not checked."""
        values = iter(self._values(q))
        pose = np.eye(4)
        for joint in self.joints:
            pose = pose @ joint.transform(next(values) if joint.moves else 0.0)
        return pose

    def tip_home(self) -> np.ndarray:
        """The tip's pose with every joint at zero."""
        return self.fk(np.zeros(len(self.moving)))

    def joint_lines(self) -> list[tuple[str, np.ndarray, np.ndarray]]:
        """For each moving joint, ``(kind, point, direction)`` of its axis line
        in the base frame with every joint at zero: the point is the joint
        frame's origin, the direction a unit vector."""
        lines = []
        pose = np.eye(4)
        for joint in self.joints:
            frame = pose @ joint.origin
            if joint.moves:
                lines.append((joint.kind, frame[:3, 3].copy(), frame[:3, :3] @ joint.axis))
            pose = frame  # the motion is the identity at zero
        return lines


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotation by ``angle`` about the unit vector ``axis`` (Rodrigues)."""
    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return c * np.eye(3) + s * k + (1 - c) * np.outer(axis, axis)


def rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """``Rz(yaw) @ Ry(pitch) @ Rx(roll)``: the URDF's fixed-axis roll, pitch, yaw."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )

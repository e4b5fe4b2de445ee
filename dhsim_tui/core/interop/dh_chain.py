"""The D-H chains :func:`dhsim_tui.core.interop.dh_extract.extract` returns:
:class:`DHRow` and :class:`DHChain` (an arm as ``base · T_1(q_1) ···
T_n(q_n) · tool`` in one convention, angles in radians), one row's transform
(:func:`link_matrix`), the same arm in the other convention (:func:`convert`,
:func:`tool_link`), and the transform helpers and input checks they share.

Joint values and offsets (as the Robotics Toolbox): the D-H variable is the
user's joint value plus the row's offset, ``theta_i = q_i + offset_i`` for a
revolute joint and ``d_i = q_i + offset_i`` for a prismatic one. A
:class:`DHRow` holds the D-H table *at q = 0*, and ``offset`` repeats the
variable's entry of it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.model.errors import DhsimError

CONVENTIONS = ("standard", "modified")
KINDS = ("revolute", "prismatic")
#: modified → standard takes Tx(a)·Rx(alpha) out of a tool this close to having
#: one (looser than dh_extract's PARALLEL_TOL and LENGTH_TOL, so what they leave
#: in a tool still counts; the forward kinematics stay exact either way)
PEEL_TOL = 1e-9
#: a rotation block further than this from orthonormal is not a rigid transform
RIGID_TOL = 1e-9


@dataclass(frozen=True)
class DHRow:
    """One joint's D-H row at q = 0, angles in radians.

    ``theta``, ``d``, ``a``, ``alpha`` are the table at q = 0; ``offset`` is
    the variable's value there (``theta`` for a revolute joint, ``d`` for a
    prismatic one), so the D-H variable is ``q + offset``. In a modified
    chain ``a`` and ``alpha`` are a_{i-1} and alpha_{i-1}.
    """

    kind: str
    theta: float
    d: float
    a: float
    alpha: float
    offset: float

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise DhsimError(f"joint kind {self.kind!r}: expected 'revolute' or 'prismatic'")
        values = (self.theta, self.d, self.a, self.alpha, self.offset)
        if not all(math.isfinite(v) for v in values):
            raise DhsimError(f"D-H row {values}: every number must be finite")
        home = self.theta if self.kind == "revolute" else self.d
        if self.offset != home:
            name = "theta" if self.kind == "revolute" else "d"
            raise DhsimError(
                f"{self.kind} D-H row: offset {self.offset!r} must equal its {name} {home!r}"
            )

    def variables(self, q: float) -> tuple[float, float]:
        """(theta, d) with the joint at value q."""
        if self.kind == "revolute":
            return q + self.offset, self.d
        return self.theta, q + self.offset


@dataclass(frozen=True, eq=False)
class DHChain:
    """An arm as ``base · T_1(q_1) ··· T_n(q_n) · tool`` in one convention."""

    convention: str
    base: np.ndarray
    rows: tuple[DHRow, ...]
    tool: np.ndarray

    def __post_init__(self) -> None:
        if self.convention not in CONVENTIONS:
            raise DhsimError(
                f"D-H convention {self.convention!r}: expected 'standard' or 'modified'"
            )
        object.__setattr__(self, "base", checked_rigid(self.base, "base"))
        object.__setattr__(self, "tool", checked_rigid(self.tool, "tool"))
        object.__setattr__(self, "rows", tuple(self.rows))

    def frames(self, q: Sequence[float]) -> list[np.ndarray]:
        """World frames 0..n: ``base · T_1 ··· T_i`` (without the tool)."""
        q = _joint_values(q, len(self.rows))
        current = self.base.copy()
        out = [current]
        for row, qi in zip(self.rows, q, strict=True):
            theta, d = row.variables(qi)
            current = current @ link_matrix(self.convention, theta, d, row.a, row.alpha)
            out.append(current)
        return out

    def fk(self, q: Sequence[float]) -> np.ndarray:
        """The tip's 4×4 pose in the base's parent frame at joint values q."""
        return self.frames(q)[-1] @ self.tool


def link_matrix(convention: str, theta: float, d: float, a: float, alpha: float) -> np.ndarray:
    """One row's transform: standard Rz·Tz·Tx·Rx, modified Rx·Tx·Rz·Tz."""
    ct, st = math.cos(theta), math.sin(theta)
    ca, sa = math.cos(alpha), math.sin(alpha)
    if convention == "standard":
        return np.array(
            [
                [ct, -st * ca, st * sa, a * ct],
                [st, ct * ca, -ct * sa, a * st],
                [0.0, sa, ca, d],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
    return np.array(
        [
            [ct, -st, 0.0, a],
            [st * ca, ct * ca, -sa, -d * sa],
            [st * sa, ct * sa, ca, d * ca],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )


def convert(chain: DHChain, convention: str) -> DHChain:
    """The same arm in ``convention``, with the same frames where both have them.

    Standard → modified moves the last row's Tx(a_n)·Rx(alpha_n) into the
    tool (row 1 gets a_0 = alpha_0 = 0); modified → standard moves the first
    row's Rx(alpha_0)·Tx(a_0) into the base, and takes the last row's a_n and
    alpha_n back out of the tool when it begins with Tx(a)·Rx(alpha) followed
    by a screw along z (its z axis crosses frame n's x axis at a right angle:
    what standard → modified puts there), else they are 0. So standard →
    modified → standard gives back the same table, and every conversion the
    same forward kinematics.
    """
    if convention not in CONVENTIONS:
        raise DhsimError(f"D-H convention {convention!r}: expected 'standard' or 'modified'")
    rows = chain.rows
    if convention == chain.convention or not rows:
        return DHChain(convention, chain.base, rows, chain.tool)
    # (a, alpha) pairs shift by one row; Tx(a) and Rx(alpha) commute
    if convention == "modified":
        pairs = [(0.0, 0.0)] + [(r.a, r.alpha) for r in rows[:-1]]
        base = chain.base
        tool = link_matrix("standard", 0.0, 0.0, rows[-1].a, rows[-1].alpha) @ chain.tool
    else:
        size = max(
            [
                1.0,
                float(np.linalg.norm(chain.base[:3, 3])),
                float(np.linalg.norm(chain.tool[:3, 3])),
            ]
            + [abs(r.d) + abs(r.a) for r in rows]
        )
        a_n, alpha_n = tool_link(chain.tool, PEEL_TOL * size)
        pairs = [(r.a, r.alpha) for r in rows[1:]] + [(a_n, alpha_n)]
        base = chain.base @ link_matrix("modified", 0.0, 0.0, rows[0].a, rows[0].alpha)
        tool = invert_transform(link_matrix("standard", 0.0, 0.0, a_n, alpha_n)) @ chain.tool
    new_rows = tuple(
        DHRow(r.kind, r.theta, r.d, a, alpha, r.offset)
        for r, (a, alpha) in zip(rows, pairs, strict=True)
    )
    return DHChain(convention, base, new_rows, tool)


# -- transforms ---------------------------------------------------------------------------


def tool_link(tool: np.ndarray, tol: float) -> tuple[float, float]:
    """(a, alpha) with ``tool = Tx(a)·Rx(alpha)·Tz(d)·Rz(theta)``, or (0, 0)."""
    z, o = tool[:3, 2], tool[:3, 3]
    if abs(float(z[0])) > PEEL_TOL or abs(float(o[1] * z[2] - o[2] * z[1])) > tol:
        return 0.0, 0.0
    return float(o[0]), wrap_angle(math.atan2(-float(z[1]), float(z[2])))


def wrap_angle(angle: float) -> float:
    """-π (from a -0.0) as π, so angles lie in (-π, π]."""
    return math.pi if angle <= -math.pi else angle


def invert_transform(t: np.ndarray) -> np.ndarray:
    """The inverse of the rigid 4×4 transform ``t``."""
    out = np.eye(4)
    out[:3, :3] = t[:3, :3].T
    out[:3, 3] = -t[:3, :3].T @ t[:3, 3]
    return out


# -- checking the input -----------------------------------------------------------------


def _joint_values(q: Sequence[float], n: int) -> list[float]:
    values = [float(v) for v in np.asarray(q, dtype=float).reshape(-1)]
    if len(values) != n:
        raise DhsimError(f"expected {n} joint values, got {len(values)}")
    if not all(math.isfinite(v) for v in values):
        raise DhsimError(f"joint values {values}: every value must be finite")
    return values


def checked_rigid(matrix: np.ndarray, name: str) -> np.ndarray:
    """``matrix`` as a float 4×4 array; a :class:`DhsimError` naming ``name`` if
    it is not a finite rigid transform."""
    m = np.array(matrix, dtype=float)
    if m.shape != (4, 4) or not np.all(np.isfinite(m)):
        raise DhsimError(f"{name}: expected a finite 4×4 transform")
    r = m[:3, :3]
    if (
        not np.allclose(m[3], [0.0, 0.0, 0.0, 1.0], rtol=0.0, atol=RIGID_TOL)
        or not np.allclose(r.T @ r, np.eye(3), rtol=0.0, atol=RIGID_TOL)
        or np.linalg.det(r) < 0
    ):
        raise DhsimError(f"{name}: not a rigid transform (rotation and translation)")
    m.setflags(write=False)
    return m

"""D-H parameters from a chain's joint axes (groundwork for importing URDF).

The source chain is given as plain data: for each moving joint, in order,
its kind and its axis line (a point and a unit direction) in the base frame
with every joint at q = 0, and the tip's pose at q = 0. Joint i turns about
(slides along) its line, so the source's forward kinematics is the product
of exponentials ``FK(q) = exp(ξ_1 q_1) ··· exp(ξ_n q_n) · tip_home``
(radians and the input's length unit).

:func:`extract` places the classic D-H frames on those lines (the D-H conventions,
kinematics reference section 1):
in the standard convention frame i-1's z axis is joint i's axis, its x axis
the common normal from joint i-1's axis to joint i's; the base transform
absorbs where the first axis is and how it is turned, the tool the rest.
The result reproduces ``FK`` at every q to rounding (about 1e-12 relative).

Joint values and offsets (as the Robotics Toolbox): the D-H variable is the
user's joint value plus the row's offset, ``theta_i = q_i + offset_i`` for a
revolute joint and ``d_i = q_i + offset_i`` for a prismatic one, so q = 0 is
the source model's zero pose. A :class:`DHRow` holds the D-H table *at
q = 0* (theta, d, a, alpha: the project's "home" row), and ``offset``
repeats the variable's entry of it: ``offset == theta`` for a revolute row,
``offset == d`` for a prismatic row. The other three numbers are fixed.

Choices where geometry leaves freedom (all deterministic):

- Frame 0: origin at the point of joint 1's axis nearest the base origin;
  x axis the base x axis made perpendicular to the axis (the base y axis when
  the axis is within 1e-6 of base x), so the base is the identity when joint
  1 already runs along base +z through the origin.
- Skew axes: x along the common normal, pointing from the earlier axis to the
  later one, so a > 0 and alpha in (-π, π].
- Intersecting axes (a = 0): x = ±(z_{i-1} × z_i) normalised, the sign that
  keeps x within 90° of the previous frame's x (so the offset stays within
  ±90°); a tie (exactly 90°) takes +.
- Parallel axes (|z_{i-1} × z_i| < 1e-12): the common normal through the
  previous frame's origin, so d = 0; x points to the later axis, a > 0;
  alpha = 0, or π for antiparallel axes.
- Coincident axes (parallel and less than 1e-12 × the chain's size apart):
  x unchanged, so theta = 0 and d = a = 0; alpha = 0 or π.
- The last frame (standard frame n, modified frame n's x): the tip's z axis
  plays joint n+1's, with the rules above, except that the common normal to
  a parallel tip axis passes through the tip's origin and the sign of an
  intersecting one, or x for a coincident one, follows the tip's x axis. The
  tool is then a screw along the tip's z axis (the identity when the tip is
  where a D-H row can put it, as for a planar 2R arm's hand).

:func:`extract` with ``convention="modified"`` returns the same frames in the
modified convention (:func:`~dhsim_tui.core.interop.dh_chain.convert`): row
i's ``a``/``alpha`` then hold a_{i-1}/alpha_{i-1} (the reference's
"(alpha_{i-1}, a_{i-1}, d_i)" rows), and row 1's are 0, since frame 0 lies on
joint 1's axis. The rows and chain it returns, and that conversion, are
:mod:`dhsim_tui.core.interop.dh_chain`'s.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Sequence

import numpy as np

from dhsim_tui.core.interop.dh_chain import (
    CONVENTIONS,
    KINDS,
    DHChain,
    DHRow,
    checked_rigid,
    convert,
    invert_transform,
    link_matrix,
    wrap_angle,
)
from dhsim_tui.core.model.errors import DhsimError

#: consecutive axes count as parallel when the sine of their angle is below this
PARALLEL_TOL = 1e-12
#: lengths below this times the chain's size count as zero (intersecting, on-axis)
LENGTH_TOL = 1e-12
#: angles this close to 0 are 0 (rounding noise)
ZERO_ANGLE = 1e-14


def extract(
    lines: Sequence[tuple[str, np.ndarray, np.ndarray]],
    tip_home: np.ndarray,
    convention: str = "standard",
    *,
    parallel_tol: float = PARALLEL_TOL,
    parallel: Collection[int] = (),
    length_tol: float = LENGTH_TOL,
) -> DHChain:
    """D-H base, rows and tool reproducing the chain of joint axis ``lines``.

    ``lines``: per moving joint, in order, (kind, a point on its axis, its
    direction), in the base frame at q = 0; ``tip_home``: the tip's 4×4 pose
    there. The result's ``fk(q)`` equals the product of exponentials of the
    lines times ``tip_home`` for every q (see the module's docstring for the
    choices made where D-H leaves freedom).

    ``parallel_tol``: consecutive axes whose angle's sine is below it count
    as parallel. Axes nearly but not quite parallel (sine s) are D-H's weak
    spot: as skew lines their common normal lies about size/s away, so d is
    huge and rounding costs about 1e-16/s of the size; as parallel lines the
    error is about s. No tolerance makes both small near s = 1e-8; the
    default keeps the geometry exact and leaves the huge d visible.

    ``parallel``: pairs taken as parallel whatever their angle, each by the
    number i of its first axis (from 1), pairing axis i with axis i + 1, or
    the last axis with the tip's z axis: for a caller that knows the pair is
    parallel but for rounding and checks that the result still reproduces
    the chain closely enough (the URDF import does). Joint i + 1's axis then
    runs parallel to joint i's, an error of the pair's angle, and the frames
    after it are placed on the true axes again.

    ``length_tol``: lengths below it times the chain's size count as zero
    (coincident or intersecting axes, a zero d): looser than the default for
    a source whose numbers were rounded (the error is then that length).
    """
    if convention not in CONVENTIONS:
        raise DhsimError(f"D-H convention {convention!r}: expected 'standard' or 'modified'")
    if not 0.0 <= parallel_tol < 1.0:
        raise DhsimError(f"parallel tolerance {parallel_tol!r}: expected 0 <= tol < 1")
    forced = set(parallel)
    tip = checked_rigid(tip_home, "tip pose")
    axes = _axes(lines)
    scale = max(
        [1.0, float(np.linalg.norm(tip[:3, 3]))]
        + [float(np.linalg.norm(_foot(np.zeros(3), p, w))) for _, p, w in axes]
    )
    if not 0.0 <= length_tol < 1e-3:
        raise DhsimError(f"length tolerance {length_tol!r}: expected 0 <= tol < 1e-3")
    tol = length_tol * scale

    _, p1, w1 = axes[0]
    frame = np.eye(4)
    frame[:3, 2] = w1
    frame[:3, 0] = _perpendicular(np.array([1.0, 0.0, 0.0]), w1, fallback=np.array([0, 1.0, 0]))
    frame[:3, 1] = np.cross(w1, frame[:3, 0])
    frame[:3, 3] = _foot(np.zeros(3), p1, w1)
    base = frame.copy()

    rows = []
    for i, (kind, _, _) in enumerate(axes):
        if i + 1 < len(axes):
            _, p_next, w_next = axes[i + 1]
            through, prefer = frame[:3, 3], frame[:3, 0]  # previous origin and x
            theta, d, a, alpha = _next_link(
                frame, p_next, w_next, through, prefer, tol, _tol(i, forced, parallel_tol)
            )
        else:  # the tip's z axis plays the next joint's
            tip_origin, tip_z, tip_x = tip[:3, 3], tip[:3, 2], tip[:3, 0]
            theta, d, a, alpha = _next_link(
                frame, tip_origin, tip_z, tip_origin, tip_x, tol, _tol(i, forced, parallel_tol)
            )
        # rounding noise on a zero (a Puma's d = 1e-17) becomes the zero
        d = 0.0 if abs(d) <= tol else d
        theta = 0.0 if abs(theta) <= ZERO_ANGLE else theta
        alpha = 0.0 if abs(alpha) <= ZERO_ANGLE else alpha
        offset = theta if kind == "revolute" else d
        rows.append(DHRow(kind, theta, d, a, alpha, offset))
        frame = frame @ link_matrix("standard", theta, d, a, alpha)

    tool = invert_transform(frame) @ tip
    chain = DHChain("standard", base, tuple(rows), tool)
    return convert(chain, convention)


def _tol(index: int, forced: set[int], parallel_tol: float) -> float:
    """The parallel tolerance for the pair after axis ``index`` (from 0)."""
    return math.inf if index + 1 in forced else parallel_tol


# -- geometry ---------------------------------------------------------------------------


def _next_link(
    frame: np.ndarray,
    p: np.ndarray,
    w: np.ndarray,
    through: np.ndarray,
    prefer: np.ndarray,
    tol: float,
    parallel_tol: float,
) -> tuple[float, float, float, float]:
    """(theta, d, a, alpha) taking ``frame`` (z on the current axis) to a
    frame on the common normal whose z runs along the line (p, w).

    Where the common normal is not unique it passes through the point of the
    line (p, w) nearest ``through`` (parallel lines) or through ``through``'s
    foot (coincident lines); ``prefer`` picks x's sign when the lines meet and
    is x itself when they coincide.
    """
    origin, x_prev, z = frame[:3, 3], frame[:3, 0], frame[:3, 2]
    cross = np.cross(z, w)
    sine = float(np.linalg.norm(cross))
    if sine < parallel_tol:
        alpha = 0.0 if float(z @ w) > 0 else math.pi
        offset = _foot(through, p, w) - origin
        d = float(offset @ z)
        radial = offset - d * z
        a = float(np.linalg.norm(radial))
        if a <= tol:  # coincident
            x = _perpendicular(prefer, z, fallback=x_prev)
            return _angle(x_prev, x, z), d, 0.0, alpha
        return _angle(x_prev, radial / a, z), d, a, alpha
    normal = cross / sine
    r = p - origin
    d = float(np.cross(r, w) @ cross) / sine**2  # the foot on the current axis
    signed = float(r @ normal)
    if abs(signed) > tol:
        x = normal if signed > 0 else -normal
        a = abs(signed)
    else:  # intersecting
        x = -normal if float(normal @ prefer) < -1e-9 else normal
        a = 0.0
    alpha = wrap_angle(math.atan2(float(cross @ x), float(z @ w)))
    return _angle(x_prev, x, z), d, a, alpha


def _angle(x_from: np.ndarray, x_to: np.ndarray, z: np.ndarray) -> float:
    """The angle about z from x_from to x_to (both perpendicular to z)."""
    return wrap_angle(math.atan2(float(np.cross(x_from, x_to) @ z), float(x_from @ x_to)))


def _foot(point: np.ndarray, p: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The point of the line (p, w) nearest ``point``."""
    return p + float((point - p) @ w) * w


def _perpendicular(v: np.ndarray, z: np.ndarray, fallback: np.ndarray) -> np.ndarray:
    """v made perpendicular to unit z and normalised (fallback when v ∥ z)."""
    for candidate in (v, fallback):
        out = candidate - float(candidate @ z) * z
        if float(np.linalg.norm(out)) > 1e-6:
            out = out - float(out @ z) * z  # twice, for a clean right angle
            return out / np.linalg.norm(out)
    raise AssertionError("two perpendicular vectors cannot both be parallel to z")


# -- checking the input -----------------------------------------------------------------


def _axes(
    lines: Sequence[tuple[str, np.ndarray, np.ndarray]],
) -> list[tuple[str, np.ndarray, np.ndarray]]:
    if len(lines) == 0:
        raise DhsimError("the chain has no moving joint: nothing to give D-H parameters")
    out = []
    for i, line in enumerate(lines, start=1):
        kind, point, direction = line
        if kind not in KINDS:
            raise DhsimError(f"joint {i}: kind {kind!r}, expected 'revolute' or 'prismatic'")
        p = np.asarray(point, dtype=float).reshape(-1)
        w = np.asarray(direction, dtype=float).reshape(-1)
        if p.shape != (3,) or w.shape != (3,):
            raise DhsimError(f"joint {i}: its axis point and direction must be 3-vectors")
        if not (np.all(np.isfinite(p)) and np.all(np.isfinite(w))):
            raise DhsimError(f"joint {i}: its axis point and direction must be finite")
        length = float(np.linalg.norm(w))
        if length < 1e-9:
            raise DhsimError(f"joint {i}: its axis direction is zero")
        out.append((kind, p, w / length))
    return out

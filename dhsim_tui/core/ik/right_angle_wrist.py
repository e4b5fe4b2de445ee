"""The spherical-wrist closed form worked in frames fitted to the arm, for the
commonest industrial geometry: axes 2 and 3 parallel and a wrist whose axes
are at right angles (axis 4 ⊥ axis 5 ⊥ axis 6: the Puma 560, the IRB 140).

It gives the same solutions and words as :func:`dhsim_tui.core.ik.wrist.solve_spherical_wrist`
(a test compares the two on random poses and random arms), in about half the
arithmetic:

* **the arm frame** A: origin on axis 1, z along axis 1, x toward axis 2's
  direction at home. Joint 1 is then a turn about z, axis 2's direction is
  ``(s2, 0, c2)``, and the shoulder's equation ``a cos t1 + b sin t1 = c``
  has its coefficients read off the wrist centre's coordinates.
* **the plane of joints 2 and 3** (perpendicular to axis 2): the elbow is a
  planar two-link in 2-D coordinates, links ``a`` (shoulder to elbow) and
  ``b`` (elbow to wrist centre) at home.
* **the wrist frame** B: z along axis 4, y along axis 5. Joints 4-6 are then
  the Euler angles Z-Y-Z of a matrix N (axis 6 lies at a fixed angle φ from
  axis 4 about axis 5 at home, folded into N), so each arm solution gives its
  two wrist solutions with three ``atan2`` each.

Joint values come back as :func:`dhsim_tui.core.ik.analytic.solve` gives
them: in degrees, within half a turn of home.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

from dhsim_tui.core.ik.subproblems import DOUBLE_ROOT, EPS
from dhsim_tui.core.ik.vectors import (
    Motion,
    Vec,
    apply_motion,
    cross_product,
    dot,
    norm,
    scaled,
    sub,
)

_RAD = 180.0 / math.pi
#: two axes count as at right angles when the cosine between them is below this
#: (the axes come from frames built with exact quarter turns: 0 or ~1e-17)
RIGHT_ANGLE_TOL = 1e-12


class ArmFrames(NamedTuple):
    """What :func:`solve` needs that does not depend on the pose."""

    origin: Vec  # a point on axis 1 (world)
    to_arm: tuple[float, ...]  # A^T: world directions to arm-frame coordinates (row-major)
    s2: float  # axis 2's direction in the arm frame: (s2, 0, c2)
    c2: float
    height: float  # axis 2's direction . the wrist centre (arm frame): kept by joints 2, 3
    shoulder: Vec  # a point on axis 2 (arm frame)
    link_a: tuple[float, float]  # shoulder to elbow, in the plane of joints 2 and 3
    link_b: tuple[float, float]  # elbow to wrist centre, in that plane
    lengths: float  # |a|^2 + |b|^2
    ab: float  # |a| |b|
    ab_phase: float  # a . R(t) b = |a| |b| cos(t - ab_phase)
    sign3: float  # +1 when axis 3 points as axis 2 does, else -1
    centre_tool: Vec  # the wrist centre in the end effector's frame
    right: tuple[float, ...]  # M^-1 rotation · B · Ry(phi) (row-major)
    arm_to_wrist: tuple[float, ...]  # Q = B^T A (row-major)
    axis2_wrist: tuple[float, ...]  # axis 2's direction in the wrist frame, and its products
    phi: float  # axis 6 from axis 4, about axis 5, at home
    singular: float  # joint 5's turn (from home) at which axis 6 lines up with axis 4


def arm_frames(
    axes: tuple[Vec, ...],
    points: tuple[Vec, ...],
    centre: Vec,
    home_inverse: Motion,
    singular: float,
    size: float,
    tol: float,
) -> ArmFrames | None:
    """The constants of :func:`solve` for an arm of this geometry (axes 2 and 3
    parallel, a spherical wrist at ``centre``), or None when its wrist axes are
    not at right angles or a link of the plane is too short (``tol`` × ``size``)."""
    w1, w2, w3, w4, w5, w6 = axes
    if abs(dot(w4, w5)) > RIGHT_ANGLE_TOL or abs(dot(w5, w6)) > RIGHT_ANGLE_TOL:
        return None
    origin = points[0]
    c2 = dot(w2, w1)
    across = sub(w2, scaled(w1, c2))
    s2 = norm(across)
    x = scaled(across, 1.0 / s2)
    y = cross_product(w1, x)
    z = w1

    def arm(v: Vec) -> Vec:
        d = sub(v, origin)
        return (dot(x, d), dot(y, d), dot(z, d))

    def plane(v: Vec) -> tuple[float, float]:
        """A vector's coordinates across axis 2: along y and along axis 2 × y."""
        return (v[1], -c2 * v[0] + s2 * v[2])

    shoulder, elbow, wrist = arm(points[1]), arm(points[2]), arm(centre)
    a = plane(sub(elbow, shoulder))
    b = plane(sub(wrist, elbow))
    length_a, length_b = math.hypot(*a), math.hypot(*b)
    if length_a <= tol * size or length_b <= tol * size:
        return None
    ab_cos = a[0] * b[0] + a[1] * b[1]
    ab_sin = a[1] * b[0] - a[0] * b[1]
    # the wrist frame B: z along axis 4, y along axis 5
    bx, by, bz = cross_product(w5, w4), w5, w4
    phi = math.atan2(dot(w6, bx), dot(w6, bz))
    cp, sp = math.cos(phi), math.sin(phi)
    d0 = tuple(cp * bx[i] - sp * bz[i] for i in range(3))
    d2 = tuple(sp * bx[i] + cp * bz[i] for i in range(3))
    inverse_rotation = home_inverse[0]
    right = []
    for row in range(3):
        m = inverse_rotation[3 * row : 3 * row + 3]
        right += [dot(m, d0), dot(m, by), dot(m, d2)]
    to_arm = (*x, *y, *z)
    arm_to_wrist = tuple(dot(bi, aj) for bi in (bx, by, bz) for aj in (x, y, z))
    k0, k1, k2 = dot(bx, w2), dot(by, w2), dot(bz, w2)
    return ArmFrames(
        origin=origin,
        to_arm=to_arm,
        s2=s2,
        c2=c2,
        height=s2 * wrist[0] + c2 * wrist[2],
        shoulder=shoulder,
        link_a=a,
        link_b=b,
        lengths=length_a * length_a + length_b * length_b,
        ab=length_a * length_b,
        ab_phase=math.atan2(ab_sin, ab_cos),
        sign3=1.0 if dot(w2, w3) > 0.0 else -1.0,
        centre_tool=apply_motion(home_inverse, centre),
        right=tuple(right),
        arm_to_wrist=arm_to_wrist,
        axis2_wrist=(k0, k1, k2, k0 * k0, k0 * k1, k0 * k2, k1 * k1, k1 * k2, k2 * k2),
        phi=phi,
        singular=singular,
    )


def _roots(a: float, b: float, c: float) -> list[float] | None:
    """``a cos t + b sin t = c`` as ``solve_cos_sin`` solves it, or None
    when ``(a, b)`` is too short to say (the caller decides)."""
    rho = math.hypot(a, b)
    if rho < EPS:
        return None
    ratio = c / rho
    if abs(ratio) > 1.0 + 1e-12:
        return []
    phase = math.atan2(b, a)
    spread = math.acos(max(-1.0, min(1.0, ratio)))
    return [phase] if spread < DOUBLE_ROOT else [phase + spread, phase - spread]


def solve(
    c: ArmFrames,
    f: list[float],
    home: tuple[float, ...],
    preferred: tuple[float, ...],
    fits: Callable[[int, float], bool] | None = None,
) -> tuple[list[tuple[tuple[float, ...], str]], int]:
    """Every solution for a world target (``f``: its 16 numbers, row-major) as
    (joint values in degrees within half a turn of ``home``, words), and how
    many arm solutions were dropped because ``fits(joint index, value)`` said
    one of joints 1-3 cannot be within its limits. ``preferred``: the joint
    values for the angles a singular pose leaves free.

    The turns come from ``atan2`` (within half a turn) except joints 1, 3
    and 5 (a phase plus a spread, or less a constant): only those are
    wrapped."""
    (
        (o0, o1, o2),
        (x0, x1, x2, y0, y1, y2, z0, z1, z2),
        s2,
        c2,
        height,
        (sh0, sh1, sh2),
        (a0, a1),
        (b0, b1),
        lengths,
        ab,
        ab_phase,
        sign3,
        (m0, m1, m2),
        (e0, e1, e2, e3, e4, e5, e6, e7, e8),
        (q0, q1, q2, q3, q4, q5, q6, q7, q8),
        (k0, k1, k2, k00, k01, k02, k11, k12, k22),
        phi,
        singular,
    ) = c
    f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11 = f[:12]
    h1, h2, h3, h4, h5, h6 = home
    cos, sin, atan2, acos, sqrt = math.cos, math.sin, math.atan2, math.acos, math.sqrt
    remainder, tau = math.remainder, 2 * math.pi
    # the wrist centre's target, in the arm frame
    v0 = f0 * m0 + f1 * m1 + f2 * m2 + f3 - o0
    v1 = f4 * m0 + f5 * m1 + f6 * m2 + f7 - o1
    v2 = f8 * m0 + f9 * m1 + f10 * m2 + f11 - o2
    px = x0 * v0 + x1 * v1 + x2 * v2
    py = y0 * v0 + y1 * v1 + y2 * v2
    pz = z0 * v0 + z1 * v1 + z2 * v2
    # joint 1 keeps the centre's height along axis 2: s2 (px cos t1 + py sin t1) = height - c2 pz
    shoulders = _roots(s2 * px, s2 * py, height - c2 * pz)
    if shoulders is None:  # the centre on axis 1: joint 1 is free
        shoulders = [(preferred[0] - h1) / _RAD] if abs(height - c2 * pz) < 1e-9 else []
    if not shoulders:
        return [], 0
    # K = A^T T_R (M^-1 B Ry(phi)): the target's rotation between the two frames
    r0 = f0 * e0 + f1 * e3 + f2 * e6
    r1 = f0 * e1 + f1 * e4 + f2 * e7
    r2 = f0 * e2 + f1 * e5 + f2 * e8
    r3 = f4 * e0 + f5 * e3 + f6 * e6
    r4 = f4 * e1 + f5 * e4 + f6 * e7
    r5 = f4 * e2 + f5 * e5 + f6 * e8
    r6 = f8 * e0 + f9 * e3 + f10 * e6
    r7 = f8 * e1 + f9 * e4 + f10 * e7
    r8 = f8 * e2 + f9 * e5 + f10 * e8
    kx0 = x0 * r0 + x1 * r3 + x2 * r6
    kx1 = x0 * r1 + x1 * r4 + x2 * r7
    kx2 = x0 * r2 + x1 * r5 + x2 * r8
    ky0 = y0 * r0 + y1 * r3 + y2 * r6
    ky1 = y0 * r1 + y1 * r4 + y2 * r7
    ky2 = y0 * r2 + y1 * r5 + y2 * r8
    kz0 = z0 * r0 + z1 * r3 + z2 * r6
    kz1 = z0 * r1 + z1 * r4 + z2 * r7
    kz2 = z0 * r2 + z1 * r5 + z2 * r8
    out = []
    dropped = 0
    for t1 in shoulders:
        c1, s1 = cos(t1), sin(t1)
        # the centre turned back into the arm's home plane
        hx = c1 * px + s1 * py
        hy = c1 * py - s1 * px
        dx, dy, dz = hx - sh0, hy - sh1, pz - sh2
        p0, p1 = dy, s2 * dz - c2 * dx  # across axis 2
        # joint 3: |a + R(t3) b| = |p|, i.e. ab_cos cos t3 + ab_sin sin t3 = k
        ratio = 0.5 * (p0 * p0 + p1 * p1 - lengths) / ab
        if abs(ratio) > 1.0 + 1e-12:
            continue
        spread = acos(max(-1.0, min(1.0, ratio)))
        elbows = (ab_phase,) if spread < DOUBLE_ROOT else (ab_phase + spread, ab_phase - spread)
        joint1 = h1 + _RAD * remainder(t1, tau)
        if fits is not None and not fits(0, joint1):
            dropped += len(elbows)
            continue
        shoulder_word = "shoulder right" if s2 * hy >= 0.0 else "shoulder left"
        up = s2 * dy
        if up * up <= 1e-18 * (dx * dx + dy * dy + dz * dz):
            up = 1.0
        p_small = p0 * p0 + p1 * p1 < EPS
        # M = Q Rz(-t1) K
        n0, n1, n2 = c1 * kx0 + s1 * ky0, c1 * kx1 + s1 * ky1, c1 * kx2 + s1 * ky2
        u0, u1, u2 = c1 * ky0 - s1 * kx0, c1 * ky1 - s1 * kx1, c1 * ky2 - s1 * kx2
        ma0 = q0 * n0 + q1 * u0 + q2 * kz0
        ma1 = q0 * n1 + q1 * u1 + q2 * kz1
        ma2 = q0 * n2 + q1 * u2 + q2 * kz2
        mb0 = q3 * n0 + q4 * u0 + q5 * kz0
        mb1 = q3 * n1 + q4 * u1 + q5 * kz1
        mb2 = q3 * n2 + q4 * u2 + q5 * kz2
        mc0 = q6 * n0 + q7 * u0 + q8 * kz0
        mc1 = q6 * n1 + q7 * u1 + q8 * kz1
        mc2 = q6 * n2 + q7 * u2 + q8 * kz2
        for t3p in elbows:
            c3, s3 = cos(t3p), sin(t3p)
            rb0, rb1 = b0 * c3 - b1 * s3, b0 * s3 + b1 * c3  # R(t3) b
            w0, w1 = a0 + rb0, a1 + rb1  # the wrist centre from the shoulder, at t2 = 0
            if p_small or w0 * w0 + w1 * w1 < EPS:
                t2 = remainder((preferred[1] - h2) / _RAD, tau)
            else:
                t2 = atan2(w0 * p1 - w1 * p0, w0 * p0 + w1 * p1)
            joint2 = h2 + _RAD * t2
            joint3 = h3 + _RAD * remainder(sign3 * t3p, tau)
            if fits is not None and not (fits(1, joint2) and fits(2, joint3)):
                dropped += 1
                continue
            sigma = a0 * rb1 - a1 * rb0  # the elbow's side of the line shoulder-centre
            arm_words = f"{shoulder_word}, {'elbow up' if -sigma * up >= 0.0 else 'elbow down'}"
            # N = R_b(-tau) M: the wrist's rotation in the wrist frame (Z-Y-Z)
            turn = t2 + t3p
            c, s = cos(turn), -sin(turn)
            v = 1.0 - c
            g00, g01, g02 = c + v * k00, v * k01 - s * k2, v * k02 + s * k1
            g10, g11, g12 = v * k01 + s * k2, c + v * k11, v * k12 - s * k0
            g20, g21, g22 = v * k02 - s * k1, v * k12 + s * k0, c + v * k22
            n02 = g00 * ma2 + g01 * mb2 + g02 * mc2
            n12 = g10 * ma2 + g11 * mb2 + g12 * mc2
            n20 = g20 * ma0 + g21 * mb0 + g22 * mc0
            n21 = g20 * ma1 + g21 * mb1 + g22 * mc1
            n22 = g20 * ma2 + g21 * mb2 + g22 * mc2
            across = sqrt(n02 * n02 + n12 * n12)  # |sin| of joint 5 from the singular turn
            if across > DOUBLE_ROOT:
                for sign in (1.0, -1.0):
                    t5 = atan2(sign * across, n22) - phi
                    q = (
                        joint1,
                        joint2,
                        joint3,
                        h4 + _RAD * atan2(sign * n12, sign * n02),
                        h5 + _RAD * remainder(t5, tau),
                        h6 + _RAD * atan2(sign * n21, -sign * n20),
                    )
                    flip = "wrist no flip" if sin(t5 - singular) <= 0.0 else "wrist flip"
                    out.append((q, f"{arm_words}, {flip}"))
                continue
            # axis 6 on axis 4's line: only joint 4 + joint 6 (or their difference) counts
            n00 = g00 * ma0 + g01 * mb0 + g02 * mc0
            n10 = g10 * ma0 + g11 * mb0 + g12 * mc0
            t4 = (preferred[3] - h4) / _RAD
            t5 = atan2(across, n22) - phi
            if n22 > 0.0:
                t6 = atan2(n10, n00) - t4
            else:
                n11 = g10 * ma1 + g11 * mb1 + g12 * mc1
                t6 = t4 + atan2(n10, n11)
            q = (
                joint1,
                joint2,
                joint3,
                h4 + _RAD * remainder(t4, tau),
                h5 + _RAD * remainder(t5, tau),
                h6 + _RAD * remainder(t6, tau),
            )
            flip = "wrist no flip" if sin(t5 - singular) <= 0.0 else "wrist flip"
            out.append((q, f"{arm_words}, {flip}"))
    return out, dropped

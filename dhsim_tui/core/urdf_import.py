"""A robot from a URDF's serial chain (:func:`from_urdf`): the chain from
the root link (or ``base``) to the tip link (or the only leaf) is read by
:mod:`dhsim_tui.core.urdf`, and :func:`dhsim_tui.core.dh_extract.extract`
places D-H frames on its joint axes. The robot it gives has

- joint values equal to the URDF's (degrees and the chosen unit instead of
  radians and metres): each row's offset is its D-H variable at the URDF's
  zero, so ``q = 0`` is the URDF's zero pose;
- the world frame of the URDF's base link, frame 0 placed by ``base_xyz`` and
  ``base_rpy``, and the tip link as the tool frame;
- the URDF's limits (a continuous joint gets a full turn each way), and a
  home at ``q = 0`` or, for a joint whose range excludes 0, the middle of it;
- the floor at the base link's z = 0 (lower if frame 0 is below it).

Its forward kinematics is then checked against the URDF's own (computed
independently, link by link from the URDF's origins and axes) at the home
and at seeded random joint values; the largest difference is one of the
import's notes, and a difference above 1e-9 m or 1e-9 rad is refused.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from dhsim_tui.core.convert import parts, tidy
from dhsim_tui.core.dh_extract import DHChain, extract
from dhsim_tui.core.errors import DhsimError
from dhsim_tui.core.imported import ImportResult, check_choice
from dhsim_tui.core.model import CONVENTIONS, UNITS, Joint, Robot, Tool
from dhsim_tui.core.text import printable
from dhsim_tui.core.units import min_length
from dhsim_tui.core.urdf import UrdfChain, read_chain
from dhsim_tui.core.validation import fmt

#: the imported robot must match the URDF's forward kinematics this closely (m, rad)
MATCH_TOL = 1e-9
#: random joint vectors the import is checked at (seeded: the same every time)
CHECKS = 200
#: an angle this close to a multiple of 90° (but not on it) gets a note
NEAR_ROUND_DEG = 1e-5
#: consecutive axes whose angle's sine is below this (but not 0) get a note
NEAR_PARALLEL = 1e-3


def from_urdf(
    text: str,
    *,
    source: str = "<urdf>",
    tip: str | None = None,
    base: str | None = None,
    convention: str | None = None,
    units: str | None = None,
    name: str | None = None,
) -> ImportResult:
    """The robot of a URDF's serial chain (see the module's docstring)."""
    convention = convention or "standard"
    check_choice(convention, CONVENTIONS, "--convention", source)
    units = units or "m"
    check_choice(units, tuple(UNITS), "--units", source)
    chain = read_chain(text, tip=tip, base=base, source=source)
    lines = chain.joint_lines()
    skewed = _near_parallel(lines)
    dh = extract(lines, chain.tip_home(), convention)
    scale = 1000.0 / UNITS[units]  # metres -> units
    size = _size(dh) * scale
    joints = tuple(
        _joint(row, urdf_joint, scale, size, units)
        for row, urdf_joint in zip(dh.rows, chain.moving, strict=True)
    )
    base_xyz, base_rpy = _parts(dh.base, scale, size, units)
    tool_xyz, tool_rpy = _parts(dh.tool, scale, size, units)
    robot_name = printable(name or chain.name or Path(source).stem or "imported robot").strip()
    try:
        robot = Robot(
            name=robot_name or "imported robot",
            joints=joints,
            units=units,
            convention=convention,
            base_height=max(0.0, -base_xyz[2]),
            base_xyz=base_xyz,
            base_rpy=base_rpy,
            tool=Tool(tool_xyz, tool_rpy),
        )
    except DhsimError as exc:
        why = f"; {skewed[0]}" if skewed else ""
        raise DhsimError(printable(f"{source}: the D-H robot is not valid: {exc}{why}")) from None
    position, rotation = max_difference(robot, chain)
    if position > MATCH_TOL or rotation > MATCH_TOL:
        raise DhsimError(
            f"{printable(source)}: no D-H table reproduces this chain to 1e-9 "
            f"(off by {position:.1e} m, {rotation:.1e} rad; nearly parallel axes?)"
        )
    notes = [
        f"{len(joints)} joints from link {chain.base!r} to link {chain.tip!r}, "
        f"{convention} D-H, lengths in {units}",
        f"checked at home and {CHECKS} random joint values: the tool's pose matches the "
        f"URDF to {position:.0e} m and {rotation:.0e} rad",
        *_near_round(robot),
        *skewed,
    ]
    header = (
        f"Imported by dhsim from {Path(source).name} ({printable(chain.name) or 'no name'}): "
        f"link {chain.base} to link {chain.tip}, {convention} D-H.",
        "Joint values equal the URDF's (degrees instead of radians, "
        f"{units} instead of metres): D-H variable = q + offset.",
        *(
            f"joint {i}: {printable(j.name)} ({j.kind})"
            for i, j in enumerate(chain.moving, start=1)
        ),
    )
    return ImportResult(robot, tuple(printable(n) for n in notes), header)


def _joint(row, urdf_joint, scale: float, size: float, units: str) -> Joint:
    revolute = row.kind == "revolute"
    lower, upper = urdf_joint.lower, urdf_joint.upper
    if revolute:
        lower, upper = math.degrees(lower), math.degrees(upper)
    else:
        lower, upper = lower * scale, upper * scale
    lower, upper = tidy(lower, 360.0), tidy(upper, 360.0)
    home = 0.0 if lower <= 0.0 <= upper else (lower + upper) / 2
    theta = tidy(math.degrees(row.theta), 360.0)
    d = _length(row.d * scale, size, units)
    offset = theta if revolute else d
    if revolute:
        theta = offset + home
    else:
        d = offset + home
    return Joint(
        type=row.kind,
        theta=theta,
        d=d,
        a=_length(row.a * scale, size, units),
        alpha=tidy(math.degrees(row.alpha), 360.0),
        min=lower,
        max=upper,
        offset=offset,
    )


def _length(value: float, size: float, units: str) -> float:
    """A length without rounding noise; below a nanometre it is 0 (robots hold
    no shorter nonzero length)."""
    value = tidy(value, size)
    return 0.0 if abs(value) < min_length(units) else value


def _parts(matrix: np.ndarray, scale: float, size: float, units: str) -> tuple[tuple, tuple]:
    scaled = matrix.copy()
    scaled[:3, 3] *= scale
    return parts(scaled, size, units)


def _size(dh: DHChain) -> float:
    lengths = [abs(r.a) + abs(r.d) for r in dh.rows]
    lengths += [float(np.linalg.norm(dh.base[:3, 3])), float(np.linalg.norm(dh.tool[:3, 3]))]
    return max([1e-9, *lengths])


def max_difference(robot: Robot, chain: UrdfChain, count: int = CHECKS) -> tuple[float, float]:
    """The largest position (m) and rotation (rad) difference between the
    robot's tool pose and the URDF's tip pose, at home and at ``count``
    seeded random joint values within the limits."""
    rng = np.random.default_rng(20101)
    lower, upper = np.array(robot.lower), np.array(robot.upper)
    samples = [np.array(robot.home), *(rng.uniform(lower, upper) for _ in range(count))]
    to_si = np.array(
        [math.radians(1.0) if j.is_revolute else UNITS[robot.units] / 1000.0 for j in robot.joints]
    )
    metres = UNITS[robot.units] / 1000.0
    position = rotation = 0.0
    for q in samples:
        ours = robot.kinematics.pose(q)
        theirs = chain.fk(q * to_si)
        position = max(position, float(np.abs(ours[:3, 3] * metres - theirs[:3, 3]).max()))
        rotation = max(rotation, float(np.abs(ours[:3, :3] - theirs[:3, :3]).max()))
    return position, rotation


def _near_parallel(lines) -> list[str]:
    """Consecutive axes a hair from parallel: D-H puts their common normal
    far away (d of about the distance over the angle), which is exact but
    rarely what the URDF's author meant (a rounded π/2?)."""
    notes = []
    for i in range(len(lines) - 1):
        (_, p1, w1), (_, p2, w2) = lines[i], lines[i + 1]
        sine = float(np.linalg.norm(np.cross(w1, w2)))
        if 0.0 < sine < NEAR_PARALLEL:
            gap = float(np.linalg.norm(np.cross(p2 - p1, w1)))
            notes.append(
                f"the axes of joints {i + 1} and {i + 2} are {math.asin(sine):.1e} rad from "
                f"parallel, so their common normal lies about {gap / sine:.0e} m away"
            )
    return notes


def _near_round(robot: Robot) -> list[str]:
    """Notes for angles a hair off a multiple of 90° (π/2 written as 1.5708)."""
    notes = []
    for i, j in enumerate(robot.joints, start=1):
        for field in ("alpha", "offset" if j.is_revolute else "theta"):
            value = getattr(j, field)
            off = abs(value - 90.0 * round(value / 90.0))
            if 0.0 < off < NEAR_ROUND_DEG:
                notes.append(
                    f"joint {i} {field} = {fmt(value)} deg is {off:.1e} deg from "
                    f"{fmt(90.0 * round(value / 90.0))}: kept, as the URDF has it"
                )
    return notes

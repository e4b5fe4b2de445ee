"""A robot from a URDF's serial chain (:func:`from_urdf`): the chain from
the root link (or ``base``) to the tip link (or the only leaf) is read by
:mod:`dhsim_tui.core.interop.urdf`, and :func:`dhsim_tui.core.interop.dh_extract.extract`
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

Axes a hair from parallel (a URDF writing π/2 as ``1.570796327`` leaves
consecutive axes some 1e-10 rad apart; as skew lines their common normal
would lie ~1e9 m away) are first taken as parallel, each run of them turned
to its mean direction (:class:`~dhsim_tui.core.interop.urdf_axes.AxisPlan`):
every pair less than :data:`~dhsim_tui.core.interop.urdf_axes.PARALLEL_TRY`
from parallel, then only those whose common normal lies far off the arm.
The first of these D-H tables that passes the check is kept (a note names
the pairs); otherwise the axes are imported as the skew lines they are, and
the file is refused only when none of them passes.

Numbers are then rounded to the shortest decimals that keep the check: every
length and angle of the table, the base and the tool becomes the number with
the fewest significant digits within ``eps`` of it (metres for lengths,
radians for angles), for the coarsest ``eps`` of
:data:`~dhsim_tui.core.interop.urdf_rounding.ROUNDING` with which the robot
still passes the check (:data:`~dhsim_tui.core.interop.urdf_rounding.ROUND_TOL`), so
``alpha = 90.0000000118`` from a rounded π/2 becomes 90. Limits do not
enter the forward kinematics: each becomes the shortest decimal within
:data:`~dhsim_tui.core.interop.urdf_rounding.LIMIT_ROUNDING` (relative) of the
URDF's radians or metres converted (2.8 rad is 160.4281826 deg).

A URDF that ``dhsim export`` wrote holds the robot it came from in a
``dhsim-robot`` comment (:mod:`dhsim_tui.core.interop.urdf_export`). When that robot
still matches the URDF (the same joints, kinds and limits, and the same
forward kinematics by the check above), the import gives it back exactly:
name, unit, convention, D-H table, base, tool and named poses. When it does
not (someone edited the URDF since) or cannot be read, the URDF is imported
as any other, with a note saying why.

Each step has its module: the check in :mod:`~dhsim_tui.core.interop.urdf_check`,
the restored robot in :mod:`~dhsim_tui.core.interop.urdf_restore`, nearly
parallel axes in :mod:`~dhsim_tui.core.interop.urdf_axes` and the rounding in
:mod:`~dhsim_tui.core.interop.urdf_rounding`; this one reads the chain and
builds the robot from the D-H frames.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from dhsim_tui.core.interop.convert import parts, tidy
from dhsim_tui.core.interop.dh_chain import DHChain
from dhsim_tui.core.interop.imported import ImportResult, check_choice, quoted
from dhsim_tui.core.interop.urdf import read_chain
from dhsim_tui.core.interop.urdf_axes import (
    LENGTH_TRY,
    AxisPlan,
    arm_size,
    axis_pairs,
    pair_notes,
    refusal_message,
)
from dhsim_tui.core.interop.urdf_chain import UrdfChain
from dhsim_tui.core.interop.urdf_check import UrdfReference, checked_note, joint_name_lines
from dhsim_tui.core.interop.urdf_restore import restore_stored_robot
from dhsim_tui.core.interop.urdf_rounding import rounded_limits, rounded_robot, rounding_notes
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import CONVENTIONS, UNITS, Joint, Robot, Tool
from dhsim_tui.core.model.text import printable, shortened
from dhsim_tui.core.model.units import min_length
from dhsim_tui.core.model.validation import fmt

#: an angle this close to a multiple of 90° (but not on it) gets a note
NEAR_ROUND_DEG = 1e-5
#: a longer robot name (the URDF's) is cut in the middle (a note says so)
MAX_NAME = 200
UNIT_NAMES = {"mm": "millimetres", "cm": "centimetres", "m": "metres", "in": "inches"}


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
    if convention is not None:
        check_choice(convention, CONVENTIONS, "--convention", source)
    if units is not None:
        check_choice(units, tuple(UNITS), "--units", source)
    chain = read_chain(text, tip=tip, base=base, source=source)
    remarks: list[str] = []
    if chain.stored is not None:
        restored = restore_stored_robot(chain, source, convention, units, name)
        if isinstance(restored, ImportResult):
            return restored
        remarks.append(restored)
    result = _import(chain, source, convention or "standard", units or "m", name)
    return replace(result, notes=(*(printable(r) for r in remarks), *result.notes))


# -- any URDF: D-H frames on its axes ------------------------------------------------------


def _import(
    chain: UrdfChain, source: str, convention: str, units: str, name: str | None
) -> ImportResult:
    lines = chain.joint_lines()
    tip_home = chain.tip_home()
    pairs = axis_pairs(lines, tip_home)
    scale = 1000.0 / UNITS[units]  # metres -> units
    limits = [rounded_limits(j, scale) for j in chain.moving]
    homes = [0.0 if low <= 0.0 <= high else (low + high) / 2 for low, high in limits]
    kinds = [j.kind for j in chain.moving]
    reference = UrdfReference(
        chain,
        [lo for lo, _ in limits],
        [hi for _, hi in limits],
        homes,
        [kind == "revolute" for kind in kinds],
        units,
    )
    robot_name, cut = _robot_name(name, chain, source)

    def build(values: list[float]) -> Robot:
        return _assemble(values, kinds, limits, homes, units, convention, robot_name)

    size = arm_size(lines, tip_home)
    every, far = AxisPlan(lines, LENGTH_TRY), AxisPlan(lines, LENGTH_TRY)
    every.take_pairs_as_parallel(tip_home, size, far_only=False)
    far.take_pairs_as_parallel(tip_home, size, far_only=True)
    plans = [every] if every.parallel else []
    if far.parallel and far.parallel != every.parallel:
        plans.append(far)
    plans.append(AxisPlan(lines))

    def attempt(plan: AxisPlan) -> tuple[Robot, AxisPlan, list[float], list[bool]] | str:
        """The plan's robot and numbers if it passes the check, else why not."""
        values, lengths = _values(plan.extract(tip_home, convention), units)
        try:
            robot = build(values)
        except DhsimError as exc:
            return f"the D-H robot is not valid: {exc}"
        position, rotation = reference.difference(robot)
        if reference.matches(position, rotation):
            return robot, plan, values, lengths
        return f"the tool is off by {position:.1e} m, {rotation:.1e} rad"

    chosen: tuple[Robot, AxisPlan, list[float], list[bool]] | None = None
    failures = []
    for plan in plans:
        outcome = attempt(plan)
        if isinstance(outcome, str):
            failures.append(outcome)
        else:
            chosen = outcome
            break
    if chosen is None:
        raise DhsimError(printable(f"{source}: {refusal_message(pairs, failures)}"))
    # the pairs not all taken as parallel at once: each one that keeps the match
    for number in sorted(every.parallel - chosen[1].parallel):
        outcome = attempt(chosen[1].with_pair(number))
        if not isinstance(outcome, str):
            chosen = outcome
    robot, plan, values, lengths = chosen
    robot, eps = rounded_robot(robot, values, lengths, units, build, reference)
    position, rotation = reference.difference(robot)
    notes = [
        f"{robot.dof} joints from link {quoted(chain.base, 60)} to link "
        f"{quoted(chain.tip, 60)}, {convention} D-H, lengths in {units}",
        checked_note(position, rotation),
        *rounding_notes(eps),
        *pair_notes(pairs, plan.parallel, lines, tip_home),
        *_near_round(robot),
        *([f"the robot's name is cut to {MAX_NAME} characters"] if cut else []),
    ]
    header = (
        f"Imported by dhsim from {Path(source).name} "
        f"({shortened(printable(chain.name)) or 'no name'}): link {shortened(chain.base)} to "
        f"link {shortened(chain.tip)}, {convention} D-H.",
        f"Joint values equal the URDF's ({_unit_words(units)}): D-H variable = q + offset.",
        *joint_name_lines(chain),
    )
    return ImportResult(
        robot, tuple(printable(n) for n in notes), tuple(printable(h) for h in header)
    )


def _robot_name(name: str | None, chain: UrdfChain, source: str) -> tuple[str, bool]:
    """The robot's name (given, the URDF's, the file's) and whether it was cut."""
    text = printable(name or chain.name or Path(source).stem or "imported robot").strip()
    cut = shortened(text, MAX_NAME)
    return cut or "imported robot", cut != text


def _unit_words(units: str) -> str:
    if units == "m":
        return "degrees instead of radians; lengths in metres, as in the URDF"
    return f"degrees instead of radians, {UNIT_NAMES[units]} instead of metres"


def _values(dh: DHChain, units: str) -> tuple[list[float], list[bool]]:
    """The numbers of a D-H chain's geometry, in robot units and degrees, and
    which are lengths: per joint its fixed angle or offset angle (theta of a
    prismatic joint, the offset of a revolute one), its d or offset length,
    a and alpha; then base xyz and rpy, tool xyz and rpy. Rounding noise is
    gone (12 digits); a length below a nanometre, which a robot cannot hold,
    is 0."""
    scale = 1000.0 / UNITS[units]
    size = _dh_size(dh) * scale
    floor = min_length(units)

    def length(value: float) -> float:
        value = tidy(value * scale, size)
        return 0.0 if abs(value) < floor else value

    values: list[float] = []
    lengths: list[bool] = []
    for row in dh.rows:
        theta, alpha = (tidy(math.degrees(v), 360.0) for v in (row.theta, row.alpha))
        values += [theta, length(row.d), length(row.a), alpha]
        lengths += [False, True, True, False]
    for matrix in (dh.base, dh.tool):
        xyz, rpy = _parts(matrix, scale, size, units)
        values += [*xyz, *rpy]
        lengths += [True, True, True, False, False, False]
    return values, lengths


def _assemble(
    values: list[float],
    kinds: list[str],
    limits: list[tuple[float, float]],
    homes: list[float],
    units: str,
    convention: str,
    name: str,
) -> Robot:
    """The robot of :func:`_values`' numbers, joint limits and homes."""
    joints = []
    for i, (kind, (low, high), home) in enumerate(zip(kinds, limits, homes, strict=True)):
        angle, length, a, alpha = values[4 * i : 4 * i + 4]
        if kind == "revolute":
            theta, d, offset = angle + home, length, angle
        else:
            theta, d, offset = angle, length + home, length
        joints.append(Joint(kind, theta, d, a, alpha, low, high, offset))  # type: ignore[arg-type]
    rest = values[4 * len(kinds) :]
    base_xyz, base_rpy, tool_xyz, tool_rpy = (tuple(rest[k : k + 3]) for k in (0, 3, 6, 9))
    return Robot(
        name=name,
        joints=tuple(joints),
        units=units,
        convention=convention,
        base_height=max(0.0, -base_xyz[2]),
        base_xyz=base_xyz,  # type: ignore[arg-type]
        base_rpy=base_rpy,  # type: ignore[arg-type]
        tool=Tool(tool_xyz, tool_rpy),  # type: ignore[arg-type]
    )


def _parts(matrix: np.ndarray, scale: float, size: float, units: str) -> tuple[tuple, tuple]:
    scaled = matrix.copy()
    scaled[:3, 3] *= scale
    return parts(scaled, size, units)


def _dh_size(dh: DHChain) -> float:
    lengths = [abs(r.a) + abs(r.d) for r in dh.rows]
    lengths += [float(np.linalg.norm(dh.base[:3, 3])), float(np.linalg.norm(dh.tool[:3, 3]))]
    return max([1e-9, *lengths])


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

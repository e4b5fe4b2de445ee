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
to its mean direction (:class:`_Plan`): every pair less than
:data:`PARALLEL_TRY` from parallel, then only those whose common normal lies
far off the arm. The first of these D-H tables that passes the check is kept
(a note names the pairs); otherwise the axes are imported as the skew lines
they are, and the file is refused only when none of them passes.

Numbers are then rounded to the shortest decimals that keep the check: every
length and angle of the table, the base and the tool becomes the number with
the fewest significant digits within ``eps`` of it (metres for lengths,
radians for angles), for the coarsest ``eps`` of :data:`ROUNDING` with which
the robot still passes the check (:data:`ROUND_TOL`), so
``alpha = 90.0000000118`` from a rounded π/2 becomes 90. Limits do not
enter the forward kinematics: each becomes the shortest decimal within
:data:`LIMIT_ROUNDING` (relative) of the URDF's radians or metres
converted (2.8 rad is 160.4281826 deg).

A URDF that ``dhsim export`` wrote holds the robot it came from in a
``dhsim-robot`` comment (:mod:`dhsim_tui.core.interop.urdf_export`). When that robot
still matches the URDF (the same joints, kinds and limits, and the same
forward kinematics by the check above), the import gives it back exactly:
name, unit, convention, D-H table, base, tool and named poses. When it does
not (someone edited the URDF since) or cannot be read, the URDF is imported
as any other, with a note saying why.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from dhsim_tui.core.interop.convert import convert, parts, tidy
from dhsim_tui.core.interop.dh_extract import LENGTH_TOL, PARALLEL_TOL, DHChain, extract
from dhsim_tui.core.interop.imported import ImportResult, check_choice, quoted
from dhsim_tui.core.interop.urdf import DHSIM_COMMENT, UrdfChain, read_chain
from dhsim_tui.core.interop.urdf_export import STORED_FORMAT, STORED_JOINT_FIELDS, STORED_VERSION
from dhsim_tui.core.model.editing import set_units
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import CONVENTIONS, MAX_ABS, MAX_JOINTS, UNITS, Joint, Robot, Tool
from dhsim_tui.core.model.text import counted, printable, shortened
from dhsim_tui.core.model.units import min_length
from dhsim_tui.core.model.validation import fmt

#: the imported robot must match the URDF's forward kinematics this closely (m, rad)
MATCH_TOL = 1e-9
#: random joint vectors the import is checked at (seeded: the same every time)
CHECKS = 200
#: an angle this close to a multiple of 90° (but not on it) gets a note
NEAR_ROUND_DEG = 1e-5
#: consecutive axes whose angle's sine is below this (but not 0) get a note
NEAR_PARALLEL = 1e-3
#: consecutive axes whose angle's sine is below this are first tried as parallel:
#: what a rounded π/2 leaves (2e-10) is far below it, and a pair further off
#: turns the tool by more than the check allows
PARALLEL_TRY = 1e-8
#: with axes taken as parallel, lengths below this times the arm's size are 0
#: (two axes meant to be one, apart by the rounding of the URDF's numbers)
LENGTH_TRY = 1e-10
#: a common normal further than this many times the arm's size is far off it
FAR = 10.0
#: rounding tolerances tried, coarsest first (metres for lengths, radians for angles)
ROUNDING = (5e-10, 2e-10, 1e-10, 5e-11, 2e-11, 1e-11, 1e-12, 1e-13)
#: rounded numbers keep the match this close: the check's own tolerance
ROUND_TOL = MATCH_TOL
#: a limit becomes the shortest decimal this close (relative) to the URDF's
LIMIT_ROUNDING = 1e-9
#: the seed of the check's random joint values
SEED = 20101
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
        restored = _restore(chain, source, convention, units, name)
        if isinstance(restored, ImportResult):
            return restored
        remarks.append(restored)
    result = _import(chain, source, convention or "standard", units or "m", name)
    return replace(result, notes=(*(printable(r) for r in remarks), *result.notes))


# -- the check against the URDF ----------------------------------------------------------


class _Reference:
    """The URDF's tip poses at the check's joint vectors (the home and
    :data:`CHECKS` seeded random ones within the limits), computed once."""

    def __init__(
        self, chain: UrdfChain, lower, upper, home, revolute, units: str, count: int = CHECKS
    ) -> None:
        rng = np.random.default_rng(SEED)
        lower, upper = np.array(lower, dtype=float), np.array(upper, dtype=float)
        samples = (rng.uniform(lower, upper) for _ in range(count))
        self.qs = np.array([np.array(home, dtype=float), *samples])
        self.metres = UNITS[units] / 1000.0
        to_si = np.array([math.radians(1.0) if r else self.metres for r in revolute])
        self.theirs = np.array([chain.fk(q * to_si) for q in self.qs])

    @classmethod
    def of(cls, chain: UrdfChain, robot: Robot, count: int = CHECKS) -> _Reference:
        revolute = [j.is_revolute for j in robot.joints]
        return cls(chain, robot.lower, robot.upper, robot.home, revolute, robot.units, count)

    def difference(self, robot: Robot) -> tuple[float, float]:
        """The largest position (m) and rotation (rad) difference between the
        robot's tool pose and the URDF's tip pose."""
        ours = robot.kinematics.batch(self.qs)
        position = float(np.abs(ours[:, :3, 3] * self.metres - self.theirs[:, :3, 3]).max())
        rotation = float(np.abs(ours[:, :3, :3] - self.theirs[:, :3, :3]).max())
        return position, rotation


def max_difference(robot: Robot, chain: UrdfChain, count: int = CHECKS) -> tuple[float, float]:
    """The largest position (m) and rotation (rad) difference between the
    robot's tool pose and the URDF's tip pose, at home and at ``count``
    seeded random joint values within the limits."""
    return _Reference.of(chain, robot, count).difference(robot)


def _checked(position: float, rotation: float) -> str:
    return (
        f"checked at home and {CHECKS} random joint values: the tool's pose matches the "
        f"URDF to {position:.0e} m and {rotation:.0e} rad"
    )


# -- a URDF dhsim exported: the robot it stored ------------------------------------------


def _restore(
    chain: UrdfChain, source: str, convention: str | None, units: str | None, name: str | None
) -> ImportResult | str:
    """The robot stored in the file's dhsim comment, if it still matches the
    chain; else a remark saying why it was not used."""
    fallback = "imported from the URDF's joints alone"
    try:
        stored = _stored_robot(chain.stored or "")
    except DhsimError as exc:
        return (
            f"the robot dhsim stored in the file's {DHSIM_COMMENT} comment cannot be read "
            f"({shortened(str(exc))}); {fallback}"
        )
    why = _mismatch(stored, chain)
    if why is not None:
        return (
            f"the robot dhsim stored in the file ({quoted(stored.name, 60)}) does not match "
            f"its joints from link {quoted(chain.base, 60)} to link {quoted(chain.tip, 60)} "
            f"({why}; edited since dhsim exported it?): {fallback}"
        )
    robot = stored
    notes = [
        f"{counted(robot.dof, 'joint')} restored as dhsim exported them ({robot.convention} D-H, "
        f"lengths in {robot.units}, {len(robot.poses)} named poses)"
    ]
    try:
        if units is not None and units != robot.units:
            robot = set_units(robot, units)
            notes.append(f"lengths converted from {stored.units} to {units}")
        if convention is not None and convention != robot.convention:
            robot = convert(robot, convention)
            notes.append(f"converted from {stored.convention} to {convention} D-H (the same arm)")
        if name:
            robot = replace(robot, name=printable(name).strip() or robot.name)
    except DhsimError as exc:
        raise DhsimError(printable(f"{source}: {exc}")) from None
    position, rotation = _Reference.of(chain, robot).difference(robot)
    if position > MATCH_TOL or rotation > MATCH_TOL:  # a conversion lost the match
        raise DhsimError(
            printable(
                f"{source}: the restored robot, converted, is off the URDF by "
                f"{position:.1e} m, {rotation:.1e} rad"
            )
        )
    notes.append(_checked(position, rotation))
    header = (
        f"Imported by dhsim from {Path(source).name} ({shortened(robot.name)}): the robot "
        f"dhsim exported to it, restored from its {DHSIM_COMMENT} comment.",
        f"Checked against the URDF's joints from link {shortened(chain.base)} to link "
        f"{shortened(chain.tip)}: they still match.",
        *_joint_lines(chain),
    )
    return ImportResult(
        robot, tuple(printable(n) for n in notes), tuple(printable(h) for h in header)
    )


def _stored_robot(text: str) -> Robot:
    """The robot of a ``dhsim-robot`` comment: dhsim's JSON export of it."""
    start = text.find("{")
    if start < 0:
        raise DhsimError("it holds no JSON object")
    try:
        data, end = json.JSONDecoder().raw_decode(text, start)
    except (ValueError, RecursionError) as exc:
        raise DhsimError(f"not valid JSON: {exc}") from None
    if text[end:].strip():
        raise DhsimError("text follows its JSON object")
    if not isinstance(data, dict):
        raise DhsimError("its JSON is not an object")
    if data.get("format") != STORED_FORMAT or data.get("version") != STORED_VERSION:
        raise DhsimError(f"it is not format {STORED_FORMAT!r} version {STORED_VERSION}")
    if data.get("parameter_order") != list(STORED_JOINT_FIELDS):
        raise DhsimError(f"parameter_order: expected {list(STORED_JOINT_FIELDS)}")
    units, base, tool = (_object(data, key) for key in ("units", "base", "tool"))
    if units.get("angle") != "deg":
        raise DhsimError("units.angle: expected 'deg'")
    joints = data.get("joints")
    if not isinstance(joints, list) or not 1 <= len(joints) <= MAX_JOINTS:
        raise DhsimError(f"joints: expected a list of 1 to {MAX_JOINTS} joints")
    poses = _object(data, "poses")
    rows = []
    for number, joint in enumerate(joints, start=1):
        if not isinstance(joint, dict):
            raise DhsimError(f"joints[{number}]: expected an object")
        missing = [key for key in ("type", *STORED_JOINT_FIELDS) if key not in joint]
        if missing:
            raise DhsimError(f"joints[{number}]: no {', '.join(missing)}")
        values = {key: _number(joint[key]) for key in STORED_JOINT_FIELDS}
        rows.append(Joint(type=joint["type"], **values))
    return Robot(
        name=data.get("name"),  # type: ignore[arg-type]
        joints=tuple(rows),
        units=units.get("length"),  # type: ignore[arg-type]
        convention=data.get("convention"),  # type: ignore[arg-type]
        base_height=_number(base.get("height")),  # type: ignore[arg-type]
        base_z=base.get("z"),  # type: ignore[arg-type]
        base_x=base.get("x"),  # type: ignore[arg-type]
        base_xyz=_numbers(base.get("xyz")),  # type: ignore[arg-type]
        base_rpy=_numbers(base.get("rpy")),  # type: ignore[arg-type]
        tool=Tool(_numbers(tool.get("xyz")), _numbers(tool.get("rpy"))),  # type: ignore[arg-type]
        poses=tuple((key, _numbers(values)) for key, values in poses.items()),  # type: ignore[misc]
    )


def _object(data: dict, key: str) -> dict:
    value = data.get(key)
    if not isinstance(value, dict):
        raise DhsimError(f"{key}: expected an object")
    return value


def _number(value: object) -> object:
    """A JSON number as a float; anything else as it is, for the robot's own
    checks to name (a huge integer stays one: float() would overflow)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return value
    return float(value) if isinstance(value, float) or abs(value) <= MAX_ABS else value


def _numbers(values: object) -> object:
    if not isinstance(values, list):
        return values
    return tuple(_number(v) for v in values)


def _mismatch(robot: Robot, chain: UrdfChain) -> str | None:
    """What differs between the stored robot and the URDF's chain, or None."""
    moving = chain.moving
    if len(moving) != robot.dof:
        return f"{len(moving)} moving joints, the stored robot has {robot.dof}"
    metres = UNITS[robot.units] / 1000.0
    for number, (joint, theirs) in enumerate(zip(robot.joints, moving, strict=True), start=1):
        if joint.type != theirs.kind:
            return f"joint {number} is {theirs.kind} in the URDF, {joint.type} in the robot"
        scale = math.radians(1.0) if joint.is_revolute else metres
        ours = (joint.min * scale, joint.max * scale)
        if not all(
            math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
            for a, b in zip(ours, (theirs.lower, theirs.upper), strict=True)
        ):
            return f"joint {number}'s limits differ"
    position, rotation = _Reference.of(chain, robot).difference(robot)
    if position > MATCH_TOL or rotation > MATCH_TOL:
        return f"the tool is off by {position:.1e} m and {rotation:.1e} rad"
    return None


# -- any URDF: D-H frames on its axes ------------------------------------------------------


def _import(
    chain: UrdfChain, source: str, convention: str, units: str, name: str | None
) -> ImportResult:
    lines = chain.joint_lines()
    tip_home = chain.tip_home()
    pairs = _pairs(lines, tip_home)
    scale = 1000.0 / UNITS[units]  # metres -> units
    limits = [_limits(j, scale) for j in chain.moving]
    homes = [0.0 if low <= 0.0 <= high else (low + high) / 2 for low, high in limits]
    kinds = [j.kind for j in chain.moving]
    reference = _Reference(
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

    size = _size(lines, tip_home)
    every, far = _Plan(lines, LENGTH_TRY), _Plan(lines, LENGTH_TRY)
    every.take_pairs_as_parallel(tip_home, size, far_only=False)
    far.take_pairs_as_parallel(tip_home, size, far_only=True)
    plans = [every] if every.parallel else []
    if far.parallel and far.parallel != every.parallel:
        plans.append(far)
    plans.append(_Plan(lines))

    def attempt(plan: _Plan) -> tuple[Robot, _Plan, list[float], list[bool]] | str:
        """The plan's robot and numbers if it passes the check, else why not."""
        values, lengths = _values(plan.extract(tip_home, convention), units)
        try:
            robot = build(values)
        except DhsimError as exc:
            return f"the D-H robot is not valid: {exc}"
        position, rotation = reference.difference(robot)
        if position <= MATCH_TOL and rotation <= MATCH_TOL:
            return robot, plan, values, lengths
        return f"the tool is off by {position:.1e} m, {rotation:.1e} rad"

    chosen: tuple[Robot, _Plan, list[float], list[bool]] | None = None
    failures = []
    for plan in plans:
        outcome = attempt(plan)
        if isinstance(outcome, str):
            failures.append(outcome)
        else:
            chosen = outcome
            break
    if chosen is None:
        raise DhsimError(printable(f"{source}: {_refusal(pairs, failures)}"))
    # the pairs not all taken as parallel at once: each one that keeps the match
    for number in sorted(every.parallel - chosen[1].parallel):
        outcome = attempt(chosen[1].with_pair(number))
        if not isinstance(outcome, str):
            chosen = outcome
    robot, plan, values, lengths = chosen
    robot, eps = _round(robot, values, lengths, units, build, reference)
    position, rotation = reference.difference(robot)
    notes = [
        f"{robot.dof} joints from link {quoted(chain.base, 60)} to link "
        f"{quoted(chain.tip, 60)}, {convention} D-H, lengths in {units}",
        _checked(position, rotation),
        *_rounding_notes(eps),
        *_pair_notes(pairs, plan.parallel, lines, tip_home),
        *_near_round(robot),
        *([f"the robot's name is cut to {MAX_NAME} characters"] if cut else []),
    ]
    header = (
        f"Imported by dhsim from {Path(source).name} "
        f"({shortened(printable(chain.name)) or 'no name'}): link {shortened(chain.base)} to "
        f"link {shortened(chain.tip)}, {convention} D-H.",
        f"Joint values equal the URDF's ({_unit_words(units)}): D-H variable = q + offset.",
        *_joint_lines(chain),
    )
    return ImportResult(
        robot, tuple(printable(n) for n in notes), tuple(printable(h) for h in header)
    )


def _round(
    robot: Robot,
    values: list[float],
    lengths: list[bool],
    units: str,
    build,
    reference: _Reference,
) -> tuple[Robot, list[float]]:
    """The robot with its numbers rounded (see the module's docstring), and
    each number's rounding tolerance (0: not rounded): all of them at the
    coarsest of :data:`ROUNDING` that keeps the match, then, one at a time,
    each number that would be shorter at the coarsest by itself."""
    # up to ROUND_TOL, or to the unrounded robot's own difference if that is more
    budget = [max(ROUND_TOL, v) for v in reference.difference(robot)]

    def passing(candidate: list[float]) -> Robot | None:
        try:
            built = build(candidate)
        except DhsimError:
            return None
        position, rotation = reference.difference(built)
        return built if position <= budget[0] and rotation <= budget[1] else None

    eps = [0.0] * len(values)
    current = values
    for level in ROUNDING:
        trial = [level] * len(values)
        rounded = _rounded(values, lengths, trial, units)
        built = passing(rounded)
        if built is not None:
            robot, eps, current = built, trial, rounded
            break
    coarsest = ROUNDING[0]
    for i, (value, is_length) in enumerate(zip(values, lengths, strict=True)):
        if eps[i] == coarsest:
            continue
        alone = _rounded([value], [is_length], [coarsest], units)[0]
        if alone == current[i]:
            continue
        candidate = [*current[:i], alone, *current[i + 1 :]]
        built = passing(candidate)
        if built is not None:
            robot, current = built, candidate
            eps[i] = coarsest
    return robot, eps


def _robot_name(name: str | None, chain: UrdfChain, source: str) -> tuple[str, bool]:
    """The robot's name (given, the URDF's, the file's) and whether it was cut."""
    text = printable(name or chain.name or Path(source).stem or "imported robot").strip()
    cut = shortened(text, MAX_NAME)
    return cut or "imported robot", cut != text


def _unit_words(units: str) -> str:
    if units == "m":
        return "degrees instead of radians; lengths in metres, as in the URDF"
    return f"degrees instead of radians, {UNIT_NAMES[units]} instead of metres"


def _joint_lines(chain: UrdfChain) -> list[str]:
    return [
        f"joint {i}: {shortened(printable(j.name))} ({j.kind})"
        for i, j in enumerate(chain.moving, start=1)
    ]


def _limits(joint, scale: float) -> tuple[float, float]:
    """The URDF joint's limits in degrees or robot units, each the shortest
    decimal within :data:`LIMIT_ROUNDING` of the exact conversion."""
    if joint.kind == "revolute":
        values = (math.degrees(joint.lower), math.degrees(joint.upper))
    else:
        values = (joint.lower * scale, joint.upper * scale)
    return (
        _shortest(values[0], LIMIT_ROUNDING * abs(values[0])),
        _shortest(values[1], LIMIT_ROUNDING * abs(values[1])),
    )


def _shortest(value: float, tol: float) -> float:
    """The number with the fewest significant digits within ``tol`` of ``value``."""
    if abs(value) <= tol:
        return 0.0
    for digits in range(1, 18):
        candidate = float(f"{value:.{digits - 1}e}")
        if abs(candidate - value) <= tol:
            return candidate
    return value


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


def _rounded(values: list[float], lengths: list[bool], eps: list[float], units: str) -> list[float]:
    """Each number the shortest decimal within its ``eps`` (metres for a
    length, radians for an angle; 0: as it is); a length below a nanometre is 0."""
    scale = 1000.0 / UNITS[units]
    floor = min_length(units)
    out = []
    for value, is_length, tol in zip(values, lengths, eps, strict=True):
        if not tol:
            out.append(value)
        elif is_length:
            rounded = _shortest(value, tol * scale)
            out.append(0.0 if abs(rounded) < floor else rounded)
        else:
            out.append(_shortest(value, math.degrees(tol)))
    return out


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


# -- nearly parallel axes --------------------------------------------------------------------

#: (first joint, sine of the angle, distance to the common normal, last joint or None: the tip)
_Pair = tuple[int, float, float, int | None]


def _pairs(lines, tip_home: np.ndarray) -> list[_Pair]:
    """Each consecutive pair of axes, the last joint's with the tip's z axis:
    the sine of their angle and how far along the first axis their common
    normal lies (inf when parallel)."""
    axes = [(p, w) for _, p, w in lines] + [(tip_home[:3, 3], tip_home[:3, 2])]
    out = []
    for i in range(len(axes) - 1):
        (p1, w1), (p2, w2) = axes[i], axes[i + 1]
        cross = np.cross(w1, w2)
        sine = float(np.linalg.norm(cross))
        far = float(np.cross(p2 - p1, w2) @ cross) / sine**2 if sine else math.inf
        last = i + 2 if i + 2 <= len(lines) else None
        out.append((i + 1, sine, abs(far), last))
    return out


def _size(lines, tip_home: np.ndarray) -> float:
    """A length the size of the arm (m): its farthest axis point or the tip."""
    points = [tip_home[:3, 3], *(p for _, p, _ in lines)]
    return max(1e-3, *(float(np.linalg.norm(p)) for p in points))


class _Plan:
    """Which consecutive axes to take as parallel (``parallel``: the number of
    each pair's first joint; the last joint's pairs it with the tip's z axis),
    and the axis lines that makes: each run of joints taken as parallel turns
    to the mean of its directions, so each joint's axis is off by at most half
    the run's spread; the tip's z axis is left alone (the tool frame takes up
    the difference, exactly)."""

    def __init__(self, lines, length_tol: float = LENGTH_TOL) -> None:
        self.source = list(lines)
        self.lines = list(lines)
        self.parallel: set[int] = set()
        self.length_tol = length_tol

    def with_pair(self, number: int) -> _Plan:
        """This plan with the pair after joint ``number`` taken as parallel too."""
        plan = _Plan(self.source, LENGTH_TRY)
        plan.parallel = {*self.parallel, number}
        plan._snap()
        return plan

    def extract(self, tip_home: np.ndarray, convention: str) -> DHChain:
        last = {len(self.lines)} & self.parallel
        return extract(self.lines, tip_home, convention, parallel=last, length_tol=self.length_tol)

    def take_pairs_as_parallel(self, tip_home: np.ndarray, size: float, far_only: bool) -> None:
        """Take as parallel, one at a time from the base, each pair of axes
        less than :data:`PARALLEL_TRY` from parallel (as the frames before it
        place it), or only those whose common normal lies more than
        :data:`FAR` times the arm's size away (where D-H puts a huge d)."""
        for _ in range(len(self.lines) + 1):
            rows = self.extract(tip_home, "standard").rows
            found = [
                number
                for number, row in enumerate(rows, start=1)
                if number not in self.parallel
                and PARALLEL_TOL <= abs(math.sin(row.alpha)) < PARALLEL_TRY
                and (abs(row.d) > FAR * size or not far_only)
            ]
            if not found:
                return
            self.parallel.add(found[0])
            self._snap()

    def _snap(self) -> None:
        """Each run of joints in ``parallel`` pairs to its mean direction."""
        self.lines = list(self.source)
        runs: list[list[int]] = []
        for first in sorted(n for n in self.parallel if n < len(self.source)):
            if runs and runs[-1][-1] == first - 1:
                runs[-1].append(first)
            else:
                runs.append([first - 1, first])  # joint indices from 0
        for run in runs:
            reference = self.source[run[0]][2]
            signs = [1.0 if float(self.source[i][2] @ reference) >= 0 else -1.0 for i in run]
            mean = sum(sign * self.source[i][2] for sign, i in zip(signs, run, strict=True))
            mean = mean / np.linalg.norm(mean)
            for sign, i in zip(signs, run, strict=True):
                kind, point, _ = self.source[i]
                self.lines[i] = (kind, point, sign * mean)


def _refusal(pairs: list[_Pair], failures: list[str]) -> str:
    """Why no D-H table passed: what the skew (last) try gave, the nearly
    parallel pair whose common normal lies farthest, and what taking pairs
    as parallel gave, if that was tried."""
    near = [pair for pair in pairs if PARALLEL_TOL <= pair[1] < NEAR_PARALLEL]
    skew = failures[-1]
    if skew.startswith("the tool"):
        skew = f"no D-H table reproduces this chain to 1e-9 ({skew})"
    if not near:
        return skew
    worst = max(near, key=lambda pair: pair[2])
    if len(failures) == 1:
        return f"{skew}; {_skew_note(worst)}"
    return (
        f"no D-H table reproduces this chain to 1e-9: {_skew_note(worst)}; taken as "
        f"parallel, {failures[0].removeprefix('the D-H robot is not valid: ')}, and as skew "
        f"lines, {failures[-1].removeprefix('the D-H robot is not valid: ')}"
    )


def _pair_name(pair: _Pair) -> str:
    first, _, _, last = pair
    if last is None:
        return f"the axis of joint {first} and the tip link's z axis are"
    return f"the axes of joints {first} and {last} are"


def _skew_note(pair: _Pair) -> str:
    _, sine, far, _ = pair
    return (
        f"{_pair_name(pair)} {math.asin(sine):.1e} rad from parallel, so their common "
        f"normal lies about {far:.0e} m away"
    )


def _pair_notes(
    pairs: list[_Pair], parallel: frozenset[int], lines, tip_home: np.ndarray
) -> list[str]:
    """Nearly parallel pairs: taken as parallel, or kept skew with their
    common normal far off the arm."""
    size = _size(lines, tip_home)
    notes = []
    for pair in pairs:
        first, sine, far, _ = pair
        if first in parallel and sine >= PARALLEL_TOL:
            notes.append(
                f"{_pair_name(pair)} {math.asin(sine):.1e} rad from parallel (a rounded "
                "angle in the URDF?): imported as parallel, which keeps the match"
            )
        elif first not in parallel and PARALLEL_TOL <= sine < NEAR_PARALLEL and far > FAR * size:
            notes.append(_skew_note(pair))
    return notes


def _rounding_notes(eps: list[float]) -> list[str]:
    used = [e for e in eps if e]
    if not used:
        return []
    within = f"{max(used):.0e}" if min(used) == max(used) else f"{min(used):.0e} to {max(used):.0e}"
    return [
        f"numbers rounded to the fewest digits that keep that match (each within {within} "
        f"m or rad); limits to {LIMIT_ROUNDING:.0e} of the URDF's, relative"
    ]


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

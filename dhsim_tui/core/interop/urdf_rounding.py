"""Numbers of a robot imported from a URDF rounded to the shortest decimals
that keep the check (:mod:`dhsim_tui.core.interop.urdf_import`): every
length and angle of the D-H table, the base and the tool becomes the number
with the fewest significant digits within ``eps`` of it (metres for lengths,
radians for angles), for the coarsest ``eps`` of :data:`ROUNDING` with which
the robot still passes the check (:data:`ROUND_TOL`); a limit becomes the
shortest decimal within :data:`LIMIT_ROUNDING` (relative) of the URDF's
radians or metres converted.
"""

from __future__ import annotations

import math

from dhsim_tui.core.interop.urdf_check import MATCH_TOL, UrdfReference
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import UNITS, Robot
from dhsim_tui.core.model.units import min_length

#: rounding tolerances tried, coarsest first (metres for lengths, radians for angles)
ROUNDING = (5e-10, 2e-10, 1e-10, 5e-11, 2e-11, 1e-11, 1e-12, 1e-13)
#: rounded numbers keep the match this close: the check's own tolerance
ROUND_TOL = MATCH_TOL
#: a limit becomes the shortest decimal this close (relative) to the URDF's
LIMIT_ROUNDING = 1e-9


def rounded_robot(
    robot: Robot,
    values: list[float],
    lengths: list[bool],
    units: str,
    build,
    reference: UrdfReference,
) -> tuple[Robot, list[float]]:
    """The robot with its numbers rounded (see the module's docstring), and
    each number's rounding tolerance (0: not rounded): all of them at the
    coarsest of :data:`ROUNDING` that keeps the match, then, one at a time,
    each number that would be shorter at the coarsest by itself."""
    # up to ROUND_TOL, or to the unrounded robot's own difference if that is more
    allowed = (reference.position_tol - MATCH_TOL + ROUND_TOL, ROUND_TOL)
    budget = [max(tol, v) for tol, v in zip(allowed, reference.difference(robot), strict=True)]

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


def rounded_limits(joint, scale: float) -> tuple[float, float]:
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


def rounding_notes(eps: list[float]) -> list[str]:
    """The note on how far the numbers were rounded (none if none was)."""
    used = [e for e in eps if e]
    if not used:
        return []
    within = f"{max(used):.0e}" if min(used) == max(used) else f"{min(used):.0e} to {max(used):.0e}"
    return [
        f"numbers rounded to the fewest digits that keep that match (each within {within} "
        f"m or rad); limits to {LIMIT_ROUNDING:.0e} of the URDF's, relative"
    ]

"""Why an inverse-kinematics solve failed, read off the state it ended in.

A failed solve stops where no joint can lower the error any more. What
stopped it is a fact of that state:

* **a limit**: a joint sits on one of its limits and the direction that would
  lower the error pushes it further in (the gradient ``Jᵀe`` at that joint
  points past the limit, while the free joints have nothing left to give);
* **a lost direction**: no joint moves the tool along the error at all (the
  Jacobian's smallest task singular value is ~0 along it). If the target can
  be reached from elsewhere this is a singularity here; if not, the target is
  out of reach (or the arm cannot turn its tool that way);
* **no joint for it**: the error lies in a direction the arm can never move
  (a SCARA asked to tilt, a planar arm asked to leave its plane);
* otherwise the solve ran out of iterations.

Numbers are rounded as people read them (:func:`amount`): never ``5e-14 mm``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dhsim_tui.core.model.robot import Robot
from dhsim_tui.core.model.units import LENGTH_DECIMALS

#: decimals shown for angles in degrees
ANGLE_DECIMALS = 2
#: a joint on a limit blocks when the error's gradient along it is at least
#: this share of what that joint could do (|column| · |error|)
PUSH = 1e-2
#: a direction is lost when the normalised Jacobian's singular value along it
#: is below this (a healthy arm has values of order 0.1 to 1)
LOST_SIGMA = 0.05
#: ...and the error has at least this share along the lost directions
LOST_SHARE = 0.1
#: a joint is on its limit within this (radians, or reach fractions)
ON_LIMIT = 1e-9

#: causes: what :func:`diagnose` finds, then LOST told apart as SINGULAR
#: (reachable from elsewhere) or OUT_OF_REACH
LIMIT = "limit"
LOST = "lost"
NO_JOINT = "no joint"
STOPPED = "stopped"
SINGULAR = "singular"
OUT_OF_REACH = "out of reach"
CAUSES = (LIMIT, NO_JOINT, STOPPED, SINGULAR, OUT_OF_REACH)


def amount(value: float, decimals: int) -> str:
    """``value`` to ``decimals`` places, trailing zeros dropped; a value too
    small to show there gets two significant digits (``0.00052``), and one
    below 1e-12 is ``0``. Never an exponent, never ``nan``."""
    if not math.isfinite(value):
        return "an unknown amount"  # guarded upstream; never print "nan"
    size = abs(value)
    if size < 1e-12:
        return "0"
    places = decimals
    if size < 10.0**-decimals:
        places = min(13, 1 - math.floor(math.log10(size)))
    text = f"{value:.{places}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return text


def length(robot: Robot, value: float) -> str:
    return f"{amount(value, LENGTH_DECIMALS.get(robot.units, 4))} {robot.units}"


def angle(radians: float) -> str:
    return f"{amount(math.degrees(radians), ANGLE_DECIMALS)} deg"


def limit_value(robot: Robot, index: int, high: bool) -> str:
    """A joint's limit as written in its file (``304.8 mm``, ``-50 deg``)."""
    joint = robot.joints[index]
    value = joint.max if high else joint.min
    return f"{value:.12g} {joint.unit(robot.units)}"


def at_limits(robot: Robot, limited: tuple[tuple[int, bool], ...]) -> str:
    """``d3 is at its limit 304.8 mm``; several: ``Th1 and Th5 are at their
    limits (-50 deg, 100 deg)``."""
    names = [robot.labels[i] for i, _ in limited]
    values = [limit_value(robot, i, high) for i, high in limited]
    if len(names) == 1:
        return f"{names[0]} is at its limit {values[0]}"
    joined = ", ".join(names[:-1]) + f" and {names[-1]}"
    return f"{joined} are at their limits ({', '.join(values)})"


@dataclass(frozen=True)
class Diagnosis:
    cause: str  # LIMIT, LOST, NO_JOINT or STOPPED
    #: joints pinned at a limit that block: (index, True for the upper limit)
    limited: tuple[tuple[int, bool], ...] = ()


def diagnose(
    jac: np.ndarray,
    error: np.ndarray,
    rows: np.ndarray,
    x: np.ndarray,
    low: np.ndarray,
    high: np.ndarray,
    rank: int,
    weight: np.ndarray | None = None,
) -> Diagnosis:
    """What stopped a solve at joint vector ``x`` (internal units).

    ``jac`` (6×n) and ``error`` (6) are dimensionless; ``rows`` are the
    directions the solve worked on; ``weight`` the row weights it used (the
    limit test follows the weighted problem the solve minimised); ``rank``
    the number of directions the arm moves in general."""
    with np.errstate(all="ignore"):
        w = np.ones(6) if weight is None else weight
        jac_rows, e_rows = jac[rows], error[rows]
        size = float(np.linalg.norm(error))
        if size == 0.0 or not np.isfinite(size):
            return Diagnosis(STOPPED)
        if float(np.linalg.norm(e_rows)) < LOST_SHARE * size:
            return Diagnosis(NO_JOINT)  # nearly all the error is where no joint moves
        gradient = (jac_rows * w[rows, None] ** 2).T @ e_rows  # descent direction of ½|We|²
        reach = np.linalg.norm(jac_rows, axis=0) * float(np.linalg.norm(e_rows))
        push = np.divide(gradient, reach, out=np.zeros_like(gradient), where=reach > 1e-300)
        on_low = x <= low + ON_LIMIT
        on_high = x >= high - ON_LIMIT
        blocking = (on_low & (push < -PUSH)) | (on_high & (push > PUSH))
        if blocking.any():
            limited = tuple((int(i), bool(on_high[i])) for i in np.flatnonzero(blocking))
            return Diagnosis(LIMIT, limited)
        weak, never = _shares(jac_rows, e_rows, rank)
        if weak >= LOST_SHARE:
            return Diagnosis(LOST)
        if never >= LOST_SHARE:
            return Diagnosis(NO_JOINT)  # more directions asked than the arm has joints for
        return Diagnosis(STOPPED)


def _shares(jac_rows: np.ndarray, e_rows: np.ndarray, rank: int) -> tuple[float, float]:
    """The shares of ``e_rows`` along the directions the arm has lost here
    (singular values below LOST_SIGMA among the first ``rank``) and along those
    it never moves in (beyond ``rank``)."""
    size = float(np.linalg.norm(e_rows))
    if size == 0.0 or not np.isfinite(size) or not np.isfinite(jac_rows).all():
        return 0.0, 0.0
    u, sigma, _ = np.linalg.svd(jac_rows)
    keep = min(rank, len(sigma))
    weak = u[:, :keep][:, sigma[:keep] < LOST_SIGMA]
    never = u[:, keep:]
    return (
        float(np.linalg.norm(weak.T @ e_rows)) / size,
        float(np.linalg.norm(never.T @ e_rows)) / size,
    )


def lost_along(jac_rows: np.ndarray, e_rows: np.ndarray, rank: int) -> bool:
    """Whether motion ``e_rows`` lies (in part) along a direction the arm has lost here."""
    with np.errstate(all="ignore"):
        return _shares(jac_rows, e_rows, rank)[0] >= LOST_SHARE


def explain(
    robot: Robot,
    failed: str,
    cause: str,
    limited: tuple[tuple[int, bool], ...],
    position_error: float,
    orientation_error: float,
) -> str:
    """The reason of a failed solve, for ``dhsim ik``: the part that failed
    first, then why."""
    if failed == "orientation":
        head = f"position reached, but the orientation is {angle(orientation_error)} away"
        return f"{head}: {why_not_turned(robot, cause, limited)}"
    closest = f"closest found {length(robot, position_error)} away"
    if cause == LIMIT:
        return f"not reachable within the joint limits: {at_limits(robot, limited)}; {closest}"
    if cause == SINGULAR:
        return f"singular here: the arm can't move the tool that way from this pose ({closest})"
    if cause == NO_JOINT:
        return f"out of reach: no joint moves the tool that way ({closest})"
    if cause == OUT_OF_REACH:
        return f"out of reach ({closest})"
    return f"no solution found ({closest})"


def why_not_moved(robot: Robot, cause: str, limited: tuple[tuple[int, bool], ...]) -> str:
    """Why the tool's position can't go there (short: it fits a status line)."""
    if cause == LIMIT:
        return at_limits(robot, limited)
    if cause == SINGULAR:
        return "singular here: the arm can't move the tool that way from this pose"
    if cause == NO_JOINT:
        return "the arm has no joint that moves the tool that way"
    if cause == OUT_OF_REACH:
        return "out of reach"
    return "no solution found"


def why_not_turned(robot: Robot, cause: str, limited: tuple[tuple[int, bool], ...]) -> str:
    """Why the tool can't take that orientation (its position can be reached)."""
    if cause == LIMIT:
        return at_limits(robot, limited)
    if cause == SINGULAR:
        return "singular here: the arm can't turn the tool that way from this pose"
    if cause == NO_JOINT:
        return "this arm cannot turn the tool that way"
    if cause == OUT_OF_REACH:
        return "this arm cannot turn the tool that way here"
    return "no closer orientation found"

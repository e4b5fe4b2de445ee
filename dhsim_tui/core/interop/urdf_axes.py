"""Nearly parallel joint axes in a URDF (:mod:`dhsim_tui.core.interop.urdf_import`):
axes a hair from parallel (a URDF writing π/2 as ``1.570796327`` leaves
consecutive axes some 1e-10 rad apart; as skew lines their common normal
would lie ~1e9 m away) are tried as parallel, each run of them turned to
its mean direction (:class:`AxisPlan`): every pair less than
:data:`PARALLEL_TRY` from parallel, or only those whose common normal lies
more than :data:`FAR` times the arm's size away. Also the notes such pairs
get, and the words of a refusal when no D-H table passes the check.
"""

from __future__ import annotations

import math

import numpy as np

from dhsim_tui.core.interop.dh_chain import DHChain
from dhsim_tui.core.interop.dh_extract import LENGTH_TOL, PARALLEL_TOL, extract

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

#: (first joint, sine of the angle, distance to the common normal, last joint or None: the tip)
_Pair = tuple[int, float, float, int | None]


def axis_pairs(lines, tip_home: np.ndarray) -> list[_Pair]:
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


def arm_size(lines, tip_home: np.ndarray) -> float:
    """A length the size of the arm (m): its farthest axis point or the tip."""
    points = [tip_home[:3, 3], *(p for _, p, _ in lines)]
    return max(1e-3, *(float(np.linalg.norm(p)) for p in points))


class AxisPlan:
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

    def with_pair(self, number: int) -> AxisPlan:
        """This plan with the pair after joint ``number`` taken as parallel too."""
        plan = AxisPlan(self.source, LENGTH_TRY)
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


def refusal_message(pairs: list[_Pair], failures: list[str]) -> str:
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


def pair_notes(
    pairs: list[_Pair], parallel: frozenset[int], lines, tip_home: np.ndarray
) -> list[str]:
    """Nearly parallel pairs: taken as parallel, or kept skew with their
    common normal far off the arm."""
    size = arm_size(lines, tip_home)
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

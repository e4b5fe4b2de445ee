"""The check of a robot imported from a URDF against the URDF's own forward
kinematics (:mod:`dhsim_tui.core.interop.urdf_import`): the URDF's tip poses
at the home and at :data:`CHECKS` seeded random joint values
(:class:`UrdfReference`), the largest difference from the robot's tool pose,
the tolerance it must meet (:data:`MATCH_TOL`) and the note that reports it;
also the header's lines naming the chain's moving joints, which a restored
robot (:mod:`dhsim_tui.core.interop.urdf_restore`) and an imported one share.
"""

from __future__ import annotations

import math

import numpy as np

from dhsim_tui.core.interop.urdf_chain import UrdfChain
from dhsim_tui.core.model.robot import UNITS, Robot
from dhsim_tui.core.model.text import printable, shortened

#: the imported robot must match the URDF's forward kinematics this closely (m, rad)
MATCH_TOL = 1e-9
#: and in position, this much more per metre of the chain's size: a long arm
#: rounds off more (a 1 km tool came back off by 3e-12 of its length)
SIZE_TOL = 1e-11
#: random joint vectors the import is checked at (seeded: the same every time)
CHECKS = 200
#: the seed of the check's random joint values
SEED = 20101


class UrdfReference:
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
        #: how far the check allows the positions to differ (m)
        size = float(np.abs(self.theirs[:, :3, 3]).max())
        self.position_tol = MATCH_TOL + SIZE_TOL * size

    def matches(self, position: float, rotation: float, tol: float = MATCH_TOL) -> bool:
        """Whether differences (:meth:`difference`) meet the check: ``tol`` in
        rad, and in position ``tol`` m plus :data:`SIZE_TOL` per metre."""
        return position <= self.position_tol - MATCH_TOL + tol and rotation <= tol

    @classmethod
    def of(cls, chain: UrdfChain, robot: Robot, count: int = CHECKS) -> UrdfReference:
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
    return UrdfReference.of(chain, robot, count).difference(robot)


def checked_note(position: float, rotation: float) -> str:
    """The note saying how closely the tool's pose matches the URDF's."""
    return (
        f"checked at home and {CHECKS} random joint values: the tool's pose matches the "
        f"URDF to {position:.0e} m and {rotation:.0e} rad"
    )


def joint_name_lines(chain: UrdfChain) -> list[str]:
    """One line per moving joint: its number, name and kind."""
    return [
        f"joint {i}: {shortened(printable(j.name))} ({j.kind})"
        for i, j in enumerate(chain.moving, start=1)
    ]

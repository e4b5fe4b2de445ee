"""The bundled robots' joint speeds and accelerations: the datasheet values
where they are published (UR5, Panda, IRB 140), each file naming its source;
the Puma 560 keeps the defaults (its toolbox model gives none) and its demo
stays clean."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.model.program import REVOLUTE_AMAX, REVOLUTE_VMAX, top_acceleration, top_speed
from dhsim_tui.core.motion.path_check import check_path
from dhsim_tui.core.motion.trajectory import sample

ROBOTS = Path(__file__).resolve().parents[2] / "robots"

SPEEDS = {
    "ur5": (180,) * 6,
    "panda": (150, 150, 150, 150, 180, 180, 180),
    "irb140": (200, 200, 260, 360, 360, 450),
}
#: the Panda's accelerations, rad/s² (FCI's robot and interface specifications)
PANDA_RAD_S2 = (15, 7.5, 10, 12.5, 15, 20, 20)


@pytest.mark.parametrize("name", sorted(SPEEDS))
def test_datasheet_speeds_and_their_source(name):
    robot, path = load_robot(name)
    assert tuple(joint.vmax for joint in robot.joints) == pytest.approx(SPEEDS[name])
    head = path.read_text().split("[[joints]]")[0]
    assert "vmax" in head and ("specification" in head or "datasheet" in head)


def test_the_panda_accelerations():
    robot, _ = load_robot("panda")
    wanted = [math.degrees(a) for a in PANDA_RAD_S2]
    assert [joint.amax for joint in robot.joints] == pytest.approx(wanted, abs=0.01)


def test_the_others_keep_the_defaults():
    """UR and ABB publish no joint accelerations; the Puma no speeds."""
    for name in ("ur5", "irb140"):
        robot, _ = load_robot(name)
        assert all(top_acceleration(j, robot.units) == REVOLUTE_AMAX for j in robot.joints)
    puma, path = load_robot("puma560")
    assert all(j.vmax is None and j.amax is None for j in puma.joints)
    assert all(top_speed(j, puma.units) == REVOLUTE_VMAX for j in puma.joints)
    assert "defaults" in path.read_text().split("[[joints]]")[0]


def test_every_bundled_program_is_still_clean():
    for path in sorted(ROBOTS.glob("*.toml")):
        robot, _ = load_robot(str(path))
        for program in robot.programs:
            assert check_path(sample(robot, program)) == (), (path.name, program.name)

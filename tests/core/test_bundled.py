"""Each bundled robot against its reference position (reference §6), in mm."""

from __future__ import annotations

import numpy as np
import pytest

from dhsim_tui.core import bundled_names, dumps, load, load_robot, loads, save

# name -> (joint values, expected world XYZ in the robot's unit)
REFERENCE = {
    "puma560": ((0, 0, 0, 0, 0, 0), (452.10, -150.05, 431.80)),
    "puma560_modified": ((0, 0, 0, 0, 0, 0), (411.5, 150.1, 433.1)),
    "stanford": ((0, 0, 0, 0, 0, 0), (0.0, 154.0, 675.0)),  # d3 = 0, outside its limits
    "cobra600": ((0, 0, 0, 0), (600.0, 0.0, 387.0)),
    "irb140": ((0, 0, 0, 0, 0, 0), (430.0, 0.0, 797.0)),
    "ur5": ((0, 0, 0, 0, 0, 0), (-817.2, -191.4, -5.2)),
    "panda": ((0, 0, 0, 0, 0, 0, 0), (88.0, 0.0, 823.0)),
    "planar2": ((0, 0), (2.0, 0.0, 0.0)),
    "gantry": ((100, 200, 300), (100.0, 200.0, 300.0)),
    "scara_pedestal": ((0, 0, 0, 0), (600.0, 0.0, 0.0)),
}


def test_every_bundled_robot_has_a_reference():
    assert sorted(REFERENCE) == bundled_names()


@pytest.mark.parametrize("name", sorted(REFERENCE))
def test_reference_position(name):
    robot, _ = load_robot(name)
    q, xyz = REFERENCE[name]
    tolerance = 0.06 if robot.units == "mm" else 1e-9
    assert np.allclose(robot.kinematics.position(q), xyz, atol=tolerance)


def test_puma_has_limits_poses_and_d1_zero():
    robot, _ = load_robot("puma560")
    assert robot.units == "mm" and robot.joints[0].d == 0.0
    assert [(j.min, j.max) for j in robot.joints] == [
        (-160, 160),
        (-45, 225),
        (-225, 45),
        (-110, 170),
        (-100, 100),
        (-266, 266),
    ]
    assert robot.pose_names == ("qz", "qr", "qs", "qn")
    assert robot.pose("qr") == (0, 90, -90, 0, 0, 0)
    # qn's joint 3 is the toolbox's +180 written as -180 to stay within limits
    assert np.allclose(
        robot.kinematics.pose(robot.pose("qn")), robot.kinematics.pose((0, 45, 180, 0, 45, 0))
    )


def test_ready_pose_matches_reference(puma):
    assert np.allclose(
        puma.kinematics.position(puma.pose("qr")), (20.30, -150.05, 863.60), atol=0.005
    )


def test_stanford_and_cobra_have_prismatic_joints():
    assert load_robot("stanford")[0].type_string == "RRPRRR"
    assert load_robot("cobra600")[0].type_string == "RRPR"
    assert load_robot("gantry")[0].type_string == "PPP"
    assert load_robot("panda")[0].convention == "modified"
    assert load_robot("panda")[0].dof == 7


def test_pedestal_scara_stands_250mm_up():
    robot, _ = load_robot("scara_pedestal")
    assert robot.base_height == 250.0


def test_every_home_and_pose_is_within_limits(bundled):
    bundled.check_q(bundled.home)
    for name in bundled.pose_names:
        bundled.check_q(bundled.pose(name))


def test_bundled_files_round_trip(bundled, tmp_path):
    assert loads(dumps(bundled)) == bundled
    assert load(save(bundled, tmp_path / "robot.toml")) == bundled


def test_lookup_by_name_is_case_insensitive_and_accepts_suffix():
    assert load_robot("PUMA560")[0] == load_robot("puma560.toml")[0]


# -- bundled is dhsim's own list, not "any file in that folder" --------------------


def test_the_bundled_list_names_every_file_dhsim_ships():
    """The list and the shipped files agree (a robot added to robots/ must be
    added to the list, or it is not bundled)."""
    from dhsim_tui.core.files.library import BUNDLED_ROBOTS, bundled_dir

    shipped = {path.stem for path in bundled_dir().glob("*.toml")} - _users_own()
    assert sorted(shipped) == sorted(BUNDLED_ROBOTS) == bundled_names()


def _users_own() -> set[str]:
    """Files a user saved into an editable install's robots/ (not ours)."""
    from dhsim_tui.core.files.library import BUNDLED_ROBOTS, bundled_dir

    return {p.stem for p in bundled_dir().glob("*.toml")} - set(BUNDLED_ROBOTS)


def test_a_file_saved_beside_the_bundled_ones_is_the_users(tmp_path, monkeypatch):
    """With an editable install robots/ is the bundled folder: a robot the
    user saves there is theirs - not listed, not treated as a template."""
    from dhsim_tui.core.files import library
    from dhsim_tui.tui.flows.save import is_bundled

    folder = tmp_path / "robots"
    folder.mkdir()
    for name in library.BUNDLED_ROBOTS:
        (folder / f"{name}.toml").write_text((library.bundled_dir() / f"{name}.toml").read_text())
    mine = folder / "irb120.toml"
    mine.write_text((folder / "irb140.toml").read_text().replace("IRB 140", "IRB 120"))
    monkeypatch.setattr(library, "bundled_dir", lambda: folder)
    assert "irb120" not in library.bundled_names()
    assert library.bundled_path("irb120") is None
    assert not library.is_bundled_file(mine) and not is_bundled(mine)
    assert library.is_bundled_file(folder / "irb140.toml") and is_bundled(folder / "irb140.toml")
    assert not is_bundled(None)

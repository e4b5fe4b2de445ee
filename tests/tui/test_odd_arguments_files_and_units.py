"""Odd input outside the screens: command-line arguments that get a one-line
message and exit 2, saves that keep a file's mode and symlinks, unit
conversion without float noise, a planar arm's Cartesian jog."""

from __future__ import annotations

import os
import stat

import pytest

from dhsim_tui.cli.main import main
from dhsim_tui.core import load, load_robot, save
from dhsim_tui.core.model.editing import set_units
from dhsim_tui.core.motion.jog import cartesian_move, cartesian_target


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["fk", "puma560", "--q", "--"], "--q: expected one argument"),
        (["fk", "~nosuchuser/x"], "no such file"),
        (["check", "/dev/zero"], "not a regular file"),
        (["fk", "puma560", "--q", "1_0,0,0,0,0,0"], "('1_0') is not a number"),
        (["ik", "puma560", "--xyz", "1e308,0,0"], "not a finite number of sane size"),
    ],
)
def test_odd_arguments_get_one_line_and_exit_2(capsys, argv, message):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1


def test_save_keeps_the_files_mode_and_symlinks(tmp_path):
    robot, _ = load_robot("gantry")
    file = tmp_path / "g.toml"
    save(robot, file)
    os.chmod(file, 0o644)
    save(robot, file)
    assert stat.S_IMODE(file.stat().st_mode) == 0o644
    link = tmp_path / "link.toml"
    link.symlink_to(file)
    save(robot, link)
    assert link.is_symlink() and load(link) == robot


def test_unit_conversion_round_trips_without_float_noise():
    robot, _ = load_robot("stanford")
    there = set_units(robot, "cm")
    assert there.joints[2].min == 30.48
    assert set_units(there, "mm") == robot


def test_planar_arm_jogs_in_its_plane_and_says_what_it_cannot_do():
    planar, _ = load_robot("planar2")
    q = (30.0, 60.0)
    for row in (0, 1):
        assert cartesian_move(planar, q, cartesian_target(planar, q, row, 0.01)).moved
    assert "can't turn it" in cartesian_move(planar, q, cartesian_target(planar, q, 5, 1)).reason
    scara, _ = load_robot("cobra600")
    q = (10.0, 20.0, 50.0, 0.0)
    move = cartesian_move(scara, q, cartesian_target(scara, q, 3, 1.0))
    assert not move.moved and "no joint that moves the tool that way" in move.reason

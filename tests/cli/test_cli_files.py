"""`dhsim import`, `export` and `convert` as a user runs them.

The issue's promise, checked literally: after `dhsim import FILE -o OUT`,
`dhsim fk OUT --q V` equals the URDF's forward kinematics of the tip link
(yourdfpy, radians and metres) at the same joint values.
"""

from __future__ import annotations

import io
import json
import math
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import yourdfpy

from dhsim_tui.cli.main import main
from dhsim_tui.core.files.library import bundled_names, bundled_path, load_robot
from dhsim_tui.core.files.robotfile import load
from dhsim_tui.core.interop.export import export_text
from dhsim_tui.core.model.errors import DhsimError

URDFS = Path(__file__).resolve().parents[1] / "urdfs"


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def fk_json(capsys, robot: str, q: list[float]) -> dict:
    code, out, err = run(capsys, "fk", robot, "--q", ",".join(repr(v) for v in q), "--json")
    assert code == 0, err
    return json.loads(out)


def test_import_then_fk_equals_the_urdf_at_random_joint_values(capsys, tmp_path):
    out = tmp_path / "ur5.toml"
    code, stdout, err = run(
        capsys, "import", str(URDFS / "ur5.urdf"), "--tip", "tool0", "--units", "mm", "-o", str(out)
    )
    assert code == 0, err
    assert f"wrote {out}" in stdout and "matches the URDF" in stdout
    urdf = yourdfpy.URDF.load(str(URDFS / "ur5.urdf"), build_scene_graph=True, load_meshes=False)
    names = [
        "shoulder_pan_joint",
        "shoulder_lift_joint",
        "elbow_joint",
        "wrist_1_joint",
        "wrist_2_joint",
        "wrist_3_joint",
    ]
    robot = load(out)
    rng = np.random.default_rng(5)
    for _ in range(10):
        q = [float(rng.uniform(lo, hi)) for lo, hi in zip(robot.lower, robot.upper, strict=True)]
        result = fk_json(capsys, str(out), q)
        urdf.update_cfg({n: math.radians(v) for n, v in zip(names, q, strict=True)})
        expected = urdf.get_transform(frame_to="tool0", frame_from="world")
        ours = np.array(result["T"])
        np.testing.assert_allclose(ours[:3, 3] / 1000.0, expected[:3, 3], rtol=0, atol=1e-9)
        np.testing.assert_allclose(ours[:3, :3], expected[:3, :3], rtol=0, atol=1e-9)


def test_the_imported_file_says_where_it_came_from(capsys, tmp_path):
    out = tmp_path / "arm.toml"
    assert run(capsys, "import", str(URDFS / "spherical_wrist.urdf"), "-o", str(out))[0] == 0
    text = out.read_text()
    assert text.startswith("# Imported by dhsim from spherical_wrist.urdf")
    assert "# joint 1: " in text


def test_import_without_o_prints_the_robot_file_and_notes_on_stderr(capsys, tmp_path):
    code, out, err = run(capsys, "import", str(URDFS / "planar_elbow.urdf"))
    assert code == 0 and "matches the URDF" in err
    path = tmp_path / "x.toml"
    path.write_text(out)
    assert load(path).dof == 3


def test_a_tree_needs_a_tip_one_line_exit_2(capsys):
    code, out, err = run(capsys, "import", str(URDFS / "ur5.urdf"))
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1
    assert "choose a tip among its 3 leaf links: 'ee_link', 'tool0', 'base'" in err


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("<robot", "not valid XML"),
        ('<!DOCTYPE r [<!ENTITY e "x">]><robot name="r"/>', "DOCTYPE"),
        (
            '<robot name="r"><link name="a"/><link name="b"/><joint name="m" type="revolute">'
            '<parent link="a"/><child link="b"/><limit lower="-1" upper="1"/>'
            '<mimic joint="x"/></joint></robot>',
            "'m'",
        ),
        (
            '<robot name="r"><link name="a"/><link name="b"/><joint name="p" type="planar">'
            '<parent link="a"/><child link="b"/></joint></robot>',
            "'p'",
        ),
        (
            '<robot name="r"><link name="a"/><link name="b"/>'
            '<joint name="j1" type="revolute"><parent link="a"/><child link="b"/>'
            '<limit lower="-1" upper="1"/></joint>'
            '<joint name="j2" type="revolute"><parent link="b"/><child link="a"/>'
            '<limit lower="-1" upper="1"/></joint></robot>',
            "cycle",
        ),
        (
            '<robot name="r"><link name="a"/><joint name="j" type="revolute">'
            '<parent link="a"/><child link="gone"/><limit lower="-1" upper="inf"/></joint></robot>',
            "gone",
        ),
    ],
)
def test_bad_urdfs_are_one_line_and_exit_2(capsys, tmp_path, text, fragment):
    path = tmp_path / "bad.urdf"
    path.write_text(text)
    code, out, err = run(capsys, "import", str(path))
    assert code == 2 and out == ""
    assert err.startswith(f"dhsim: error: {path}: ") and fragment in err
    assert len(err.strip().splitlines()) == 1


def test_o_refuses_to_overwrite_without_force_and_keeps_comments_with_it(capsys, tmp_path):
    target = tmp_path / "puma.toml"
    target.write_text(bundled_path("puma560").read_text())
    code, _, err = run(
        capsys, "convert", str(target), "--convention", "modified", "-o", str(target)
    )
    assert code == 2 and "exists" in err
    code, _, err = run(
        capsys, "convert", str(target), "--convention", "modified", "-o", str(target), "--force"
    )
    assert code == 0, err
    text = target.read_text()
    assert "# Unimation Puma 560, standard D-H, lengths in mm." in text  # the user's words
    assert load(target).convention == "modified"


@pytest.mark.parametrize("name", bundled_names())
def test_convert_through_the_cli_keeps_fk(capsys, tmp_path, name):
    robot, _ = load_robot(name)
    other = "modified" if robot.convention == "standard" else "standard"
    out = tmp_path / "c.toml"
    assert run(capsys, "convert", name, "--convention", other, "-o", str(out))[0] == 0
    rng = np.random.default_rng(1)
    q = [float(rng.uniform(lo, hi)) for lo, hi in zip(robot.lower, robot.upper, strict=True)]
    ours, theirs = fk_json(capsys, str(out), q), fk_json(capsys, name, q)
    np.testing.assert_allclose(ours["T"], theirs["T"], rtol=0, atol=1e-9)


@pytest.mark.parametrize("fmt", ["urdf", "csv", "json"])
def test_export_prints_or_writes_the_same_text(capsys, tmp_path, fmt):
    robot, _ = load_robot("stanford")
    code, out, err = run(capsys, "export", "stanford", "--format", fmt)
    assert code == 0 and out == export_text(robot, fmt) and err == ""
    path = tmp_path / f"s.{fmt}"
    assert run(capsys, "export", "stanford", "--format", fmt, "-o", str(path))[0] == 0
    assert path.read_text() == out
    code, _, err = run(capsys, "export", "stanford", "--format", fmt, "-o", str(path))
    assert code == 2 and str(path) in err and len(err.strip().splitlines()) == 1


def test_export_to_urdf_then_import_gives_the_same_arm(capsys, tmp_path):
    urdf = tmp_path / "irb.urdf"
    assert run(capsys, "export", "irb140", "--format", "urdf", "-o", str(urdf))[0] == 0
    back = tmp_path / "irb.toml"
    assert run(capsys, "import", str(urdf), "--units", "mm", "-o", str(back))[0] == 0
    q = [10.0, -20.0, 30.0, 40.0, -50.0, 60.0]
    np.testing.assert_allclose(
        fk_json(capsys, str(back), q)["T"], fk_json(capsys, "irb140", q)["T"], rtol=0, atol=1e-9
    )


def test_csv_export_then_import_gives_the_same_robot(capsys, tmp_path):
    for name in bundled_names():
        csv_path = tmp_path / f"{name}.csv"
        assert run(capsys, "export", name, "--format", "csv", "-o", str(csv_path))[0] == 0
        out = tmp_path / f"{name}.toml"
        code, _, err = run(capsys, "import", str(csv_path), "-o", str(out))
        assert code == 0, err
        # a D-H table: everything but the programs and the joint speeds (the JSON carries those)
        robot = load_robot(name)[0]
        table = tuple(replace(joint, vmax=None, amax=None) for joint in robot.joints)
        assert load(out) == replace(robot, joints=table, programs=()), name


@pytest.mark.parametrize(
    "argv",
    [
        ["export", "puma560", "--format", "step"],
        ["export", "puma560"],
        ["convert", "puma560", "--convention", "craig"],
        ["import", "nothing_here.urdf"],
        ["import", str(URDFS / "planar_elbow.urdf"), "--units", "furlong"],
        ["import", str(URDFS / "planar_elbow.urdf"), "-o", "x.txt"],
    ],
)
def test_bad_arguments_are_one_line_and_exit_2(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1


def test_the_commands_work_without_a_terminal_and_into_a_pipe():
    result = subprocess.run(
        [sys.executable, "-m", "dhsim_tui", "export", "puma560", "--format", "json"],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0 and json.load(io.StringIO(result.stdout))["name"] == "Puma 560"


# -- a URDF or a CSV where a robot file is expected ------------------------------------


@pytest.mark.parametrize("command", ["check", "fk", "ik", "workspace", "export", "edit"])
def test_a_urdf_given_as_a_robot_names_the_import_command_that_then_works(
    capsys, tmp_path, command
):
    urdf = tmp_path / "arm.urdf"
    urdf.write_bytes((URDFS / "planar_elbow.urdf").read_bytes())
    extra = {"ik": ["--xyz", "1,0,0"], "export": ["--format", "json"]}.get(command, [])
    code, out, err = run(capsys, command, str(urdf), *extra)
    if command == "edit":  # no terminal here: the simulator says so before loading
        assert code == 2 and "interactive terminal" in err
        from dhsim_tui.cli.main import _open

        with pytest.raises(DhsimError) as caught:
            _open(str(urdf))  # what it loads the robot with, in a terminal
        err = f"dhsim: error: {caught.value}\n"
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1, err
    assert "a URDF, not a dhsim robot file" in err and "not valid TOML" not in err
    suggested = err.strip()[err.index("dhsim import ") :]
    assert suggested == f"dhsim import {urdf} -o {tmp_path / 'arm.toml'}"
    code, _, err = run(capsys, *suggested.split()[1:])
    assert code == 0, err
    assert load(tmp_path / "arm.toml").dof == 3  # the elbow arm's three revolute joints


def test_a_csv_given_as_a_robot_names_the_import_command(capsys, tmp_path):
    table = tmp_path / "dh.csv"
    table.write_text("theta,d,a,alpha\n0,0,100,0\n0,0,50,0\n", encoding="utf-8")
    code, out, err = run(capsys, "fk", str(table))
    assert code == 2 and out == ""
    assert "a CSV file, not a dhsim robot file" in err
    suggested = err.strip()[err.index("dhsim import ") :]
    code, _, err = run(capsys, *suggested.split()[1:])
    assert code == 0, err
    assert load(tmp_path / "dh.toml").dof == 2

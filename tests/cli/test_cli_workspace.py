"""``dhsim workspace ROBOT [--n N] [--seed S] [--json]``: the workspace's
bounding box and reach in aligned lines or one JSON object; a bad --n or
--seed is one line and status 2."""

from __future__ import annotations

import json

import pytest

from dhsim_tui.cli import main as cli
from dhsim_tui.cli.main import UsageError, _Parser
from dhsim_tui.cli.workspace import format_workspace, subparsers
from dhsim_tui.core import load_robot
from dhsim_tui.core.analysis.workspace import arm_reach, reach, sample_summary


def run(argv: list[str], capsys) -> tuple[int, str, str]:
    """The command as ``dhsim workspace`` runs it: its parser, then its function."""
    parser = subparsers(_Parser)["workspace"]
    args = parser.parse_args(argv)
    status = args.func(args)
    out, err = capsys.readouterr()
    return status, out, err


def test_text_lists_the_box_and_reach_in_aligned_lines_with_units(capsys):
    status, out, err = run(["puma560", "--n", "3000", "--seed", "4"], capsys)
    assert status == 0 and err == ""
    robot, _ = load_robot("puma560")
    summary = sample_summary(robot, 3000, 4)
    lines = out.splitlines()
    assert lines[0] == "Puma 560" and "3000 random joint vectors" in lines[1]
    assert "(seed 4)" in lines[1]
    body = lines[2:]
    assert [line.split()[0] for line in body] == ["x", "y", "z", "reach", "reached", "horizontal"]
    assert all(" mm" in line for line in body)
    # the first numbers end in one column
    ends = {line.index(" mm") for line in body[3:]}
    assert len(ends) == 1
    for axis, line in zip("xyz", body[:3], strict=True):
        k = "xyz".index(axis)
        low, high = float(line.split()[1]), float(line.split()[3])
        assert low == pytest.approx(summary.xyz_min[k], abs=0.006)
        assert high == pytest.approx(summary.xyz_max[k], abs=0.006)
    assert f"{arm_reach(robot):.2f} mm" in body[3]
    assert f"{summary.reach_reached:.2f} mm" in body[4]
    assert f"link lengths' sum {reach(robot):.2f} mm" in body[4]
    assert out == format_workspace(robot, summary, 4) + "\n"


def test_json_is_one_object(capsys):
    status, out, _ = run(["ur5", "--n", "2000", "--json"], capsys)
    assert status == 0 and len(out.strip().splitlines()) == 1
    data = json.loads(out)
    robot, _ = load_robot("ur5")
    summary = sample_summary(robot, 2000, 0)
    assert data["robot"] == robot.name and data["units"] == "mm" and data["seed"] == 0
    assert data["samples"] == 2000
    assert data["min"] == list(summary.xyz_min) and data["max"] == list(summary.xyz_max)
    assert data["reach_reached"] == summary.reach_reached <= data["reach"] == arm_reach(robot)
    assert data["reach"] <= data["reach_bound"] == reach(robot)
    assert data["horizontal_radius"] == summary.horizontal_radius
    assert data["z_range"] == [summary.xyz_min[2], summary.xyz_max[2]]
    assert data["origin"] == [0.0, 0.0, 0.0]


def test_the_default_is_twenty_thousand_samples_and_repeatable(capsys):
    first = run(["planar2", "--json"], capsys)[1]
    assert json.loads(first)["samples"] == 20000
    assert run(["planar2", "--json"], capsys)[1] == first
    assert run(["planar2", "--json", "--seed", "1"], capsys)[1] != first


@pytest.mark.parametrize(
    "argv",
    [
        ["--n", "0"],
        ["--n", "-5"],
        ["--n", "10000001"],
        ["--n", "abc"],
        ["--n", "1.5"],
        ["--n", ""],
        ["--n", "1_000"],
        ["--seed", "-1"],
        ["--seed", "x"],
    ],
)
def test_a_bad_n_or_seed_is_one_line(argv):
    parser = subparsers(_Parser)["workspace"]
    with pytest.raises(UsageError) as caught:
        parser.parse_args(["puma560", *argv])
    message = str(caught.value)
    assert "\n" not in message and message.startswith("dhsim workspace: error: argument ")
    assert argv[0] in message


def test_an_unknown_robot_is_a_dhsim_error():
    parser = subparsers(_Parser)["workspace"]
    args = parser.parse_args(["no-such-robot"])
    with pytest.raises(cli.DhsimError):
        args.func(args)


def test_through_dhsim_main(monkeypatch, capsys):
    """As ``dhsim workspace`` (registered here if cli.py does not yet)."""
    if "workspace" not in cli._subparsers():
        original = cli._subparsers
        monkeypatch.setattr(cli, "_subparsers", lambda: {**original(), **subparsers(_Parser)})
    assert cli.main(["workspace", "puma560", "--n", "500"]) == 0
    assert "reach" in capsys.readouterr().out
    assert cli.main(["workspace", "puma560", "--n", "0"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "--n" in err
    assert cli.main(["workspace", "puma560", "--n", "-3"]) == 2
    assert cli.main(["workspace", "puma560", "--n", "x"]) == 2
    assert cli.main(["workspace", "nowhere.toml"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 3 and err[2].startswith("dhsim: error: ")

"""The closed form's configuration words against the Robotics Toolbox for
Python's letters (issue 17): l/r shoulder left/right, u/d elbow up/down, n/f
wrist no flip/flip.

tests/data/rtb_puma560_configs.json holds Puma 560 joint vectors and the
letters the toolbox's ``Puma560.ikine_a`` gives each (the configuration whose
solution is that vector); tests/data/README.md says how it was made. dhsim
solves the vector's tool pose and the solution equal to the vector must carry
the same words.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from dhsim_tui.core import load_robot
from dhsim_tui.core.ik.analytic import detect, solve
from dhsim_tui.core.ik.solutions import all_solutions

PAIRS = json.loads(
    (Path(__file__).resolve().parents[1] / "data" / "rtb_puma560_configs.json").read_text()
)
WORDS = {
    "l": "shoulder left",
    "r": "shoulder right",
    "u": "elbow up",
    "d": "elbow down",
    "n": "wrist no flip",
    "f": "wrist flip",
}
SAME = 1e-6  # degrees
#: puma560_modified (Armstrong, Khatib and Burdick's table) is the standard
#: table's arm with frame 0 turned half a turn about axis 1 and joints 2 and 3
#: counted from half a turn away: modified(q + SHIFT) = Rz(180°) standard(q) Rz(180°)
SHIFT = (0.0, -180.0, -180.0, 0.0, 0.0, 0.0)
#: the two tables' lengths differ a little (d4 433.1 against 431.8 mm)
TABLES_AGREE_MM = 2.0


def _words(config: str) -> str:
    return ", ".join(WORDS[letter] for letter in config)


def _same(a, b) -> bool:
    return max(abs(math.remainder(x - y, 360.0)) for x, y in zip(a, b, strict=True)) < SAME


def _closed_form(robot, q) -> list[tuple[tuple[float, ...], str]]:
    """Every closed-form solution of FK(q), limits not applied."""
    return solve(robot, detect(robot), robot.kinematics.pose(q), q)[0]


def test_the_reference_holds_the_quoted_pairs_and_every_configuration():
    quoted = {
        (0.0, 30.0, 45.0, 100.0, 40.0, 20.0): "luf",
        (0.0, 30.0, 45.0, -80.0, -40.0, -160.0): "lun",
        (10.0, 40.0, -100.0, 20.0, 30.0, 40.0): "ruf",  # the README's example
    }
    stored = {tuple(p["q"]): p["config"] for p in PAIRS}
    assert all(stored.get(q) == config for q, config in quoted.items())
    assert len(PAIRS) >= 300
    assert {p["config"] for p in PAIRS} == {s + e + w for s in "lr" for e in "ud" for w in "nf"}


def test_the_puma_words_are_the_toolboxs_letters():
    robot = load_robot("puma560")[0]
    wrong = []
    for pair in PAIRS:
        q = pair["q"]
        found = all_solutions(robot, robot.kinematics.pose(q), q).solutions
        hits = [s.config for s in found if _same(s.q, q)]
        assert len(hits) == 1, (q, [s.q for s in found])
        if hits[0] != _words(pair["config"]):
            wrong.append((q, pair["config"], hits[0]))
    assert not wrong, wrong[:5]


def test_each_puma_pose_has_eight_solutions_with_eight_configurations():
    """Away from the wrist's singular position (the stored vectors keep joint
    5 two degrees from it) the closed form gives all 8, one per word set."""
    robot = load_robot("puma560")[0]
    every = {_words(s + e + w) for s in "lr" for e in "ud" for w in "nf"}
    for pair in PAIRS:
        solutions = _closed_form(robot, pair["q"])
        assert len(solutions) == 8 and {words for _, words in solutions} == every, pair


def test_the_modified_puma_words_the_same_configurations_alike():
    """The Puma in modified D-H (puma560_modified): each stored vector's
    configuration is ``q + SHIFT`` in that table (checked by the poses), and
    must get the toolbox's letters too. Its limits copy the standard table's
    numbers, so the closed form is read without them."""
    standard = load_robot("puma560")[0]
    modified = load_robot("puma560_modified")[0]
    turn = np.diag([-1.0, -1.0, 1.0, 1.0])  # half a turn about z
    wrong = []
    for pair in PAIRS:
        q = pair["q"]
        qm = [a + b for a, b in zip(q, SHIFT, strict=True)]
        expected = turn @ standard.kinematics.pose(q) @ turn
        pose = modified.kinematics.pose(qm)
        assert np.allclose(pose[:3, :3], expected[:3, :3], atol=1e-12), q
        assert np.linalg.norm(pose[:3, 3] - expected[:3, 3]) < TABLES_AGREE_MM, q
        hits = [words for s, words in _closed_form(modified, qm) if _same(s, qm)]
        assert len(hits) == 1, qm
        if hits[0] != _words(pair["config"]):
            wrong.append((q, pair["config"], hits[0]))
    assert not wrong, wrong[:5]


@pytest.mark.parametrize("pair", PAIRS[:3], ids=lambda p: p["config"])
def test_the_modified_puma_words_the_wrist_alike_at_the_same_angles(pair):
    """At the same joint values the two tables put the upper arm differently
    (see SHIFT), so the shoulder and elbow words may differ, but joints 4-6
    turn the same way about the same axes: the wrist's word is the same."""
    q = pair["q"]
    hits = [words for s, words in _closed_form(load_robot("puma560_modified")[0], q) if _same(s, q)]
    assert len(hits) == 1 and hits[0].endswith(", " + WORDS[pair["config"][2]])

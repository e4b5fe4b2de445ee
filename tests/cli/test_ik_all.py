"""Every IK solution (issue 11): the closed forms against an exhaustive
numerical search, the textbook FK of conftest, and the limits.

The exhaustive search here is the test's own: Gauss-Newton on a 12-number
residual (position per reach and the 9 rotation entries) with a
finite-difference Jacobian, from many random starts at once, joint angles
left free to wander (no limits, no wrapping) so that solutions near a limit
are found too; the results are then reduced modulo a turn and kept if some
turn of them fits the limits. It uses nothing of ik.py, ik_all.py or
ik_analytic.py. It is the expensive part, so it runs on fewer poses
(:data:`EXHAUSTIVE_POSES` per robot) than the cheaper checks (:data:`POSES`).
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
from conftest import random_q, reference_frames

from dhsim_tui.cli.main import main
from dhsim_tui.core import load_robot, reach
from dhsim_tui.core.ik.analytic import (
    SPHERICAL_MEETING,
    SPHERICAL_PARALLEL,
    THREE_PARALLEL,
    detect,
)
from dhsim_tui.core.ik.solutions import Solutions, all_solutions
from dhsim_tui.core.interop.convert import convert
from dhsim_tui.core.model.robot import Tool

ANALYTIC = {
    "puma560": SPHERICAL_PARALLEL,
    "puma560_modified": SPHERICAL_PARALLEL,
    "irb140": SPHERICAL_PARALLEL,
    "stanford": SPHERICAL_MEETING,
    "ur5": THREE_PARALLEL,
}
#: poses per robot for the cheap checks, and for the exhaustive comparison
POSES = 60
EXHAUSTIVE_POSES = 30
#: random starts of the exhaustive search per pose
STARTS = 160
#: the accuracy the API promises
POSITION_TOL = 1e-6
ORIENTATION_TOL = 1e-6


# -- helpers ---------------------------------------------------------------------------
def _offset_robot():
    """The Puma with offsets on every joint, a general base and a tool: the same
    geometry in other joint values, placed elsewhere in the world."""
    puma, _ = load_robot("puma560")
    offsets = (30.0, -90.0, 45.0, 10.0, -20.0, 60.0)
    joints = tuple(
        dataclasses.replace(j, offset=o, min=j.min - o, max=j.max - o)
        for j, o in zip(puma.joints, offsets, strict=True)
    )
    return dataclasses.replace(
        puma,
        name="Puma with offsets",
        joints=joints,
        poses=(),
        programs=(),
        base_z="-y",
        base_x="+z",
        base_xyz=(100.0, -250.0, 1200.0),
        base_rpy=(10.0, -25.0, 40.0),
        tool=Tool(xyz=(10.0, 20.0, 120.0), rpy=(5.0, 15.0, -30.0)),
    )


def _modified_ur5():
    """The UR5 converted to modified D-H, with offsets and a general base."""
    ur5 = convert(load_robot("ur5")[0], "modified")
    offsets = (15.0, -30.0, 0.0, 90.0, -45.0, 5.0)
    joints = tuple(
        dataclasses.replace(j, offset=j.offset + o, min=j.min - o, max=j.max - o)
        for j, o in zip(ur5.joints, offsets, strict=True)
    )
    return dataclasses.replace(
        ur5, joints=joints, poses=(), base_xyz=(5.0, 6.0, 7.0), base_rpy=(0.0, 30.0, -60.0)
    )


ROBOTS = {name: (lambda name=name: load_robot(name)[0]) for name in ANALYTIC}
ROBOTS["puma with offsets"] = _offset_robot
ROBOTS["modified ur5 with offsets"] = _modified_ur5
KINDS = {**ANALYTIC, "puma with offsets": SPHERICAL_PARALLEL}
KINDS["modified ur5 with offsets"] = THREE_PARALLEL


def _poses(robot, count, seed):
    rng = np.random.default_rng(seed)
    qs = random_q(robot, rng, count)
    return qs, [reference_frames(robot, q)[-1] for q in qs]


def _pose_errors(robot, q, target):
    """Position (robot units) and orientation (rad) error of the textbook FK."""
    pose = reference_frames(robot, q)[-1]
    position = float(np.linalg.norm(pose[:3, 3] - target[:3, 3]))
    r = target[:3, :3] @ pose[:3, :3].T
    orientation = math.acos(max(-1.0, min(1.0, (np.trace(r) - 1.0) / 2.0)))
    return position, orientation


def _within_limits(robot, q):
    return all(j.min <= v <= j.max for j, v in zip(robot.joints, q, strict=True))


def _wrapped(robot, a, b):
    """Per-joint |a - b| (deg / units), revolute joints modulo a turn."""
    d = np.asarray(a, float) - np.asarray(b, float)
    revolute = np.array([j.is_revolute for j in robot.joints])
    return np.where(revolute, np.abs((d + 180.0) % 360.0 - 180.0), np.abs(d))


def _classes(robot, qs, tol):
    """The joint vectors, one per class modulo a turn."""
    kept = []
    for q in qs:
        if all(_wrapped(robot, q, other).max() > tol for other in kept):
            kept.append(np.asarray(q, float))
    return kept


def _fits(robot, q):
    """Whether some whole number of turns of each revolute joint fits the limits."""
    for joint, value in zip(robot.joints, q, strict=True):
        if joint.is_revolute:
            k = math.ceil((joint.min - 1e-7 - value) / 360.0)
            if value + 360.0 * k > joint.max + 1e-7:
                return False
        elif not joint.min - 1e-7 <= value <= joint.max + 1e-7:
            return False
    return True


def _exhaustive(robot, target, count=STARTS, seed=1):
    """Every solution a many-start Gauss-Newton finds, one per class modulo a turn."""
    rng = np.random.default_rng(seed)
    scale = reach(robot)
    revolute = np.array([j.is_revolute for j in robot.joints])
    unit = np.where(revolute, 180.0 / math.pi, scale)  # internal -> deg / units
    x = random_q(robot, rng, count) / unit
    kin = robot.kinematics

    def residual(x):
        poses = kin.batch(x * unit)
        return np.concatenate(
            [
                (poses[:, :3, 3] - target[:3, 3]) / scale,
                (poses[:, :3, :3] - target[:3, :3]).reshape(len(x), 9),
            ],
            axis=1,
        )

    h = 1e-7
    for _ in range(60):
        e = residual(x)
        jac = np.empty((len(x), 12, robot.dof))
        for k in range(robot.dof):
            shifted = x.copy()
            shifted[:, k] += h
            jac[:, :, k] = (residual(shifted) - e) / h
        jt = jac.transpose(0, 2, 1)
        damping = 1e-9 + 1e-2 * np.minimum((e * e).sum(axis=1), 1.0)
        lhs = jt @ jac + damping[:, None, None] * np.eye(robot.dof)
        step = np.linalg.solve(lhs, -(jt @ e[:, :, None]))[:, :, 0]
        step *= np.minimum(1.0, 0.5 / np.maximum(np.abs(step).max(axis=1), 1e-300))[:, None]
        x = x + step
    e = residual(x)
    good = np.sqrt((e * e).sum(axis=1)) < 1e-9
    qs = [q for q in x[good] * unit if _fits(robot, q)]
    return _classes(robot, qs, 1e-4)


# -- the closed forms: detection ----------------------------------------------------
@pytest.mark.parametrize("name", list(KINDS))
def test_closed_form_detected_from_the_geometry(name):
    geometry = detect(ROBOTS[name]())
    assert geometry is not None and geometry.kind == KINDS[name], name


@pytest.mark.parametrize("name", ["panda", "cobra600", "planar2", "gantry", "scara_pedestal"])
def test_no_closed_form_where_the_geometry_has_none(name):
    assert detect(load_robot(name)[0]) is None


def test_a_wrist_that_is_not_spherical_is_not_taken_for_one():
    """A Puma whose wrist axes miss each other by 1 mm has no closed form."""
    puma, _ = load_robot("puma560")
    joints = list(puma.joints)
    joints[4] = dataclasses.replace(joints[4], d=1.0)
    assert detect(dataclasses.replace(puma, joints=tuple(joints))) is None


# -- the closed forms: every solution -----------------------------------------------------
@pytest.mark.parametrize("name", list(ROBOTS))
def test_every_solution_reaches_the_pose_within_limits_once(name):
    """On random poses: each solution reaches the target (textbook FK), lies
    within the limits, appears once, and the joints the pose was made from
    are among them; labels tell the distinct branches apart."""
    robot = ROBOTS[name]()
    size = reach(robot)
    qs, targets = _poses(robot, POSES, seed=11)
    for q0, target in zip(qs, targets, strict=True):
        found = all_solutions(robot, target)
        assert found.method == "analytic" and not found.family
        sols = [s.q for s in found.solutions]
        assert sols, f"{name}: no solution for a pose made from {q0}"
        # the textbook FK for one of each class modulo a turn (the UR5 has up
        # to 512 solutions, 8 classes), the compiled batch FK for all
        for q in _classes(robot, sols, 1e-9):
            position, orientation = _pose_errors(robot, q, target)
            assert position <= POSITION_TOL * size, (name, q, position)
            assert orientation <= ORIENTATION_TOL, (name, q, orientation)
        poses = robot.kinematics.batch(np.array(sols))
        assert np.abs(poses[:, :3, 3] - target[:3, 3]).max() <= POSITION_TOL * size
        assert np.abs(poses[:, :3, :3] - target[:3, :3]).max() <= ORIENTATION_TOL
        for s in found.solutions:
            assert s.residual <= POSITION_TOL * size and s.orientation_error <= ORIENTATION_TOL
            assert _within_limits(robot, s.q), (name, s.q)
        # no two alike and the original among them, revolute joints modulo a turn
        array = np.array(sols)
        apart = _gap(robot, array[:, None, :], array[None, :, :]).max(axis=2)
        np.fill_diagonal(apart, np.inf)
        assert apart.min() > 1e-6, name
        assert _gap(robot, array, np.asarray(q0)).max(axis=1).min() < 1e-6, (name, q0)
        # one label per branch (class modulo a turn), different across branches
        labels = {}
        for s in found.solutions:
            key = tuple(round(v % 360.0, 5) for v in s.q)
            labels.setdefault(key, set()).add(s.config)
        assert all(len(words) == 1 for words in labels.values()), labels
        words = [next(iter(w)) for w in labels.values()]
        assert len(set(words)) == len(words), (name, words)
        assert all(words), (name, words)


@pytest.mark.parametrize("name", list(ROBOTS))
def test_the_closed_form_finds_what_an_exhaustive_search_finds(name):
    """The same solutions, class for class (modulo a turn), as a many-start
    numerical search of the test's own, on EXHAUSTIVE_POSES random poses."""
    robot = ROBOTS[name]()
    _, targets = _poses(robot, EXHAUSTIVE_POSES, seed=23)
    for target in targets:
        analytic = _classes(robot, [s.q for s in all_solutions(robot, target).solutions], 1e-4)
        searched = _exhaustive(robot, target)
        assert len(analytic) == len(searched), (name, analytic, searched)
        for q in searched:
            assert min(_wrapped(robot, q, a).max() for a in analytic) < 1e-3, (name, q)


def _gap(robot, a, b) -> np.ndarray:
    """|a - b| per joint, revolute joints modulo a turn."""
    revolute = np.array([j.is_revolute for j in robot.joints])
    diff = np.subtract(a, b)
    wrapped = np.remainder(diff + 180.0, 360.0) - 180.0
    return np.abs(np.where(revolute, wrapped, diff))


def test_each_solution_is_listed_once_at_the_turn_nearest_the_start():
    """UR5 joints turn ±360°: a solution and its other turns are one solution,
    listed at the turn nearest the start (the issue: duplicates modulo a turn)."""
    robot, _ = load_robot("ur5")
    _, targets = _poses(robot, 5, seed=5)
    start = (100.0, -200.0, 300.0, -100.0, 200.0, -300.0)
    for target in targets:
        sols = all_solutions(robot, target, start).solutions
        assert 1 <= len(sols) <= 8
        for s in sols:
            for j, joint in enumerate(robot.joints):
                for turn in (-360.0, 360.0):  # no other turn of this joint is nearer
                    other = s.q[j] + turn
                    if joint.min <= other <= joint.max:
                        assert abs(other - start[j]) >= abs(s.q[j] - start[j]) - 1e-9
        for a in range(len(sols)):  # and no two are the same modulo a turn
            for b in range(a):
                gap = np.remainder(np.subtract(sols[a].q, sols[b].q) + 180.0, 360.0) - 180.0
                assert np.abs(gap).max() > 1e-6


def test_solutions_are_ordered_by_distance_from_the_start():
    robot, _ = load_robot("puma560")
    _, targets = _poses(robot, 5, seed=3)
    start = (10.0, 50.0, -120.0, 20.0, 30.0, -40.0)
    for target in targets:
        sols = all_solutions(robot, target, start).solutions
        distances = [np.linalg.norm(np.radians(np.subtract(s.q, start))) for s in sols]
        assert distances == sorted(distances)


def test_a_wrist_singular_pose_still_has_solutions():
    """At home the Puma's axes 4 and 6 line up (joint 5 = 0): the closed form
    picks the free angle and still reaches the pose."""
    robot, _ = load_robot("puma560")
    target = reference_frames(robot, robot.home)[-1]
    found = all_solutions(robot, target)
    assert any(np.abs(np.subtract(s.q, robot.home)).max() < 1e-6 for s in found.solutions)
    for s in found.solutions:
        assert _pose_errors(robot, s.q, target)[0] <= POSITION_TOL * reach(robot)


@pytest.mark.parametrize(("name", "pose"), [("ur5", None), ("puma560", "qs"), ("puma560", "qr")])
def test_a_singular_pose_is_not_listed_twice(name, pose):
    """At a singular pose (UR5 at home: arm stretched and wrist lined up; the
    Puma stretched) a double root must not come out as two solutions a
    rounding error apart."""
    robot, _ = load_robot(name)
    q = robot.home if pose is None else robot.pose(pose)
    target = reference_frames(robot, q)[-1]
    sols = [s.q for s in all_solutions(robot, target).solutions]
    assert len(_classes(robot, sols, 1e-9)) == len(_classes(robot, sols, 1e-3)), sols


def test_out_of_reach_gives_no_solution_and_says_why():
    robot, _ = load_robot("puma560")
    target = np.eye(4)
    target[:3, 3] = (5000.0, 0.0, 0.0)
    found = all_solutions(robot, target)
    assert found.solutions == () and "out of reach" in found.note


# -- numerical ---------------------------------------------------------------------------
def test_a_redundant_arm_gives_a_family_of_representatives():
    robot, _ = load_robot("panda")
    q0 = np.array([10.0, 20.0, -30.0, -100.0, 15.0, 120.0, 40.0])
    target = reference_frames(robot, q0)[-1]
    found = all_solutions(robot, target)
    assert found.method == "numerical" and found.family
    assert "continuous family" in found.note
    assert len(found.solutions) >= 2
    for s in found.solutions:
        position, orientation = _pose_errors(robot, s.q, target)
        assert position <= POSITION_TOL * reach(robot) and orientation <= ORIENTATION_TOL
        assert _within_limits(robot, s.q)
    classes = _classes(robot, [s.q for s in found.solutions], 1.0)
    assert len(classes) == len(
        {tuple(np.round(np.remainder(s.q, 360), 6)) for s in found.solutions}
    )


def test_position_only_on_a_six_axis_arm_is_a_family():
    robot, _ = load_robot("puma560")
    target = np.eye(4)
    target[:3, 3] = (300.0, 100.0, 400.0)
    found = all_solutions(robot, target, position_only=True)
    assert found.family and found.method == "numerical" and found.solutions
    for s in found.solutions:
        assert _pose_errors(robot, s.q, target)[0] <= POSITION_TOL * reach(robot)


def test_an_arm_without_a_closed_form_is_searched_numerically():
    """The Cobra (RRPR, four joints, a four-direction task): both elbows, and
    the tool joint's turn copies, all reaching the pose."""
    robot, _ = load_robot("cobra600")
    q0 = np.array([30.0, 60.0, 100.0, 20.0])
    target = reference_frames(robot, q0)[-1]
    found = all_solutions(robot, target)
    assert found.method == "numerical" and not found.family
    assert "no closed form" in found.note
    assert min(np.abs(np.subtract(s.q, q0)).max() for s in found.solutions) < 1e-6
    for s in found.solutions:
        assert _pose_errors(robot, s.q, target)[0] <= POSITION_TOL * reach(robot)
        assert _within_limits(robot, s.q)
    searched = _exhaustive(robot, target)
    assert len(_classes(robot, [s.q for s in found.solutions], 1e-4)) == len(searched)


# -- the command line -----------------------------------------------------------------------
def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def _oat_args(robot, q):
    pose = robot.kinematics.end_effector(q)
    return ",".join(repr(v) for v in pose.xyz), ",".join(repr(v) for v in pose.oat)


def test_cli_all_lists_every_solution_one_line_each(capsys):
    robot, _ = load_robot("puma560")
    q0 = (20.0, 40.0, -60.0, 30.0, 50.0, 10.0)
    xyz, oat = _oat_args(robot, q0)
    code, out, err = _run(capsys, "ik", "puma560", "--xyz", xyz, "--oat", oat, "--all")
    assert code == 0 and err == ""
    lines = out.splitlines()
    solution_lines = [line for line in lines if line.startswith("q  ")]
    assert lines[0] == "Puma 560" and lines[1] == f"{len(solution_lines)} solutions (analytic)"
    found = all_solutions(robot, robot.kinematics.pose(q0), robot.home)
    assert len(solution_lines) == len(found.solutions) >= 2
    for line, s in zip(solution_lines, found.solutions, strict=True):
        assert f"  {s.config}  residual " in line and "shoulder" in s.config
    assert "Th1 20  Th2 40  Th3 -60  Th4 30  Th5 50  Th6 10  shoulder" in out


def test_cli_all_json_is_ordered_from_the_start(capsys):
    robot, _ = load_robot("puma560")
    q0 = (20.0, 40.0, -60.0, 30.0, 50.0, 10.0)
    xyz, oat = _oat_args(robot, q0)
    start = "150,100,-200,-80,-60,100"
    code, out, err = _run(
        capsys, "ik", "puma560", "--xyz", xyz, "--oat", oat, "--all", "--json", "--from", start
    )
    assert code == 0 and err == ""
    data = json.loads(out)
    assert list(data) == ["robot", "units", "solved", "method", "family", "solutions"]
    assert (data["robot"], data["units"], data["method"], data["family"]) == (
        "Puma 560",
        "mm",
        "analytic",
        False,
    )
    sols = data["solutions"]
    assert all(list(s) == ["q", "config", "residual"] for s in sols)
    begin = np.radians([float(v) for v in start.split(",")])
    distances = [np.linalg.norm(np.radians(s["q"]) - begin) for s in sols]
    assert distances == sorted(distances) and len(sols) >= 2
    assert min(np.abs(np.subtract(s["q"], q0)).max() for s in sols) < 1e-6
    target = robot.kinematics.pose(q0)
    for s in sols:
        assert _pose_errors(robot, s["q"], target)[0] < 1e-6 * reach(robot)


def test_cli_all_without_a_solution_is_one_line_exit_3(capsys):
    code, out, err = _run(capsys, "ik", "puma560", "--xyz", "5000,0,0", "--oat", "0,0,0", "--all")
    assert code == 3 and out == ""
    assert err.count("\n") == 1 and err.startswith("dhsim: no solution for Puma 560: ")
    assert "out of reach" in err


def test_cli_all_position_only_planar_arm_both_elbows(capsys):
    code, out, err = _run(capsys, "ik", "planar2", "--xyz", "1,1,0", "--all", "--json")
    data = json.loads(out)
    assert code == 0 and err == "" and data["method"] == "numerical" and data["family"] is False
    assert sorted(np.round(s["q"], 6).tolist() for s in data["solutions"]) == [
        [0.0, 90.0],
        [90.0, -90.0],
    ]


def test_all_solutions_type():
    robot, _ = load_robot("puma560")
    assert isinstance(all_solutions(robot, robot.kinematics.pose(robot.home)), Solutions)


def test_no_combination_of_turns_is_nearer_the_start():
    """Each solution is at the combination of whole turns (of every joint at
    once, within the limits) nearest the start: checked against the product
    of every joint's turns, UR5 (every joint ±360°) and Puma (joint 6 ±266°)."""
    import itertools

    for name, seed in (("ur5", 8), ("puma560", 9)):
        robot, _ = load_robot(name)
        _, targets = _poses(robot, 4, seed=seed)
        rng = np.random.default_rng(seed)
        for target in targets:
            start = tuple(rng.uniform(robot.lower, robot.upper))
            sols = all_solutions(robot, target, start).solutions
            assert sols
            for s in sols:
                options = [
                    [v + t for t in (-720.0, -360.0, 0.0, 360.0, 720.0) if lo <= v + t <= hi]
                    for v, lo, hi in zip(s.q, robot.lower, robot.upper, strict=True)
                ]
                best = min(
                    np.linalg.norm(np.radians(np.subtract(c, start)))
                    for c in itertools.product(*options)
                )
                assert np.linalg.norm(np.radians(np.subtract(s.q, start))) <= best + 1e-12

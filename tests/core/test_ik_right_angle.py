"""The closed form in the arm's fitted frames (dhsim_tui/core/ik/right_angle_wrist.py)
against the general spherical-wrist form (ik_wrist) and the textbook FK.

The two are separate derivations: the general one works with screw axes in
world coordinates and the Paden-Kahan sub-problems, the fitted one with a
frame on axis 1, a 2-D two-link and Z-Y-Z Euler angles. On random arms of
the geometry (axes 2 and 3 parallel, a spherical wrist with axes at right
angles, any lengths, twists, offsets, base and tool, either convention) they
must give the same solutions with the same words, each reaching the pose.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, assume, given, settings
from hypothesis import strategies as st
from robot_strategies import angle_triples, reference_pose, triples

from dhsim_tui.core import load_robot, reach
from dhsim_tui.core.ik.analytic import SPHERICAL_PARALLEL, detect, solve
from dhsim_tui.core.interop.convert import convert
from dhsim_tui.core.model.robot import AXES, Joint, Robot, Tool

ROBOTS = ("puma560", "puma560_modified", "irb140")
SAME = 1e-7  # degrees: the two forms agree to rounding


def _key(solutions) -> list:
    return sorted((tuple(round(v % 360.0, 4) for v in q), words) for q, words in solutions)


def _agree(robot: Robot, target: np.ndarray, preferred, singular: bool = False) -> list:
    """The fitted form's solutions, after checking them against the general
    form's. ``singular``: the wrist is straight, where "flip" and "no flip"
    are one solution and the word is rounding's choice, and where the general
    form's sine from a cosine (sqrt(1 - c^2)) keeps only ~1e-6 degrees.

    Near a straight (or fully folded) elbow the same holds for "elbow up" and
    "elbow down": within ~1e-5 degrees of it the two elbow solutions are one
    configuration to rounding (the elbow's cosine is 1 - d^2/2, so a rounding
    of 1e-16 in it moves the joints by ~1e-16/d), one form may keep both and
    the other one (4 solutions against 8: hypothesis found an arm whose elbow
    stood 0.001 degrees from straight), and the joint values agree only to
    ~1e-6 degrees. There the test compares the configurations without the
    elbow word, to 1e-4 degrees, and checks that every solution of both forms
    reaches the pose: that is what a solution must do."""
    geometry = detect(robot)
    fitted, _ = solve(robot, geometry, target, preferred)
    general, _ = solve(robot, geometry, target, preferred, generic=True)
    if _elbow_straight(fitted) or _elbow_straight(general) or len(fitted) != len(general):
        return _agree_at_a_straight_elbow(robot, target, fitted, general, singular)
    same = 1e-4 if singular else SAME
    if singular:
        fitted = [(q, words.rpartition(", wrist")[0]) for q, words in fitted]
        general = [(q, words.rpartition(", wrist")[0]) for q, words in general]
    assert len(fitted) == len(general), (_key(fitted), _key(general))
    for (qa, wa), (qb, wb) in zip(_key(fitted), _key(general), strict=True):
        assert wa == wb
        assert _apart(qa, qb) < 1e-3
    # and one to one, joint for joint, to rounding
    for q, words in fitted:
        twins = [g for g, w in general if w == words and _apart(q, g) < same]
        assert twins, (q, words)
    return fitted


def _apart(qa, qb) -> float:
    """The largest joint difference (degrees, modulo a turn)."""
    return max(abs(math.remainder(a - b, 360.0)) for a, b in zip(qa, qb, strict=True))


#: two elbow solutions closer than this (degrees) are one configuration to rounding
ELBOW_MERGED = 1e-3


def _without_elbow(words: str) -> str:
    return ", ".join(word for word in words.split(", ") if not word.startswith("elbow"))


def _elbow_straight(solutions) -> bool:
    """Two solutions differing only in their elbow word stand within
    ELBOW_MERGED of each other: the elbow is straight to rounding."""
    return any(
        wa != wb and _without_elbow(wa) == _without_elbow(wb) and _apart(qa, qb) < ELBOW_MERGED
        for i, (qa, wa) in enumerate(solutions)
        for qb, wb in solutions[i + 1 :]
    )


def _agree_at_a_straight_elbow(robot, target, fitted, general, singular) -> list:
    for solutions in (fitted, general):
        assert solutions
        for q, _ in solutions:
            _reaches(robot, q, target)

    def shown(words: str) -> str:
        words = _without_elbow(words)
        return words.rpartition(", wrist")[0] if singular else words

    for ours, theirs in ((fitted, general), (general, fitted)):
        for q, words in ours:
            twins = [g for g, w in theirs if shown(w) == shown(words) and _apart(q, g) < 1e-4]
            assert twins, (q, words)
    return fitted


def rotation_angle(r: np.ndarray) -> float:
    """The angle of a rotation matrix (from its skew part and trace: exact near 0)."""
    skew = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    return math.atan2(0.5 * np.linalg.norm(skew), 0.5 * (np.trace(r) - 1.0))


def _reaches(robot: Robot, q, target: np.ndarray) -> None:
    pose = reference_pose(robot, q)
    assert np.linalg.norm(pose[:3, 3] - target[:3, 3]) <= 1e-9 * reach(robot), q
    assert rotation_angle(pose[:3, :3].T @ target[:3, :3]) <= 1e-9, q


@pytest.mark.parametrize("name", ROBOTS)
def test_the_bundled_right_angled_wrists_use_the_fitted_frames(name):
    geometry = detect(load_robot(name)[0])
    assert geometry.kind == SPHERICAL_PARALLEL and geometry.frames is not None


def test_a_wrist_not_at_right_angles_uses_the_general_form():
    puma, _ = load_robot("puma560")
    joints = list(puma.joints)
    joints[4] = dataclasses.replace(joints[4], alpha=60.0)  # axis 5 to axis 6 at 60 degrees
    geometry = detect(dataclasses.replace(puma, joints=tuple(joints)))
    assert geometry.kind == SPHERICAL_PARALLEL and geometry.frames is None


@pytest.mark.parametrize("name", ROBOTS)
def test_the_two_forms_agree_on_random_poses_of_the_bundled_arms(name):
    robot, _ = load_robot(name)
    rng = np.random.default_rng(5)
    for q in rng.uniform(robot.lower, robot.upper, (150, 6)):
        target = reference_pose(robot, q)
        preferred = tuple(rng.uniform(robot.lower, robot.upper))
        found = _agree(robot, target, preferred)
        assert found
        for solution, _ in found:
            _reaches(robot, solution, target)


def _singular_poses(robot: Robot):
    """The Puma with its wrist straight (axis 6 on axis 4's line, both ways),
    and with the wrist centre on axis 1."""
    home = np.array(robot.home)
    for q5 in (0.0, 1e-9, 180.0):
        q = home.copy()
        q[1:4] = (30.0, -100.0, 20.0)
        q[4] = q5
        yield q


def test_singular_poses_agree_and_reach():
    puma, _ = load_robot("puma560")
    for q in _singular_poses(puma):
        target = reference_pose(puma, q)
        for solution, _ in _agree(puma, target, tuple(puma.home), singular=True):
            _reaches(puma, solution, target)


@st.composite
def right_angle_arms(draw) -> Robot:
    """Six revolute joints: axes 2 and 3 parallel (alpha2 = 0), axis 1 not
    parallel to them, a spherical wrist (a4 = a5 = d5 = 0) at right angles
    (alpha4, alpha5 = +-90), everything else drawn: lengths, twists, offsets,
    the base and the tool. Standard D-H, then perhaps converted."""
    lengths = st.floats(-600, 600).filter(lambda v: abs(v) > 20.0)
    any_length = st.one_of(st.just(0.0), lengths)
    twist = st.sampled_from([90.0, -90.0, 45.0, -60.0, 120.0])
    right = st.sampled_from([90.0, -90.0])
    angle = st.floats(-180, 180)
    # joint 3's twist: exactly 0 or 180 (with a3 = 0 the wrist centre is then
    # on axis 3: another geometry, skipped), or clear of them. A twist of
    # 1e-5 degrees leaves the centre ~1e-6 mm off axis 3: an arm whose joint
    # values are ill-defined (both forms reach the pose to 1e-14 mm by joint
    # values 1e-6 degrees apart), so they cannot be compared to 1e-7 degrees
    exact = st.sampled_from([0.0, 180.0, -180.0])
    clear = st.floats(-179.0, 179.0).filter(lambda v: abs(v) > 1.0)
    rows = [
        (draw(angle), draw(any_length), draw(any_length), draw(twist)),  # joint 1
        (draw(angle), draw(any_length), draw(lengths), 0.0),  # 2: parallel to 3
        (draw(angle), draw(any_length), draw(any_length), draw(st.one_of(exact, clear))),
        (draw(angle), draw(lengths), 0.0, draw(right)),  # the wrist: a4 = 0
        (draw(angle), 0.0, 0.0, draw(right)),  # d5 = a5 = 0
        (draw(angle), draw(any_length), draw(any_length), draw(st.floats(-180, 180))),
    ]
    offsets = [draw(st.one_of(st.just(0.0), angle)) for _ in rows]
    joints = tuple(
        Joint(
            type="revolute",
            theta=theta,
            d=d,
            a=a,
            alpha=alpha,
            offset=offset,
            min=theta - offset - 170.0,
            max=theta - offset + 170.0,
        )
        for (theta, d, a, alpha), offset in zip(rows, offsets, strict=True)
    )
    base_z = draw(st.sampled_from(AXES))
    robot = Robot(
        name="random right-angled wrist",
        joints=joints,
        units="mm",
        convention="standard",
        base_height=draw(st.one_of(st.just(0.0), st.floats(1.0, 800.0))),
        base_z=base_z,
        base_x=draw(st.sampled_from([a for a in AXES if a[1] != base_z[1]])),
        base_xyz=draw(triples),
        base_rpy=draw(angle_triples),
        tool=Tool(draw(triples), draw(angle_triples)),
    )
    return convert(robot, "modified") if draw(st.booleans()) else robot


def _straight_elbow_of_the_puma() -> float:
    """Joint 3's value (degrees) where the Puma's elbow is straight at
    q2 = -30, q5 = 40: the middle of its two elbow solutions."""
    puma, _ = load_robot("puma560")
    q = np.array(puma.home, float)
    q[1], q[2], q[4] = -30.0, -87.31, 40.0
    solutions, _ = solve(puma, detect(puma), reference_pose(puma, q), tuple(puma.home))
    elbows = sorted({round(s[2], 9) for s, _ in solutions})
    assert len(elbows) == 2
    return sum(elbows) / 2


@pytest.mark.parametrize("apart", [1e-2, 1e-3, 1e-5, 1e-6, 1e-8, 0.0])
def test_the_two_forms_agree_at_and_near_a_straight_elbow(apart):
    """The case hypothesis found (an elbow 0.001 degrees from straight): the
    fitted form gave 4 solutions and the general form 8, their joints ~3e-6
    degrees apart; both reach the pose. See :func:`_agree`."""
    puma, _ = load_robot("puma560")
    q = np.array(puma.home, float)
    q[1], q[2], q[4] = -30.0, _straight_elbow_of_the_puma() - apart, 40.0
    target = reference_pose(puma, q)
    found = _agree(puma, target, tuple(puma.home))
    assert any(_apart(s, q) < 1e-4 for s, _ in found)


#: no shrinking: a failure is reported as found, at once (shrinking a near-
#: singular arm once took 78 s); derandomized, so CI sees the same arms on
#: every run, and the explicit straight-elbow cases are tested above
@settings(
    max_examples=60,
    deadline=None,
    derandomize=True,
    database=None,
    phases=[Phase.explicit, Phase.generate],
    suppress_health_check=[HealthCheck.too_slow],
)
@given(right_angle_arms(), st.integers(0, 2**32 - 1))
def test_the_two_forms_agree_on_random_arms(robot, seed):
    geometry = detect(robot)
    # drawn degenerate (the wrist centre on axis 3's line): another geometry
    assume(geometry is not None and geometry.kind == SPHERICAL_PARALLEL)
    assert geometry.frames is not None
    rng = np.random.default_rng(seed)
    for q in rng.uniform(robot.lower, robot.upper, (8, 6)):
        target = reference_pose(robot, q)
        found = _agree(robot, target, tuple(robot.home))
        assert found, q
        for solution, _ in found:
            _reaches(robot, solution, target)

"""The compiled Jacobian, the fast manipulability and the small solvers, checked
against independent computations: the textbook FK of conftest.reference_frames
(finite differences of it, and the Jacobian read off its frames) and numpy's
own linear algebra."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import random_q, reference_frames
from hypothesis import given, settings
from hypothesis import strategies as st
from robot_strategies import robots

from dhsim_tui.core import DhsimError, Joint, Robot, load_robot
from dhsim_tui.core.analysis.cholesky import root_gram_det
from dhsim_tui.core.analysis.jacobian import (
    COMPILE_AFTER,
    dexterity,
    jacobian,
    jacobian_from_frames,
    kernel,
    manipulability,
    normalised,
)
from dhsim_tui.core.analysis.jacobian_codegen import compile_jacobian
from dhsim_tui.core.ik.rotation import rotation_error


def finite_difference_jacobian(robot: Robot, q) -> np.ndarray:
    """Central differences of the textbook FK: linear velocity per radian (or
    per unit length) over the world-frame rotation vector per radian."""
    q = np.array(q, dtype=float)
    jac = np.zeros((6, robot.dof))
    for i, joint in enumerate(robot.joints):
        h = 1e-5 if joint.is_revolute else 1e-5 * max(1.0, abs(joint.max - joint.min))
        plus, minus = q.copy(), q.copy()
        plus[i] += h
        minus[i] -= h
        ahead, behind = reference_frames(robot, plus)[-1], reference_frames(robot, minus)[-1]
        per = 2 * (math.radians(h) if joint.is_revolute else h)
        jac[:3, i] = (ahead[:3, 3] - behind[:3, 3]) / per
        jac[3:, i] = rotation_error(ahead[:3, :3], behind[:3, :3]) / per
    return jac


def close(a: np.ndarray, b: np.ndarray, rel: float) -> bool:
    """Equal to ``rel`` of the larger matrix's largest entry."""
    size = max(np.abs(a).max(), np.abs(b).max(), 1e-300)
    return bool(np.abs(a - b).max() <= rel * size)


def compiled(robot: Robot, q) -> np.ndarray:
    return np.array(compile_jacobian(robot)(tuple(q))).reshape(6, robot.dof)


def test_compiled_jacobian_is_the_jacobian_of_the_textbook_frames(bundled, rng):
    for _ in range(10):
        q = random_q(bundled, rng)
        expected = jacobian_from_frames(bundled, reference_frames(bundled, q))
        assert close(compiled(bundled, q), expected, 1e-12)


def test_compiled_jacobian_matches_finite_differences(bundled, rng):
    for _ in range(5):
        q = random_q(bundled, rng)
        assert close(compiled(bundled, q), finite_difference_jacobian(bundled, q), 1e-7)


def test_compiled_jacobian_is_the_frames_jacobian_bit_for_bit(bundled, rng):
    """The same operations on the same numbers: not merely close."""
    for _ in range(10):
        q = tuple(random_q(bundled, rng).tolist())
        assert np.array_equal(
            compiled(bundled, q), jacobian_from_frames(bundled, bundled.kinematics.frames(q))
        )


@settings(max_examples=60, deadline=None)
@given(robot=robots(), seed=st.integers(0, 2**32 - 1))
def test_random_robots_compiled_jacobian(robot, seed):
    """Both conventions, offsets, a general base, a tool, prismatic joints."""
    q = [float(v) for v in np.random.default_rng(seed).uniform(robot.lower, robot.upper)]
    expected = jacobian_from_frames(robot, reference_frames(robot, q))
    assert close(compiled(robot, q), expected, 1e-11)
    assert close(compiled(robot, q), finite_difference_jacobian(robot, q), 1e-6)
    state, flat = kernel(robot)(q)
    assert close(np.array(flat).reshape(6, -1), normalised(robot, expected), 1e-11)
    assert close(np.array(state[9:]), reference_frames(robot, q)[-1][:3, 3], 1e-11)


def test_jacobian_is_the_same_before_and_after_it_is_compiled():
    robot, _ = load_robot("irb140")
    rng = np.random.default_rng(3)
    qs = [tuple(v) for v in rng.uniform(robot.lower, robot.upper, (COMPILE_AFTER + 8, 6)).tolist()]
    got = [jacobian(robot, q) for q in qs]  # the first ones from the frames, then compiled
    for q, jac in zip(qs, got, strict=True):
        assert np.array_equal(jac, jacobian_from_frames(robot, reference_frames(robot, q))) or (
            close(jac, jacobian_from_frames(robot, reference_frames(robot, q)), 1e-12)
        )
    assert np.array_equal(got[0], jacobian(robot, qs[0]))  # compiled now: the same numbers


def test_jacobian_of_a_wrong_joint_vector_is_a_clear_error():
    robot, _ = load_robot("puma560")
    for _ in range(COMPILE_AFTER + 1):
        jacobian(robot, robot.home)
    with pytest.raises(DhsimError, match="expected 6 joint values"):
        jacobian(robot, (0.0, 0.0))
    with pytest.raises(DhsimError, match="expected 6 joint values"):
        manipulability(robot, (0.0,) * 7)


def test_manipulability_is_the_product_of_the_singular_values(bundled, rng):
    """As Dexterity defines it: the normalised Jacobian's measured rows, the
    product of the singular values (here from numpy's SVD of the textbook one)."""
    for _ in range(10):
        q = random_q(bundled, rng)
        fast = manipulability(bundled, q)
        expected = dexterity(
            bundled, jac=jacobian_from_frames(bundled, reference_frames(bundled, q))
        )
        assert math.isclose(fast, expected.manipulability, rel_tol=1e-9, abs_tol=1e-12)
        jac = jacobian_from_frames(bundled, reference_frames(bundled, q))
        assert math.isclose(
            manipulability(bundled, jac=jac), expected.manipulability, rel_tol=1e-9, abs_tol=1e-12
        )


def test_manipulability_of_known_poses():
    planar, _ = load_robot("planar2")
    assert math.isclose(manipulability(planar, (0.0, 90.0)), 0.25, rel_tol=1e-12)
    assert manipulability(planar, (0.0, 0.0)) < 1e-12  # stretched out
    puma, _ = load_robot("puma560")
    assert manipulability(puma, (0, 45, -135, 0, 0, 0)) < 1e-9  # wrist singular
    assert manipulability(puma, (0, 45, -135, 0, 45, 0)) > 0.02


def test_a_prismatic_joint_column_is_its_axis():
    robot = Robot("P", (Joint("prismatic", 0, 0, 0, 0, -100, 100),), base_z="+x", base_x="+y")
    assert np.allclose(compiled(robot, (10.0,))[:, 0], (1, 0, 0, 0, 0, 0))


@pytest.mark.parametrize(("m", "n"), [(6, 6), (6, 7), (4, 4), (3, 2), (2, 3)])
def test_root_gram_det_is_the_product_of_singular_values(m, n):
    rng = np.random.default_rng(m * 10 + n)
    jac = rng.normal(size=(m, n))
    expected = float(np.prod(np.linalg.svd(jac, compute_uv=False)))
    assert math.isclose(root_gram_det(m, n)(jac.ravel().tolist()), expected, rel_tol=1e-10)
    if m <= n:
        jac[-1] = jac[0]  # a repeated row: singular
    else:
        jac[:, -1] = jac[:, 0]  # a repeated column
    assert root_gram_det(m, n)(jac.ravel().tolist()) < 1e-6 * max(expected, 1.0)

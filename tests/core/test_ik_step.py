"""The numerical IK's compiled descent (core/ik/step_codegen.py), checked
against a plain numpy damped least-squares step, and solves with it checked
by the reference's forward kinematics."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import BUNDLED, reference_frames

from dhsim_tui.core import load_robot, reach
from dhsim_tui.core.ik.codegen_fold import Folder
from dhsim_tui.core.ik.numerical import POSITION_FIRST, solve
from dhsim_tui.core.ik.numerical_descent import (
    DAMPING,
    DAMPING_BIAS,
    FOLD_AFTER,
    _compiled,
    _plan,
)
from dhsim_tui.core.ik.numerical_problem import ORIENTATION_TOL, POSITION_TOL, IkProblem
from dhsim_tui.core.ik.rotation import rotation_error
from dhsim_tui.core.ik.step_codegen import compile_descent


def reference_step(problem: IkProblem, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(error at x, the damped least-squares step from x), by numpy: the
    Jacobian from the frames, the rows solved for, weighted, and the normal
    equations solved by np.linalg.solve."""
    frames, error = problem.evaluate(x)
    jac = problem.full_jacobian(frames)
    w = problem.weight[problem.rows]
    j, e = jac[problem.rows] * w[:, None], error[problem.rows] * w
    squared = float(e @ e)
    lam = DAMPING * squared + min(DAMPING_BIAS, squared)
    if j.shape[1] <= j.shape[0]:
        step = np.linalg.solve(j.T @ j + lam * np.eye(j.shape[1]), j.T @ e)
    else:
        step = j.T @ np.linalg.solve(j @ j.T + lam * np.eye(j.shape[0]), e)
    return error, step


def error_at(problem: IkProblem, x: np.ndarray) -> np.ndarray:
    """The error at x (internal units, not clamped to the limits), by numpy."""
    pose = problem.robot.kinematics.pose(x / problem.to_internal)
    error = np.zeros(6)
    error[:3] = (problem.target[:3, 3] - pose[:3, 3]) / problem.scale
    if not problem.position_only:
        error[3:] = rotation_error(problem.target[:3, :3], pose[:3, :3])
    return error


def one_step(problem: IkProblem, x: np.ndarray, free: bool) -> tuple[np.ndarray, np.ndarray]:
    """The compiled descent's first step from x: (x after it, error there)."""
    moved, error, iterations, _ = _compiled(problem)(
        x.tolist(), problem.goal, 1, DAMPING_BIAS, False, free
    )
    assert iterations == 1
    return np.array(moved), np.array(error)


def random_problems(name: str, count: int, rng: np.random.Generator):
    """(problem, x) pairs: random targets of every kind (whole pose, position
    only, the position weighted first) and random joint values within the
    limits, away from the target."""
    robot, _ = load_robot(name)
    for k in range(count):
        target = robot.kinematics.pose(rng.uniform(robot.lower, robot.upper))
        problem = IkProblem(robot, target, position_only=k % 3 == 1)
        if k % 3 == 2 and problem.rows[3:].any():
            weight = POSITION_FIRST[k % len(POSITION_FIRST)]
            problem.weight = np.array([weight, weight, weight, 1.0, 1.0, 1.0])
        # inside the limits (a step from a limit is clamped, tested below)
        span = problem.high - problem.low
        x = problem.low + span * rng.uniform(0.05, 0.95, robot.dof)
        yield problem, x


@pytest.mark.parametrize("name", BUNDLED)
def test_the_compiled_step_is_the_damped_least_squares_step(name):
    rng = np.random.default_rng(sum(map(ord, name)))
    for problem, x in random_problems(name, 24, rng):
        error, step = reference_step(problem, x)
        if problem.converged(error):
            continue
        moved, moved_error = one_step(problem, x, free=True)
        scale = max(1.0, float(np.abs(step).max()))
        np.testing.assert_allclose(moved - x, step, rtol=0, atol=1e-12 * scale)
        # and the error it reports where it lands (maybe past a limit) is numpy's there
        np.testing.assert_allclose(moved_error, error_at(problem, moved), rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["puma560", "panda", "stanford", "cobra600"])
def test_a_clamped_step_stops_at_the_limits_as_limit_does(name):
    rng = np.random.default_rng(7)
    for problem, x in random_problems(name, 24, rng):
        x = np.where(rng.uniform(size=len(x)) < 0.3, problem.high, x)  # some on a limit
        error, step = reference_step(problem, x)
        if problem.converged(error):
            continue
        moved, _ = one_step(problem, x, free=False)
        np.testing.assert_allclose(moved, problem.limit(x + step), rtol=0, atol=1e-12)
        assert np.all(moved >= problem.low) and np.all(moved <= problem.high)


@pytest.mark.parametrize("name", BUNDLED)
def test_the_unfolded_descent_takes_the_same_steps(name):
    """A robot's descents run unfolded at first (quicker to compile), and
    unfolded is the fallback for chain lines the folder cannot read: the
    same arithmetic to the bit, so the same call gives the same answer."""
    rng = np.random.default_rng(11)
    for problem, x in random_problems(name, 12, rng):
        unfolded = compile_descent(problem.robot, **_plan(problem), fold=False)
        arguments = (x.tolist(), problem.goal, 3, DAMPING_BIAS, False, False)
        folded = compile_descent(problem.robot, **_plan(problem), fold=True)
        moved, error, iterations, ok = folded(*arguments)
        expected = unfolded(*arguments)
        assert (moved, error, iterations, ok) == expected


def assert_reaches(robot, target, result, position_only=False):
    assert result.success, result.reason
    robot.check_q(result.q)  # within the limits
    reached = reference_frames(robot, result.q)[-1]
    position = np.linalg.norm(reached[:3, 3] - target[:3, 3])
    assert position <= 2 * POSITION_TOL * reach(robot)
    if not position_only:
        turned = np.linalg.norm(rotation_error(target[:3, :3], reached[:3, :3]))
        assert turned <= 2 * ORIENTATION_TOL
    # the solver's own FK agrees
    pose = robot.kinematics.pose(result.q)
    assert np.linalg.norm(pose[:3, 3] - target[:3, 3]) <= 2 * POSITION_TOL * reach(robot)


@pytest.mark.parametrize(
    ("name", "position_only"),
    [("puma560", False), ("panda", False), ("cobra600", False), ("planar2", True)],
)
def test_random_reachable_targets_are_solved(name, position_only):
    robot, _ = load_robot(name)
    rng = np.random.default_rng(31)
    for k in range(60):
        q = rng.uniform(robot.lower, robot.upper)
        target = reference_frames(robot, q)[-1]
        if position_only:
            target = target.copy()
            target[:3, :3] = np.eye(3)  # any orientation: the position counts
        result = solve(robot, target, robot.home, position_only=position_only, restarts=30, seed=k)
        assert_reaches(robot, target, result, position_only)
        # from nearby, without restarts (as a jog): the nearby solution
        near = np.clip(q + rng.normal(0.0, 3.0, robot.dof), robot.lower, robot.upper)
        result = solve(robot, target, tuple(near), position_only=position_only, max_iter=40)
        assert_reaches(robot, target, result, position_only)
        if not position_only and robot.dof == 6:
            assert np.abs(np.array(result.q) - q).max() < 20.0


def test_the_same_call_gives_the_same_answer():
    robot, _ = load_robot("panda")
    rng = np.random.default_rng(5)
    for _ in range(2 * FOLD_AFTER):  # before and after its descents are folded
        target = robot.kinematics.pose(rng.uniform(robot.lower, robot.upper))
        first = solve(robot, target, robot.home, restarts=30)
        again = solve(robot, target, robot.home, restarts=30)
        assert first == again


def test_the_folder_folds_constants_and_keeps_the_rest_exact():
    fold = Folder({"out"})
    lines = fold.lines(
        [
            "x0, x1, y0, y1 = 1.0, 0.0, 0.0, 1.0",
            "c = _cos(q*0.5); s = _sin(q*0.5)",
            "x0, x1, y0, y1 = c*x0 + s*y0, c*x1 + s*y1, c*y0 - s*x0, c*y1 - s*x1",
            "y0, y1 = -y0, -y1",
            "p = 0.0",
            "p += 2.0*x1 + 0.0*y1",
            "out = p - y0 * 3.0",
        ]
    )
    namespace = {"_cos": math.cos, "_sin": math.sin, "q": 0.7}
    exec("\n".join(lines), namespace)
    s = math.sin(0.35)
    assert namespace["out"] == 2.0 * s - s * 3.0  # y0 = -(-s): the same float operations
    assert len(lines) < 7 and not any("0.0 *" in line or "1.0 *" in line for line in lines)
    assert fold.ref("x0") == next(line for line in lines if line.startswith("c__")).split()[0]

"""The bundled Puma's ``demo`` program is clean as a path (issue 19), checked
here without the program runner: joint moves sampled on their straight line
in joint space (whatever the speed profile, a joint move stays on it), linear
moves sampled on the tool's straight line with the orientation turned about
one axis (slerp, written here from Rodrigues' formula), each sample's joints
solved by IK from the previous sample's and checked with the textbook
forward kinematics of tests/conftest.py.

The path starts at step 1's target: from the Puma's home (qz, the wrist
straight) any path starts in a singularity.
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import reference_frames

from dhsim_tui.core.analysis.jacobian import NEAR_SINGULAR, manipulability
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.ik.numerical import solve
from dhsim_tui.core.model.program import LINEAR_SPEED_MM, target_joints, top_speed

PUMA = load_robot("puma560")[0]
DEMO = PUMA.program("demo")
SAMPLES = 150


def turned(start: np.ndarray, end: np.ndarray, fraction: float) -> np.ndarray:
    """The rotation ``fraction`` of the way from ``start`` to ``end`` about one axis."""
    relative = start.T @ end
    angle = np.arccos(np.clip((np.trace(relative) - 1) / 2, -1, 1))
    if angle < 1e-12:
        return start
    axis = np.array(
        [
            relative[2, 1] - relative[1, 2],
            relative[0, 2] - relative[2, 0],
            relative[1, 0] - relative[0, 1],
        ]
    ) / (2 * np.sin(angle))
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    a = angle * fraction
    return start @ (np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * k @ k)


def segments():
    """(step number, move, start joints, end joints, speed) of each move after step 1."""
    out = []
    q = target_joints(PUMA, "demo", 1, DEMO.steps[0])
    for number, step in enumerate(DEMO.steps[1:], start=2):
        if step.is_wait:
            continue
        end = target_joints(PUMA, "demo", number, step)
        out.append((number, step.move, q, end, step.speed))
        q = end
    return out


def linear_samples(start, end) -> list[tuple[float, ...]]:
    first, last = reference_frames(PUMA, start)[-1], reference_frames(PUMA, end)[-1]
    path, q = [tuple(start)], tuple(start)
    for fraction in np.linspace(0, 1, SAMPLES)[1:]:
        target = np.eye(4)
        target[:3, 3] = first[:3, 3] + (last[:3, 3] - first[:3, 3]) * fraction
        target[:3, :3] = turned(first[:3, :3], last[:3, :3], fraction)
        found = solve(PUMA, target, q)
        assert found.success, f"IK failed {fraction:.3f} of the way"
        reached = reference_frames(PUMA, found.q)[-1]
        assert np.allclose(reached, target, atol=1e-6)
        q = found.q
        path.append(q)
    return path


def test_the_demo_has_joint_and_linear_moves_and_a_wait():
    moves = [step.move for step in DEMO.steps]
    assert "joint" in moves and "linear" in moves and "wait" in moves


@pytest.mark.parametrize("segment", segments(), ids=lambda s: f"step {s[0]} {s[1]}")
def test_each_move_stays_clean(segment):
    _number, move, start, end, speed = segment
    if move == "joint":
        fractions = np.linspace(0, 1, SAMPLES)
        path = [tuple(np.add(start, np.subtract(end, start) * f)) for f in fractions]
    else:
        path = linear_samples(start, end)
        assert np.allclose(path[-1], end, atol=1e-3)  # the same branch all the way
        jumps = np.abs(np.diff(np.array(path), axis=0)).max()
        assert jumps < 1.0  # degrees between samples 1/150 of the way apart
        tool = np.array([reference_frames(PUMA, q)[-1][:3, 3] for q in path])
        travel = np.linalg.norm(np.diff(tool, axis=0), axis=1)
        turn = np.abs(np.diff(np.array(path), axis=0)).max(axis=1)
        assert travel.min() > 0  # the tool moves all along a linear move
        needed = (turn / travel).max() * (speed if speed is not None else LINEAR_SPEED_MM)
        # at the move's speed, no joint needs more than 60 % of its top speed
        # (room for a speed profile that peaks above the mean)
        assert needed <= 0.6 * min(top_speed(j, PUMA.units) for j in PUMA.joints)
    for q in path:
        margin = min(min(v - j.min, j.max - v) for v, j in zip(q, PUMA.joints, strict=True))
        assert margin > 10.0
        assert manipulability(PUMA, q) > NEAR_SINGULAR
        lowest = min(frame[2, 3] for frame in reference_frames(PUMA, q))
        assert lowest > -PUMA.base_height

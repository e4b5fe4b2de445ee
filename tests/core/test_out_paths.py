"""The ``out=`` paths of forward kinematics and the Jacobian, and batch FK's
reused arrays: the same numbers as the plain paths and as an independent
computation (the textbook product of D-H matrices, written out here, and
central differences of it), the caller's array returned, clear errors for an
array of the wrong kind."""

from __future__ import annotations

import math
import threading

import numpy as np
import pytest

from dhsim_tui.core import DhsimError, bundled_names, load_robot
from dhsim_tui.core.analysis.jacobian import COMPILE_AFTER, jacobian, jacobian_from_frames
from dhsim_tui.core.model.kinematics_batch import CHUNK

# -- an independent forward kinematics: plain 4×4 products ---------------------------


def rot(axis: str, deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    m = np.eye(4)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def move(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def unit(name: str) -> np.ndarray:
    """A base axis named like "+z" or "-x"."""
    v = np.zeros(3)
    v["xyz".index(name[1])] = 1.0 if name[0] == "+" else -1.0
    return v


def dh_frames(robot, q) -> list[np.ndarray]:
    """Frames 0..n and the tool: base, then Rz(θ)·Tz(d)·Tx(a)·Rx(α) per joint
    (standard D-H) or Rx(α)·Tx(a)·Rz(θ)·Tz(d) (modified), then the tool."""
    x, z = unit(robot.base_x), unit(robot.base_z)
    axes = np.eye(4)
    axes[:3, :3] = np.column_stack([x, np.cross(z, x), z])
    roll, pitch, yaw = robot.base_rpy
    frame = move(*robot.base_xyz) @ axes @ rot("z", yaw) @ rot("y", pitch) @ rot("x", roll)
    frames = [frame]
    for joint, value in zip(robot.joints, q, strict=True):
        variable = float(value) + joint.offset
        theta = variable if joint.is_revolute else joint.theta
        d = joint.d if joint.is_revolute else variable
        if robot.convention == "standard":
            link = rot("z", theta) @ move(0, 0, d) @ move(joint.a, 0, 0) @ rot("x", joint.alpha)
        else:
            link = rot("x", joint.alpha) @ move(joint.a, 0, 0) @ rot("z", theta) @ move(0, 0, d)
        frame = frame @ link
        frames.append(frame)
    roll, pitch, yaw = robot.tool.rpy
    tool = move(*robot.tool.xyz) @ rot("z", yaw) @ rot("y", pitch) @ rot("x", roll)
    frames.append(frame @ tool)
    return frames


def size(robot) -> float:
    """A length to scale tolerances by."""
    return 1.0 + sum(abs(j.a) + abs(j.d) + abs(j.max) for j in robot.joints)


def random_qs(robot, count: int, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(robot.lower, robot.upper, size=(count, robot.dof))


@pytest.fixture(params=bundled_names())
def robot(request):
    return load_robot(request.param)[0]


def warm(robot, compiled: bool) -> None:
    """Run the chains and the Jacobian past the stepwise start (or not)."""
    if compiled:
        for _ in range(COMPILE_AFTER):
            robot.kinematics.pose(robot.home)
            robot.kinematics.frames(robot.home)
            jacobian(robot, robot.home)


# -- single poses --------------------------------------------------------------------


@pytest.mark.parametrize("compiled", [False, True])
def test_pose_and_frames_into_out_equal_plain_and_textbook(robot, compiled):
    warm(robot, compiled)
    kin = robot.kinematics
    pose_out = np.full((4, 4), np.nan)
    frames_out = np.full((robot.dof + 2, 4, 4), np.nan)
    for q in random_qs(robot, 10):
        q = tuple(q.tolist())
        expected = np.array(dh_frames(robot, q))
        got = kin.pose(q, out=pose_out)
        assert got is pose_out
        assert np.array_equal(got, kin.pose(q))  # bit for bit
        np.testing.assert_allclose(got, expected[-1], rtol=0, atol=1e-9 * size(robot))
        got = kin.frames(q, out=frames_out)
        assert got is frames_out
        assert np.array_equal(got, kin.frames(q))
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-9 * size(robot))
        assert np.array_equal(pose_out, frames_out[-1])


def test_the_same_bits_before_and_after_compiling(robot):
    """The stepwise start and the compiled chain give the same pose, frames
    and Jacobian, plain or into an array."""
    qs = [tuple(q.tolist()) for q in random_qs(robot, 5, seed=1)]
    before = [(robot.kinematics.pose(q), robot.kinematics.frames(q)) for q in qs]
    jac_before = [jacobian(robot, q) for q in qs]
    warm(robot, True)
    pose_out, frames_out = np.empty((4, 4)), np.empty((robot.dof + 2, 4, 4))
    jac_out = np.empty((6, robot.dof))
    for q, (pose, frames), jac in zip(qs, before, jac_before, strict=True):
        assert np.array_equal(robot.kinematics.pose(q, out=pose_out), pose)
        assert np.array_equal(robot.kinematics.frames(q, out=frames_out), frames)
        assert np.array_equal(jacobian(robot, q, out=jac_out), jac)


def test_a_numpy_vector_gives_the_same_bits_as_a_tuple():
    robot, _ = load_robot("panda")
    kin = robot.kinematics
    warm(robot, True)
    for q in random_qs(robot, 5):
        plain = tuple(q.tolist())
        assert kin.state(q) == kin.state(plain)
        assert kin.position(q) == kin.position(plain)
        assert np.array_equal(kin.pose(q), kin.pose(plain))
        assert np.array_equal(kin.frames(q), kin.frames(plain))
        assert np.array_equal(jacobian(robot, q), jacobian(robot, plain))


@pytest.mark.parametrize("compiled", [False, True])
def test_an_out_that_is_not_c_contiguous_is_filled_too(compiled):
    robot, _ = load_robot("puma560")
    warm(robot, compiled)
    q = (10.0, 20.0, -30.0, 40.0, 50.0, 60.0)
    pose = np.empty((4, 4), order="F")
    assert robot.kinematics.pose(q, out=pose) is pose
    assert np.array_equal(pose, robot.kinematics.pose(q))
    frames = np.empty((8, 8, 4))[:, ::2]  # every other row of a bigger array
    assert robot.kinematics.frames(q, out=frames) is frames
    assert np.array_equal(frames, robot.kinematics.frames(q))
    jac = np.empty((robot.dof, 6)).T
    assert jacobian(robot, q, out=jac) is jac
    assert np.array_equal(jac, jacobian(robot, q))


@pytest.mark.parametrize("compiled", [False, True])
def test_a_wrong_out_is_a_clear_error(compiled):
    robot, _ = load_robot("puma560")
    warm(robot, compiled)
    kin, q = robot.kinematics, robot.home
    for bad in (np.empty((3, 4)), np.empty(16), np.empty((4, 4), np.float32), [[0.0] * 4] * 4):
        with pytest.raises(DhsimError, match=r"out must be a float64 array of shape \(4, 4\)"):
            kin.pose(q, out=bad)
    with pytest.raises(DhsimError, match=r"shape \(8, 4, 4\)"):
        kin.frames(q, out=np.empty((7, 4, 4)))
    with pytest.raises(DhsimError, match=r"shape \(6, 6\)"):
        jacobian(robot, q, out=np.empty((6, 5)))
    with pytest.raises(DhsimError, match=r"shape \(6, 6\)"):
        jacobian_from_frames(robot, kin.frames(q), out=np.empty((5, 6)))
    frozen = np.zeros((4, 4))
    frozen.flags.writeable = False
    with pytest.raises(DhsimError, match="writable"):
        kin.pose(q, out=frozen)
    assert not frozen.any()
    with pytest.raises(DhsimError, match="expected 6 joint values"):  # still about q
        kin.pose((1.0, 2.0), out=np.empty((4, 4)))
    with pytest.raises(DhsimError, match="expected 6 joint values"):
        jacobian(robot, (1.0, 2.0), out=np.empty((6, 6)))


# -- the Jacobian ----------------------------------------------------------------------


def finite_differences(robot, q) -> np.ndarray:
    """Central differences of :func:`dh_frames`' tool frame: linear velocity
    per radian (per unit length for a prismatic joint) over the angular one."""
    jac = np.zeros((6, robot.dof))
    for i, joint in enumerate(robot.joints):
        h = 1e-4 if joint.is_revolute else 1e-4 * size(robot)
        plus, minus = np.array(q, float), np.array(q, float)
        plus[i] += h
        minus[i] -= h
        ahead, behind = dh_frames(robot, plus)[-1], dh_frames(robot, minus)[-1]
        step = 2 * (math.radians(h) if joint.is_revolute else h)
        jac[:3, i] = (ahead[:3, 3] - behind[:3, 3]) / step
        turn = ahead[:3, :3] @ behind[:3, :3].T  # small: its skew part is the angle's
        jac[3:, i] = 0.5 * np.array(
            [turn[2, 1] - turn[1, 2], turn[0, 2] - turn[2, 0], turn[1, 0] - turn[0, 1]]
        )
        jac[3:, i] /= step
    return jac


@pytest.mark.parametrize("compiled", [False, True])
def test_jacobian_into_out_matches_finite_differences(robot, compiled):
    warm(robot, compiled)
    out = np.full((6, robot.dof), np.nan)
    for q in random_qs(robot, 4, seed=2):
        got = jacobian(robot, q, out=out)
        assert got is out
        assert np.array_equal(got, jacobian(robot, q))
        expected = finite_differences(robot, q)
        scale = max(np.abs(expected).max(), 1.0)
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-6 * scale)


def test_jacobian_from_frames_into_out(robot):
    q = random_qs(robot, 1, seed=3)[0]
    frames = robot.kinematics.frames(q)
    out = np.full((6, robot.dof), np.nan)
    assert jacobian_from_frames(robot, frames, out=out) is out
    assert np.array_equal(out, jacobian_from_frames(robot, frames))


# -- batch FK ----------------------------------------------------------------------------


def check_batch(robot, qs: np.ndarray, poses: np.ndarray) -> None:
    """Every pose as the per-sample FK's; some, also the textbook product's."""
    assert poses.shape == (len(qs), 4, 4)
    single = np.array([robot.kinematics.pose(q) for q in qs])
    np.testing.assert_allclose(poses, single, rtol=0, atol=1e-9 * size(robot))
    for i in sorted({0, len(qs) // 2, len(qs) - 1, min(CHUNK, len(qs) - 1)}):
        expected = dh_frames(robot, qs[i])[-1]
        np.testing.assert_allclose(poses[i], expected, rtol=0, atol=1e-9 * size(robot))


def test_batch_into_out_matches_per_sample_fk(robot):
    qs = random_qs(robot, 300, seed=4)
    out = np.full((300, 4, 4), np.nan)
    assert robot.kinematics.batch(qs, out=out) is out
    assert np.array_equal(out, robot.kinematics.batch(qs))
    check_batch(robot, qs, out)
    laid_out = np.full((4, 4, 300), np.nan).transpose(2, 0, 1)  # as a new result is
    assert robot.kinematics.batch(qs, out=laid_out) is laid_out
    assert np.array_equal(laid_out, out)


@pytest.mark.parametrize("name", ["puma560", "panda"])  # without and with a tool
def test_batch_calls_of_other_sizes_reuse_the_arrays_rightly(name):
    """Bigger than a chunk, then smaller, then bigger again, plain and into
    arrays: each right, and no result changed by a later call."""
    robot, _ = load_robot(name)
    kin = robot.kinematics
    sizes = [CHUNK + 7, 5, 2 * CHUNK + 1, 1, 0, 64]
    batches = [random_qs(robot, n, seed=n) for n in sizes]
    results = [kin.batch(qs) for qs in batches]
    kept = [r.copy() for r in results]
    for qs, poses in zip(batches, results, strict=True):
        if len(qs):
            check_batch(robot, qs, poses)
    outs = [np.full((n, 4, 4), np.nan) for n in sizes]
    for qs, out, poses in zip(batches, outs, results, strict=True):
        assert kin.batch(qs, out=out) is out
        assert np.array_equal(out, poses)
    for before, after in zip(kept, results, strict=True):
        assert np.array_equal(before, after)


def test_batch_from_two_threads_at_once():
    """A second thread gets arrays of its own, not the ones in use."""
    robot, _ = load_robot("panda")
    kin = robot.kinematics
    work = [random_qs(robot, 3 * CHUNK // 2, seed=s) for s in (5, 6)]
    expected = [kin.batch(qs) for qs in work]
    failures = []

    def run(qs, want):
        out = np.empty_like(want)
        for _ in range(6):
            if not np.array_equal(kin.batch(qs, out=out), want):
                failures.append(1)

    threads = [threading.Thread(target=run, args=pair) for pair in zip(work, expected, strict=True)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not failures


def test_batch_with_a_wrong_out_is_a_clear_error():
    robot, _ = load_robot("puma560")
    qs = random_qs(robot, 10)
    with pytest.raises(DhsimError, match=r"shape \(10, 4, 4\)"):
        robot.kinematics.batch(qs, out=np.empty((9, 4, 4)))
    with pytest.raises(DhsimError, match=r"float64"):
        robot.kinematics.batch(qs, out=np.empty((10, 4, 4), np.float32))
    shared = np.zeros((10, 4, 4))
    with pytest.raises(DhsimError, match="share memory"):
        robot.kinematics.batch(shared.reshape(-1)[:60].reshape(10, 6), out=shared)

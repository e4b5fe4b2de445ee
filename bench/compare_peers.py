"""dhsim against its peers: Robotics Toolbox, Pinocchio and ikpy (a benchmark).

    python bench/compare_peers.py [--count N] [--arms puma560,panda] [--json]

Times, in one process and on the same targets, dhsim's kinematics and each
peer's fastest path, after checking that they all compute the same thing:

- the Robotics Toolbox (``roboticstoolbox-python``), its C++ ETS:
  ``ets().eval(q)``, ``ets().eval(qs)`` on an (N, n) array (one C call for
  the whole batch), ``ets().jacob0(q)`` and ``ets().ik_LM`` at ``tol=1e-13``
  and at its default ``tol=1e-6``, on ``rtb.models.DH.Puma560()`` and
  ``rtb.models.DH.Panda()`` (the D-H tables dhsim's ``puma560`` and
  ``panda`` were copied from);
- Pinocchio (``pin``), on the URDF dhsim exports (``to_urdf``, as ``dhsim
  export --format urdf``): ``forwardKinematics`` + ``updateFramePlacement``
  of the tool frame or ``framesForwardKinematics``, whichever is faster
  here, and ``computeFrameJacobian`` in ``LOCAL_WORLD_ALIGNED`` (the world
  Jacobian). Pinocchio has no IK of its own (a CLIK loop written in Python
  around it is not its fastest path) and no batch FK (its row is a Python
  loop into a caller's (N, 4, 4) array): no IK rows for it;
- ikpy, on the same URDF: ``chain.forward_kinematics`` and
  ``chain.inverse_kinematics_frame(..., orientation_mode="all")`` (SciPy's
  least squares); it has no Jacobian and no batch call.

dhsim's rows: ``robot.kinematics.pose(q)``, ``robot.kinematics.batch(qs)``,
``jacobian(robot, q)``, ``numerical.solve`` (from home with ``restarts=30``
as ``dhsim ik`` calls it, and from a start about 5° off on each joint with
no restarts), and, when this dhsim has them, the ``out=`` forms (into a
caller's array) and ``dhsim_tui.core.ik.nearest.inverse`` (the closed form
where the arm has one): the script looks for them and times what it finds.

Method. Targets: FK of ``--count`` random joint vectors within dhsim's
limits (seeded). Agreement first: every peer's FK of every target and its
Jacobian must match dhsim's within ``AGREE`` (metres after mm -> m; the
toolbox's Puma stands on the floor, dhsim's at the shoulder: a constant
``base_height`` shift), the batches too, or the script stops. Then the
libraries take turns (each target rotates which goes first): FK and the
Jacobian as blocks of ``CALLS`` calls per target (per-call time, median and
95th percentile over the targets), the batch as ``BATCH_ROUNDS`` rounds, IK
as rounds in which each library solves every target back to back (the
libraries' order rotating by round), each target's fastest of ``IK_REPEAT``
rounds.
Ratio: the row's median over the group's first dhsim row (above 1: dhsim is
faster); /best: a peer's median over the group's fastest dhsim row. Every
IK answer is checked with dhsim's FK: "solved" counts the answers the
solver called solved that are within the joint limits and within the row's
own tolerance of the target.

Caveats. What solved means differs: dhsim stops within 5e-7 of its reach
(about 1 um here) and 5e-7 rad; ik_LM when 0.5*|e|^2 < tol, e the 6-vector
of position (m) and angle-axis (rad) errors: tol=1e-13 is |e| < 4.5e-7, its
default 1e-6 is |e| < 1.4e-3, so it accepts errors up to about 1.4 mm (the
largest seen is printed); ikpy reports no success, so its answers count
when within dhsim's tolerance. ik_LM from a nearby start makes one search
(``slimit=1``) as dhsim's solve makes one descent; from home it makes up to
100 random restarts, drawn from C ``rand`` (varies between rounds). Each
library gets its inputs prepared in its own form beforehand (dhsim: tuples
of degrees; the others: arrays of radians); Pinocchio leaves the pose in its
``data`` (no array made). None of the peers is a dependency of dhsim: to
compare, install them beside it in a scratch virtual environment (``pip
install roboticstoolbox-python pin ikpy`` and dhsim's runtime dependencies)
and run with dhsim's folder on ``PYTHONPATH``. Missing peers are left out
and named; with none, the script prints dhsim's figures alone.
"""

from __future__ import annotations

import argparse
import gc
import inspect
import json
import math
import os
import statistics
import tempfile
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from dhsim_tui.core import load_robot
from dhsim_tui.core.analysis.jacobian import jacobian
from dhsim_tui.core.analysis.workspace import length_scale
from dhsim_tui.core.ik.numerical import solve
from dhsim_tui.core.interop.urdf_export import to_urdf

try:  # the closed form where the arm has one, else the search (newer dhsim)
    from dhsim_tui.core.ik.nearest import inverse
except ImportError:  # pragma: no cover - depends on the dhsim version
    inverse = None

# optional: the peers are only compared with, never needed
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    try:
        import roboticstoolbox as rtb
    except ImportError:  # pragma: no cover - depends on the environment
        rtb = None
    try:
        import pinocchio as pin
    except ImportError:  # pragma: no cover
        pin = None
    try:
        import ikpy
        import ikpy.chain
    except ImportError:  # pragma: no cover
        ikpy = None

#: the arms: dhsim's bundled name and the toolbox's D-H model
ARMS = {"puma560": "Puma560", "panda": "Panda"}
RESTARTS = 30  # as cli.IK_RESTARTS
#: FK and Jacobian: calls per timed block (one block per target and library)
CALLS = 50
#: the 100,000-vector batch: rounds, the libraries taking turns
BATCH = 100_000
BATCH_ROUNDS = 5
#: IK: each target's fastest of this many rounds
IK_REPEAT = 3
#: FK and Jacobians must agree within this (metres, radians, unitless)
AGREE = 1e-12
#: dhsim's IK tolerance (numerical_problem: 5e-7 of the reach, twice for the
#: position it reports; 5e-7 rad, twice likewise)
DHSIM_POSITION = 2 * 5e-7
DHSIM_ORIENTATION = 2 * 5e-7
#: ik_LM's default tol (its E = 0.5 |e|^2) and the tight one
RTB_TOLS = (1e-13, 1e-6)
LIMIT_SLACK = 1e-9  # degrees


def takes(keyword: str, fn: Callable) -> bool:
    """Whether ``fn`` takes the keyword (dhsim's newer arguments)."""
    try:
        return keyword in inspect.signature(fn).parameters
    except (TypeError, ValueError):  # pragma: no cover - builtins
        return False


def takes_out(fn: Callable) -> bool:
    """Whether ``fn`` takes an ``out=`` keyword (the caller's array)."""
    return takes("out", fn)


def p95(values: list[float]) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(0.95 * len(ordered)))]


def blocks(calls: dict[str, tuple[Callable, list[tuple]]], count: int) -> dict[str, list[float]]:
    """Per-call seconds of ``CALLS`` calls of ``fn(*args[k])`` for each target
    k, the libraries taking turns at going first (no garbage collection)."""
    names = list(calls)
    samples: dict[str, list[float]] = {name: [] for name in names}
    loop = range(CALLS)
    for k in range(count):
        shift = k % len(names)
        for name in names[shift:] + names[:shift]:
            fn, args = calls[name][0], calls[name][1][k]
            gc.disable()
            t = time.perf_counter_ns()
            for _ in loop:
                fn(*args)
            elapsed = time.perf_counter_ns() - t
            gc.enable()
            samples[name].append(elapsed * 1e-9 / CALLS)
    return samples


def rounds(calls: dict[str, Callable[[int], Any]], count: int, repeat: int):
    """One call per target and library, each target's fastest of ``repeat``
    rounds, and the first round's results. In a round each library solves
    every target back to back, as a loop of a program would (a library timed
    between another's calls finds its caches taken: ikpy's 3 ms of SciPy
    slowed dhsim's pure-Python solver by 1.6x when the calls alternated
    target by target); the libraries' order rotates from round to round, so
    the machine's drift touches each alike."""
    names = list(calls)
    times = {name: [math.inf] * count for name in names}
    results: dict[str, list] = {name: [None] * count for name in names}
    for round_ in range(repeat):
        shift = round_ % len(names)
        for name in names[shift:] + names[:shift]:
            for k in range(count):
                gc.disable()
                t = time.perf_counter_ns()
                result = calls[name](k)
                elapsed = time.perf_counter_ns() - t
                gc.enable()
                times[name][k] = min(times[name][k], elapsed * 1e-9)
                if round_ == 0:
                    results[name][k] = result
    return times, results


@dataclass
class Row:
    group: str
    library: str
    call: str
    times: list[float]
    unit: str = "us"
    solved: float | None = None
    notes: dict = field(default_factory=dict)

    def figures(self, base: Row | None) -> dict:
        median = statistics.median(self.times)
        out = {
            "group": self.group,
            "library": self.library,
            "call": self.call,
            "unit": self.unit,
            "median_s": median,
            "p95_s": p95(self.times),
            "ratio": median / statistics.median(base.times) if base and base is not self else None,
        }
        if self.solved is not None:
            out["solved"] = self.solved
        return out | self.notes


@dataclass
class IKCall:
    library: str
    call: str
    run: Callable[[int], Any]
    #: the result -> (solved by its own account, joint values in degrees or None)
    read: Callable[[Any], tuple[bool, Any]]
    #: the row's own tolerance: position (m) and orientation (rad)
    tolerance: tuple[float, float]


def read_dhsim(result) -> tuple[bool, Any]:
    if result is None:
        return False, None
    q = getattr(result, "q", result)
    return bool(getattr(result, "success", q is not None)), q


def read_rtb(result) -> tuple[bool, Any]:
    return bool(result.success), np.degrees(result.q)


def rotation_angle(a: np.ndarray, b: np.ndarray) -> float:
    """The angle (rad) between two rotations, accurate when tiny."""
    r = a.T @ b
    sine = 0.5 * math.hypot(r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1])
    return math.atan2(sine, 0.5 * (np.trace(r) - 1.0))


class Arm:
    """One arm: dhsim's robot, the targets, and the peers' models of it."""

    def __init__(self, name: str, count: int) -> None:
        self.name = name
        self.robot, _ = load_robot(name)
        robot, n = self.robot, self.robot.dof
        self.kin = robot.kinematics
        self.lower, self.upper = np.array(robot.lower), np.array(robot.upper)
        rng = np.random.default_rng(7)
        self.qdeg = rng.uniform(self.lower, self.upper, size=(count, n))
        near = self.qdeg + rng.normal(0.0, 5.0, size=(count, n))
        self.near = np.clip(near, self.lower, self.upper)
        self.qt = [tuple(q.tolist()) for q in self.qdeg]  # dhsim's input
        self.qr = [np.radians(q) for q in self.qdeg]  # the peers' input
        self.targets = [self.kin.pose(q) for q in self.qt]  # mm, dhsim's world
        self.targets_m = []
        for t in self.targets:
            t = t.copy()
            t[:3, 3] /= 1000.0
            self.targets_m.append(t)
        self.qs = np.random.default_rng(1).uniform(self.lower, self.upper, size=(BATCH, n))
        self.qs_rad = np.radians(self.qs)
        self.scale_m = length_scale(robot) / 1000.0
        self.urdf = to_urdf(robot)
        # the toolbox's world is on the floor, dhsim's base_height above it
        self.shift = np.eye(4)
        self.shift[2, 3] = robot.base_height / 1000.0
        self.agreement: dict[str, dict] = {}
        self.rows: list[Row] = []
        self.notes: list[str] = []
        self.peers: dict[str, Any] = {}
        if rtb is not None:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                model = getattr(rtb.models.DH, ARMS[name])()
            self.peers["rtb"] = (model, model.ets())
        if pin is not None:
            model = pin.buildModelFromXML(self.urdf)
            self.peers["pin"] = (model, model.createData(), model.getFrameId("tool"))
        if ikpy is not None:
            with tempfile.TemporaryDirectory() as folder:
                path = os.path.join(folder, f"{name}.urdf")
                with open(path, "w", encoding="utf-8") as f:
                    f.write(self.urdf)
                with warnings.catch_warnings():  # first read: which links move
                    warnings.simplefilter("ignore")
                    links = ikpy.chain.Chain.from_urdf_file(path, base_elements=["world"]).links
                active = np.array([link.joint_type != "fixed" for link in links])
                chain = ikpy.chain.Chain.from_urdf_file(
                    path, base_elements=["world"], active_links_mask=active
                )
            self.peers["ikpy"] = (chain, active)

    # -- helpers ---------------------------------------------------------

    def ikpy_full(self, qrad: np.ndarray) -> np.ndarray:
        chain, active = self.peers["ikpy"]
        full = np.zeros(len(chain.links))
        full[active] = qrad
        return full

    def pin_fk(self):
        """Pinocchio's faster FK of the tool frame here, as (fn, args maker, name)."""
        model, data, frame = self.peers["pin"]

        def placement(q):
            pin.forwardKinematics(model, data, q)
            return pin.updateFramePlacement(model, data, frame)

        candidates = {
            "forwardKinematics + updateFramePlacement": (placement, lambda q: (q,)),
            "framesForwardKinematics": (pin.framesForwardKinematics, lambda q: (model, data, q)),
        }
        best, fastest = None, math.inf
        for name, (fn, args) in candidates.items():
            a = args(self.qr[0])
            for _ in range(3):
                t = time.perf_counter_ns()
                for _ in range(2000):
                    fn(*a)
                elapsed = time.perf_counter_ns() - t
                if elapsed < fastest:
                    best, fastest = name, elapsed
        return (*candidates[best], best)

    def warm(self) -> None:
        for _ in range(64):  # past COMPILE_AFTER: the compiled chain and Jacobian
            self.kin.pose(self.qt[0]), jacobian(self.robot, self.qt[0])
        self.kin.batch(self.qs[:100])

    # -- agreement -------------------------------------------------------

    def check(self) -> None:
        """Every peer's FK and Jacobian against dhsim's; stop when they differ."""
        jacs = []
        for q in self.qt:
            jac = jacobian(self.robot, q).copy()
            jac[:3] /= 1000.0
            jacs.append(jac)
        batch = self.kin.batch(self.qs)
        batch_m = batch.copy()
        batch_m[:, :3, 3] /= 1000.0
        if "rtb" in self.peers:
            _, ets = self.peers["rtb"]
            fk = max(
                np.abs(ets.eval(q) - self.shift @ t).max()
                for q, t in zip(self.qr, self.targets_m, strict=True)
            )
            jac = max(np.abs(ets.jacob0(q) - j).max() for q, j in zip(self.qr, jacs, strict=True))
            many = np.abs(ets.eval(self.qs_rad) - self.shift @ batch_m).max()
            self.agreement["rtb"] = {"fk": fk, "jacobian": jac, "batch": many}
        if "pin" in self.peers:
            model, data, frame = self.peers["pin"]
            fk = jac = 0.0
            for q, t, j in zip(self.qr, self.targets_m, jacs, strict=True):
                pin.framesForwardKinematics(model, data, q)
                fk = max(fk, np.abs(data.oMf[frame].homogeneous - t).max())
                got = pin.computeFrameJacobian(model, data, q, frame, pin.LOCAL_WORLD_ALIGNED)
                jac = max(jac, np.abs(got - j).max())
            many = 0.0
            for q, t in zip(self.qs_rad[:1000], batch_m[:1000], strict=True):
                pin.framesForwardKinematics(model, data, q)
                many = max(many, np.abs(data.oMf[frame].homogeneous - t).max())
            self.agreement["pin"] = {"fk": fk, "jacobian": jac, "batch (first 1000)": many}
        if "ikpy" in self.peers:
            chain, _ = self.peers["ikpy"]
            fk = max(
                np.abs(chain.forward_kinematics(self.ikpy_full(q)) - t).max()
                for q, t in zip(self.qr, self.targets_m, strict=True)
            )
            self.agreement["ikpy"] = {"fk": fk}
        # dhsim's out= forms give what the plain ones do
        ours = {}
        if takes_out(self.kin.pose):
            out = np.empty((4, 4))
            self.kin.pose(self.qt[0], out=out)
            ours["pose(out=)"] = np.abs(out - self.targets[0]).max()
        if takes_out(self.kin.batch):
            out = np.empty((BATCH, 4, 4))
            self.kin.batch(self.qs, out=out)
            ours["batch(out=)"] = np.abs(out - batch).max()
        if takes_out(jacobian):
            out = np.empty((6, self.robot.dof))
            jacobian(self.robot, self.qt[0], out=out)
            ours["jacobian(out=)"] = np.abs(out - jacobian(self.robot, self.qt[0])).max()
        if ours:
            self.agreement["dhsim"] = ours
        bad = [
            f"{peer} {what}: {value:.2e}"
            for peer, figures in self.agreement.items()
            for what, value in figures.items()
            if not value <= AGREE
        ]
        if bad:
            raise SystemExit(f"{self.robot.name}: the libraries disagree: " + "; ".join(bad))

    # -- timing ----------------------------------------------------------

    def time_fk(self, count: int) -> None:
        kin, qt, qr = self.kin, self.qt, self.qr
        calls: dict[str, tuple[Callable, list[tuple]]] = {
            "dhsim|robot.kinematics.pose(q)": (kin.pose, [(q,) for q in qt])
        }
        if takes_out(kin.pose):
            out = np.empty((4, 4))

            def pose_into(q, out=out):
                return kin.pose(q, out=out)

            calls["dhsim|kinematics.pose(q, out=arr): FK into caller's array"] = (
                pose_into,
                [(q,) for q in qt],
            )
        if "rtb" in self.peers:
            calls["rtb|ets().eval(q)"] = (self.peers["rtb"][1].eval, [(q,) for q in qr])
        if "pin" in self.peers:
            fn, args, name = self.pin_fk()
            calls[f"pin|{name}"] = (fn, [args(q) for q in qr])
        if "ikpy" in self.peers:
            chain = self.peers["ikpy"][0]
            calls["ikpy|chain.forward_kinematics(q)"] = (
                chain.forward_kinematics,
                [(self.ikpy_full(q),) for q in qr],
            )
        self.add("FK, end effector", blocks(calls, count))

    def time_jacobian(self, count: int) -> None:
        robot, qt, qr = self.robot, self.qt, self.qr
        calls: dict[str, tuple[Callable, list[tuple]]] = {
            "dhsim|jacobian(robot, q)": (jacobian, [(robot, q) for q in qt])
        }
        if takes_out(jacobian):
            out = np.empty((6, robot.dof))

            def jacobian_into(q, out=out):
                return jacobian(robot, q, out=out)

            calls["dhsim|jacobian(robot, q, out=arr)"] = (jacobian_into, [(q,) for q in qt])
        if "rtb" in self.peers:
            calls["rtb|ets().jacob0(q)"] = (self.peers["rtb"][1].jacob0, [(q,) for q in qr])
        if "pin" in self.peers:
            model, data, frame = self.peers["pin"]
            world = pin.LOCAL_WORLD_ALIGNED
            calls["pin|computeFrameJacobian(.., LOCAL_WORLD_ALIGNED)"] = (
                pin.computeFrameJacobian,
                [(model, data, q, frame, world) for q in qr],
            )
        self.add("Jacobian (world)", blocks(calls, count))

    def time_batch(self) -> None:
        kin, qs = self.kin, self.qs
        calls: dict[str, Callable[[int], Any]] = {
            "dhsim|robot.kinematics.batch(qs)": lambda _: kin.batch(qs)
        }
        if takes_out(kin.batch):
            out = np.empty((BATCH, 4, 4))
            calls["dhsim|kinematics.batch(qs, out=arr)"] = lambda _: kin.batch(qs, out=out)
        if "rtb" in self.peers:
            ets, qs_rad = self.peers["rtb"][1], self.qs_rad
            calls["rtb|ets().eval(qs), qs an (N, n) array: one C call"] = lambda _: ets.eval(qs_rad)
        if "pin" in self.peers:
            model, data, frame = self.peers["pin"]
            poses = np.empty((BATCH, 4, 4))

            def pin_loop(_):
                for i, q in enumerate(self.qs_rad):
                    pin.framesForwardKinematics(model, data, q)
                    poses[i] = data.oMf[frame].homogeneous
                return poses

            calls["pin|Python loop of framesForwardKinematics"] = pin_loop
        names, spread = list(calls), {name: [] for name in calls}
        for round_ in range(BATCH_ROUNDS):  # the libraries taking turns at going first
            shift = round_ % len(names)
            for name in names[shift:] + names[:shift]:
                gc.disable()
                t = time.perf_counter_ns()
                calls[name](0)
                spread[name].append((time.perf_counter_ns() - t) * 1e-9)
                gc.enable()
        self.add(f"FK, {BATCH:,} joint vectors", spread, unit="ms")
        if "ikpy" in self.peers:
            self.notes.append("ikpy: no batch FK (a loop is 100,000 times its FK row)")

    def ik_calls(self, near: bool) -> dict[str, IKCall]:
        robot, count = self.robot, len(self.qt)
        starts = [tuple(s.tolist()) for s in self.near] if near else [robot.home] * count
        starts_rad = [np.radians(s) for s in starts]
        pos, ori = DHSIM_POSITION * self.scale_m, DHSIM_ORIENTATION
        calls: dict[str, IKCall] = {}
        targets = self.targets
        if near:
            call = "numerical.solve(robot, T, start)"

            def ours(k):
                return solve(robot, targets[k], starts[k])
        else:
            call = f"numerical.solve(robot, T, home, restarts={RESTARTS})"

            def ours(k):
                return solve(robot, targets[k], starts[k], restarts=RESTARTS, seed=k)

        calls["dhsim|" + call] = IKCall("dhsim", call, ours, read_dhsim, (pos, ori))
        if inverse is not None:
            # from home as solve is called (restarts, when it takes them)
            more = {} if near or not takes("restarts", inverse) else {"restarts": RESTARTS}
            call = f"nearest.inverse(robot, T, {'start' if near else 'home'}"
            call += f", restarts={RESTARTS})" if more else ")"

            # the signature is read once, here: inspect.signature in the timed
            # call cost about 16 us a call and was counted as dhsim's time
            seeded = bool(more) and takes("seed", inverse)

            def closest(k, more=more, seeded=seeded):
                if seeded:
                    return inverse(robot, targets[k], starts[k], seed=k, **more)
                return inverse(robot, targets[k], starts[k], **more)

            calls["dhsim|" + call] = IKCall("dhsim", call, closest, read_dhsim, (pos, ori))
        if "rtb" in self.peers:
            ets = self.peers["rtb"][1]
            goals = [self.shift @ t for t in self.targets_m]
            searches = {"slimit": 1} if near else {}
            for tol in RTB_TOLS:
                bound = math.sqrt(2 * tol)
                tight = tol < 1e-6
                call = f"ets().ik_LM(T, q0{', slimit=1' if near else ''}, tol={tol:g})"
                call += "" if tight else " (default tol)"
                kwargs = searches | ({"tol": tol} if tight else {})

                def theirs(k, kwargs=kwargs):
                    return ets.ik_LM(goals[k], q0=starts_rad[k], **kwargs)

                calls["rtb|" + call] = IKCall("rtb", call, theirs, read_rtb, (bound, bound))
        if "ikpy" in self.peers:
            chain, active = self.peers["ikpy"]
            firsts = [self.ikpy_full(s) for s in starts_rad]
            frames = self.targets_m

            def ikpy_solve(k):
                return chain.inverse_kinematics_frame(
                    frames[k], initial_position=firsts[k], orientation_mode="all"
                )

            def read_ikpy(result):
                return True, np.degrees(np.asarray(result)[active])

            call = 'inverse_kinematics_frame(T, q0, orientation_mode="all")'
            calls["ikpy|" + call] = IKCall("ikpy", call, ikpy_solve, read_ikpy, (pos, ori))
        return calls

    def time_ik(self, near: bool) -> None:
        calls = self.ik_calls(near)
        self.warm_ik(calls)
        times, results = rounds({name: c.run for name, c in calls.items()}, len(self.qt), IK_REPEAT)
        solved, notes = {}, {}
        for name, c in calls.items():
            ok, claimed, worst, worst_ok = 0, 0, [0.0, 0.0], [0.0, 0.0]
            for result, target in zip(results[name], self.targets, strict=True):
                success, q = c.read(result)
                if not success or q is None:
                    continue
                claimed += 1
                q = np.asarray(q, dtype=float)
                reached = self.kin.pose(tuple(q.tolist()))
                p = np.linalg.norm(reached[:3, 3] - target[:3, 3]) / 1000.0
                o = rotation_angle(reached[:3, :3], target[:3, :3])
                inside = np.all(q >= self.lower - LIMIT_SLACK) and np.all(
                    q <= self.upper + LIMIT_SLACK
                )
                worst = [max(worst[0], p), max(worst[1], o)]
                if inside and p <= c.tolerance[0] and o <= c.tolerance[1]:
                    ok += 1
                    worst_ok = [max(worst_ok[0], p), max(worst_ok[1], o)]
            count = len(self.qt)
            solved[name] = ok / count
            notes[name] = {
                "claimed": claimed / count,
                # over the answers counted solved, and over all it called solved
                "max_position_error_m": worst_ok[0],
                "max_orientation_error_rad": worst_ok[1],
                "max_position_error_claimed_m": worst[0],
                "max_orientation_error_claimed_rad": worst[1],
                "tolerance": {"position_m": c.tolerance[0], "orientation_rad": c.tolerance[1]},
            }
        group = "IK from a nearby start (~5 deg)" if near else "IK from home"
        self.add(group, times, solved=solved, notes=notes)

    def warm_ik(self, calls: dict[str, IKCall]) -> None:
        for c in calls.values():
            for k in range(min(10, len(self.qt))):
                c.run(k)

    def add(self, group: str, samples: dict, unit: str = "us", solved=None, notes=None) -> None:
        for name, times in samples.items():
            library, call = name.split("|", 1)
            self.rows.append(
                Row(
                    group,
                    library,
                    call,
                    times,
                    unit,
                    None if solved is None else solved[name],
                    {} if notes is None else notes[name],
                )
            )

    def measure(self, count: int) -> dict:
        self.warm()
        self.check()
        self.time_fk(count)
        self.time_jacobian(count)
        self.time_batch()
        self.time_ik(near=True)
        self.time_ik(near=False)
        if "pin" in self.peers:
            self.notes.append("pinocchio: no IK of its own (a Python CLIK loop is not its path)")
        rows, base, best = [], {}, {}
        for row in self.rows:
            if row.library == "dhsim":
                base.setdefault(row.group, row)
                if statistics.median(row.times) < statistics.median(best.get(row.group, row).times):
                    best[row.group] = row
                best.setdefault(row.group, row)
        for row in self.rows:
            figures = row.figures(base.get(row.group))
            fastest = best.get(row.group)
            if fastest is not None and row.library != "dhsim":
                figures["ratio_best"] = figures["median_s"] / statistics.median(fastest.times)
            rows.append(figures)
        return {
            "name": self.robot.name,
            "targets": count,
            "agreement": self.agreement,
            "rows": rows,
            "notes": self.notes,
        }


LIBRARIES = {"dhsim": "dhsim", "rtb": "RTB", "pin": "Pinocchio", "ikpy": "ikpy"}


def versions() -> dict:
    found = {}
    for key, module in (("rtb", rtb), ("pin", pin), ("ikpy", ikpy)):
        if module is not None:
            found[key] = getattr(module, "__version__", "?")
    return found


def show(seconds: float, unit: str) -> str:
    return f"{seconds * {'us': 1e6, 'ms': 1e3}[unit]:.1f} {unit}"


def print_arm(arm: dict) -> None:
    print(f"\n{arm['name']} ({arm['targets']} targets)")
    print(f"  {'':<68}{'median':>10}{'p95':>11}{'ratio':>8}{'/best':>8}{'solved':>8}")
    group = None
    for row in arm["rows"]:
        if row["group"] != group:
            group = row["group"]
            print(f"  {group}")
        label = f"{LIBRARIES[row['library']]:<10}{row['call']}"
        line = f"    {label:<66}{show(row['median_s'], row['unit']):>10}"
        line += f"{show(row['p95_s'], row['unit']):>11}"
        line += f"{row['ratio']:>7.2f}x" if row["ratio"] is not None else f"{'':>8}"
        line += f"{row['ratio_best']:>7.2f}x" if "ratio_best" in row else f"{'':>8}"
        if "solved" in row:
            line += f"{row['solved'] * 100:>7.1f}%"
            if abs(row["claimed"] - row["solved"]) > 1e-12 and row["library"] != "ikpy":
                line += f" (claimed {row['claimed'] * 100:.1f}%)"
            line += f"  max err {row['max_position_error_m'] * 1000:.1e} mm"
        print(line)
    for peer, figures in arm["agreement"].items():
        text = ", ".join(f"{what} {value:.1e}" for what, value in figures.items())
        who = "dhsim's out= forms" if peer == "dhsim" else LIBRARIES[peer]
        print(f"  agreement with dhsim (max abs difference), {who}: {text}")
    for note in arm["notes"]:
        print(f"  {note}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=500, help="targets per arm")
    parser.add_argument("--arms", default=",".join(ARMS), help="comma-separated: puma560,panda")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    puma = load_robot("puma560")[0]
    results = {
        "versions": versions(),
        "missing": [LIBRARIES[k] for k in ("rtb", "pin", "ikpy") if k not in versions()],
        "dhsim_optional": {
            "pose(out=)": takes_out(puma.kinematics.pose),
            "batch(out=)": takes_out(puma.kinematics.batch),
            "jacobian(out=)": takes_out(jacobian),
            "nearest.inverse": inverse is not None,
        },
        "arms": {},
    }
    for name in args.arms.split(","):
        results["arms"][name] = Arm(name, args.count).measure(args.count)
    if args.json:
        print(json.dumps(results, indent=2))
        return
    found = ", ".join(f"{LIBRARIES[k]} {v}" for k, v in results["versions"].items())
    print(f"dhsim against {found or 'no peer'}")
    for arm in results["arms"].values():
        print_arm(arm)
    print(
        "\nratio: the row's median / the group's first dhsim row's (above 1: dhsim is faster);"
        " /best: a peer's median / the group's fastest dhsim row's;"
        " solved: answers within the limits and the row's own tolerance (checked with dhsim's FK)."
        "\nik_LM's default tol=1e-6 accepts errors up to ~1.4 mm (0.5|e|^2 < tol);"
        " tol=1e-13 about 0.45 um, near dhsim's ~1 um and 1e-6 rad."
    )
    if results["missing"]:
        print(
            "not installed: " + ", ".join(results["missing"]) + " (pip install "
            "roboticstoolbox-python pin ikpy beside dhsim to compare)"
        )


if __name__ == "__main__":
    main()

"""The editor's undo history keeps robots, not what was computed from them:
3,000 edits of a 32-joint robot, each previewed through its kinematics as the
editor does, must not keep 3,000 compiled kinematics (about 41 KiB each)."""

from __future__ import annotations

import gc
import tracemalloc

import numpy as np

from dhsim_tui.core import bundled_names, load_robot
from dhsim_tui.core.analysis.jacobian import controllable_rows, dexterity
from dhsim_tui.core.model.editing import History, Robot, new_robot, set_joint_field
from dhsim_tui.core.model.kinematics import COMPILE_AFTER, _compile, _stepwise

EDITS = 3000
MEASURED = 300
JOINTS = 32
FIELDS = set(Robot.__dataclass_fields__)


def edit(history: History, step: int) -> None:
    """One accepted edit, then the editor's preview: the new robot's frames."""
    robot = history.current
    index = step % JOINTS
    assert history.push(set_joint_field(robot, index, "a", robot.joints[index].a + 0.5))
    history.current.kinematics.frames(history.current.home)


def cached(robot: Robot) -> set[str]:
    """What is stored on the robot besides its fields (caches)."""
    return set(vars(robot)) - FIELDS


def test_undo_history_keeps_no_compiled_kinematics_and_grows_little():
    history = History(new_robot(joints=JOINTS))
    for step in range(EDITS):
        edit(history, step)
        if step % 100 == 0:  # the control screen's read-outs cache Jacobian samples too
            dexterity(history.current)
            controllable_rows(history.current)
    for _ in range(50):
        history.undo()
    history.current.kinematics.frames(history.current.home)
    for robot in (*history._undo, *history._redo):
        assert not cached(robot), cached(robot)
    assert "kinematics" in vars(history.current)  # the robot on screen keeps its own
    # growth per step, measured over further edits (tracemalloc slows them ~5x)
    gc.collect()
    tracemalloc.start()
    try:
        start = tracemalloc.get_traced_memory()[0]
        for step in range(EDITS, EDITS + MEASURED):
            edit(history, step)
        gc.collect()
        grown = tracemalloc.get_traced_memory()[0] - start
    finally:
        tracemalloc.stop()
    assert len(history._undo) == EDITS - 50 + MEASURED
    per_step = grown / MEASURED
    assert per_step < 2 * 1024, f"{per_step / 1024:.1f} KiB per undo step"


def test_undo_and_redo_give_back_the_same_robot_and_kinematics():
    history = History(new_robot(joints=4))
    first = history.current
    before = first.kinematics.frames((10.0, 20.0, 30.0, 40.0))
    edit(history, 0)
    assert not cached(first)
    history.undo()
    assert history.current is first and history.current == first
    assert (history.current.kinematics.frames((10.0, 20.0, 30.0, 40.0)) == before).all()
    history.redo()
    assert history.current.joints[0].a == 0.5


def test_stepwise_and_compiled_chains_give_the_same_bits():
    """Kinematics runs a per-joint loop first and compiles the whole chain once
    it is in use: both must give bit-identical frames."""
    rng = np.random.default_rng(3)
    for name in bundled_names():
        robot, _ = load_robot(name)
        tool = None if robot.tool.is_identity else robot.kinematics.tool
        for record in (False, True):
            whole, stepwise = _compile(robot, tool, record), _stepwise(robot, tool, record)
            for _ in range(20):
                q = rng.uniform(robot.lower, robot.upper)
                assert list(whole(q)) == list(stepwise(q)), name
    robot, _ = load_robot("puma560")
    q = (10.0, 20.0, -30.0, 40.0, 50.0, 60.0)
    first = robot.kinematics.frames(q)
    for _ in range(COMPILE_AFTER + 1):
        assert (robot.kinematics.frames(q) == first).all()

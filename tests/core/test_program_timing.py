"""A program's length is known before anything is sampled (program_timing).

The fault campaign's programs: a linear move at 1e-4 mm/s passed ``dhsim
check`` and then grew ``dhsim run`` to 5.7 GB; 5e-324 gave ZeroDivisionError;
1e-6, 1e-9 and 1e-300 MemoryError or ValueError. Now speeds have floors, and
each step's duration is computed in closed form on load, on import and before
sampling: anything over the limits is refused naming the step, how long it
takes and the limit, in little memory.

The closed-form durations are checked against the sampler's (which samples
the profiles point by point) and against a trapezoid written here.
"""

from __future__ import annotations

import json
import math
import resource
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pytest
from waiting import HANG

from dhsim_tui.core.files.robotfile import loads
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.model.program_timing import (
    MAX_DURATION,
    MIN_JOINT_PERCENT,
    check_timing,
    step_durations,
)
from dhsim_tui.core.motion.trajectory import sample

ARM = """\
name = "slow arm"
units = "mm"

[poses]
a = [0.0, 0.0]
b = [90.0, 0.0]

[programs]
p = [
  {{ move = "joint", to = "a" }},
  {{ {step} }},
]

[[joints]]
theta = 0.0
d = 0.0
a = 400.0
alpha = 0.0

[[joints]]
theta = 0.0
d = 0.0
a = 300.0
alpha = 0.0
"""


def arm_with(step: str) -> str:
    return ARM.format(step=step)


@pytest.mark.parametrize(
    "speed", ["1e-4", "1e-3", "5e-324", "1e-6", "1e-9", "1e-300", "0.001", "0.009"]
)
def test_the_campaigns_linear_speeds_are_refused_on_load(speed):
    with pytest.raises(DhsimError) as caught:
        loads(arm_with(f'move = "linear", to = "b", speed = {speed}'), "arm.toml")
    message = str(caught.value)
    assert message.startswith("arm.toml: programs.p, step 2, speed: ")
    assert "a linear move's speed is at least 0.01 mm/s" in message
    assert "\n" not in message


@pytest.mark.parametrize("speed", ["5e-324", "1e-9", "0.001"])
def test_joint_speeds_below_the_floor_are_refused(speed):
    with pytest.raises(DhsimError, match=f"at least {MIN_JOINT_PERCENT:g} %"):
        loads(arm_with(f'move = "joint", to = "b", speed = {speed}'), "arm.toml")


def test_a_slow_move_over_the_hour_is_refused_naming_its_step_and_length():
    # 0.02 mm/s over the 700 mm * sqrt(2) between a's and b's tool points: ~14 h
    with pytest.raises(DhsimError) as caught:
        loads(arm_with('move = "linear", to = "b", speed = 0.02'), "arm.toml")
    message = str(caught.value)
    assert "programs.p, step 2: this linear move takes" in message
    assert f"a program may take at most {MAX_DURATION:g} s" in message
    seconds = float(message.split("takes ")[1].split(" s")[0])
    length = math.hypot(700.0, 700.0)  # the tool at (700, 0), then at (0, 700)
    assert seconds == pytest.approx(length / 0.02, rel=1e-3)


def test_tiny_joint_top_speeds_are_refused():
    text = arm_with("wait = 1").replace("a = 300.0\n", "a = 300.0\nvmax = 1e-300\n")
    with pytest.raises(DhsimError, match=r"joints\[2\]\.vmax: .* give at least 0\.01 deg/s"):
        loads(text, "arm.toml")


def trapezoid_seconds(distance: float, top: float, acceleration: float) -> float:
    """A trapezoid's duration, written here: a triangle when the top speed is
    never reached."""
    if distance == 0:
        return 0.0
    if distance < top * top / acceleration:
        return 2.0 * math.sqrt(distance / acceleration)
    return distance / top + top / acceleration


def test_joint_move_durations_are_the_slowest_joints_trapezoid(puma):
    goal = (30.0, 60.0, -150.0, 100.0, -20.0, 200.0)
    program = Program("p", (Step("joint", goal, speed=40.0),))
    (seconds,) = step_durations(puma, program)
    # every joint at 40 % of 90 deg/s and 360 deg/s^2 (the Puma's defaults or
    # its file's vmax/amax): the longest one sets the pace
    expected = max(
        trapezoid_seconds(
            abs(g - h),
            0.4 * (j.vmax if j.vmax is not None else 90.0),
            j.amax if j.amax is not None else 360.0,
        )
        for g, h, j in zip(goal, puma.home, puma.joints, strict=True)
    )
    assert seconds == pytest.approx(expected, rel=1e-12)


def test_closed_form_durations_equal_the_sampled_ones(puma):
    steps = (
        Step("joint", "qn"),
        Step("linear", "qr", speed=300.0),
        Step("wait", seconds=0.25),
        Step("joint", (10.0, 40.0, -120.0, 20.0, 30.0, 40.0), speed=25.0),
        Step("linear", (0.0, 45.0, -150.0, 0.0, 50.0, 0.0)),
    )
    program = Program("p", steps)
    robot = replace(puma, programs=(program,))
    trajectory = sample(robot, program, 100.0)
    assert not trajectory.failures  # nominal and actual starts agree
    durations = step_durations(robot, program)
    assert [s.duration for s in trajectory.spans] == pytest.approx(durations, rel=1e-12)
    assert check_timing(robot, program, 100.0) == pytest.approx(trajectory.duration)
    assert trajectory.time[-1] >= sum(durations) - 1e-9


def test_a_rate_that_would_make_too_many_samples_is_refused_before_sampling(puma):
    program = Program("p", (Step("wait", seconds=1800.0),))
    robot = replace(puma, programs=(program,))
    with pytest.raises(DhsimError, match="at 1000 Hz a program may take at most 360 s"):
        sample(robot, program, 1000.0)


MEASURE = """
import json, resource, sys
from dhsim_tui.cli.main import main
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
code = main(sys.argv[1:])
grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
print(json.dumps({"code": code, "grown_mb": grown / 1024}))
"""


@pytest.mark.parametrize("command", ["check", "run"])
def test_check_and_run_refuse_the_campaigns_program_in_little_memory(tmp_path, command):
    path = tmp_path / "slow.toml"
    path.write_text(arm_with('move = "linear", to = "b", speed = 0.02'))
    cap = 2 << 30  # a regression fails this test, not the machine

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))

    argv = [command, str(path)] + (["p"] if command == "run" else [])
    done = subprocess.run(
        [sys.executable, "-c", MEASURE, *argv],
        capture_output=True,
        text=True,
        timeout=HANG,
        preexec_fn=limit,
    )
    result = json.loads(done.stdout.strip().splitlines()[-1])
    assert result["code"] == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "programs.p, step 2: this linear move takes" in lines[0]
    assert result["grown_mb"] < 50


def test_every_bundled_program_is_timed_within_the_limit(bundled):
    for program in bundled.programs:
        total = check_timing(bundled, program)
        assert 0 <= total <= MAX_DURATION and np.isfinite(total)

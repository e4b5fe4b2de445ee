"""Random valid robots for hypothesis, and the independent forward kinematics.

``reference_frames`` (from tests/conftest.py) is the reference's plain
product of 4×4 matrices (§1), written from the definitions with numpy and
nothing from dhsim's kinematics, offsets and base included.
"""

from __future__ import annotations

import numpy as np
from conftest import reference_frames
from hypothesis import strategies as st

from dhsim_tui.core.model.robot import AXES, UNITS, Joint, Robot, Tool


def reference_pose(robot: Robot, q) -> np.ndarray:
    """The tool's world pose by the textbook product (tests/conftest.py)."""
    return reference_frames(robot, q)[-1]


lengths = st.one_of(st.just(0.0), st.floats(-800, 800).filter(lambda v: abs(v) > 1e-2))
angles = st.one_of(st.sampled_from([0.0, 90.0, -90.0, 180.0]), st.floats(-180, 180))
triples = st.tuples(lengths, lengths, lengths)
angle_triples = st.tuples(angles, angles, angles)


@st.composite
def joints(draw, units: str) -> Joint:
    kind = draw(st.sampled_from(["revolute", "prismatic"]))
    theta, d, a, alpha = draw(angles), draw(lengths), draw(lengths), draw(angles)
    offset = draw(st.one_of(st.just(0.0), angles if kind == "revolute" else lengths))
    home = (theta if kind == "revolute" else d) - offset
    span = draw(st.floats(1.0, 300.0))

    def limit(value: float) -> float:
        # a prismatic limit is a length: a sum that rounds to 1e-16 is 0 (a
        # length under a nanometre is refused, and hypothesis found this one)
        return 0.0 if abs(value) < 1e-6 else value

    return Joint(
        type=kind,
        theta=theta,
        d=d,
        a=a,
        alpha=alpha,
        min=limit(home - span),
        max=limit(home + span),
        offset=offset,
    )


@st.composite
def robots(draw, max_joints: int = 7) -> Robot:
    """A valid robot of either convention: revolute and prismatic joints,
    offsets, a general base (shorthand axes and xyz/rpy) and a tool."""
    units = draw(st.sampled_from(sorted(UNITS)))
    base_z = draw(st.sampled_from(AXES))
    base_x = draw(st.sampled_from([a for a in AXES if a[1] != base_z[1]]))
    count = draw(st.integers(1, max_joints))
    return Robot(
        name="random",
        joints=tuple(draw(joints(units)) for _ in range(count)),
        units=units,
        convention=draw(st.sampled_from(["standard", "modified"])),
        base_height=draw(st.one_of(st.just(0.0), st.floats(1.0, 1000))),
        base_z=base_z,
        base_x=base_x,
        base_xyz=draw(triples),
        base_rpy=draw(angle_triples),
        tool=Tool(draw(triples), draw(angle_triples)),
    )


def random_q(robot: Robot, rng: np.random.Generator) -> list[float]:
    return [float(rng.uniform(j.min, j.max)) for j in robot.joints]

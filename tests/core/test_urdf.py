"""Serial chains read from a URDF (dhsim_tui.core.interop.urdf), checked against yourdfpy.

yourdfpy is an independent, well-kept URDF implementation: every ``fk`` here
is compared with its scene graph (``update_cfg`` + ``get_transform``) to
1e-9, on the hand-written awkward arms in ``tests/urdfs/``, a UR5 (also
checked against its published D-H table) and random trees made by
hypothesis. ``joint_lines`` is checked against the screw motion it claims:
turning (or sliding) one joint moves the tip by a rotation about (a
translation along) that line.
"""

from __future__ import annotations

import io
import json
import math
import re
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yourdfpy
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from waiting import HANG

from dhsim_tui.core.interop.urdf import CONTINUOUS_LIMIT, read_chain
from dhsim_tui.core.interop.urdf_chain import UrdfChain
from dhsim_tui.core.model.errors import DhsimError

URDFS = Path(__file__).resolve().parents[1] / "urdfs"
TOL = 1e-9

#: file, tip, base (None: the defaults)
CASES = [
    ("planar_elbow.urdf", None, None),
    ("spherical_wrist.urdf", None, None),
    ("tilted_first.urdf", None, None),
    ("fixed_run.urdf", None, None),
    ("oblique_prismatic.urdf", None, None),
    ("range_without_zero.urdf", None, None),
    ("continuous.urdf", None, None),
    ("ur5.urdf", "tool0", None),
    ("ur5.urdf", "ee_link", "base_link"),
    ("ur5.urdf", "wrist_3_link", "upper_arm_link"),
    ("fixed_run.urdf", "a_bracket", "plate"),
]
CASE_IDS = [f"{name}:{tip}:{base}" for name, tip, base in CASES]


def _text(name: str) -> str:
    return (URDFS / name).read_text(encoding="utf-8")


def _chain(name: str, tip: str | None = None, base: str | None = None) -> UrdfChain:
    return read_chain(_text(name), tip=tip, base=base, source=name)


def _reference(text: str) -> yourdfpy.URDF:
    return yourdfpy.URDF.load(
        io.BytesIO(text.encode("utf-8")), build_scene_graph=True, load_meshes=False
    )


def _reference_fk(urdf: yourdfpy.URDF, chain: UrdfChain, q) -> np.ndarray:
    urdf.update_cfg({joint.name: float(v) for joint, v in zip(chain.moving, q, strict=True)})
    return urdf.get_transform(frame_to=chain.tip, frame_from=chain.base)


def _rot(axis, angle: float) -> np.ndarray:
    """Rotation about a unit axis, written out by components (not Rodrigues' form)."""
    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    t = 1 - c
    return np.array(
        [
            [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
        ]
    )


def _rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Rz(yaw) @ Ry(pitch) @ Rx(roll), as a product of the three elementary turns."""
    return _rot((0, 0, 1), yaw) @ _rot((0, 1, 0), pitch) @ _rot((1, 0, 0), roll)


def _screw(kind: str, point, direction, value: float) -> np.ndarray:
    """The rigid motion of turning ``value`` rad about, or sliding ``value`` m
    along, the line through ``point`` with unit ``direction``."""
    m = np.eye(4)
    if kind == "prismatic":
        m[:3, 3] = value * np.asarray(direction)
    else:
        r = _rot(direction, value)
        m[:3, :3] = r
        m[:3, 3] = np.asarray(point) - r @ np.asarray(point)
    return m


# -- the hand-written arms against yourdfpy ----------------------------------------


@pytest.mark.parametrize(("name", "tip", "base"), CASES, ids=CASE_IDS)
def test_fk_matches_yourdfpy(name, tip, base):
    chain = _chain(name, tip, base)
    reference = _reference(_text(name))
    rng = np.random.default_rng(10)
    for _ in range(25):
        q = rng.uniform(-4, 4, len(chain.moving))
        np.testing.assert_allclose(chain.fk(q), _reference_fk(reference, chain, q), atol=TOL)
    zeros = np.zeros(len(chain.moving))
    np.testing.assert_allclose(chain.tip_home(), _reference_fk(reference, chain, zeros), atol=TOL)


@pytest.mark.parametrize(("name", "tip", "base"), CASES, ids=CASE_IDS)
def test_joint_lines_match_yourdfpy(name, tip, base):
    """Each line's point is its child link's origin at q = 0 and its direction
    the joint's (normalised) axis in that frame, per yourdfpy."""
    chain = _chain(name, tip, base)
    reference = _reference(_text(name))
    reference.update_cfg({j.name: 0.0 for j in chain.moving})
    lines = chain.joint_lines()
    assert len(lines) == len(chain.moving)
    for joint, (kind, point, direction) in zip(chain.moving, lines, strict=True):
        ref_joint = reference.joint_map[joint.name]
        frame = reference.get_transform(frame_to=ref_joint.child, frame_from=chain.base)
        axis = np.asarray(ref_joint.axis, float)
        assert kind == joint.kind
        np.testing.assert_allclose(point, frame[:3, 3], atol=TOL)
        np.testing.assert_allclose(direction, frame[:3, :3] @ axis / np.linalg.norm(axis), atol=TOL)
        assert np.linalg.norm(direction) == pytest.approx(1, abs=1e-12)


@pytest.mark.parametrize(("name", "tip", "base"), CASES, ids=CASE_IDS)
def test_joint_lines_are_the_screw_axes(name, tip, base):
    """Moving one joint from zero moves the tip by the screw about its line:
    points on a revolute joint's line stay put, everything else turns about it."""
    chain = _chain(name, tip, base)
    home = chain.tip_home()
    count = len(chain.moving)
    for index, (kind, point, direction) in enumerate(chain.joint_lines()):
        for value in (1e-3, -0.7, 2.5):
            q = np.zeros(count)
            q[index] = value
            moved = chain.fk(q)
            np.testing.assert_allclose(
                moved, _screw(kind, point, direction, value) @ home, atol=TOL
            )
            if kind == "revolute":  # a point of the line, carried by the tip, stays on it
                on_line = np.append(point + 0.37 * direction, 1.0)
                carried = np.linalg.solve(home, on_line)
                np.testing.assert_allclose(moved @ carried, on_line, atol=TOL)


# -- what each awkward arm is about ---------------------------------------------------


def test_planar_elbow_axes_are_parallel():
    chain = _chain("planar_elbow.urdf")
    assert (chain.base, chain.tip) == ("base", "hand")
    lines = chain.joint_lines()
    for _, point, direction in lines:
        np.testing.assert_allclose(direction, [0, 0, 1], atol=TOL)
        assert point[2] == pytest.approx(0.1)
    np.testing.assert_allclose([p[0] for _, p, _ in lines], [0, 0.4, 0.7], atol=TOL)
    # stretched out, then folded: the reach is the sum, then the difference
    np.testing.assert_allclose(chain.fk([0, 0, 0])[:3, 3], [0.7, 0, 0.1], atol=TOL)
    np.testing.assert_allclose(chain.fk([0, math.pi / 2, 0])[:3, 3], [0.4, 0.3, 0.1], atol=TOL)


def test_spherical_wrist_axes_meet_in_one_point():
    chain = _chain("spherical_wrist.urdf")
    assert chain.tip == "flange"
    wrist = chain.joint_lines()[1:]
    centre = wrist[0][1]
    np.testing.assert_allclose(centre, [0.5, 0, 0.5], atol=TOL)
    for _, point, _ in wrist:
        np.testing.assert_allclose(point, centre, atol=TOL)
    directions = np.array([d for _, _, d in wrist])
    np.testing.assert_allclose(directions @ directions.T, np.eye(3), atol=TOL)
    # the wrist never moves its centre, whatever its three joints do
    rng = np.random.default_rng(3)
    for _ in range(10):
        q = rng.uniform(-3, 3, 4)
        q[0] = 0
        flange = chain.fk(q)
        np.testing.assert_allclose(flange[:3, 3] - 0.08 * flange[:3, 2], centre, atol=TOL)


def test_first_joint_off_the_origin_and_tilted():
    chain = _chain("tilted_first.urdf")
    first = chain.joints[0]
    np.testing.assert_allclose(first.origin[:3, 3], [0.3, -0.2, 0.5])
    np.testing.assert_allclose(first.origin[:3, :3], _rpy(0.4, -0.7, 1.1), atol=TOL)
    np.testing.assert_allclose(first.axis, np.array([0.2, 0.5, 1]) / math.sqrt(1.29), atol=TOL)
    np.testing.assert_allclose(chain.joints[1].axis, [0, -1, 0])  # "0 -2 0", normalised
    _, point, direction = chain.joint_lines()[0]
    np.testing.assert_allclose(point, [0.3, -0.2, 0.5], atol=TOL)
    np.testing.assert_allclose(direction, _rpy(0.4, -0.7, 1.1) @ first.axis, atol=TOL)


def test_consecutive_fixed_joints_are_kept_in_order():
    chain = _chain("fixed_run.urdf")
    assert (chain.base, chain.tip) == ("floor", "tool")
    names = [j.name for j in chain.joints]
    assert names == [
        "floor_plate",
        "plate_riser",
        "ja",
        "a_to_cap",
        "cap_to_bracket",
        "bracket_to_spacer",
        "jb",
        "b_mount",
        "mount_tool",
    ]
    assert [j.name for j in chain.moving] == ["ja", "jb"]
    assert [j.kind for j in chain.moving] == ["revolute", "prismatic"]
    assert all(j.lower == j.upper == 0 for j in chain.joints if j.kind == "fixed")
    product = np.eye(4)
    for joint in chain.joints:
        product = product @ joint.origin
    np.testing.assert_allclose(chain.tip_home(), product, atol=TOL)


def test_prismatic_joint_slides_along_its_oblique_axis():
    chain = _chain("oblique_prismatic.urdf")
    reach = chain.moving[1]
    assert reach.kind == "prismatic"
    assert (reach.lower, reach.upper) == (-0.2, 0.5)
    kind, _, direction = chain.joint_lines()[1]
    assert kind == "prismatic"
    for turn in (0.0, 1.1):
        start = chain.fk([turn, 0, 0.4])
        moved = chain.fk([turn, 0.3, 0.4])
        if turn == 0:
            np.testing.assert_allclose(moved[:3, 3] - start[:3, 3], 0.3 * direction, atol=TOL)
        np.testing.assert_allclose(moved[:3, :3], start[:3, :3], atol=TOL)
        assert np.linalg.norm(moved[:3, 3] - start[:3, 3]) == pytest.approx(0.3)


def test_an_axis_is_normalised():
    unit = _text("oblique_prismatic.urdf")
    long = unit.replace(
        'xyz="0.5773502691896258 0.5773502691896258 0.5773502691896258"', 'xyz="2 2 2"'
    )
    assert long != unit
    q = [0.3, 0.45, -1.2]
    np.testing.assert_allclose(read_chain(long).fk(q), read_chain(unit).fk(q), atol=TOL)
    np.testing.assert_allclose(read_chain(long).moving[1].axis, [3**-0.5] * 3, atol=1e-15)


def test_a_range_that_excludes_zero_is_kept():
    chain = _chain("range_without_zero.urdf")
    assert [(j.lower, j.upper) for j in chain.moving] == [(0.5, 2.0), (-0.4, -0.1)]
    # home is the URDF's zero pose even though zero is outside both ranges
    np.testing.assert_allclose(chain.tip_home()[:3, 3], [0.2, 0, 0.15], atol=TOL)


def test_a_continuous_joint_gets_a_full_turn_each_way():
    chain = _chain("continuous.urdf")
    swing, spin = chain.moving
    assert (swing.kind, swing.continuous, swing.lower, swing.upper) == ("revolute", False, -1, 1)
    assert (spin.kind, spin.continuous) == ("revolute", True)
    assert (
        (spin.lower, spin.upper)
        == (-2 * math.pi, 2 * math.pi)
        == (-CONTINUOUS_LIMIT, CONTINUOUS_LIMIT)
    )
    np.testing.assert_allclose(chain.fk([0.2, 2 * math.pi]), chain.fk([0.2, 0]), atol=TOL)


def test_a_continuous_joint_ignores_limits_it_is_given():
    text = _text("continuous.urdf").replace(
        '<limit effort="3" velocity="10"/>', '<limit lower="-0.5" upper="0.5"/>'
    )
    assert read_chain(text).moving[1].upper == 2 * math.pi


def test_fk_wants_one_value_per_moving_joint():
    chain = _chain("fixed_run.urdf")
    with pytest.raises(DhsimError, match="expected 2 joint values"):
        chain.fk([0.1, 0.2, 0.3])


def test_joints_are_read_only():
    joint = _chain("planar_elbow.urdf").joints[0]
    with pytest.raises(ValueError):
        joint.origin[0, 3] = 1.0
    with pytest.raises(AttributeError):
        joint.lower = 0.0  # type: ignore[misc]


# -- a 6-axis industrial arm ---------------------------------------------------------------


def _dh(a: float, alpha: float, d: float, theta: float) -> np.ndarray:
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0, sa, ca, d],
            [0, 0, 0, 1],
        ]
    )


def test_ur5_matches_its_published_dh_table():
    """Universal Robots' D-H table for the UR5 gives tool0 in the ``base``
    frame, which is ``base_link`` turned half a turn about z. The URDF writes
    pi/2 as 1.570796325, hence the looser tolerance."""
    chain = _chain("ur5.urdf", tip="tool0")
    assert chain.base == "world"
    assert [j.name for j in chain.moving] == [
        "shoulder_pan_joint",
        "shoulder_lift_joint",
        "elbow_joint",
        "wrist_1_joint",
        "wrist_2_joint",
        "wrist_3_joint",
    ]
    a = (0, -0.425, -0.39225, 0, 0, 0)
    d = (0.089159, 0, 0, 0.10915, 0.09465, 0.0823)
    alpha = (math.pi / 2, 0, 0, math.pi / 2, -math.pi / 2, 0)
    half_turn = np.diag([-1.0, -1.0, 1.0, 1.0])
    rng = np.random.default_rng(5)
    for q in [np.zeros(6), *rng.uniform(-math.pi, math.pi, (20, 6))]:
        expected = np.eye(4)
        for i in range(6):
            expected = expected @ _dh(a[i], alpha[i], d[i], q[i])
        np.testing.assert_allclose(half_turn @ chain.fk(q), expected, atol=1e-7)
    np.testing.assert_allclose(chain.tip_home()[:3, 3], [0.81725, 0.19145, -0.005491], atol=1e-8)
    assert chain.moving[2].lower == pytest.approx(-math.pi)


# -- random trees against yourdfpy ----------------------------------------------------------

_coordinate = st.floats(-2, 2, allow_nan=False, allow_infinity=False)
_angle = st.floats(-2 * math.pi, 2 * math.pi, allow_nan=False, allow_infinity=False)
_axis = st.tuples(*[st.floats(-1, 1, allow_nan=False)] * 3).filter(lambda v: math.hypot(*v) > 0.1)
_numbers = " ".join


@st.composite
def random_trees(draw):
    """(URDF text, tip, base, joint values): a random tree of up to 8 joints
    (mostly a chain), a random tip (mostly the last link) and one of its
    ancestors as the base (mostly the root)."""
    count = draw(st.integers(1, 8))
    parents = [-1]
    parts = ['<robot name="random">', *(f'<link name="l{i}"/>' for i in range(count + 1))]
    for i in range(1, count + 1):
        parent = draw(st.one_of(st.just(i - 1), st.integers(0, i - 1)))  # mostly a chain
        parents.append(parent)
        urdf_type = draw(st.sampled_from(["revolute", "continuous", "prismatic", "fixed"]))
        body = [f'<parent link="l{parent}"/>', f'<child link="l{i}"/>']
        if draw(st.booleans()):
            xyz = _numbers(repr(v) for v in draw(st.tuples(*[_coordinate] * 3)))
            rpy = _numbers(repr(v) for v in draw(st.tuples(*[_angle] * 3)))
            body.append(f'<origin xyz="{xyz}" rpy="{rpy}"/>')
        if draw(st.booleans()):
            axis = np.array(draw(_axis))
            if urdf_type == "prismatic":  # yourdfpy slides by the axis as written
                axis = axis / np.linalg.norm(axis)
            body.append(f'<axis xyz="{_numbers(repr(float(v)) for v in axis)}"/>')
        if urdf_type in ("revolute", "prismatic"):
            body.append('<limit lower="-7" upper="7" effort="1" velocity="1"/>')
        parts.append(f'<joint name="j{i}" type="{urdf_type}">{"".join(body)}</joint>')
    parts.append("</robot>")
    tip = draw(st.one_of(st.just(count), st.integers(0, count)))
    ancestors = [tip]
    while parents[ancestors[-1]] >= 0:
        ancestors.append(parents[ancestors[-1]])
    base = draw(st.one_of(st.just(0), st.sampled_from(ancestors)))
    values = draw(st.lists(st.floats(-7, 7, allow_nan=False), min_size=count, max_size=count))
    # yourdfpy (the reference) ignores a change of configuration under its
    # EQUALITY_TOLERANCE (1e-8): a joint at 2.6e-9 rad stays at 0 there
    values = [0.0 if abs(v) < 1e-7 else v for v in values]
    return "\n".join(parts), f"l{tip}", f"l{base}", values


@settings(
    max_examples=80,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
@given(random_trees())
def test_random_trees_match_yourdfpy(case):
    text, tip, base, values = case
    try:
        chain = read_chain(text, tip=tip, base=base)
    except DhsimError as exc:  # only a chain without a moving joint is refused
        assert f"no moving joint between link {base!r} and link {tip!r}" in str(exc)
        return
    q = values[: len(chain.moving)]
    reference = _reference(text)
    np.testing.assert_allclose(chain.fk(q), _reference_fk(reference, chain, q), atol=TOL)
    home = chain.tip_home()
    for index, (kind, point, direction) in enumerate(chain.joint_lines()):
        turned = np.zeros(len(chain.moving))
        turned[index] = q[index]
        expected = _screw(kind, point, direction, q[index]) @ home
        np.testing.assert_allclose(chain.fk(turned), expected, atol=TOL)


# -- refusals: one line naming the culprit ---------------------------------------------------


def _urdf(joints: str, *, links: tuple[str, ...] = ()) -> str:
    """A robot holding ``joints`` and every link they name (plus ``links``)."""
    named = dict.fromkeys([*re.findall(r'link="([^"]*)"', joints), *links])
    declared = "".join(f'<link name="{name}"/>' for name in named)
    return f'<?xml version="1.0"?>\n<robot name="t">{declared}{joints}</robot>'


def _joint(name: str, parent: str, child: str, urdf_type: str = "revolute", extra: str = "") -> str:
    limit = '<limit lower="-1" upper="1"/>' if urdf_type in ("revolute", "prismatic") else ""
    return (
        f'<joint name="{name}" type="{urdf_type}"><parent link="{parent}"/>'
        f'<child link="{child}"/>{limit}{extra}</joint>'
    )


ARM = _joint("j1", "base", "l1") + _joint("j2", "l1", "l2")


def _refusal(text: str, **names) -> str:
    with pytest.raises(DhsimError) as caught:
        read_chain(text, source="arm.urdf", **names)
    message = str(caught.value)
    assert message.startswith("arm.urdf: ")
    assert "\n" not in message
    return message


def test_the_plain_arm_is_accepted():
    chain = read_chain(_urdf(ARM))
    assert (chain.base, chain.tip, [j.name for j in chain.joints]) == ("base", "l2", ["j1", "j2"])


def test_a_tree_without_tip_is_refused_listing_its_leaves():
    message = _refusal(_text("ur5.urdf"))
    assert "tree" in message
    for leaf in ("'ee_link'", "'tool0'", "'base'"):
        assert leaf in message
    assert "'wrist_3_link'" not in message


def test_a_tree_is_fine_below_a_base_on_one_branch():
    text = _urdf(ARM + _joint("side", "base", "side_link"))
    assert "'l2', 'side_link'" in _refusal(text)
    assert read_chain(text, base="l1").joints[0].name == "j2"


@pytest.mark.parametrize("urdf_type", ["floating", "planar"])
def test_floating_and_planar_joints_on_the_chain_are_refused(urdf_type):
    text = _urdf(ARM + _joint("odd_one", "l2", "l3", urdf_type))
    message = _refusal(text)
    assert "'odd_one'" in message and urdf_type in message


def test_a_mimic_joint_on_the_chain_is_refused():
    text = _urdf(ARM + _joint("finger", "l2", "l3", extra='<mimic joint="j2" multiplier="2"/>'))
    message = _refusal(text)
    assert "'finger'" in message and "mimic" in message


def test_mimic_floating_and_planar_joints_off_the_chain_are_ignored():
    off = (
        _joint("finger", "l2", "f1", extra='<mimic joint="j2"/>')
        + _joint("float", "l1", "f2", "floating")
        + _joint("plane", "base", "f3", "planar")
    )
    chain = read_chain(_urdf(ARM + off), tip="l2")
    assert [j.name for j in chain.joints] == ["j1", "j2"]


def test_an_unknown_joint_type_is_refused():
    message = _refusal(_urdf(_joint("j1", "base", "l1", "revolving")))
    assert "'j1'" in message and "'revolving'" in message


def test_a_cycle_is_refused():
    # a loop beside a proper tree (so there is still one root)
    loop = _joint("a", "x", "y") + _joint("b", "y", "z") + _joint("c", "z", "x")
    message = _refusal(_urdf(_joint("j1", "base", "l1") + loop))
    assert "cycle" in message
    assert "'x'" in message and "'y'" in message and "'z'" in message
    # a loop through every link (so there is no root at all)
    message = _refusal(_urdf(ARM + _joint("back", "l2", "base")))
    assert "cycle" in message and "'base'" in message and "'l2'" in message


def test_a_joint_onto_its_own_parent_is_a_cycle():
    message = _refusal(_urdf(_joint("j1", "base", "l1") + _joint("loop", "l2", "l2")))
    assert "cycle" in message and "'l2'" in message


@pytest.mark.parametrize("end", ["parent", "child"])
def test_a_missing_link_is_refused(end):
    joint = _joint("j2", "l1", "ghost") if end == "child" else _joint("j2", "ghost", "l1")
    text = f'<robot name="t"><link name="base"/><link name="l1"/>{joint}</robot>'
    message = _refusal(text)
    assert "'j2'" in message and f"{end} link 'ghost'" in message


def test_a_joint_without_a_child_element_is_refused():
    joint = '<joint name="j" type="fixed"><parent link="a"/></joint>'
    text = f'<robot name="t"><link name="a"/>{joint}</robot>'
    message = _refusal(text)
    assert "'j'" in message and "<child" in message


def test_a_link_with_two_parents_is_refused():
    text = _urdf(ARM + _joint("j3", "base", "l2"))
    message = _refusal(text)
    assert "'l2'" in message and "two parents" in message
    assert "'j2'" in message and "'j3'" in message


def test_two_roots_are_refused():
    message = _refusal(_urdf(ARM, links=("lonely",)))
    assert "'base'" in message and "'lonely'" in message and "root" in message


@pytest.mark.parametrize("what", ["link", "joint"])
def test_duplicate_names_are_refused(what):
    text = _urdf(ARM, links=()) if what == "joint" else _urdf(ARM)
    if what == "joint":
        text = text.replace('name="j2"', 'name="j1"')
    else:
        text = text.replace('<link name="l2"/>', '<link name="l2"/><link name="l2"/>')
    message = _refusal(text)
    assert "two" in message and ("'j1'" if what == "joint" else "'l2'") in message


@pytest.mark.parametrize("word", ["nan", "inf", "-inf", "1e999", "NaN", "0x10", "1_0", "one", ""])
@pytest.mark.parametrize(
    ("template", "where"),
    [
        ('<origin xyz="0 {} 0"/>', "<origin xyz>"),
        ('<origin rpy="{} 0 0"/>', "<origin rpy>"),
        ('<axis xyz="0 0 {}"/>', "<axis xyz>"),
    ],
)
def test_a_non_finite_number_is_refused(word, template, where):
    text = _urdf(
        _joint("j1", "base", "l1") + _joint("bad", "l1", "l2", extra=template.format(word))
    )
    message = _refusal(text)
    assert "'bad'" in message and where in message
    if word:
        assert repr(word) in message


@pytest.mark.parametrize("end", ["lower", "upper"])
def test_a_non_finite_limit_is_refused(end):
    joint = _joint("bad", "base", "l1").replace(f'{end}="', f'{end}="nan" old="')
    message = _refusal(_urdf(joint))
    assert "'bad'" in message and f"<limit {end}>" in message and "'nan'" in message


def test_a_limit_is_needed_and_ordered():
    joint = '<joint name="slide" type="prismatic"><parent link="a"/><child link="b"/></joint>'
    message = _refusal(_urdf(joint))
    assert "'slide'" in message and "<limit" in message
    upside_down = _joint("j1", "base", "l1").replace('lower="-1" upper="1"', 'lower="1" upper="-1"')
    message = _refusal(_urdf(upside_down))
    assert "'j1'" in message and "lower" in message
    missing = _joint("j1", "base", "l1").replace('upper="1"', "")
    assert "<limit upper>" in _refusal(_urdf(missing))


def test_a_zero_axis_is_refused():
    message = _refusal(_urdf(_joint("j1", "base", "l1", extra='<axis xyz="0 0 0"/>')))
    assert "'j1'" in message and "zero" in message


def test_an_axis_needs_three_numbers():
    message = _refusal(_urdf(_joint("j1", "base", "l1", extra='<axis xyz="0 1"/>')))
    assert "'j1'" in message and "3 numbers" in message


@pytest.mark.parametrize(
    "text",
    [
        "",
        "<robot>",
        '<robot name="t"><link name="a"></robot>',
        '<robot name="t"><link name="a" name="b"/></robot>',
        "not xml at all",
        '<robot name="t"/><robot name="u"/>',
    ],
)
def test_malformed_xml_is_refused(text):
    message = _refusal(text)
    assert "not valid XML" in message


def test_the_top_element_must_be_robot():
    message = _refusal('<sdf version="1.6"><link name="a"/></sdf>')
    assert "<sdf>" in message and "<robot>" in message


def test_a_robot_without_links_is_refused():
    assert "no <link>" in _refusal('<robot name="t"/>')


def test_a_doctype_is_refused():
    text = '<?xml version="1.0"?>\n<!DOCTYPE robot>\n' + _urdf(ARM).split("\n", 1)[1]
    message = _refusal(text)
    assert "DOCTYPE" in message and "line 2" in message


ENTITY_BOMB = """
import json, resource, sys
from dhsim_tui.core.interop.urdf import read_chain
from dhsim_tui.core.model.errors import DhsimError
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
try:
    read_chain(sys.argv[1], source="arm.urdf")
    message = None
except DhsimError as exc:
    message = str(exc)
grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
print(json.dumps({"megabytes": grown / 1024, "message": message}))
"""


def test_an_entity_bomb_is_refused_before_it_expands():
    entities = '<!ENTITY a "aaaaaaaaaa">' + "".join(
        f'<!ENTITY {b} "&{a};&{a};&{a};&{a};&{a};&{a};&{a};&{a};&{a};&{a};">'
        for a, b in zip("abcdefgh", "bcdefghi", strict=True)
    )
    text = f'<?xml version="1.0"?>\n<!DOCTYPE robot [{entities}]>\n<robot name="&i;"/>'
    # in a fresh interpreter, capped: expanded, the name would be 10**9 characters
    cap = 4 << 30

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))

    done = subprocess.run(
        [sys.executable, "-c", ENTITY_BOMB, text],
        capture_output=True,
        text=True,
        timeout=HANG,  # a hang guard only
        preexec_fn=limit,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    outcome = json.loads(done.stdout)
    message = outcome["message"]
    assert message is not None, "read"
    assert message.startswith("arm.urdf: ") and "\n" not in message
    assert "DOCTYPE" in message and "line 2" in message
    assert outcome["megabytes"] < 100, outcome  # unexpanded: no gigabyte of a's


def test_an_external_entity_is_refused():
    text = '<!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]><robot name="&x;"/>'
    assert "DOCTYPE" in _refusal(text)


@pytest.mark.parametrize(
    ("names", "expected"),
    [
        ({"tip": "nowhere"}, "tip: no link named 'nowhere'"),
        ({"base": "nowhere"}, "base: no link named 'nowhere'"),
        ({"tip": "l1", "base": "l2"}, "link 'l2' is not an ancestor of link 'l1'"),
        ({"tip": "side_link", "base": "l1"}, "link 'l1' is not an ancestor of link 'side_link'"),
    ],
)
def test_tip_and_base_are_checked(names, expected):
    text = _urdf(ARM + _joint("side", "base", "side_link"))
    assert expected in _refusal(text, **names)


def test_a_chain_without_a_moving_joint_is_refused():
    text = _urdf(_joint("j1", "base", "l1") + _joint("bolt", "l1", "l2", "fixed"))
    assert "no moving joint between link 'l1' and link 'l2'" in _refusal(text, base="l1")
    assert "no moving joint" in _refusal(text, tip="base")


def test_file_text_in_messages_is_escaped():
    text = _urdf(ARM + _joint("side", "base", "evil\u202elink"))
    message = _refusal(text)
    assert "\u202e" not in message
    assert "evil\\u202elink" in message


def test_no_source_no_prefix():
    with pytest.raises(DhsimError) as caught:
        read_chain("<robot")
    assert str(caught.value).startswith("not valid XML")


def test_a_byte_order_mark_is_accepted():
    assert read_chain("\ufeff" + _urdf(ARM)).tip == "l2"


def test_a_dhsim_comment_is_kept_and_other_comments_are_not():
    plain = _urdf(ARM)
    assert read_chain(plain).stored is None
    body = plain.split("\n", 1)[1]
    text = (
        '<?xml version="1.0"?>\n<!-- a note -->\n<!-- dhsim-robot 1: first {"a": 1} -->\n'
        + body.replace("</robot>", "<!-- dhsim-robot 1: second --></robot>")
    )
    chain = read_chain(text)
    assert chain.stored == ' dhsim-robot 1: first {"a": 1} '
    # the chain itself is the same as without the comments
    assert [j.name for j in chain.joints] == [j.name for j in read_chain(plain).joints]

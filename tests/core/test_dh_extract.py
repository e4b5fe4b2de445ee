"""D-H parameters from joint axes (dhsim_tui.core.interop.dh_extract), checked against an
independent product-of-exponentials FK and a separate D-H matrix product."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from dhsim_tui.core.interop.dh_chain import DHChain, DHRow, convert
from dhsim_tui.core.interop.dh_extract import extract
from dhsim_tui.core.model.errors import DhsimError

DEG = math.pi / 180.0
TOL = 1e-9

# -- an independent model of both sides -------------------------------------------------


def _rodrigues(w: np.ndarray, angle: float) -> np.ndarray:
    k = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)


def _twist(kind: str, p: np.ndarray, w: np.ndarray, q: float) -> np.ndarray:
    """exp(ξ q): turn by q about the line (p, w), or slide q along w."""
    out = np.eye(4)
    if kind == "revolute":
        r = _rodrigues(w, q)
        out[:3, :3] = r
        out[:3, 3] = p - r @ p
    else:
        out[:3, 3] = q * w
    return out


def _poe(lines, tip: np.ndarray, q) -> np.ndarray:
    out = np.eye(4)
    for (kind, p, w), qi in zip(lines, q, strict=True):
        out = out @ _twist(kind, p, w, qi)
    return out @ tip


def _moved_lines(lines, q):
    """Each joint's line at joint values q (moved by the joints before it)."""
    out, carry = [], np.eye(4)
    for (kind, p, w), qi in zip(lines, q, strict=True):
        out.append((carry[:3, :3] @ p + carry[:3, 3], carry[:3, :3] @ w))
        carry = carry @ _twist(kind, p, w, qi)
    return out


def _rot_z(t):
    m = np.eye(4)
    m[:2, :2] = [[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]]
    return m


def _rot_x(t):
    m = np.eye(4)
    m[1:3, 1:3] = [[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]]
    return m


def _trans(x=0.0, z=0.0):
    m = np.eye(4)
    m[0, 3], m[2, 3] = x, z
    return m


def _dh(convention, theta, d, a, alpha):
    if convention == "standard":
        return _rot_z(theta) @ _trans(z=d) @ _trans(x=a) @ _rot_x(alpha)
    return _rot_x(alpha) @ _trans(x=a) @ _rot_z(theta) @ _trans(z=d)


def _table_frames(chain: DHChain, q):
    """base · T_1 ··· T_i for i = 0..n from the table, with the offset semantics."""
    frames = [np.array(chain.base)]
    for row, qi in zip(chain.rows, q, strict=True):
        theta = qi + row.offset if row.kind == "revolute" else row.theta
        d = qi + row.offset if row.kind == "prismatic" else row.d
        frames.append(frames[-1] @ _dh(chain.convention, theta, d, row.a, row.alpha))
    return frames


def _table_fk(chain: DHChain, q):
    return _table_frames(chain, q)[-1] @ chain.tool


def _assert_same_pose(got, want, size):
    assert np.abs(got[:3, 3] - want[:3, 3]).max() <= TOL * size, (got, want)
    # |R_gotᵀ R_want - I| is about the angle between them (arccos would lose it)
    assert np.abs(got[:3, :3].T @ want[:3, :3] - np.eye(3)).max() <= TOL, (got, want)
    assert np.array_equal(got[3], [0.0, 0.0, 0.0, 1.0])


def _angle_gap(a, b):
    """|a - b| modulo 2π (π and -π + 1e-14 are the same alpha)."""
    return abs(math.remainder(a - b, 2 * math.pi))


def _size(lines, tip):
    return max([1.0, float(np.linalg.norm(tip[:3, 3]))] + [np.linalg.norm(p) for _, p, _ in lines])


def _assert_frames_on_lines(chain: DHChain, lines, q, size):
    """Frame i-1 (standard) or frame i (modified) has its origin on joint i's
    line at q and its z axis along the joint's direction."""
    frames = _table_frames(chain, q)
    shift = 0 if chain.convention == "standard" else 1
    for i, (point, direction) in enumerate(_moved_lines(lines, q)):
        frame = frames[i + shift]
        assert np.abs(frame[:3, 2] - direction).max() <= TOL, (i, frame, direction)
        off_line = np.cross(frame[:3, 3] - point, direction)
        assert np.abs(off_line).max() <= TOL * size, (i, frame, point, direction)


# -- random chains with the special cases forced --------------------------------------

RELATIONS = (
    "free",
    "parallel",
    "antiparallel",
    "intersecting",
    "coincident",
    "perpendicular",
    "perpendicular-intersecting",
)
coords = st.floats(-1.0, 1.0, allow_nan=False, allow_infinity=False)
vectors = st.tuples(coords, coords, coords).map(np.array)


@st.composite
def unit_vectors(draw):
    v = draw(vectors)
    assume(np.linalg.norm(v) > 0.2)
    return v / np.linalg.norm(v)


@st.composite
def perpendicular_to(draw, w):
    v = draw(vectors)
    v = v - (v @ w) * w
    assume(np.linalg.norm(v) > 0.2)
    return v / np.linalg.norm(v)


@st.composite
def next_line(draw, p, w, scale, relation):
    """A line (point, unit direction) in ``relation`` to the line (p, w)."""
    along = draw(coords) * scale
    if relation in ("coincident", "parallel", "antiparallel"):
        direction = w if relation != "antiparallel" else -w
        if relation == "coincident":
            direction = draw(st.sampled_from([w, -w]))
            return p + along * w, direction
        return p + draw(vectors) * scale, direction
    if relation.startswith("perpendicular"):
        direction = draw(perpendicular_to(w))
    else:
        direction = draw(unit_vectors())
        assume(np.linalg.norm(np.cross(w, direction)) > 1e-4)
    if relation.endswith("intersecting"):
        return p + along * w + draw(coords) * scale * direction, direction
    return p + draw(vectors) * scale, direction


@st.composite
def quaternion_rotations(draw):
    qv = np.array([draw(coords) for _ in range(4)])
    assume(np.linalg.norm(qv) > 0.2)
    w, x, y, z = qv / np.linalg.norm(qv)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


@st.composite
def source_chains(draw):
    """(lines, tip_home, size, joint values): a random chain and a few q."""
    n = draw(st.integers(1, 7))
    scale = draw(st.sampled_from([1.0, 0.05, 800.0]))
    p = draw(vectors) * scale  # the first axis off the origin and tilted
    w = draw(unit_vectors())
    lines = [(draw(st.sampled_from(["revolute", "prismatic"])), p, w)]
    for _ in range(n - 1):
        p, w = draw(next_line(p, w, scale, draw(st.sampled_from(RELATIONS))))
        lines.append((draw(st.sampled_from(["revolute", "prismatic"])), p, w))
    tip = np.eye(4)
    tip_origin, tip_z = draw(next_line(p, w, scale, draw(st.sampled_from(RELATIONS))))
    x = draw(perpendicular_to(tip_z))
    tip[:3, :3] = np.column_stack([x, np.cross(tip_z, x), tip_z])
    if draw(st.booleans()):  # or any orientation at all
        tip[:3, :3] = draw(quaternion_rotations())
    tip[:3, 3] = tip_origin
    # nearly parallel (not parallel) axes are D-H's weak spot: no float result
    # holds to 1e-9 there (see test_nearly_parallel_axes_and_the_parallel_tolerance)
    zs = [w for _, _, w in lines] + [tip[:3, 2]]
    for u, v in itertools.pairwise(zs):
        sine = np.linalg.norm(np.cross(u, v))
        assume(sine < 1e-15 or sine > 1e-4)
    qs = [
        [draw(coords) * (math.pi if kind == "revolute" else scale) for kind, _, _ in lines]
        for _ in range(3)
    ]
    return lines, tip, _size(lines, tip), qs


@pytest.mark.slow  # a long hypothesis run
@pytest.mark.parametrize("convention", ["standard", "modified"])
@settings(max_examples=300, deadline=None)
@given(source=source_chains())
def test_extracted_chain_matches_product_of_exponentials(convention, source):
    lines, tip, size, qs = source
    chain = extract(lines, tip, convention)
    assert chain.convention == convention
    assert [row.kind for row in chain.rows] == [kind for kind, _, _ in lines]
    for q in [[0.0] * len(lines), *qs]:
        want = _poe(lines, tip, q)
        _assert_same_pose(_table_fk(chain, q), want, size)
        _assert_same_pose(chain.fk(q), want, size)
        _assert_frames_on_lines(chain, lines, q, size)


@pytest.mark.slow  # a long hypothesis run
@settings(max_examples=200, deadline=None)
@given(source=source_chains())
def test_rows_follow_the_documented_choices(source):
    lines, tip, size, _ = source
    chain = extract(lines, tip)
    for i, row in enumerate(chain.rows):
        assert row.a >= 0.0
        assert -math.pi < row.alpha <= math.pi and -math.pi < row.theta <= math.pi
        assert row.offset == (row.theta if row.kind == "revolute" else row.d)
        if i + 1 < len(chain.rows):
            w, w_next = lines[i][2], lines[i + 1][2]
            if np.linalg.norm(np.cross(w, w_next)) < 1e-12:  # parallel: d = 0
                assert abs(row.d) <= TOL * size and abs(math.sin(row.alpha)) <= TOL
    # frame 0 lies on joint 1's axis, nearest the base origin
    p, w = lines[0][1], lines[0][2]
    assert np.abs(chain.base[:3, 3] - (p - (p @ w) * w)).max() <= TOL * size
    # the tool is a screw along its z axis
    tool = chain.tool
    assert np.abs(tool[:3, 2] - [0.0, 0.0, 1.0]).max() <= TOL
    assert np.abs(tool[:2, 3]).max() <= TOL * size


@pytest.mark.slow  # a long hypothesis run
@settings(max_examples=200, deadline=None)
@given(source=source_chains())
def test_standard_modified_standard_returns_the_same_table(source):
    lines, tip, size, qs = source
    standard = extract(lines, tip, "standard")
    modified = convert(standard, "modified")
    back = convert(modified, "standard")
    assert modified.rows[0].a == 0.0 and modified.rows[0].alpha == 0.0
    # nearly parallel axes give huge d (and tool z); rounding scales with them
    size = max([size, np.abs(standard.tool[:3, 3]).max()] + [abs(r.d) for r in standard.rows])
    for row, other in zip(standard.rows, back.rows, strict=True):
        assert row.kind == other.kind
        assert (row.theta, row.d, row.offset) == (other.theta, other.d, other.offset)
        assert abs(row.a - other.a) <= 1e-12 * size
        assert _angle_gap(row.alpha, other.alpha) <= 1e-12
    assert np.abs(back.base - standard.base).max() <= 1e-12 * size
    assert np.abs(back.tool - standard.tool).max() <= 1e-12 * size
    # the modified extraction is the conversion of the standard one
    direct = extract(lines, tip, "modified")
    assert direct.rows == modified.rows
    for q in qs:
        want = _poe(lines, tip, q)
        for chain in (modified, back, direct):
            _assert_same_pose(_table_fk(chain, q), want, size)


rows_strategy = st.lists(
    st.tuples(
        st.sampled_from(["revolute", "prismatic"]),
        st.floats(-3.0, 3.0),
        st.floats(-2.0, 2.0),
        st.floats(-2.0, 2.0),
        st.floats(-3.0, 3.0),
    ),
    min_size=1,
    max_size=7,
)


def _rows(raw):
    return tuple(
        DHRow(kind, t, d, a, al, t if kind == "revolute" else d) for kind, t, d, a, al in raw
    )


def _rigid_from(rot, t):
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = rot, t
    return out


@pytest.mark.slow  # a long hypothesis run
@pytest.mark.parametrize("convention", ["standard", "modified"])
@settings(max_examples=200, deadline=None)
@given(
    raw=rows_strategy,
    base_rot=quaternion_rotations(),
    base_t=vectors,
    tool_rot=quaternion_rotations(),
    tool_t=vectors,
    q=st.lists(coords, min_size=7, max_size=7),
)
def test_convert_keeps_forward_kinematics(convention, raw, base_rot, base_t, tool_rot, tool_t, q):
    chain = DHChain(
        convention, _rigid_from(base_rot, base_t), _rows(raw), _rigid_from(tool_rot, tool_t)
    )
    other = "modified" if convention == "standard" else "standard"
    q = q[: len(raw)]
    converted = convert(chain, other)
    assert converted.convention == other
    _assert_same_pose(_table_fk(converted, q), _table_fk(chain, q), 10.0)
    _assert_same_pose(_table_fk(convert(converted, convention), q), _table_fk(chain, q), 10.0)
    assert convert(chain, convention).rows == chain.rows


@pytest.mark.slow  # a long hypothesis run
@settings(max_examples=200, deadline=None)
@given(raw=rows_strategy, d=coords, theta=coords)
def test_standard_table_with_a_screw_tool_round_trips(raw, d, theta):
    tool = _trans(z=d) @ _rot_z(theta)
    chain = DHChain("standard", np.eye(4), _rows(raw), tool)
    back = convert(convert(chain, "modified"), "standard")
    for row, other in zip(chain.rows, back.rows, strict=True):
        assert (row.theta, row.d) == (other.theta, other.d)
        assert abs(row.a - other.a) <= 1e-12 and _angle_gap(row.alpha, other.alpha) <= 1e-12
    assert np.abs(back.tool - tool).max() <= 1e-12


# -- known answers ---------------------------------------------------------------------


def test_planar_two_link_arm():
    z = np.array([0.0, 0.0, 1.0])
    lines = [("revolute", np.zeros(3), z), ("revolute", np.array([1.0, 0.0, 0.0]), z)]
    tip = _trans(x=1.5)
    chain = extract(lines, tip)
    assert [r.a for r in chain.rows] == [1.0, 0.5]
    assert [r.alpha for r in chain.rows] == [0.0, 0.0]
    assert [r.d for r in chain.rows] == [0.0, 0.0]
    assert [r.offset for r in chain.rows] == [0.0, 0.0]
    assert np.array_equal(chain.base, np.eye(4)) and np.array_equal(chain.tool, np.eye(4))
    q = [0.3, -1.1]
    _assert_same_pose(chain.fk(q), _poe(lines, tip, q), 1.0)


#: Puma 560, standard D-H (reference §5): theta, d, a (mm), alpha (deg)
PUMA = [
    (0, 0, 0, 90),
    (0, 0, 431.8, 0),
    (0, 150.05, 20.3, -90),
    (0, 431.8, 0, 90),
    (0, 0, 0, -90),
    (0, 0, 0, 0),
]


def _puma_lines(q_deg):
    """Joint lines and the tip with the table's arm at q (degrees)."""
    frame, lines = np.eye(4), []
    for (theta, d, a, alpha), qi in zip(PUMA, q_deg, strict=True):
        lines.append(("revolute", frame[:3, 3].copy(), frame[:3, 2].copy()))
        frame = frame @ _dh("standard", (theta + qi) * DEG, d, a, alpha * DEG)
    return lines, frame


@pytest.mark.parametrize(
    ("pose", "offsets"),
    [((0, 0, 0, 0, 0, 0), (0, 0, 0, 0, 0, 0)), ((0, 90, -90, 0, 0, 0), (0, 90, -90, 0, 0, 0))],
    ids=["qz", "qr"],
)
def test_puma560_table_comes_back(pose, offsets):
    """Lines taken at qz give the published table; at qr, the same d, a,
    alpha with qr's angles as offsets (the documented freedom: where q = 0 is)."""
    lines, tip = _puma_lines(pose)
    chain = extract(lines, tip)
    np.testing.assert_allclose(chain.base, np.eye(4), atol=1e-12)
    np.testing.assert_allclose(chain.tool, np.eye(4), atol=1e-12)
    got = [(r.offset / DEG, r.d, r.a, r.alpha / DEG) for r in chain.rows]
    want = [(o, d, a, al) for o, (_, d, a, al) in zip(offsets, PUMA, strict=True)]
    np.testing.assert_allclose(got, want, atol=1e-9)
    for q_deg in ([30] * 6, [0, 30, 45, 60, 90, 0], [-20, 100, 10, -50, 70, 200]):
        q = [v * DEG for v in q_deg]
        want_pose = _puma_lines([p + v for p, v in zip(pose, q_deg, strict=True)])[1]
        _assert_same_pose(chain.fk(q), want_pose, 1000.0)
        _assert_same_pose(chain.fk(q), _poe(lines, tip, q), 1000.0)


def test_puma560_at_all_30_degrees_matches_the_reference():
    lines, tip = _puma_lines([0] * 6)
    for convention in ("standard", "modified"):
        pose = extract(lines, tip, convention).fk([30 * DEG] * 6)
        np.testing.assert_allclose(pose[:3, 3], [83.82, -124.87, 449.38], atol=0.01)


def test_prismatic_joint_on_a_coincident_axis():
    """Stanford-like: the slide's axis is the next joint's, so the slide's d
    at q = 0 (the source's 0.5) goes to the next row, which is allowed."""
    z = np.array([0.0, 0.0, 1.0])
    lines = [
        ("revolute", np.zeros(3), z),
        ("prismatic", np.array([0.0, 0.2, 0.4]), np.array([1.0, 0.0, 0.0])),
        ("revolute", np.array([0.5, 0.2, 0.4]), np.array([1.0, 0.0, 0.0])),
    ]
    tip = _trans(x=0.7) @ _rot_x(0.3)
    tip[1, 3], tip[2, 3] = 0.2, 0.4
    chain = extract(lines, tip)
    assert chain.rows[1].kind == "prismatic" and chain.rows[1].a == 0.0
    assert chain.rows[1].alpha == 0.0 and chain.rows[1].d == chain.rows[1].offset == 0.0
    for q in ([0.0, 0.0, 0.0], [0.4, 0.25, -1.0]):
        _assert_same_pose(chain.fk(q), _poe(lines, tip, q), 1.0)


# -- errors ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("lines", "tip", "convention", "message"),
    [
        ([], np.eye(4), "standard", "no moving joint"),
        ([("fixed", np.zeros(3), np.ones(3))], np.eye(4), "standard", "kind"),
        ([("revolute", np.zeros(3), np.zeros(3))], np.eye(4), "standard", "zero"),
        ([("revolute", np.zeros(2), np.ones(3))], np.eye(4), "standard", "3-vectors"),
        ([("revolute", np.full(3, np.nan), np.ones(3))], np.eye(4), "standard", "finite"),
        ([("revolute", np.zeros(3), np.ones(3))], 2 * np.eye(4), "standard", "rigid"),
        ([("revolute", np.zeros(3), np.ones(3))], np.eye(3), "standard", "4×4"),
        ([("revolute", np.zeros(3), np.ones(3))], np.eye(4), "craig", "convention"),
    ],
)
def test_bad_input_raises_one_line(lines, tip, convention, message):
    with pytest.raises(DhsimError, match=message) as info:
        extract(lines, tip, convention)
    assert "\n" not in str(info.value)


def test_row_offset_must_be_its_variable():
    with pytest.raises(DhsimError, match="offset"):
        DHRow("revolute", 0.5, 0.0, 1.0, 0.0, 0.0)
    with pytest.raises(DhsimError, match="offset"):
        DHRow("prismatic", 0.5, 0.2, 1.0, 0.0, 0.5)
    with pytest.raises(DhsimError, match="joint values"):
        extract([("revolute", np.zeros(3), np.ones(3))], np.eye(4)).fk([0.0, 1.0])


def test_nearly_parallel_axes_and_the_parallel_tolerance():
    """Axes 1e-9 rad from parallel: as skew lines (the default) the common
    normal is ~1e9 away, so d is huge yet FK holds to rounding of that size;
    with parallel_tol=1e-6 they count as parallel: d ~ 0, FK off by ~1e-9."""
    tilt = 1e-9
    z = np.array([0.0, 0.0, 1.0])
    leaning = np.array([-math.sin(tilt), 0.0, math.cos(tilt)])
    lines = [("revolute", np.zeros(3), z), ("revolute", np.array([1.0, 0.0, 0.0]), leaning)]
    tip = _trans(x=1.5)
    q = [0.7, -0.4]
    skew = extract(lines, tip)
    assert abs(skew.rows[0].d) > 1e8
    _assert_same_pose(skew.fk(q), _poe(lines, tip, q), 1e2)
    parallel = extract(lines, tip, parallel_tol=1e-6)
    assert abs(parallel.rows[0].d) < 1e-8 and parallel.rows[0].a == pytest.approx(1.0)
    assert np.abs(parallel.fk(q) - _poe(lines, tip, q)).max() < 1e-8
    with pytest.raises(DhsimError, match="parallel tolerance"):
        extract(lines, tip, parallel_tol=2.0)


def test_pairs_can_be_taken_as_parallel_by_number():
    """``parallel``: a pair 3e-10 rad from parallel, its common normal ~3e9 away
    as skew lines, is parallel when asked: a = the lines' distance, d ~ 0, and
    the forward kinematics off by about the angle times the lever (~1e-9)."""
    tilt = 3e-10
    z = np.array([0.0, 0.0, 1.0])
    leaning = np.array([-math.sin(tilt), 0.0, math.cos(tilt)])
    lines = [("revolute", np.zeros(3), z), ("revolute", np.array([1.0, 0.0, 0.0]), leaning)]
    tip = _trans(x=1.5)
    assert abs(extract(lines, tip).rows[0].d) > 1e9
    chain = extract(lines, tip, parallel={1})
    first = chain.rows[0]
    assert first.alpha == 0.0 and abs(first.d) < 1e-9 and first.a == pytest.approx(1.0, abs=1e-12)
    for q in ([0.0, 0.0], [2.5, -3.0], [-1.0, 3.1]):
        assert np.abs(_table_fk(chain, q) - _poe(lines, tip, q)).max() < 5 * tilt


def test_the_last_axis_and_the_tip_taken_as_parallel_cost_nothing():
    """Pair n (the last axis with the tip's z axis) taken as parallel: the tool
    frame takes up the angle, so the chain is as exact as ever."""
    tilt = 3e-10
    tip = _trans(x=0.5) @ np.array(
        [
            [math.cos(tilt), 0.0, math.sin(tilt), 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [-math.sin(tilt), 0.0, math.cos(tilt), 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )
    lines = [("revolute", np.zeros(3), np.array([0.0, 0.0, 1.0]))]
    assert abs(extract(lines, tip).rows[0].d) > 1e8
    chain = extract(lines, tip, parallel={1})
    assert abs(chain.rows[0].d) < 1e-12 and chain.rows[0].a == pytest.approx(0.5, abs=1e-12)
    for q in ([0.0], [2.0], [-3.0]):
        np.testing.assert_allclose(_table_fk(chain, q), _poe(lines, tip, q), rtol=0, atol=1e-14)


def test_a_looser_length_tolerance_makes_near_coincident_axes_one():
    """Parallel axes 1e-11 apart: two lines by default (a = 1e-11 and x along
    that hair), one line with ``length_tol=1e-10`` (a = 0, x kept)."""
    z = np.array([0.0, 0.0, 1.0])
    lines = [("revolute", np.zeros(3), z), ("revolute", np.array([0.0, 1e-11, 0.3]), z)]
    tip = _trans(x=0.4)
    apart = extract(lines, tip)
    assert apart.rows[0].a == pytest.approx(1e-11) and abs(apart.rows[0].theta) > 1.0
    one = extract(lines, tip, length_tol=1e-10)
    assert (one.rows[0].a, one.rows[0].theta) == (0.0, 0.0)
    for q in ([0.0, 0.0], [1.0, -2.0]):
        assert np.abs(_table_fk(one, q) - _poe(lines, tip, q)).max() < 1e-10
    with pytest.raises(DhsimError, match="length tolerance"):
        extract(lines, tip, length_tol=0.5)

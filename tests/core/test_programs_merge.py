"""Programs and joint top speeds through the robot's edits and the reload
merge (issue 19): joint edits and unit changes carry the programs' own joint
values and linear speeds along; the three-way merge keeps both sides'
programs, each program one field, and asks only about one both changed."""

from __future__ import annotations

from dataclasses import replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dhsim_tui.core.files.robotfile import loads
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.merge import merge
from dhsim_tui.core.model.program import Program, Step

#: R, R, P with a top speed on the prismatic joint and a program of each kind of step
ARM = loads(
    """\
name = "arm"
[poses]
ready = [0.0, 90.0, 100.0]
low = [10.0, -45.0, 0.0]
[programs]
demo = [
  { move = "joint", to = "ready" },
  { move = "linear", to = [10, -45, 150], speed = 250 },
  { move = "joint", to = [0, 45, 50], speed = 50 },
  { wait = 0.5 },
]
[[joints]]
theta = 0.0
d = 300.0
a = 0.0
alpha = 90.0
vmax = 60
[[joints]]
theta = 0.0
d = 0.0
a = 400.0
alpha = 0.0
[[joints]]
type = "prismatic"
theta = 0.0
d = 100.0
a = 0.0
alpha = 0.0
min = 0.0
max = 200.0
vmax = 500
amax = 2000
"""
)


def targets(robot, name: str = "demo") -> list:
    return [step.to for step in robot.program(name).steps]


# -- edits ---------------------------------------------------------------------------


def test_joint_edits_carry_the_programs_own_joint_values():
    inserted = editing.insert_joint(ARM, 0)  # a new joint 2, home 0
    assert targets(inserted) == ["ready", (10.0, 0.0, -45.0, 150.0), (0.0, 0.0, 45.0, 50.0), None]
    deleted = editing.delete_joint(ARM, 1)
    assert targets(deleted) == ["ready", (10.0, 150.0), (0.0, 50.0), None]
    moved = editing.move_joint(ARM, 0, 1)
    assert targets(moved) == ["ready", (-45.0, 10.0, 150.0), (45.0, 0.0, 50.0), None]


def test_retyping_a_joint_sets_its_values_to_home_and_drops_its_top_speeds():
    toggled = editing.toggle_type(ARM, 2)  # prismatic -> revolute: home theta 0
    assert targets(toggled)[1:3] == [(10.0, -45.0, 0.0), (0.0, 45.0, 0.0)]
    assert (toggled.joints[2].vmax, toggled.joints[2].amax) == (None, None)
    assert toggled.joints[0].vmax == 60.0  # the other joints keep theirs


def test_a_change_of_unit_converts_lengths_speeds_and_prismatic_top_speeds():
    metres = editing.set_units(ARM, "m")
    steps = metres.program("demo").steps
    assert steps[1] == Step("linear", (10.0, -45.0, 0.15), 0.25)  # 250 mm/s is 0.25 m/s
    assert steps[2] == Step("joint", (0.0, 45.0, 0.05), 50.0)  # a percentage stays
    assert steps[3] == ARM.program("demo").steps[3]
    assert (metres.joints[2].vmax, metres.joints[2].amax) == (0.5, 2.0)
    assert metres.joints[0].vmax == 60.0  # deg/s: no length in it
    assert editing.set_units(metres, "mm") == ARM


def test_a_pose_a_program_moves_to_cannot_be_deleted():
    with pytest.raises(DhsimError, match=r"programs\.demo, step 1, to: no pose named 'ready'"):
        editing.delete_pose(ARM, "ready")
    assert "low" not in editing.delete_pose(ARM, "low").pose_names  # not used: deleted


def test_set_and_delete_program():
    new = Program(" nod ", (Step("wait", seconds=1.0),))
    added = editing.set_program(ARM, new)
    assert added.program_names == ("demo", "nod")
    changed = editing.set_program(added, Program("demo", ()))
    assert changed.program_names == ("demo", "nod") and changed.program("demo").steps == ()
    assert editing.delete_program(changed, "demo").program_names == ("nod",)
    with pytest.raises(DhsimError, match="a program needs a name"):
        editing.set_program(ARM, Program("  ", ()))
    with pytest.raises(DhsimError, match=r"programs\.bad, step 1, to: expected 3 joint values"):
        editing.set_program(ARM, Program("bad", (Step("joint", (1.0, 2.0)),)))


JOINT_EDITS = st.lists(
    st.one_of(
        st.tuples(st.just("insert"), st.integers(0, 5)),
        st.tuples(st.just("delete"), st.integers(0, 5)),
        st.tuples(st.just("move"), st.integers(0, 5), st.sampled_from((-1, 1))),
        st.tuples(st.just("toggle"), st.integers(0, 5)),
        st.tuples(st.just("units"), st.sampled_from(("mm", "cm", "m", "in"))),
    ),
    max_size=8,
)


def apply(robot, kind: str, args: list):
    """One joint edit, as the editor makes it."""
    if kind == "units":
        return editing.set_units(robot, args[0])
    index = args[0] % robot.dof
    if kind == "insert":
        return editing.insert_joint(robot, index)
    if kind == "delete":
        return editing.delete_joint(robot, index)
    if kind == "move":
        return editing.move_joint(robot, index, args[1])
    return editing.toggle_type(robot, index)


@settings(max_examples=80, deadline=None)
@given(JOINT_EDITS)
def test_a_steps_own_values_follow_the_joints_as_a_pose_with_the_same_values_does(edits):
    """Poses followed joint edits before programs existed: a step whose
    values are a pose's must still be that pose's after any joint edit."""
    robot = editing.set_pose(ARM, "same", (10.0, -45.0, 150.0))
    for kind, *args in edits:
        try:
            robot = apply(robot, kind, args)
        except DhsimError:
            continue  # an edit the editor refuses (the last joint, the table's end)
        assert targets(robot)[1] == robot.pose("same")


# -- the merge on reload -----------------------------------------------------------------


def with_demo(robot, *steps: Step):
    return editing.set_program(robot, Program("demo", steps))


def test_a_program_only_one_side_changed_takes_that_side():
    mine = with_demo(ARM, Step("wait", seconds=9.0))
    assert merge(ARM, mine, ARM).resolve({}) == mine
    assert merge(ARM, ARM, mine).resolve({}) == mine
    assert merge(ARM, mine, mine).conflicts == ()


def test_programs_added_on_both_sides_are_both_kept():
    mine = editing.set_program(ARM, Program("mine", (Step("wait", seconds=1.0),)))
    theirs = editing.set_program(ARM, Program("theirs", (Step("joint", "low"),)))
    found = merge(ARM, mine, theirs)
    assert found.conflicts == ()
    assert found.resolve({}).program_names == ("demo", "theirs", "mine")


def test_a_program_both_changed_is_one_question_about_the_whole_program():
    mine = with_demo(ARM, Step("wait", seconds=1.0))
    theirs = with_demo(ARM, Step("joint", "low", 20.0), Step("wait", seconds=2.0))
    found = merge(ARM, mine, theirs)
    (conflict,) = found.conflicts
    assert (conflict.label, conflict.mine) == ("program demo", "1 step: wait 1 s")
    assert conflict.theirs == "2 steps: joint to low at 20%; wait 2 s"
    assert found.resolve({"program demo": "mine"}).program("demo") == mine.program("demo")
    assert found.resolve({}).program("demo") == theirs.program("demo")


def test_a_deleted_program_stays_deleted_unless_the_other_side_changed_it():
    mine = editing.delete_program(ARM, "demo")
    assert merge(ARM, mine, ARM).resolve({}).programs == ()
    theirs = with_demo(ARM, Step("wait", seconds=3.0))
    (conflict,) = merge(ARM, mine, theirs).conflicts
    assert (conflict.label, conflict.mine) == ("program demo", "(none)")
    assert merge(ARM, mine, theirs).resolve({"program demo": "mine"}).programs == ()


def test_top_speeds_merge_per_joint():
    def rate(robot, index, **values):
        joints = list(robot.joints)
        joints[index] = replace(joints[index], **values)
        return replace(robot, joints=tuple(joints))

    mine = rate(ARM, 1, vmax=30.0)
    theirs = rate(ARM, 2, amax=1500.0)
    robot = merge(ARM, mine, theirs).resolve({})
    assert (robot.joints[1].vmax, robot.joints[2].amax) == (30.0, 1500.0)
    found = merge(ARM, rate(ARM, 0, vmax=None), rate(ARM, 0, vmax=75.0))
    (conflict,) = found.conflicts
    assert (conflict.label, conflict.mine, conflict.theirs) == ("joint 1 vmax", "(none)", "75")
    assert found.resolve({"joint 1 vmax": "mine"}).joints[0].vmax is None


def test_a_change_of_unit_on_one_side_converts_the_other_sides_programs():
    mine = editing.set_units(ARM, "m")
    theirs = editing.set_program(ARM, Program("fast", (Step("linear", "low", 500.0),)))
    robot = merge(ARM, mine, theirs).resolve({})
    assert robot.units == "m"
    assert robot.program("fast").steps == (Step("linear", "low", 0.5),)
    assert robot.program("demo") == mine.program("demo")


def test_a_program_moving_to_a_pose_the_other_side_deleted_cannot_be_combined():
    mine = editing.set_program(ARM, Program("pick", (Step("joint", "low"),)))
    theirs = editing.delete_pose(ARM, "low")
    with pytest.raises(DhsimError, match=r"cannot be combined: programs\.pick, step 1, to"):
        merge(ARM, mine, theirs).resolve({})


def test_a_long_program_is_shortened_in_the_question():
    many = tuple(Step("joint", (float(i), 45.0, 50.0)) for i in range(40))
    found = merge(ARM, with_demo(ARM, *many), with_demo(ARM, Step("wait", seconds=1.0)))
    (conflict,) = found.conflicts
    assert conflict.mine.startswith("40 steps: joint to [0, 45, 50]; joint to [1, 45, 50]")
    assert len(conflict.mine) < 140 and conflict.mine.endswith("…")

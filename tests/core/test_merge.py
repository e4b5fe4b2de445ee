"""Reload keeps both sides (issue 17): the three-way merge of my unsaved
edits onto the file as another program left it."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dhsim_tui.core import load_robot
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.merge import WHOLE, merge

PUMA = load_robot("puma560")[0]


def test_only_one_side_changed_takes_that_side():
    mine = editing.set_joint_field(PUMA, 0, "max", 150.0)
    assert merge(PUMA, mine, PUMA).resolve({}) == mine
    assert merge(PUMA, PUMA, mine).resolve({}) == mine
    assert merge(PUMA, mine, mine).conflicts == ()  # the same change on both sides


def test_the_trials_case_asks_only_about_the_value_both_changed():
    mine = editing.set_joint_field(PUMA, 0, "max", 150.0)
    theirs = editing.set_joint_field(PUMA, 0, "max", 155.0)
    theirs = editing.set_joint_field(theirs, 4, "min", -120.0)
    found = merge(PUMA, mine, theirs)
    (conflict,) = found.conflicts
    assert (conflict.label, conflict.mine, conflict.theirs) == ("joint 1 max", "150", "155")
    kept_mine = found.resolve({"joint 1 max": "mine"})
    assert kept_mine.joints[0].max == 150.0 and kept_mine.joints[4].min == -120.0
    assert found.resolve({}).joints[0].max == 155.0  # unanswered: the file's


def test_poses_from_both_sides_are_kept_and_a_pose_both_changed_is_asked():
    mine = editing.set_pose(PUMA, "mine", PUMA.home)
    mine = editing.set_pose(mine, "qr", (0.0, 80.0, -90.0, 0.0, 0.0, 0.0))
    theirs = editing.set_pose(PUMA, "theirs", PUMA.home)
    theirs = editing.set_pose(theirs, "qr", (0.0, 85.0, -90.0, 0.0, 0.0, 0.0))
    found = merge(PUMA, mine, theirs)
    assert [c.label for c in found.conflicts] == ["pose qr"]
    robot = found.resolve({"pose qr": "mine"})
    assert {"mine", "theirs", "qr"} <= set(robot.pose_names)
    assert robot.pose("qr")[1] == 80.0


def test_a_deleted_pose_stays_deleted_unless_the_other_side_changed_it():
    mine = editing.delete_pose(PUMA, "qs")
    assert "qs" not in merge(PUMA, mine, PUMA).resolve({}).pose_names
    theirs = editing.set_pose(PUMA, "qs", PUMA.home)
    found = merge(PUMA, mine, theirs)
    assert [c.label for c in found.conflicts] == ["pose qs"]
    assert found.conflicts[0].mine == "(none)"


def test_a_units_change_on_one_side_converts_the_other():
    mine = editing.set_units(PUMA, "m")
    theirs = editing.set_joint_field(PUMA, 1, "a", 500.0)
    robot = merge(PUMA, mine, theirs).resolve({})
    assert robot.units == "m" and robot.joints[1].a == pytest.approx(0.5)
    assert robot.joints[2].d == pytest.approx(0.15005)


def test_units_changed_on_both_sides_is_one_question_about_the_whole_robot():
    mine, theirs = editing.set_units(PUMA, "m"), editing.set_units(PUMA, "in")
    found = merge(PUMA, mine, theirs)
    assert [c.key for c in found.conflicts] == [WHOLE]
    assert found.resolve({WHOLE: "mine"}) == mine and found.resolve({}) == theirs


def test_a_table_changed_on_both_sides_in_shape_is_one_question():
    mine = editing.insert_joint(PUMA, 2)
    theirs = editing.delete_joint(PUMA, 5)
    found = merge(PUMA, mine, theirs)
    # the table, and the poses (their values follow the joints) on both sides
    keys = [c.key for c in found.conflicts]
    assert keys[0] == "joints" and all(key.startswith(("pose ", "program ")) for key in keys[1:])
    with pytest.raises(DhsimError, match="cannot be combined"):
        found.resolve({"joints": "mine"})  # 7 joints, and the file's 5-value poses
    assert found.resolve(dict.fromkeys(keys, "mine")) == mine


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(st.integers(0, 5), st.sampled_from(["a", "d", "max"])), max_size=4),
    st.lists(st.tuples(st.integers(0, 5), st.sampled_from(["alpha", "min", "offset"])), max_size=4),
)
def test_edits_of_different_fields_never_conflict_and_both_survive(mine_edits, their_edits):
    """Mine touch a, d, max; theirs alpha, min, offset: every edit lands."""
    mine = theirs = PUMA
    for index, name in mine_edits:
        mine = editing.set_joint_field(mine, index, name, getattr(mine.joints[index], name) + 1)
    for index, name in their_edits:
        value = getattr(theirs.joints[index], name) - 1
        theirs = editing.set_joint_field(theirs, index, name, value)
    found = merge(PUMA, mine, theirs)
    assert found.conflicts == ()
    robot = found.resolve({})
    for index, name in mine_edits:
        assert getattr(robot.joints[index], name) == getattr(mine.joints[index], name)
    for index, name in their_edits:
        assert getattr(robot.joints[index], name) == getattr(theirs.joints[index], name)

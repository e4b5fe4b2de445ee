"""Issue 27 in the editor: offsets without a trap (the home joint value shown
live beside theta and offset; a new offset shows what home becomes and
offers to keep the home joint value), the type chosen from a list, a joint
switched back with its own limits, and a preview wide enough to show links."""

from __future__ import annotations

from dataclasses import replace

import pytest
from pilot_helpers import non_ascii_outside_views, press, settled, showing, started, until
from textual.widgets import Label, OptionList

from dhsim_tui.core import load_robot
from dhsim_tui.core.model.editing import new_robot, set_joint_field, set_pose
from dhsim_tui.render.picture import ROLE_INDEX
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.dialogs import Choice
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.editor_joint_values import (
    Retype,
    offset_choices,
    offset_edits,
    offset_live,
    retyped_robot,
)
from dhsim_tui.tui.screens.editor_keys import EDITOR_HELP_NOTES
from dhsim_tui.tui.screens.editor_table import JOINT_COLUMNS, joint_rows
from dhsim_tui.tui.screens.value_entry import ValueEntry
from tui.conftest import editor

HOME = JOINT_COLUMNS.index("home")
OFFSET = JOINT_COLUMNS.index("offset")
THETA = JOINT_COLUMNS.index("theta")
TYPE = JOINT_COLUMNS.index("type")


@pytest.fixture(autouse=True)
def in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def puma():
    return load_robot("puma560")[0]


def cell(app: DhsimApp, row: int, column: int) -> str:
    return str(editor(app).query_one("#joints-table").get_cell_at((row, column)))


async def open_cell(pilot, row: int, column: int) -> None:
    table = editor(pilot.app).query_one("#joints-table")
    table.focus()
    table.move_cursor(row=row, column=column)
    await press(pilot, "enter")


def live_line(app: DhsimApp) -> str:
    return str(app.screen.query_one("#live", Label).render())


def options(app: DhsimApp) -> list[tuple[str, str, bool]]:
    """The choice in front: (value, text, disabled) per option."""
    option_list = app.screen.query_one(OptionList)
    return [
        (str(o.id), str(o.prompt), o.disabled)
        for o in (option_list.get_option_at_index(i) for i in range(option_list.option_count))
    ]


# -- the home column -------------------------------------------------------------------


def test_the_home_column_is_theta_less_offset_beside_offset_and_the_limits():
    robot = set_joint_field(puma(), 1, "offset", -90.0)  # theta 0: home 90
    rows = dict(joint_rows(robot))
    assert JOINT_COLUMNS[OFFSET + 1 : OFFSET + 4] == ("home", "min", "max")
    assert rows["joint:2"][HOME] == "90"
    assert rows["joint:1"][HOME] == "0"
    gantry = load_robot("gantry")[0]
    shifted = set_joint_field(gantry, 0, "offset", 25.0)
    assert dict(joint_rows(shifted))["joint:1"][HOME] == str(shifted.joints[0].d - 25.0)[:-2]
    # derived, so shown without the subtraction's float noise (0 - 0.2 - 0.1...)
    noisy = set_joint_field(set_joint_field(puma(), 2, "theta", 0.1), 2, "offset", 0.3)
    assert noisy.joints[2].home != -0.2  # -0.19999999999999998
    assert dict(joint_rows(noisy))["joint:3"][HOME] == "-0.2"


async def test_home_follows_theta_live_and_its_entry_shows_it_as_typed(status, editor_app):
    app = editor_app(set_joint_field(puma(), 1, "offset", -90.0))
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert cell(app, 1, HOME) == "90"
        await open_cell(pilot, 1, THETA)
        assert isinstance(app.screen, ValueEntry)
        assert live_line(app) == "home Th2 = 90 deg (theta - offset -90)"
        await press(pilot, "ctrl+u", "-", "9", "0")
        assert live_line(app) == "home Th2 = 0 deg (theta - offset -90)"
        await press(pilot, "enter")
        assert editor(app).robot.joints[1].theta == -90.0
        assert cell(app, 1, HOME) == "0"
        assert "joint 2 theta = -90 deg: home Th2 = 0 deg" in status(app)


async def test_enter_on_home_sets_theta_to_home_plus_offset(status, editor_app):
    app = editor_app(set_joint_field(puma(), 1, "offset", -90.0))
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await open_cell(pilot, 1, HOME)
        assert isinstance(app.screen, ValueEntry)
        assert app.screen.query_one("Input").value == "90"
        await press(pilot, "ctrl+u", "3", "0")
        assert live_line(app) == "theta becomes -60 deg"
        await press(pilot, "enter")
        joint = editor(app).robot.joints[1]
        assert (joint.theta, joint.offset, joint.home) == (-60.0, -90.0, 30.0)
        assert cell(app, 1, THETA) == "-60*"
        assert "joint 2 home Th2 = 30 deg: theta = -60 deg" in status(app)


# -- a new offset: what home becomes, and keeping it ---------------------------------------


async def test_the_offset_entry_shows_what_home_becomes_as_it_is_typed(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await open_cell(pilot, 1, OFFSET)
        assert isinstance(app.screen, ValueEntry)
        assert live_line(app) == "home Th2 stays 0 deg"
        await press(pilot, "ctrl+u", "-", "9", "0")
        shown = live_line(app)
        assert "home Th2 becomes 90 deg (theta stays 0)" in shown
        assert "keep home 0: theta becomes -90" in shown
        await press(pilot, "backspace")  # -9
        assert "home Th2 becomes 9 deg" in live_line(app)
        await press(pilot, "ctrl+u", "x")
        assert live_line(app) == ""  # not a number yet: enter says why
        await press(pilot, "escape")
        assert editor(app).robot == puma()


async def test_the_toolbox_row_keeping_the_home_joint_value_puts_theta_at_the_offset(
    status, editor_app
):
    """The trap: the Toolbox's row (theta 0, offset -90). Keeping the home
    joint value gives theta = -90, home q = 0, as the Toolbox reads it."""
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        before = editor(app).robot
        await open_cell(pilot, 1, OFFSET)
        await press(pilot, "ctrl+u", "-", "9", "0", "enter")
        assert await showing(pilot, Choice)
        values = [value for value, _, _ in options(app)]
        assert values == ["pose", "home"]
        texts = [text for _, text, _ in options(app)]
        assert texts[0] == "keep theta 0: the home pose stays, home Th2 becomes 90 deg"
        assert texts[1] == "keep home Th2 0 deg: theta becomes -90, the home pose moves"
        await press(pilot, "down", "enter")
        joint = editor(app).robot.joints[1]
        assert (joint.theta, joint.offset, joint.home) == (-90.0, -90.0, 0.0)
        assert editor(app).robot.home == before.home
        assert editor(app).robot.poses == before.poses  # joint values keep their numbers
        assert cell(app, 1, THETA) == "-90*" and cell(app, 1, HOME) == "0"
        assert "joint 2 offset = -90 deg (home Th2 kept): theta = -90" in status(app)
        await press(pilot, "ctrl+z")
        assert editor(app).robot == before  # one edit


async def test_an_offset_that_would_put_home_outside_the_limits_offers_only_keeping_it(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await open_cell(pilot, 0, OFFSET)  # joint 1: limits -160..160
        await press(pilot, "ctrl+u", "2", "0", "0", "enter")
        assert await showing(pilot, Choice)
        (_, pose_text, pose_off), (_, _, home_off) = options(app)
        assert pose_off and not home_off
        assert pose_text.endswith(
            "home Th1 becomes -200 deg (not possible: outside its limits -160..160 deg)"
        )
        assert app.screen.query_one(OptionList).highlighted == 1
        await press(pilot, "enter")
        joint = editor(app).robot.joints[0]
        assert (joint.theta, joint.offset, joint.home) == (200.0, 200.0, 0.0)


async def test_escape_on_the_choice_or_the_same_offset_changes_nothing(status, editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await open_cell(pilot, 1, OFFSET)
        await press(pilot, "ctrl+u", "5", "enter")
        assert await showing(pilot, Choice)
        await press(pilot, "escape")
        assert editor(app).robot == puma() and not editor(app).history.can_undo
        assert "joint 2 offset not changed" in status(app)
        await open_cell(pilot, 1, OFFSET)
        await press(pilot, "enter")  # 0 again
        assert isinstance(app.screen, EditorScreen)
        assert "joint 2 offset stays 0 deg" in status(app)


def test_offset_choices_for_a_prismatic_joint_speak_of_d_in_its_unit():
    gantry = load_robot("gantry")[0]
    joint = gantry.joints[0]
    edit = offset_edits(gantry, 0, 10.0)
    choices, disabled = offset_choices(gantry, 0, edit)
    assert disabled == ()
    assert choices[0][1].startswith(f"keep d {joint.d:g}: the home pose stays")
    assert choices[1][1].endswith(f"d becomes {joint.home + 10:g}, the home pose moves")
    assert "mm" in offset_live(gantry, 0, 10.0) or "d stays" in offset_live(gantry, 0, 10.0)


# -- the type ------------------------------------------------------------------------


async def test_enter_on_the_type_cell_offers_revolute_or_prismatic(status, editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        await open_cell(pilot, 2, TYPE)
        assert await showing(pilot, Choice)
        assert [value for value, _, _ in options(app)] == ["revolute", "prismatic"]
        assert app.screen.query_one(OptionList).highlighted == 0  # what it is now
        await press(pilot, "enter")  # the same type: nothing changes
        assert editor(app).robot == puma()
        assert "joint 3 stays revolute" in status(app)
        await open_cell(pilot, 2, TYPE)
        await press(pilot, "escape")
        assert editor(app).robot == puma()
        await open_cell(pilot, 2, TYPE)
        await press(pilot, "down", "enter")
        assert editor(app).robot.joints[2].type == "prismatic"
        assert cell(app, 2, TYPE) == "P"


async def test_switching_a_joint_and_back_restores_its_limits_offset_and_speeds(status, editor_app):
    robot = puma()
    joint = replace(robot.joints[2], offset=10.0, theta=10.0, vmax=50.0, amax=100.0)
    robot = replace(robot, joints=(*robot.joints[:2], joint, *robot.joints[3:]))
    app = editor_app(robot)
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        editor(app).query_one("#joints-table").move_cursor(row=2)
        await press(pilot, "t")
        assert editor(app).robot.joints[2].type == "prismatic"
        assert (editor(app).robot.joints[2].min, editor(app).robot.joints[2].max) == (-400, 400)
        await press(pilot, "t")
        assert editor(app).robot == robot
        assert "joint 3 is now revolute again, its own limits -225..45 deg back" in status(app)


async def test_switched_back_after_other_edits_the_joint_gets_its_limits_back(editor_app):
    app = editor_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        table = editor(app).query_one("#joints-table")
        table.move_cursor(row=1)
        await press(pilot, "t")
        table.focus()
        table.move_cursor(row=0, column=JOINT_COLUMNS.index("a"))
        await press(pilot, "enter", "ctrl+u", "5", "enter")  # another joint edited
        table.move_cursor(row=1, column=TYPE)
        await press(pilot, "enter")
        await showing(pilot, Choice)
        await press(pilot, "up", "enter")
        joint = editor(app).robot.joints[1]
        assert joint.type == "revolute" and (joint.min, joint.max) == (-45.0, 225.0)
        assert editor(app).robot.joints[0].a == 5.0


def test_switching_back_restores_limits_when_poses_changed_in_between():
    robot = puma()
    kept: list[Retype] = []
    prismatic, restored = retyped_robot(robot, 4, kept)
    assert not restored and prismatic.joints[4].min == -400
    posed = set_pose(prismatic, "qz", (1, 2, 3, 4, 0, 6))
    back, restored = retyped_robot(posed, 4, kept)
    assert restored and (back.joints[4].min, back.joints[4].max) == (-100.0, 100.0)
    assert back.pose("qz")[:4] == (1, 2, 3, 4)
    # a joint whose a or alpha changed is another joint: the defaults
    fresh = new_robot("arm", 2)
    moved, _ = retyped_robot(fresh, 0, kept := [])
    other = set_joint_field(moved, 0, "a", 7.0)
    _, restored = retyped_robot(other, 0, kept)
    assert not restored


# -- help and the preview ------------------------------------------------------------


def test_the_editor_help_gives_the_toolbox_mapping_and_what_offsets_mean():
    notes = " ".join(EDITOR_HELP_NOTES.split())
    assert "home = theta - offset" in notes
    assert "Robotics Toolbox" in notes and "theta = offset" in notes


def test_the_simulator_help_gives_the_toolbox_mapping_too():
    from dhsim_tui.tui.screens.control_keys import HELP_NOTES

    notes = " ".join(HELP_NOTES.split())
    assert "theta - offset" in notes
    assert "Robotics Toolbox" in notes and "theta = offset" in notes


@pytest.mark.parametrize("size", [(80, 24), (120, 36)])
async def test_the_preview_has_room_to_draw_the_links(size, editor_app):
    """Under the joints, beside the fields, framed on the arm: its links are
    drawn, not only its joints' glyphs (at 80x24 it was 18 columns wide)."""
    app = editor_app()
    async with app.run_test(size=size) as pilot:
        await started(pilot)
        panel = editor(app).query_one("#preview")
        assert panel.fit
        assert panel.size.width >= 36  # was 18 at 80x24
        joints = editor(app).query_one("#joints-table")
        assert panel.region.y >= joints.region.bottom  # under the joints table
        front = panel.views[1]
        await until(pilot, lambda: front.picture is not None, "the front view drawn")
        roles = front.picture.roles
        links = int((roles == ROLE_INDEX["link"]).sum())
        marks = ("revolute", "prismatic", "tool")
        joint_cells = int(sum((roles == ROLE_INDEX[r]).sum() for r in marks))
        assert links >= 8 and links > joint_cells


async def test_the_offset_questions_are_ascii_in_ascii_mode(screen_text):
    robot, path = load_robot("puma560")
    app = DhsimApp(robot, path, animate=False, ascii=True, start="edit")
    async with app.run_test(size=(80, 24)) as pilot:
        await started(pilot)
        assert non_ascii_outside_views(app) == []
        await open_cell(pilot, 1, OFFSET)
        await press(pilot, "ctrl+u", "-", "9", "0")
        assert "home Th2 becomes 90 deg" in live_line(app)
        assert non_ascii_outside_views(app) == []
        await press(pilot, "enter")
        assert await showing(pilot, Choice)
        await until(pilot, lambda: settled(app), "the choice drawn")
        assert non_ascii_outside_views(app) == []
        lines = screen_text(app).split("\n")
        assert any("joint 2 offset 0 -> -90 deg" in line for line in lines)
        assert any("keep home Th2 0 deg" in line for line in lines)  # both shown whole
        await press(pilot, "escape")
        await open_cell(pilot, 1, TYPE)
        assert await showing(pilot, Choice)
        await until(pilot, lambda: settled(app), "the choice drawn")
        assert non_ascii_outside_views(app) == []

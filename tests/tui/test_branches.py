"""b: the arm's other inverse-kinematics solutions (branches) for the tool
pose it is at. The tool stays; the pose panel says which branch, of how many."""

from __future__ import annotations

import threading

import numpy as np
import pytest
from pilot_helpers import HANG, press, settled, until
from textual import events

from dhsim_tui.core import load_robot
from dhsim_tui.core.analysis.workspace import reach
from dhsim_tui.core.ik import solutions as ik_all
from dhsim_tui.core.ik.numerical import rotation_error
from dhsim_tui.core.model.editing import set_pose
from dhsim_tui.core.motion.jog import branch_caption, branch_index
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.palette import commands_for
from dhsim_tui.tui.widgets.pose_panel import PosePanel
from dhsim_tui.tui.widgets.views_panel import ViewsPanel

GOOD = (-20.0, 50.0, -170.0, 10.0, 40.0, 0.0)  # a Puma pose with room to move


def app_for(name: str = "puma560", q=GOOD, animate: bool = False, ascii: bool = False):
    robot, path = load_robot(name)
    if q is not None:
        robot = set_pose(robot, "start", q)
    return DhsimApp(robot, path, animate=animate, ascii=ascii)


async def go_start(pilot) -> ControlScreen:
    """p cycles the robot's poses; 'start' is the last one."""
    app = pilot.app
    if "start" in app.robot.pose_names:
        await press(pilot, *["p"] * len(app.robot.pose_names))
    await pilot.pause()
    screen = app.screen
    assert isinstance(screen, ControlScreen)
    return screen


async def press_b(pilot, screen: ControlScreen) -> None:
    """b, and wait until the solutions are found and the arm is where it goes."""
    await press(pilot, "b")
    await until(pilot, lambda: not screen.finding_branches and not screen.moving, "b's move")
    await until(pilot, lambda: settled(pilot.app), "b's move drawn")


def same_tool(robot, q1, q2) -> bool:
    a, b = robot.kinematics.pose(q1), robot.kinematics.pose(q2)
    position = np.linalg.norm(a[:3, 3] - b[:3, 3]) <= 1e-6 * reach(robot)
    return position and np.linalg.norm(rotation_error(a[:3, :3], b[:3, :3])) <= 1e-6


def pose_panel(app) -> str:
    return str(app.screen.query_one(PosePanel).render())


# -- the core's helpers --------------------------------------------------------------
def test_branch_index_finds_the_configuration_the_arm_is_in():
    robot, _ = load_robot("puma560")
    found = ik_all.all_solutions(robot, robot.kinematics.pose(GOOD), GOOD)
    assert branch_index(robot, found.solutions, GOOD) == 0  # nearest the start first
    assert branch_index(robot, found.solutions, found.solutions[3].q) == 3
    assert branch_index(robot, found.solutions, (0.0, 1.0, 2.0, 3.0, 4.0, 5.0)) == -1


def test_captions_say_n_of_n_the_only_one_or_one_of_a_family():
    one = ik_all.Solution((0.0,), "elbow up", 0.0, 0.0)
    two = ik_all.Solution((1.0,), "elbow down", 0.0, 0.0)
    assert branch_caption(ik_all.Solutions((one, two), "analytic", False), 1) == (
        "branch 2/2: elbow down"
    )
    assert branch_caption(ik_all.Solutions((one,), "analytic", False), 0) == (
        "the only solution for this pose: elbow up"
    )
    family = ik_all.Solutions((one, two), "numerical", True)
    assert branch_caption(family, 0) == "branch 1/2 (one of a family): elbow up"
    turned = ik_all.Solution((1.0 - 360.0,), "elbow down", 0.0, 0.0)
    three = ik_all.Solutions((one, two, turned), "analytic", False)
    assert branch_caption(three, 2, ("Th1",)) == "branch 3/3: elbow down, Th1 -360°"
    assert branch_caption(three, 1, ("Th1",)) == "branch 2/3: elbow down"
    bare = ik_all.Solution((2.0,), "", 0.0, 0.0)
    assert branch_caption(ik_all.Solutions((one, bare), "numerical", False), 1) == "branch 2/2"


# -- the screen ----------------------------------------------------------------------
async def test_b_cycles_the_pumas_configurations_with_the_tool_fixed(status):
    app = app_for()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        robot = app.robot
        found = ik_all.all_solutions(robot, robot.kinematics.pose(GOOD), GOOD)
        count = len(found.solutions)
        assert count >= 4  # up to 8; one or two may be outside the Puma's limits
        readout = pose_panel(app).splitlines()[:6]  # X Y Z O A T
        seen = {GOOD}
        configs = set()
        captions = set()
        for pressed in range(1, count + 1):
            await press_b(pilot, screen)
            q = screen.q
            assert same_tool(robot, q, GOOD), pressed
            assert pose_panel(app).splitlines()[:6] == readout  # to display precision
            index = pressed % count
            solution = found.solutions[index]
            caption = f"branch {index + 1}/{count}: {solution.config}"
            assert caption in " ".join(pose_panel(app).split())  # wrapped in the panel
            assert caption in status(app)
            seen.add(q)
            configs.add(solution.config)
            captions.add(status(app))
        assert screen.q == pytest.approx(GOOD, abs=1e-6)  # round the cycle, back at the start
        assert len(seen) == count and len(captions) == count  # no two read the same
        assert len(configs) >= 5  # any others differ by whole turns of a joint, and say so
        assert any("shoulder left" in c for c in configs)
        assert any("elbow down" in c for c in configs)
        assert any("wrist flip" in c for c in configs)


async def test_any_move_of_the_arm_ends_the_cycle():
    app = app_for()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await press_b(pilot, screen)
        assert "branch 2/" in pose_panel(app)
        await press(pilot, "right")  # a joint step
        await pilot.pause()
        assert screen._branches is None and "branch" not in pose_panel(app)
        moved = screen.q
        await press_b(pilot, screen)  # starts again from the new pose
        assert "branch 2/" in pose_panel(app) and same_tool(app.robot, screen.q, moved)
        await press(pilot, "h")
        await pilot.pause()
        assert "branch" not in pose_panel(app)


def type_without_waiting(app, key: str) -> None:
    """A key press that does not wait for the app to be idle (``pilot.press``
    does: on a busy machine the 30 Hz move keeps it busy until the move ends)."""
    app.post_message(events.Key(key, key))


async def test_b_moves_smoothly_when_motion_is_on_and_escape_stops_it(monkeypatch):
    monkeypatch.setattr("dhsim_tui.core.motion.smooth.DURATION", 2.0)
    on_the_way = []  # (q, pose panel) of each drawing during a move, however many there are
    refresh = ControlScreen._refresh_pose

    def recording_refresh(self):
        refresh(self)
        if self.moving:
            on_the_way.append((self.q, pose_panel(self.app)))

    monkeypatch.setattr(ControlScreen, "_refresh_pose", recording_refresh)
    app = app_for(animate=True)
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await until(pilot, lambda: not screen.moving and screen.q == GOOD, "the start")
        on_the_way.clear()  # the move to the start: not b's
        type_without_waiting(app, "b")
        await until(pilot, lambda: screen.moving, "the move to start")
        goal = screen.motion_goal
        assert goal is not None and same_tool(app.robot, goal, GOOD)
        await until(pilot, lambda: not screen.moving, "the move to end")
        await until(pilot, lambda: settled(app), "the end of the move drawn")
        assert screen.q == goal and "branch 2/" in pose_panel(app)
        # it went through poses between, and said which branch on the way too
        between = [text for q, text in on_the_way if q not in (GOOD, goal)]
        assert between and all("branch 2/" in text for text in between)
        # the next one, and stop it on the way: a move that lasts till it is stopped
        monkeypatch.setattr("dhsim_tui.core.motion.smooth.DURATION", 10 * HANG)
        type_without_waiting(app, "b")
        await until(pilot, lambda: screen.moving, "the next move")
        await press(pilot, "escape")
        assert not screen.moving and screen._branches is None
        assert "branch" not in pose_panel(app)


async def test_an_arm_with_one_solution_says_so(status):
    app = app_for("stanford", q=None)
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        home = screen.q
        await press_b(pilot, screen)
        assert screen.q == home
        assert "the only solution for this pose" in " ".join(pose_panel(app).split())
        assert "the only solution" in status(app)


async def test_a_redundant_arm_says_its_solution_is_one_of_a_family():
    app = app_for("panda", q=None)
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        home = screen.q
        await press_b(pilot, screen)
        assert screen.q != home and same_tool(app.robot, screen.q, home)
        assert "(one of a family)" in " ".join(pose_panel(app).split())


async def test_a_planar_arm_flips_its_elbow_with_the_tool_in_place():
    app = app_for("planar2", q=(30.0, 60.0))
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await press_b(pilot, screen)
        assert screen.q == pytest.approx((90.0, -60.0), abs=1e-4)
        position = app.robot.kinematics.position
        assert np.allclose(position(screen.q), position((30.0, 60.0)), atol=1e-6)


def held_search(monkeypatch) -> threading.Event:
    """Make the search for solutions wait until the returned event is set (or a hang)."""
    release = threading.Event()
    real = ik_all.all_solutions

    def slow(*args, **kwargs):
        release.wait(HANG)
        return real(*args, **kwargs)

    monkeypatch.setattr(ik_all, "all_solutions", slow)
    return release


async def test_keys_go_on_while_searching_and_every_b_counts(monkeypatch, status):
    release = held_search(monkeypatch)
    app = app_for()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await press(pilot, "b")
        await until(pilot, lambda: screen.finding_branches, "the search")
        assert "finding" in status(app)
        await press(pilot, "v", "3")  # other keys go on meanwhile
        assert screen.readout == "rpy" and screen.query_one(ViewsPanel).selected == 2
        assert screen.q == GOOD
        await press(pilot, "b", "b")  # pressed three times in all: three branches on
        release.set()
        await until(pilot, lambda: not screen.finding_branches, "the search to end")
        await until(pilot, lambda: settled(app), "the branch drawn")
        assert same_tool(app.robot, screen.q, GOOD) and screen.q != GOOD
        assert "branch 4/" in status(app)


async def test_an_arm_moved_during_the_search_stays_where_it_was_put(monkeypatch):
    release = held_search(monkeypatch)
    app = app_for()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await press(pilot, "b")
        await until(pilot, lambda: screen.finding_branches, "the search")
        await press(pilot, "right")  # the joint moves
        stepped = screen.q
        release.set()
        await until(pilot, lambda: not screen.finding_branches, "the search to end")
        await until(pilot, lambda: settled(app), "the answer handled")
        assert screen.q == stepped and screen._branches is None


async def test_the_palette_offers_the_next_branch():
    app = app_for()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        command = next(c for c in commands_for(app, screen) if c.title == "Next IK branch")
        command.run()
        await until(pilot, lambda: not screen.finding_branches, "the search")
        await until(pilot, lambda: settled(app), "the branch drawn")
        assert screen.q != GOOD and same_tool(app.robot, screen.q, GOOD)


async def test_the_branch_caption_is_ascii_in_ascii_mode():
    app = app_for(ascii=True)
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await press_b(pilot, screen)
        text = pose_panel(app)
        assert "branch 2/" in text and text.isascii()

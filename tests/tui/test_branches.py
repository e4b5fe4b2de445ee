"""b: the arm's other inverse-kinematics solutions (branches) for the tool
pose it is at. The tool stays; the pose panel says which branch, of how many."""

from __future__ import annotations

import threading

import numpy as np
import pytest
from pilot_helpers import until
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
        await pilot.press(*["p"] * len(app.robot.pose_names))
    await pilot.pause()
    screen = app.screen
    assert isinstance(screen, ControlScreen)
    return screen


async def press_b(pilot, screen: ControlScreen) -> None:
    """b, and wait until the solutions are found and the arm is where it goes."""
    await pilot.press("b")
    await until(pilot, lambda: not screen.finding_branches and not screen.moving, "b's move")
    await pilot.pause()


def same_tool(robot, q1, q2) -> bool:
    a, b = robot.kinematics.pose(q1), robot.kinematics.pose(q2)
    position = np.linalg.norm(a[:3, 3] - b[:3, 3]) <= 1e-6 * reach(robot)
    return position and np.linalg.norm(rotation_error(a[:3, :3], b[:3, :3])) <= 1e-6


def pose_panel(app) -> str:
    return str(app.screen.query_one(PosePanel).render())


def status(app) -> str:
    return str(app.screen.query_one("#status").render())


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
async def test_b_cycles_the_pumas_configurations_with_the_tool_fixed():
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
        for press in range(1, count + 1):
            await press_b(pilot, screen)
            q = screen.q
            assert same_tool(robot, q, GOOD), press
            assert pose_panel(app).splitlines()[:6] == readout  # to display precision
            index = press % count
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
        await pilot.press("right")  # a joint step
        await pilot.pause()
        assert screen._branches is None and "branch" not in pose_panel(app)
        moved = screen.q
        await press_b(pilot, screen)  # starts again from the new pose
        assert "branch 2/" in pose_panel(app) and same_tool(app.robot, screen.q, moved)
        await pilot.press("h")
        await pilot.pause()
        assert "branch" not in pose_panel(app)


async def sampled(pilot, condition, what: str) -> None:
    """Wait (up to 10 s) for ``condition``, looking every 20 ms: a pause that
    waits for the app to be idle would wait out a whole smooth move."""
    for _ in range(500):
        await pilot.pause(0.02)
        if condition():
            return
    raise AssertionError(f"timed out waiting for {what}")


def type_without_waiting(app, key: str) -> None:
    """A key press that does not wait for the app to be idle (``pilot.press``
    does: on a busy machine the 30 Hz move keeps it busy until the move ends)."""
    app.post_message(events.Key(key, key))


async def test_b_moves_smoothly_when_motion_is_on_and_escape_stops_it(monkeypatch):
    monkeypatch.setattr(
        "dhsim_tui.core.motion.smooth.DURATION", 2.0
    )  # slow enough for a busy machine
    app = app_for(animate=True)
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await sampled(pilot, lambda: not screen.moving and screen.q == GOOD, "the start")
        type_without_waiting(app, "b")
        await sampled(pilot, lambda: screen.moving, "the move to start")
        goal = screen.motion_goal
        assert goal is not None and same_tool(app.robot, goal, GOOD)
        await sampled(pilot, lambda: screen.q not in (GOOD, goal), "a step on the way")
        assert "branch 2/" in pose_panel(app)  # said on the way too
        await sampled(pilot, lambda: not screen.moving, "the move to end")
        await pilot.pause()
        assert screen.q == goal and "branch 2/" in pose_panel(app)
        type_without_waiting(app, "b")  # the next one, and stop it on the way
        await sampled(pilot, lambda: screen.moving, "the next move")
        await pilot.press("escape")
        await pilot.pause()
        assert not screen.moving and screen._branches is None
        assert "branch" not in pose_panel(app)


async def test_an_arm_with_one_solution_says_so():
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
    """Make the search for solutions wait (up to 5 s) until the returned event is set."""
    release = threading.Event()
    real = ik_all.all_solutions

    def slow(*args, **kwargs):
        release.wait(5)
        return real(*args, **kwargs)

    monkeypatch.setattr(ik_all, "all_solutions", slow)
    return release


async def test_keys_go_on_while_searching_and_every_b_counts(monkeypatch):
    release = held_search(monkeypatch)
    app = app_for()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await pilot.press("b")
        await until(pilot, lambda: screen.finding_branches, "the search")
        assert "finding" in status(app)
        await pilot.press("v", "3")  # other keys go on meanwhile
        await pilot.pause()
        assert screen.readout == "rpy" and screen.query_one(ViewsPanel).selected == 2
        assert screen.q == GOOD
        await pilot.press("b", "b")  # pressed three times in all: three branches on
        release.set()
        await until(pilot, lambda: not screen.finding_branches, "the search to end")
        await pilot.pause()
        assert same_tool(app.robot, screen.q, GOOD) and screen.q != GOOD
        assert "branch 4/" in status(app)


async def test_an_arm_moved_during_the_search_stays_where_it_was_put(monkeypatch):
    release = held_search(monkeypatch)
    app = app_for()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await pilot.press("b")
        await until(pilot, lambda: screen.finding_branches, "the search")
        await pilot.press("right")  # the joint moves
        await pilot.pause()
        stepped = screen.q
        release.set()
        await until(pilot, lambda: not screen.finding_branches, "the search to end")
        await pilot.pause()
        assert screen.q == stepped and screen._branches is None


async def test_the_palette_offers_the_next_branch():
    app = app_for()
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        command = next(c for c in commands_for(app, screen) if c.title == "Next IK branch")
        command.run()
        await until(pilot, lambda: not screen.finding_branches, "the search")
        await pilot.pause()
        assert screen.q != GOOD and same_tool(app.robot, screen.q, GOOD)


async def test_the_branch_caption_is_ascii_in_ascii_mode():
    app = app_for(ascii=True)
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await go_start(pilot)
        await press_b(pilot, screen)
        text = pose_panel(app)
        assert "branch 2/" in text and text.isascii()

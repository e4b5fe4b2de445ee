"""Issue 8 on the control screen: smooth moves stop only for keys that move the
arm, bursts of keys all count without a backlog, Cartesian mode and the status
line show their whole text at 80x24, and file content is never a terminal
command or markup."""

from __future__ import annotations

import re

import pytest
from pilot_helpers import dialog_workers, frames_pass, press, settled, until
from rich.cells import cell_len
from textual import events

from dhsim_tui.core import Joint, Robot, load, load_robot, save
from dhsim_tui.core.model.editing import set_pose
from dhsim_tui.core.model.kinematics import read_out
from dhsim_tui.tui.app import DhsimApp
from dhsim_tui.tui.screens.dialogs import short_path
from dhsim_tui.tui.screens.editor import EditorScreen
from dhsim_tui.tui.screens.help import HelpScreen
from dhsim_tui.tui.screens.value_entry import ValueEntry
from dhsim_tui.tui.widgets.pose_panel import PosePanel
from dhsim_tui.tui.widgets.views_panel import ViewsPanel
from tui.conftest import control, screen_strips, status_of, text_of

SIZE = (80, 24)
BRACKETS = "arm [/] [b]x"


def lines(app: DhsimApp) -> list[str]:
    """The composed screen, a string per terminal row, as a person sees it."""
    return text_of(app).split("\n")


def region_text(app: DhsimApp, widget) -> list[str]:
    """The rows of the screen a widget covers, cropped to it."""
    region = widget.region
    strips = screen_strips(app)
    return [
        strips[y].crop(region.x, region.right).text
        for y in range(region.y, min(region.bottom, len(strips)))
    ]


def squeeze(text: str) -> str:
    return "".join(text.split())


def assert_status_whole(app: DhsimApp) -> str:
    """The status message, every character of it, is on the screen (wrapped
    lines joined), inside the side panel, above the footer."""
    message = status_of(app)
    status = app.screen.query_one("#status")
    shown = region_text(app, status)
    assert message, "expected a message"
    assert squeeze("".join(shown)) == squeeze(message), (message, shown)
    assert status.region.bottom <= SIZE[1] - 1  # above the footer
    return message


async def go_start(pilot) -> None:
    names = pilot.app.robot.pose_names
    await press(pilot, *["p"] * len(names))
    assert control(pilot.app).q == pilot.app.robot.pose("start")


@pytest.fixture
def slow_motion(monkeypatch):
    """Moves take 20 s, so a loaded test machine can't finish one before the
    keys under test arrive."""
    monkeypatch.setattr("dhsim_tui.core.motion.smooth.DURATION", 20.0)


async def th1_to_90_then(pilot, *keys: str) -> None:
    """Th1 to 90 deg with 45-degree steps, then start a smooth move home."""
    await press(pilot, *["right_square_bracket"] * 3, "right", "right")
    assert control(pilot.app).q[0] == 90.0
    await press(pilot, "h", *keys)


# -- step 11: only moving keys (and escape) interrupt a smooth move ------------------


async def test_view_readout_and_help_keys_leave_a_smooth_move_running(
    slow_motion, control_app, status
):
    app = control_app(animate=True)
    async with app.run_test(size=SIZE) as pilot:
        await th1_to_90_then(pilot, "1", "2", "tab", "v", "3", "up", "down", "left_square_bracket")
        screen = control(app)
        assert screen.moving
        assert (
            screen.query_one(ViewsPanel).selected == 2 and screen.readout == "rpy"
        )  # the keys did their work
        await press(pilot, "question_mark")
        assert isinstance(app.screen, HelpScreen)
        await press(pilot, "escape")  # closes help, does not reach the control screen
        assert screen.moving
        before = screen.q
        await until(pilot, lambda: screen.q[0] < before[0], "the move home to go on")
        assert screen.moving  # still on its way home
        await press(pilot, "escape")
        assert not screen.moving
        assert screen.q[0] > 0.0 and status(app) == "stopped"


@pytest.mark.parametrize(
    "keys",
    [("escape",), ("right",), ("shift+left",), ("enter",), ("c", "right")],
    ids=["escape", "step", "big-step", "enter-value", "cartesian-step"],
)
async def test_keys_that_move_the_arm_stop_a_smooth_move(keys, slow_motion, control_app):
    app = control_app(animate=True)
    async with app.run_test(size=SIZE) as pilot:
        await th1_to_90_then(pilot)
        screen = control(app)
        await until(pilot, lambda: screen.q[0] < 90.0, "the move home under way")
        assert screen.moving
        await press(pilot, *keys)
        assert not screen.moving
        stopped = screen.q
        assert stopped != app.robot.home
        if isinstance(app.screen, ValueEntry):
            await press(pilot, "escape")
        await frames_pass(pilot, 12)  # as many ticks as the move had in 0.4 s
        assert screen.q == stopped  # it stays where it was stopped
        assert not screen.moving


async def test_footer_shows_whether_smooth_motion_is_on(control_app):
    app = control_app(animate=True)
    async with app.run_test(size=SIZE) as pilot:
        await until(pilot, lambda: "m Motion" in lines(app)[-1], "the footer")
        footer = lines(app)[-1]
        assert "m Motion on" in footer and "Motion off" not in footer
        await press(pilot, "m")
        await until(pilot, lambda: "m Motion off" in lines(app)[-1], "the footer to say off")
        footer = lines(app)[-1]
        assert "m Motion off" in footer and "Motion on" not in footer
        await press(pilot, "h")  # off: a move lands at once
        assert not control(app).moving
        await press(pilot, "c")  # and it stays shown in Cartesian mode
        await until(pilot, lambda: "Move tool" in lines(app)[-1], "the Cartesian footer")
        assert "m Motion off" in lines(app)[-1]
        assert app.animate is False  # a new control screen (after the editor) keeps it


# -- step 12: a burst of keys all counts, and is drawn once -----------------------


async def burst(pilot, key: str, count: int) -> None:
    """``count`` presses posted at once, as a terminal delivers held-down auto-repeat
    over a slow link (Pilot's press waits for each key; this doesn't); then wait
    until every one of them has been handled and the redraw behind them has run."""
    app = pilot.app
    workers = dialog_workers(app)
    for _ in range(count):
        app.post_message(events.Key(key, None))
    await until(pilot, lambda: settled(app, workers), f"{count} presses of {key} handled and drawn")


def shown_pose(app: DhsimApp) -> dict[str, float]:
    text = str(app.screen.query_one(PosePanel).render())
    found = dict(re.findall(r"(\w+)\s+(-?\d+\.\d+)", text))
    return {name: float(found[name]) for name in "XYZOAT"}


def expected_pose(app: DhsimApp) -> dict[str, float]:
    pose = read_out(app.robot.kinematics.pose(control(app).q))
    return {
        **{name: round(v, 2) + 0.0 for name, v in zip("XYZ", pose.xyz, strict=True)},
        **{name: round(v, 2) + 0.0 for name, v in zip("OAT", pose.oat, strict=True)},
    }


async def test_500_quick_presses_all_count_and_the_panel_shows_the_result():
    slide = Robot("slide", (Joint("prismatic", 0.0, 0.0, 100.0, 0.0, -1000.0, 1000.0),))
    app = DhsimApp(slide, None, animate=False)
    async with app.run_test(size=SIZE) as pilot:
        screen = control(app)
        before = screen.redraws
        await burst(pilot, "right", 500)
        assert screen.q == (500.0,)  # 1 mm steps: every one of them
        # drawn now and then while keys wait, not once per key (how often
        # depends on the machine's speed: one per 0.1 s of the burst at most)
        assert screen.redraws - before < 500
        assert shown_pose(app) == expected_pose(app)
        assert "500.00 mm" in str(app.screen.query("JointRow")[0].render())


async def test_a_burst_past_the_limit_stops_there_and_says_so(control_app, status):
    app = control_app()
    async with app.run_test(size=SIZE) as pilot:
        await burst(pilot, "right", 500)  # 1 deg steps, Th1 -160..160
        assert control(app).q[0] == 160.0
        assert "Th1 is at its max limit, 160 deg" in status(app)
        assert shown_pose(app) == expected_pose(app)


async def test_a_burst_of_cartesian_steps_all_count(control_app):
    app = control_app(q=(-20.0, 50.0, -170.0, 10.0, 40.0, 0.0))
    async with app.run_test(size=SIZE) as pilot:
        await go_start(pilot)
        start = app.robot.kinematics.position(control(app).q)
        await press(pilot, "c")
        await burst(pilot, "right", 40)  # 1 mm steps along X
        now = app.robot.kinematics.position(control(app).q)
        assert now[0] - start[0] == pytest.approx(40.0, abs=1e-3)
        shown = str(app.screen.query_one("#cartesian").render())
        assert f"{now[0]:.2f}" in shown


# -- step 13: Cartesian mode and the status line at 80x24 --------------------------


async def test_cartesian_mode_at_80x24_shows_values_one_marker_and_arrow_labels(control_app):
    app = control_app()
    async with app.run_test(size=SIZE) as pilot:
        await press(pilot, "p", "p", "c", "down")
        await until(pilot, lambda: "↑↓ Axis" in lines(app)[-1], "the Cartesian footer")
        text = "\n".join(lines(app))
        assert text.count("▶") == 1  # only the Cartesian row's
        pose = read_out(app.robot.kinematics.pose(control(app).q))
        rows = region_text(app, app.screen.query_one("#cartesian"))[1:-1]
        assert len(rows) == 6
        for row, value in zip(rows, (*pose.xyz, *pose.rpy), strict=True):
            assert f"{round(value, 2) + 0.0:.2f}" in row  # every row shows its value
        assert "▶ Y" in rows[1]
        footer = lines(app)[-1]
        assert "↑↓ Axis" in footer and "←→ Move tool" in footer
        assert "Joint" not in footer.split("←→")[0]
        await press(pilot, "c")
        await until(pilot, lambda: "↑↓ Joint" in lines(app)[-1], "the joints' footer")
        footer = lines(app)[-1]
        assert "↑↓ Joint" in footer and "←→ Step" in footer
        assert "\n".join(lines(app)).count("▶") == 1  # the joint's, back again


async def test_pitch_label_keeps_clear_of_the_border(control_app):
    app = control_app()
    async with app.run_test(size=SIZE) as pilot:
        await press(pilot, "v")
        await until(pilot, lambda: any("pitch" in line for line in lines(app)), "the rpy read-out")
        row = next(line for line in lines(app) if "pitch" in line)
        assert row[row.index("pitch") - 1] == " "


@pytest.mark.parametrize("width", [80, 120, 160])
async def test_footer_fits_in_both_modes(width, control_app):
    app = control_app(animate=True)
    async with app.run_test(size=(width, 24)) as pilot:
        steps = (
            ((), ("Motion on", "Step")),
            (("m",), ("Motion off", "Step")),
            (("c",), ("Motion off", "Move tool")),
            (("m",), ("Motion on", "Move tool")),
        )
        for keys, parts in steps:
            await press(pilot, *keys)
            # the footer is recomposed after a key changes its bindings: for a
            # moment it is empty, then it shows the new ones
            await until(
                pilot,
                lambda parts=parts: all(part in lines(app)[-1] for part in parts),
                f"the footer with {parts}",
            )
            footer = lines(app)[-1].rstrip()
            assert footer.endswith("q Quit"), footer  # the last key is whole
            assert "? Help" in footer and "e Edit" in footer


GOOD = (-20.0, 50.0, -170.0, 10.0, 40.0, 0.0)  # a Puma pose with room to move
WRIST = (0.0, 45.0, -135.0, 0.0, 0.0, 0.0)  # the Puma's wrist singularity (Th5 = 0)


def typed(*keys: str, value: str) -> tuple[str, ...]:
    return (*keys, "enter", "ctrl+u", *value, "enter")


CARTESIAN_FAILURES = [
    # (robot, start q or None, keys): each ends on a real failure message from the core
    ("puma560", GOOD, typed("c", value="5000")),  # X out of reach
    ("puma560", GOOD, typed("c", "down", value="-9000")),  # Y out of reach
    ("puma560", WRIST, ("c", "f", "down", "down", "down", "right")),  # tool Rx: singular
    ("puma560", WRIST, typed("c", "down", "down", "down", "down", value="170")),  # Ry: a limit
    ("planar2", None, ("c", "up", "right")),  # Rz: it can't turn its tool
    ("gantry", None, ("c", "down", "down", "down", "right")),  # Rx: no joint turns it
    ("cobra600", None, ("c", "down", "down", "down", "right")),
    ("stanford", None, typed("c", "down", "down", value="-5000")),
]


@pytest.mark.parametrize(("name", "q", "keys"), CARTESIAN_FAILURES)
async def test_cartesian_failure_reasons_are_shown_whole_at_80x24(
    name, q, keys, control_app, status
):
    app = control_app(name, q=q)
    async with app.run_test(size=SIZE) as pilot:
        if q is not None:
            await go_start(pilot)
        before = control(app).q
        await press(pilot, *keys)
        # a typed value is applied once its dialog has closed: wait for the answer
        await until(pilot, lambda: re.match(r"R?[XYZxyz]: ", status(app)), "the reason")
        assert control(app).q == before  # nothing moved...
        message = assert_status_whole(app)  # ...and the reason is there, all of it
        assert re.match(r"R?[XYZxyz]: ", message)


async def test_joint_limit_message_is_shown_whole(control_app):
    app = control_app("stanford")
    async with app.run_test(size=SIZE) as pilot:
        await press(pilot, "down", "down", "left")  # d3 is home at its minimum
        assert "limit" in assert_status_whole(app)


async def test_a_failed_save_says_why_first_and_shows_all_of_it(tmp_path, monkeypatch, status):
    import os

    deep = tmp_path.joinpath(*["a-long-folder-name"] * 8)
    deep.mkdir(parents=True)
    file = deep / "my-robot-with-a-long-name.toml"
    robot, _ = load_robot("gantry")
    save(robot, file)

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(os, "replace", refuse)
    app = DhsimApp(load_robot(str(file))[0], file, animate=False)
    async with app.run_test(size=SIZE) as pilot:
        await press(pilot, "right", "P", "ctrl+u", *"spot", "enter")
        await until(pilot, lambda: status(app).startswith("not saved:"), "the failure")
        message = assert_status_whole(app)
        assert message.startswith("not saved:")
        assert "pose spot is kept in memory" in message


def test_short_path_keeps_both_ends():
    path = "/home/student/" + "deep/" * 30 + "arm.toml"
    short = short_path(path, 60)
    assert len(short) == 60 and short.startswith("/home/student/") and short.endswith("arm.toml")
    assert "…" in short
    assert short_path("robots/arm.toml") == "robots/arm.toml"
    assert short_path("bad\x1bname.toml") == "bad\\x1bname.toml"


# -- step 7: file content is escaped and never markup ----------------------------------


def hostile_robot() -> Robot:
    """Names with a terminal command and markup in them. Loading refuses control
    characters; the screen must not rely on that (defence in depth), so the
    names are put in after the checks."""
    robot = Robot(
        "arm [b]b[/b] [red]",
        (Joint(a=100.0), Joint(a=80.0)),
        poses=(("[link=x]p[/link]", (10.0, 20.0)),),
    )
    object.__setattr__(robot, "name", "arm\x1b[2J\x9b\u202e [b]b[/b] [red]")
    object.__setattr__(robot, "poses", (("reach\x1b]0;pwned\x07 [i]", (10.0, 20.0)),))
    return robot


async def test_robot_and_pose_names_are_shown_escaped_and_literal():
    app = DhsimApp(hostile_robot(), None, animate=False)
    async with app.run_test(size=(160, 48)) as pilot:
        await press(pilot, "p")
        await until(pilot, lambda: "(1/1)" in "\n".join(lines(app)), "the pose's name")
        text = "\n".join(lines(app))
        assert "arm\\x1b[2J\\x9b\\u202e [b]b[/b] [red]" in text  # the title
        assert "pose reach\\x1b]0;pwned\\x07 [i] (1/1)" in " ".join(text.split())
        await press(pilot, "question_mark")
        await until(pilot, lambda: isinstance(app.screen, HelpScreen), "the help")
        help_text = " ".join("\n".join(lines(app)).split())
        assert "reach\\x1b]0;pwned\\x07 [i]" in help_text
        for screen_text in (text, help_text):
            assert not any(c in screen_text for c in "\x1b\x07\x9b\u202e")


# -- nothing in the side panel is cut at 80x24 ------------------------------------------


def assert_fits(widget) -> None:
    """Every line the widget renders fits its content area, unwrapped and unclipped."""
    text = widget.render()
    rows = str(text).split("\n")
    box = widget.content_region
    assert len(rows) <= box.height, (widget, rows)
    for row in rows:
        assert cell_len(row) <= box.width, (widget, row, box.width)


@pytest.mark.parametrize("name", ["puma560", "stanford", "panda", "planar2", "gantry"])
async def test_side_panel_content_fits_at_80x24(name, control_app):
    app = control_app(name)
    async with app.run_test(size=SIZE) as pilot:
        await press(pilot, "right", "down", "left")
        for keys in ((), ("v",), ("v",), ("v", "c"), ("down", "down", "down")):
            await press(pilot, *keys)
            # a key that changes the bindings recomposes the footer: it is
            # empty for a moment, then whole
            await until(pilot, lambda: lines(app)[-1].strip(), "the footer")
            screen = control(app)
            panel = "#cartesian" if screen.cartesian else "#pose"  # the one shown at 80x24
            for widget in [*app.screen.query("JointRow"), app.screen.query_one(panel)]:
                if widget.display:
                    assert_fits(widget)
            footer = lines(app)[-1].rstrip()
            assert footer.endswith("q Quit")


async def test_square_brackets_in_names_and_typed_text_are_shown_literally(
    tmp_path, status, screen_text
):
    robot = set_pose(Robot(BRACKETS, (Joint(a=100.0), Joint(a=50.0))), "[/p]", (1.0, 2.0))
    file = tmp_path / "odd.toml"
    save(robot, file)
    app = DhsimApp(load(file), file, animate=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await press(pilot, "p")
        assert "[/p]" in status(app)
        assert BRACKETS in screen_text(app)  # what a person sees, brackets and all
        await press(pilot, "enter", "ctrl+u", "[", "/", "enter")
        assert isinstance(app.screen, ValueEntry)
        assert "'[/' is not a number" in str(app.screen.query_one("#error").render())
        await press(pilot, "escape", "question_mark")
        assert isinstance(app.screen, HelpScreen)
        await press(pilot, "escape", "e")
        assert isinstance(app.screen, EditorScreen)
        await press(pilot, "tab", "a", "ctrl+u", *"[/x]", "enter")
        assert "[/x]" in app.screen.robot.pose_names

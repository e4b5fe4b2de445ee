"""The panels on their own, outside the control screen: each owns its keys,
mouse and state, and says what it wants with messages (issue 18)."""

from __future__ import annotations

from pathlib import Path

from pilot_helpers import press, started, until
from textual.app import App, ComposeResult
from textual.message import Message

import dhsim_tui.tui
from dhsim_tui.core import load_robot
from dhsim_tui.core.motion.jog import TOOL, WORLD
from dhsim_tui.scene import build_wireframe
from dhsim_tui.tui.keys import binding_keys, forwarded, help_rows, legend_rows
from dhsim_tui.tui.screens.control import ControlScreen
from dhsim_tui.tui.screens.control_keys import CONTROL_BINDINGS, KeyHints, bindings_in_effect
from dhsim_tui.tui.widgets.cartesian_panel import CartesianPanel
from dhsim_tui.tui.widgets.joint_panel import JointPanel
from dhsim_tui.tui.widgets.joint_row import JointRow
from dhsim_tui.tui.widgets.stepping import StepSizeRequested
from dhsim_tui.tui.widgets.views_panel import ViewsPanel

ROBOT = load_robot("puma560")[0]


class Recorder(App):
    """An app around one panel that keeps every message the panel posts."""

    CSS_PATH = Path(dhsim_tui.tui.__file__).with_name("dhsim.tcss")

    def __init__(self, make) -> None:
        super().__init__()
        self.make = make
        self.seen: list[Message] = []

    def compose(self) -> ComposeResult:
        yield self.make()

    def on_joint_panel_step_requested(self, message) -> None:
        self.seen.append(message)

    def on_joint_panel_value_asked(self, message) -> None:
        self.seen.append(message)

    def on_joint_panel_value_requested(self, message) -> None:
        self.seen.append(message)

    def on_step_size_requested(self, message) -> None:
        self.seen.append(message)

    def on_cartesian_panel_jog_requested(self, message) -> None:
        self.seen.append(message)

    def on_cartesian_panel_frame_changed(self, message) -> None:
        self.seen.append(message)

    def on_views_panel_selected(self, message) -> None:
        self.seen.append(message)

    def on_views_panel_maximised(self, message) -> None:
        self.seen.append(message)


def joint_panel() -> JointPanel:
    rows = [
        JointRow(i, joint, ROBOT.units, value)
        for i, (joint, value) in enumerate(zip(ROBOT.joints, ROBOT.home, strict=True), start=1)
    ]
    return JointPanel(*rows, id="joints")


async def test_the_joint_panel_selects_itself_and_asks_for_steps_values_and_sizes():
    app = Recorder(joint_panel)
    async with app.run_test(size=(60, 12)) as pilot:
        panel = app.query_one(JointPanel)
        assert app.focused is panel  # it takes focus: its keys are its own
        await press(pilot, "down", "down", "right", "shift+left", "left_square_bracket", "enter")
        await pilot.pause()
        assert panel.selected == 2
        kinds = [(type(m).__name__, getattr(m, "index", None)) for m in app.seen]
        assert kinds == [
            ("StepRequested", 2),
            ("StepRequested", 2),
            ("StepSizeRequested", None),
            ("ValueAsked", 2),
        ]
        assert [m.steps for m in app.seen[:2]] == [1, -10]
        assert isinstance(app.seen[2], StepSizeRequested) and app.seen[2].delta == -1
        await press(pilot, "up", "up", "up")  # wraps from the first joint to the last
        assert panel.selected == ROBOT.dof - 1


async def test_queued_steps_one_way_add_up_and_the_other_way_do_not():
    step = JointPanel.StepRequested
    pending = step(1, 1)
    assert step(1, 1).can_replace(pending) and pending.steps == 2
    assert not step(1, -1).can_replace(pending) and pending.steps == 2  # a limit in between
    assert not step(2, 1).can_replace(pending)  # another joint
    drag = JointPanel.ValueRequested
    assert drag(0, 10.0).can_replace(drag(0, 20.0)) and not drag(0, 1.0).can_replace(drag(1, 2.0))


async def test_a_click_on_a_bar_asks_for_the_value_under_the_pointer():
    app = Recorder(joint_panel)
    async with app.run_test(size=(60, 40)) as pilot:
        row = app.query(JointRow)[3]
        await pilot.click(row, offset=(20, 0))
        await until(
            pilot,
            lambda: any(isinstance(m, JointPanel.ValueRequested) for m in app.seen),
            "the value asked for",
        )
        assert app.query_one(JointPanel).selected == 3
        (asked,) = [m for m in app.seen if isinstance(m, JointPanel.ValueRequested)]
        assert asked.index == 3 and row.joint.min < asked.value < row.joint.max


async def test_the_cartesian_panel_owns_its_row_and_frame():
    app = Recorder(lambda: CartesianPanel(id="cartesian"))
    async with app.run_test(size=(60, 12)) as pilot:
        panel = app.query_one(CartesianPanel)
        panel.focus()
        await pilot.pause()
        assert panel.check_action("frame", (TOOL,)) and not panel.check_action("frame", (WORLD,))
        await press(pilot, "down", "right", "f")
        await pilot.pause()
        jog, changed = app.seen
        assert (jog.row, jog.steps, jog.frame) == (1, 1, WORLD)
        assert changed.frame == TOOL == panel.frame and "TOOL" in str(panel.border_title)
        await press(pilot, "shift+left")
        await pilot.pause()
        assert (app.seen[-1].row, app.seen[-1].steps, app.seen[-1].frame) == (1, -10, TOOL)


class ViewsApp(Recorder):
    """The views panel, its keys handed on as the control screen does."""

    BINDINGS = forwarded(ViewsPanel.BINDINGS, "views")

    def __init__(self) -> None:
        super().__init__(lambda: ViewsPanel("plotext", id="views"))

    def action_forward(self, target: str, action: str, parameters: tuple = ()) -> None:
        getattr(self.query_one(f"#{target}"), f"action_{action}")(*parameters)


async def test_the_views_panel_works_on_its_own_with_keys_and_the_mouse():
    app = ViewsApp()
    async with app.run_test(size=(120, 36)) as pilot:
        app.screen.add_class("-wide")  # all four views, as the control screen has them
        views = app.query_one(ViewsPanel)
        views.show(build_wireframe(ROBOT, ROBOT.kinematics.frames(ROBOT.home)))
        await pilot.pause()
        assert views.fit  # the views open fitted to the arm
        await press(pilot, "3", "z", "x", "plus", "F")
        await pilot.pause()
        assert views.selected == 2 and views.maximised and views.frames != "all"
        assert not views.fit  # F: the work area
        await press(pilot, "F")
        assert views.fit  # F again: fitted
        await press(pilot, "z", "0")
        assert not views.maximised and not views.fit and views.zoom == 1.0
        azimuth = views.orbit.azimuth
        await press(pilot, "d")
        assert views.orbit.azimuth != azimuth and views.selected == 2  # all four are shown
        iso = views.views[3]
        await pilot.click(iso)
        await until(pilot, lambda: views.selected == 3, "the 3-D view selected")
        await pilot.click(iso, times=2)
        await until(pilot, lambda: views.maximised, "the 3-D view maximised")
        kinds = {type(m).__name__ for m in app.seen}
        assert kinds == {"Selected", "Maximised"}


async def test_the_legend_and_help_are_the_bindings_in_effect():
    app_screen = ControlScreen(ROBOT, animate=False)

    class One(App):
        def on_mount(self) -> None:
            self.push_screen(app_screen)

    async with One().run_test(size=(160, 48)) as pilot:
        await started(pilot)
        screen = app_screen
        in_effect = bindings_in_effect(screen)
        ids = {b.id for b in in_effect}
        assert {"joint.prev", "robot.home", "view.maximise", "mode.cartesian"} <= ids
        assert "mode.joints" not in ids and "cartesian.tool_frame" not in ids
        legend = str(screen.query_one(KeyHints).render())
        for _keys, words in legend_rows(in_effect):
            assert words in legend, words
        await press(pilot, "c")
        await pilot.pause()
        ids = {b.id for b in bindings_in_effect(screen)}
        assert {"cartesian.prev", "cartesian.tool_frame", "mode.joints"} <= ids
        assert "world/tool frame" in str(screen.query_one(KeyHints).render())
        # every screen key is in the help, once, with its words
        rows = dict(help_rows(CONTROL_BINDINGS))
        assert rows["b"].startswith("the arm's next solution") and rows["z"]


async def test_the_arrows_still_jog_while_a_view_is_maximised_or_the_terminal_was_too_small():
    app_screen = ControlScreen(ROBOT, animate=False)

    class One(App):
        def on_mount(self) -> None:
            self.push_screen(app_screen)

    async with One().run_test(size=(120, 36)) as pilot:
        await started(pilot)
        await press(pilot, "z", "right")
        await pilot.pause()
        assert app_screen.query_one(ViewsPanel).maximised and app_screen.q != ROBOT.home
        moved = app_screen.q
        await pilot.resize_terminal(40, 10)
        await until(pilot, lambda: app_screen.has_class("-too-small"), "the too-small layout")
        await pilot.resize_terminal(120, 36)
        await until(pilot, lambda: not app_screen.has_class("-too-small"), "the usual layout")
        await press(pilot, "right")
        await pilot.pause()
        assert app_screen.q != moved and app_screen.focused is app_screen.query_one(JointPanel)


def test_the_readme_names_every_key_of_the_simulator():
    """A new key comes with its line in the README's table (the footer, the
    legend and the help come from the binding itself)."""
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    table = readme.split("## The simulator", 1)[1].split("### The mouse", 1)[0]
    named = {cell.strip("`") for line in table.splitlines() for cell in line.split("|")[1:2]}
    named = {key for cell in named for key in cell.replace("`", " ").replace(",", " ").split()}
    for binding in [
        *CONTROL_BINDINGS,
        *JointPanel.BINDINGS,
        *CartesianPanel.BINDINGS,
        *ViewsPanel.BINDINGS,
    ]:
        group = binding.group
        if group is None or not getattr(group, "legend", False):
            continue
        (key,) = binding_keys(binding, every=False)
        assert key in named, f"{key} ({binding.id}) is not in the README's table of keys"

"""What the joints panel and the Cartesian panel share: the step size keys
``[ ]`` and the message they post (the screen keeps the step size: it is the
same in both panels)."""

from __future__ import annotations

from dataclasses import dataclass

from textual.binding import Binding
from textual.message import Message

from dhsim_tui.core.model.validation import fmt
from dhsim_tui.core.motion.jog import PRISMATIC_STEPS_MM, REVOLUTE_STEPS_DEG
from dhsim_tui.tui.keys import Keys

STEP_SIZE = Keys(
    "step size",
    help="smaller / larger step: "
    + ", ".join(fmt(s) for s in REVOLUTE_STEPS_DEG)
    + " deg; "
    + ", ".join(fmt(s) for s in PRISMATIC_STEPS_MM)
    + " mm",
)

STEP_SIZE_BINDINGS = [
    Binding("left_square_bracket", "step_size(-1)", "Step size", key_display="[]", show=False,
            id="step.smaller", tooltip="Smaller step", group=STEP_SIZE),
    Binding("right_square_bracket", "step_size(1)", "Step size", show=False,
            id="step.larger", tooltip="Larger step", group=STEP_SIZE),
]  # fmt: skip


def arrow_bindings(
    mode: str, select: str, step: str, what: str, moves: str, groups: tuple[Keys, Keys, Keys]
) -> list[Binding]:
    """A jogging panel's arrows: up/down ``select`` a row (a ``what``), left/right
    ``step`` it (labelled ``moves``), shift ten steps; ``groups``: the legend
    rows of the three pairs."""
    rows, steps, big = groups
    return [
        Binding("up", f"{select}(-1)", what, key_display="↑↓", id=f"{mode}.prev",
                tooltip=f"Select the previous {what.lower()}", group=rows),
        Binding("down", f"{select}(1)", what, show=False, id=f"{mode}.next",
                tooltip=f"Select the next {what.lower()}", group=rows),
        Binding("left", f"{step}(-1)", moves, key_display="←→", id=f"{mode}.step_down",
                tooltip=f"{moves}: one step down", group=steps),
        Binding("right", f"{step}(1)", moves, show=False, id=f"{mode}.step_up",
                tooltip=f"{moves}: one step up", group=steps),
        Binding("shift+left", f"{step}(-10)", "×10", show=False, id=f"{mode}.big_step_down",
                tooltip="Ten steps down", group=big),
        Binding("shift+right", f"{step}(10)", "×10", show=False, id=f"{mode}.big_step_up",
                tooltip="Ten steps up", group=big),
    ]  # fmt: skip


@dataclass
class StepSizeRequested(Message):
    """``[`` or ``]``: a smaller (``delta`` -1) or larger step."""

    delta: int

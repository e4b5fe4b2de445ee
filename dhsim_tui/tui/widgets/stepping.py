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


@dataclass
class StepSizeRequested(Message):
    """``[`` or ``]``: a smaller (``delta`` -1) or larger step."""

    delta: int

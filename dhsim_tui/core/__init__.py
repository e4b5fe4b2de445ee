"""The UI-free core: robot model, D-H kinematics, orientation read-outs and
robot files. It depends on numpy and the standard library only (and tomli-w
for writing), never on textual, plotext or rich; a test proves it."""

from dhsim_tui.core.analysis.workspace import WorkArea, reach, work_area
from dhsim_tui.core.files.library import bundled_names, describe, load_robot, resolve
from dhsim_tui.core.files.robotfile import dumps, load, loads, save
from dhsim_tui.core.model.errors import DhsimError, RobotFileError
from dhsim_tui.core.model.kinematics import EndEffector, Kinematics, read_out
from dhsim_tui.core.model.robot import Joint, Robot, Tool

__all__ = [
    "DhsimError",
    "EndEffector",
    "Joint",
    "Kinematics",
    "Robot",
    "RobotFileError",
    "Tool",
    "WorkArea",
    "bundled_names",
    "describe",
    "dumps",
    "load",
    "load_robot",
    "loads",
    "reach",
    "read_out",
    "resolve",
    "save",
    "work_area",
]

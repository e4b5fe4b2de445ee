"""The one error type the core raises for anything a user can get wrong."""


class DhsimError(ValueError):
    """A problem with something the user gave: a file, a value, a name.

    Its message is meant to be shown as it is: it names the culprit (file,
    field, joint) and says what was wrong. Catching this one type is enough
    for every user-facing entry point.
    """


class RobotFileError(DhsimError):
    """A robot file that cannot be read, parsed or validated."""


class TipNeeded(DhsimError):
    """A URDF's links below the base form a tree: the user must choose a tip
    (raised by :mod:`dhsim_tui.core.interop.urdf`; here so a dialog can catch it
    without loading the XML reader)."""

    def __init__(self, message: str, leaves: tuple[str, ...]) -> None:
        super().__init__(message)
        self.leaves = leaves

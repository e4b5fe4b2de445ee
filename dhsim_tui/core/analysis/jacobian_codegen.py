"""The Jacobian compiled per robot into one straight-line Python function
(:func:`jacobian_source`, :func:`compile_jacobian`): the chain's own lines
from :mod:`dhsim_tui.core.model.kinematics`, each joint's axis and origin kept
as it passes, the cross products written out at the end, constants folded
(the first joint's axis is a constant). :mod:`dhsim_tui.core.analysis.jacobian`
decides when a robot gets it and caches it.
"""

from __future__ import annotations

import math

import numpy as np

from dhsim_tui.core.analysis.workspace import length_scale
from dhsim_tui.core.model.kinematics import (
    compile_step,
    constant_transform_lines,
    joint_transform_lines,
    start_state,
)
from dhsim_tui.core.model.robot import Robot

_STATE = "x0, x1, x2, y0, y1, y2, z0, z1, z2, p0, p1, p2"


def _term(coefficient: float | str, name: str) -> str | None:
    """``coefficient * name`` with 0 and ±1 folded (None for a zero)."""
    if isinstance(coefficient, str):
        return f"{coefficient}*{name}"
    if coefficient == 0.0:
        return None
    if coefficient == 1.0:
        return name
    if coefficient == -1.0:
        return f"-{name}"
    return f"{coefficient!r}*{name}"


def _difference(first: str | None, second: str | None) -> str:
    if first is None and second is None:
        return "0.0"
    if second is None:
        return str(first)
    if first is None:
        return f"-({second})"
    return f"{first} - {second}"


def _value(v: float | str) -> str:
    return v if isinstance(v, str) else repr(float(v))


def _first_axis(robot: Robot) -> tuple[float, ...]:
    """Joint 1's axis and origin (6 floats): constants, whatever q is. Standard
    D-H: frame 0's z and origin; modified: frame 1's, whose z and (for a
    revolute joint) origin the joint's own turn leaves alone. Computed by the
    chain's own lines, so the same bits as at run time."""
    state = start_state(robot)
    if robot.convention != "standard":
        state = compile_step(tuple(joint_transform_lines(robot, 0, "qi")))(state, 0.0)
    return tuple(state[6:12])


def jacobian_parts(
    robot: Robot, *, normalise: bool = False, tool_rotation: bool = True
) -> tuple[list, list, list]:
    """The pieces of the compiled Jacobian, for code that puts other lines
    between them (the numerical IK's compiled descent):

    * the chain's lines: from ``q0 .. q{n-1}`` (the joint values) they set the
      end effector's 12-float state (the names of ``Kinematics.state``:
      ``x0 .. z2`` its axes, ``p0 p1 p2`` its origin), keeping each joint's
      axis and origin as they pass;
    * the column lines, run after them: they compute the linear entries;
    * ``columns[c][r]``: entry (r, c) of the Jacobian, a name the lines set or
      a constant (``"0.0"``, ``"1.0"``, ...).

    ``normalise`` gives :func:`normalised`'s dimensionless Jacobian (linear
    rows per reach, prismatic columns per reach). Without ``tool_rotation``
    the state's axes are the flange's (the tool's offset is in its origin):
    for code that turns its target by the tool's rotation instead, once.
    The lines also use the names
    ``c``, ``s``, ``l0 l1 l2``, ``u{i}*``, ``o{i}*`` and ``c{i}_{r}``."""
    n = robot.dof
    standard = robot.convention == "standard"
    tool = None if robot.tool.is_identity else robot.kinematics.tool
    body = [f"{_STATE} = {', '.join(repr(float(v)) for v in start_state(robot))}"]
    axes: list[tuple] = []

    def capture(i: int) -> tuple:
        if i == 0:
            return _first_axis(robot)
        body.append(f"u{i}x, u{i}y, u{i}z, o{i}x, o{i}y, o{i}z = z0, z1, z2, p0, p1, p2")
        return tuple(f"{k}{i}{c}" for k in "uo" for c in "xyz")

    for i in range(n):
        if standard:
            axes.append(capture(i))
        body += joint_transform_lines(robot, i)
        if not standard:
            axes.append(capture(i))
    if tool is not None:
        if not tool_rotation:
            tool = tool.copy()
            tool[:3, :3] = np.eye(3)
        body += constant_transform_lines(tool)
    inverse = 1.0 / length_scale(robot) if normalise else 1.0
    columns = []
    lines = []
    for i, joint in enumerate(robot.joints):
        ax, ay, az, ox, oy, oz = axes[i]
        if not joint.is_revolute:  # (z, 0): per unit length, or per reach (× reach / reach)
            columns.append([_value(ax), _value(ay), _value(az), "0.0", "0.0", "0.0"])
            continue
        linear = [
            _difference(_term(ay, "l2"), _term(az, "l1")),
            _difference(_term(az, "l0"), _term(ax, "l2")),
            _difference(_term(ax, "l1"), _term(ay, "l0")),
        ]
        for k, (p, o) in enumerate(zip(("p0", "p1", "p2"), (ox, oy, oz), strict=True)):
            if not any(f"l{k}" in term for term in linear):
                continue  # a constant axis with no component here: lever unused
            lever = f"{p} - {_value(o)}" if o != 0.0 else p
            if inverse != 1.0:
                lever = f"({lever})*{inverse!r}"
            lines.append(f"l{k} = {lever}")
        # the lever's names are reused: keep this column's values before the next
        # (constant entries stay constants, for code that folds them)
        named = [r for r in range(3) if linear[r] != "0.0"]
        if named:
            names = [f"c{i}_{r}" for r in named]
            lines.append(f"{', '.join(names)} = {', '.join(linear[r] for r in named)}")
            for r in named:
                linear[r] = f"c{i}_{r}"
        columns.append([*linear, _value(ax), _value(ay), _value(az)])
    return body, lines, columns


def jacobian_source(robot: Robot, *, normalise: bool = False, with_state: bool = False) -> str:
    """The Python source of the robot's compiled Jacobian ``f(q)``.

    It returns the 6×n Jacobian as a flat row-major list; ``with_state`` also
    returns the end effector's 12-float state (as ``Kinematics.state``) first.
    ``normalise`` gives :func:`normalised`'s dimensionless Jacobian instead
    (linear rows per reach, prismatic columns per reach)."""
    n = robot.dof
    chain, lines, columns = jacobian_parts(robot, normalise=normalise)
    body = [chain[0], f"{', '.join(f'q{i}' for i in range(n))}, = q", *chain[1:], *lines]
    flat = ", ".join(columns[c][r] for r in range(6) for c in range(n))
    body.append(f"return ({_STATE}), [{flat}]" if with_state else f"return [{flat}]")
    return "def jacobian(q):\n" + "".join(f"    {line}\n" for line in body)


def compile_jacobian(robot: Robot, *, normalise: bool = False, with_state: bool = False):
    """:func:`jacobian_source` compiled: ``f(q) -> flat list`` (or ``(state, flat)``)."""
    source = jacobian_source(robot, normalise=normalise, with_state=with_state)
    namespace: dict = {"_cos": math.cos, "_sin": math.sin}
    exec(compile(source, f"<dhsim jacobian: {robot.name}>", "exec"), namespace)
    return namespace["jacobian"]

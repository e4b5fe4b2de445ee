"""The compiled chain of :mod:`dhsim_tui.core.model.kinematics`: one robot's
forward kinematics written as straight-line Python on named values.

:class:`ChainWriter` goes through the chain joint by joint as the per-joint
lines of ``kinematics.joint_transform_lines`` do, but each entry of the frame becomes a
local computed once: a ±90° turn is a renaming (its sign carried along, not
computed), a product by 1 is no product, constants are computed now, and what
nothing needs is left out. Only rewrites that round exactly alike, so the
compiled chain gives the same bits as a run of those lines. The function packs
the pose (or every frame) straight into a float64 array (:func:`packer`);
:mod:`dhsim_tui.core.analysis.jacobian` writes the Jacobian with the same writer.

A value is a float (known now) or a local's name, ``-name`` for its negation; a
term, what an operation gives, is a float or (expression, negated). The
rewrites: x·1 = x, x·(-y) = -(x·y), x + (-y) = x - y, (-x) + y = y - x,
(-x) + (-y) = -x - y and x + (-0.0) = x.
"""

from __future__ import annotations

import functools
import math
import re
import struct
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import numpy as np

from dhsim_tui.core.model.orientation import cos_sin

if TYPE_CHECKING:
    from dhsim_tui.core.model.robot import Robot

_DEG = math.pi / 180.0
_AXES = ("x", "y", "z")
#: the chain's state: frame i's x, y, z axes (world coordinates), then its origin
NAMES = ("x0", "x1", "x2", "y0", "y1", "y2", "z0", "z1", "z2", "p0", "p1", "p2")
#: the state's names in the order of a 4×4 transform's rows (the last row is 0 0 0 1)
ROWS = ("x0", "y0", "z0", "p0", "x1", "y1", "z1", "p1", "x2", "y2", "z2", "p2")

Value = float | str
Term = float | tuple[str, bool]
_IDENTIFIER = re.compile(r"[A-Za-z_]\w*")


def signed(value: Value) -> Term:
    if isinstance(value, float):
        return value
    return (value[1:], True) if value[0] == "-" else (value, False)


def negated(term: Term) -> Term:
    return -term if isinstance(term, float) else (term[0], not term[1])


def product(a: Value, b: Value) -> Term:
    """a·b."""
    if isinstance(a, float) and isinstance(b, float):
        return a * b
    if isinstance(b, float):
        a, b = b, a
    name, negative = signed(b)
    if not isinstance(a, float):
        other, flip = signed(a)
        return (f"{other}*{name}", negative != flip)
    if a in (1.0, -1.0):
        return (name, negative != (a < 0.0))
    return (f"{a!r}*{name}", negative)


def total(a: Term, b: Term) -> Term:
    """a + b."""
    if isinstance(a, float) and isinstance(b, float):
        return a + b
    for x, y in ((a, b), (b, a)):
        if isinstance(y, float) and y == 0.0 and math.copysign(1.0, y) < 0.0:
            return x
    (first, minus_first), (second, minus_second) = (
        (repr(t), False) if isinstance(t, float) else t for t in (a, b)
    )
    if minus_first and minus_second:
        return (f"(-{first} - {second})", False)
    if minus_first:
        return (f"({second} - {first})", False)
    return (f"({first} {'-' if minus_second else '+'} {second})", False)


class ChainWriter:
    """Writes the chain of :func:`~.kinematics.joint_transform_lines` (and the
    tool's) as lines ``name = expression``, each value computed once:
    :attr:`state` holds the values of x0..z2, p0..p2 as the chain goes, joint
    by joint."""

    def __init__(self, robot: Robot, tool: np.ndarray | None, start: Sequence[float]) -> None:
        self.robot, self._tool = robot, tool
        self.lines: list[tuple[str, str]] = []
        self._known: dict[str, str] = {}
        self.state: dict[str, Value] = dict(zip(NAMES, map(float, start), strict=True))

    def bind(self, term: Term) -> Value:
        """A term as a value: a new local unless it is a name or a constant."""
        if isinstance(term, float):
            return term
        text, negative = term
        if not text.isidentifier():
            name = self._known.get(text)
            if name is None:
                name = self._known[text] = f"v{len(self._known)}"
                self.lines.append((name, text))
            text = name
        return "-" + text if negative else text

    def _rotate(self, u: str, v: str, c: Value, s: Value) -> None:
        new = {}
        for k in range(3):
            first, second = self.state[f"{u}{k}"], self.state[f"{v}{k}"]
            new[f"{u}{k}"] = total(product(c, first), product(s, second))
            new[f"{v}{k}"] = total(product(c, second), negated(product(s, first)))
        self.state.update((name, self.bind(term)) for name, term in new.items())

    def _rotate_const(self, u: str, v: str, deg: float) -> None:
        c, s = cos_sin(deg)
        if (c, s) == (1.0, 0.0):
            return
        if c != 0.0:
            self._rotate(u, v, c, s)
            return
        for k in range(3):  # ±90°: a renaming with a sign
            first, second = signed(self.state[f"{u}{k}"]), signed(self.state[f"{v}{k}"])
            first, second = (second, negated(first)) if s > 0 else (negated(second), first)
            self.state[f"{u}{k}"], self.state[f"{v}{k}"] = self.bind(first), self.bind(second)

    def _translate(self, axis: str, amount: Value) -> None:
        if isinstance(amount, float) and amount == 0.0:
            return
        for k in range(3):
            move = product(amount, self.state[f"{axis}{k}"])
            self.state[f"p{k}"] = self.bind(total(signed(self.state[f"p{k}"]), move))

    def joint(self, index: int) -> None:
        """Joint ``index``'s transform (its value is the local ``q<index>``)."""
        joint = self.robot.joints[index]
        q: Value = f"q{index}"
        if joint.offset:
            q = self.bind((f"{q} + {float(joint.offset)!r}", False))
        standard = self.robot.convention == "standard"
        if not standard:  # Rx(alpha) Tx(a) Rz(theta) Tz(d)
            self._rotate_const("y", "z", joint.alpha)
            self._translate("x", float(joint.a))
        if joint.is_revolute:
            self.lines += [(f"r{index}", f"{q}*{_DEG!r}"), (f"c{index}", f"_cos(r{index})")]
            self.lines.append((f"s{index}", f"_sin(r{index})"))
            self._rotate("x", "y", f"c{index}", f"s{index}")
            self._translate("z", float(joint.d))
        else:
            self._rotate_const("x", "y", joint.theta)
            self._translate("z", q)
        if standard:  # Rz(theta) Tz(d) Tx(a) Rx(alpha)
            self._translate("x", float(joint.a))
            self._rotate_const("y", "z", joint.alpha)

    def tool(self) -> None:
        """Post-multiply by the tool's constant transform (if any)."""
        if self._tool is None:
            return
        r, t = self._tool[:3, :3].tolist(), self._tool[:3, 3].tolist()

        def combination(weights: list[float], k: int) -> Term:
            terms = [product(weights[j], self.state[f"{_AXES[j]}{k}"]) for j in range(3)]
            return total(total(terms[0], terms[1]), terms[2])

        for k in range(3):
            self.state[f"p{k}"] = self.bind(total(signed(self.state[f"p{k}"]), combination(t, k)))
        new = {
            f"{_AXES[col]}{k}": combination([r[j][col] for j in range(3)], k)
            for col in range(3)
            for k in range(3)
        }
        self.state.update((name, self.bind(term)) for name, term in new.items())

    def matrix(self) -> list[str]:
        """The state as the 16 entries of a 4×4 transform, row by row."""
        return [*(text(self.state[name]) for name in ROWS), "0.0", "0.0", "0.0", "1.0"]

    def compile(self, tail: list[str], namespace: dict) -> Callable:
        """``chain(q, o=None)``: unpack q, the lines, then ``tail`` (which uses
        the values), without the lines it does not need, but with every
        cosine (so an infinite joint value raises as before)."""
        live = set(_IDENTIFIER.findall(" ".join(tail)))
        kept = []
        for name, expression in reversed(self.lines):
            if name in live or expression.startswith("_cos("):
                live.update(_IDENTIFIER.findall(expression))
                kept.append(f"{name} = {expression}")
        qs = "".join(f"q{i}, " for i in range(self.robot.dof))
        body = [f"{qs}= q", *reversed(kept), *tail]
        source = "def chain(q, o=None):\n" + "".join(f"    {line}\n" for line in body)
        namespace = {"_cos": math.cos, "_sin": math.sin, **namespace}
        exec(compile(source, f"<dhsim chain: {self.robot.name}>", "exec"), namespace)
        return namespace["chain"]


def text(value: Value) -> str:
    return repr(value) if isinstance(value, float) else value


def chain_function(
    robot: Robot, tool: np.ndarray | None, start: Sequence[float], record: bool
) -> Callable:
    """``f(q, o=None)`` for this robot, from frame 0 given as ``start`` (its
    axes then origin): the end effector's 12-float state (with ``record``,
    every frame as a flat list), or with ``o``, the 4×4 transform (or
    transforms) packed into that array."""
    writer = ChainWriter(robot, tool, start)
    frames = [writer.matrix()]
    for i in range(robot.dof):
        writer.joint(i)
        if record:
            frames.append(writer.matrix())
    writer.tool()
    if record:
        values = ", ".join(v for frame in (*frames, writer.matrix()) for v in frame)
        tail = ["if o is None:", f"    return [{values}]", f"_pack(o, 0, {values})"]
    else:
        state = ", ".join(text(writer.state[name]) for name in NAMES)
        tail = [
            "if o is None:",
            f"    return ({state})",
            f"_pack(o, 0, {', '.join(writer.matrix())})",
        ]
    return writer.compile(tail, {"_pack": packer(16 * (robot.dof + 2) if record else 16)})


@functools.lru_cache(maxsize=64)
def packer(size: int) -> Callable:
    """``pack(array, 0, *values)``: ``size`` floats into a C-contiguous float64
    array, in order (a TypeError for any other array)."""
    return struct.Struct(f"{size}d").pack_into

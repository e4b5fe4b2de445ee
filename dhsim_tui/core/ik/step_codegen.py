"""The numerical IK's whole descent compiled per robot into one Python
function (:func:`compile_descent`), for :mod:`dhsim_tui.core.ik.numerical_descent`.

One loop over plain float locals (no list, no call but cos, sin, sqrt and
atan2): the forward kinematics (the chain's own lines, from
:func:`~dhsim_tui.core.analysis.jacobian_codegen.jacobian_parts`), the error
(position per reach and the rotation vector), the convergence and give-up
tests, and only then (the last pass needs none) the Jacobian's columns, the
smaller Gram matrix (JJᵀ or JᵀJ) plus the damping, its Cholesky factor, the
two triangular solves and the step, clamped to the joint limits:
``(JᵀJ + λI)⁻¹ Jᵀ e = Jᵀ (JJᵀ + λI)⁻¹ e`` by the smaller matrix.

The lines go through :class:`~dhsim_tui.core.ik.codegen_fold.Folder`: the
constants (the base frame, a first axis along z, a prismatic column's
zeros, a tool's offset) are folded in and swaps of axes cost nothing. A
joint's angle goes to cos and sin as it is (not to degrees and back). The
tool's rotation is not in the loop: the target is turned back by it once.
Folded or not (:func:`compile_descent` falls back on the lines as they are
when the folder cannot read them), the arithmetic is the same.

Names: the chain uses ``c s l0 l1 l2 x* y* z* p* q* u* o* c*_*`` (and the
folder ``name__k``); the loop's own are ``v*`` (joint values, internal
units), ``g*`` (goal), ``e*`` (error), ``J*_*`` (weighted Jacobian
entries), ``L*_*`` (Cholesky), ``fz*``/``by*`` (forward and back
substitution), ``d*`` (step) and ``w*`` (clamped values).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Sequence

import numpy as np

from dhsim_tui.core.analysis.jacobian_codegen import jacobian_parts
from dhsim_tui.core.ik.codegen_fold import Folder
from dhsim_tui.core.ik.rotation import rotation_error_floats
from dhsim_tui.core.model.robot import Robot

_STATE9 = "x0, x1, x2, y0, y1, y2, z0, z1, z2"
_GOAL9 = [f"g{i}{j}" for i in range(3) for j in range(3)]


def _literal(value: float) -> str:
    """A float as source (``_inf`` for infinities, which have no literal)."""
    if math.isinf(value):
        return "_inf" if value > 0 else "-_inf"
    return repr(float(value))


def _sum(terms: list[str | None]) -> str:
    kept = [t for t in terms if t is not None]
    return " + ".join(kept) if kept else "0.0"


def _rotation_lines(position_only: bool) -> tuple[list[str], list[str]]:
    """e3 e4 e5: :func:`~dhsim_tui.core.ik.rotation.rotation_error_floats`, written
    out: the straight lines, then the branches (whose half turn reads the
    state as ``{x0}`` ... ``{z2}``, for the folder's names)."""
    if position_only:
        return [], ["e3 = e4 = e5 = 0.0"]
    straight = [
        "r00 = g00 * x0 + g01 * y0 + g02 * z0",
        "r11 = g10 * x1 + g11 * y1 + g12 * z1",
        "r22 = g20 * x2 + g21 * y2 + g22 * z2",
        "wx = 0.5 * ((g20 * x1 + g21 * y1 + g22 * z1) - (g10 * x2 + g11 * y2 + g12 * z2))",
        "wy = 0.5 * ((g00 * x2 + g01 * y2 + g02 * z2) - (g20 * x0 + g21 * y0 + g22 * z0))",
        "wz = 0.5 * ((g10 * x0 + g11 * y0 + g12 * z0) - (g00 * x1 + g01 * y1 + g02 * z1))",
        "size = _sqrt(wx * wx + wy * wy + wz * wz)",
        "cosine = (r00 + r11 + r22 - 1.0) / 2.0",
    ]
    state = ", ".join(f"{{{name}}}" for name in _STATE9.split(", "))
    goal = ", ".join(f"{{{name}}}" for name in _GOAL9)
    branches = [
        "if size > 1e-9:",
        "    kk = _atan2(size, cosine) / size",
        "    e3 = wx * kk; e4 = wy * kk; e5 = wz * kk",
        "elif cosine > 0:",
        "    e3 = wx; e4 = wy; e5 = wz",
        "else:  # a half turn: rare, the matrix way",
        f"    e3, e4, e5 = _half_turn([{goal}], ({state}))",
    ]
    return straight, branches


def _in_radians(chain: list[str], n: int) -> list[str]:
    """The chain's lines with a turn's angle in degrees taken back to radians
    (``q0*0.017453292519943295``) read as the radians the loop has (``v0``),
    not to degrees and back."""
    pattern = re.compile(rf"\b(q\d+)\*{re.escape(repr(math.pi / 180.0))}(?![\d.eE])")
    return [pattern.sub(lambda m: "v" + m.group(1)[1:], line) for line in chain]


def _reads(lines: list[str], name: str) -> bool:
    pattern = re.compile(rf"\b{name}\b")
    return any(pattern.search(line) for line in lines)


def _goal_lines(robot: Robot, fold: Folder) -> list[str]:
    """The goal's rotation turned back by the tool's, ``G Rᵀ``: compared with
    the flange's, it gives the same error as the goal with the tool's
    (``G (F R)ᵀ = (G Rᵀ) Fᵀ``), with no tool rotation in the loop."""
    if robot.tool.is_identity:
        return []
    r = robot.kinematics.tool[:3, :3].tolist()
    values = [
        " + ".join(f"g{i}{k}*{r[j][k]!r}" for k in range(3)) for i in range(3) for j in range(3)
    ]
    return fold.lines([f"{', '.join(_GOAL9)} = {', '.join(values)}"])


def _measure_lines(picked: Sequence[int], weights: Sequence[float]) -> list[str]:
    """``pos`` and ``rot``, the squared errors of the rows solved for, and
    ``sq``, the squared weighted error (as the loop it replaces sums them);
    a weighted row's error is ``e{r}w``."""
    pos = _sum([f"e{r}*e{r}" for r in picked if r < 3])
    rot = _sum([f"e{r}*e{r}" for r in picked if r >= 3])
    lines = [f"pos = {pos}", f"rot = {rot}"]
    if all(w == 1.0 for w in weights):  # the rows in order: the same sum
        return [*lines, "sq = pos + rot"]
    lines += [f"e{r}w = e{r}*{w!r}" for r, w in zip(picked, weights, strict=True) if w != 1.0]
    names = [f"e{r}w" if w != 1.0 else f"e{r}" for r, w in zip(picked, weights, strict=True)]
    return [*lines, f"sq = {_sum([f'{e}*{e}' for e in names])}"]


def _solve_lines(jac: list[list[str]], rhs_e: list[str], n: int) -> list[str]:
    """d0 .. d{n-1} = (JᵀJ + lam I)⁻¹ Jᵀ e by the smaller Gram matrix's Cholesky
    factor (its constant terms are the folder's to drop)."""
    m = len(jac)
    side = min(m, n)
    if not side:
        return [f"d{c} = 0.0" for c in range(n)]
    lines = []

    def gram(i: int, j: int) -> str:
        if n <= m:
            return _sum([f"{jac[r][i]}*{jac[r][j]}" for r in range(m)])
        return _sum([f"{jac[i][c]}*{jac[j][c]}" for c in range(n)])

    for i in range(side):
        for j in range(i + 1):
            value = gram(i, j) + (" + lam" if i == j else "")
            value += "".join(f" - L{i}_{t}*L{j}_{t}" for t in range(j))
            if i == j:
                lines.append(f"L{i}_{i} = _sqrt({value})")
            else:
                lines.append(f"L{i}_{j} = ({value}) / L{j}_{j}")
    if n <= m:  # right-hand side Jᵀe
        rhs = [_sum([f"{jac[r][c]}*{rhs_e[r]}" for r in range(m)]) for c in range(n)]
    else:
        rhs = list(rhs_e)
    for i in range(side):  # L z = rhs
        value = f"({rhs[i]})" + "".join(f" - L{i}_{t}*fz{t}" for t in range(i))
        lines.append(f"fz{i} = ({value}) / L{i}_{i}")
    for i in reversed(range(side)):  # Lᵀ y = z
        value = f"fz{i}" + "".join(f" - L{t}_{i}*by{t}" for t in range(i + 1, side))
        lines.append(f"by{i} = ({value}) / L{i}_{i}")
    if n <= m:
        lines += [f"d{c} = by{c}" for c in range(n)]
    else:  # dx = Jᵀ y
        lines += [f"d{c} = {_sum([f'{jac[r][c]}*by{r}' for r in range(m)])}" for c in range(n)]
    return lines


def _clamp_lines(i: int, low: float, high: float, revolute: bool) -> list[str]:
    """w{i} = v{i} + d{i} into the limits: a revolute joint past one takes the
    same angle a turn away when that fits, else stops on it."""
    lo, hi, w = _literal(low), _literal(high), f"w{i}"
    lines = [f"{w} = v{i} + d{i}"]
    if revolute:
        lines += [
            f"if {w} > {hi}:",
            f"    t = {w} - _turn",
            f"    {w} = t if t >= {lo} else {hi}",
            f"    if {w} > {hi}: {w} = {hi}",
            f"elif {w} < {lo}:",
            f"    t = {w} + _turn",
            f"    {w} = t if t <= {hi} else {lo}",
            f"    if {w} < {lo}: {w} = {lo}",
        ]
    else:
        lines += [f"if {w} > {hi}: {w} = {hi}", f"elif {w} < {lo}: {w} = {lo}"]
    return lines


def descent_source(
    robot: Robot,
    *,
    position_only: bool,
    picked: Sequence[int],
    weights: Sequence[float],
    to_user: Sequence[float],
    low: Sequence[float],
    high: Sequence[float],
    revolute: Sequence[bool],
    scale: float,
    tolerances: tuple[float, float],
    stall: tuple[int, float, float],
    damping: float,
    fold: bool = True,
) -> str:
    """The source of ``descend(x, goal, max_iter, bias, give_up, free,
    checkpoint, limit) -> (x, error, iterations, converged)`` for the rows
    ``picked`` (weighted by ``weights``); see
    :func:`dhsim_tui.core.ik.numerical_descent.levenberg_marquardt`.

    ``x`` holds the joint values in internal units, ``goal`` the target's
    position (robot units) then its rotation's rows (9 floats); ``tolerances``
    are the squared position and orientation tolerances, ``stall`` the stall
    test's (window, gain, squared floor), ``damping`` the damping per
    squared error. ``fold``: constants folded in (:mod:`codegen_fold`); else
    the lines as they are, which :func:`compile_descent` falls back on when
    the folder cannot read the chain's lines."""
    n = robot.dof
    chain, column_lines, columns = jacobian_parts(robot, normalise=True, tool_rotation=False)
    v = [f"v{i}" for i in range(n)]
    ret = f"[{', '.join(v)}], [e0, e1, e2, e3, e4, e5]"
    failed = f"[{', '.join(v)}], [_inf, _inf, _inf, _inf, _inf, _inf], it, False"
    window, gain, floor = stall
    pos2, rot2 = tolerances
    # what the code around the folded lines reads keeps its name
    pinned = ["e0", "e1", "e2", "wx", "wy", "wz", "size", "cosine", "pos", "rot", "sq"]
    fold = Folder({*pinned, *(f"d{c}" for c in range(n))}, fold=fold)
    body = [
        f"{', '.join(v)}, = x" if n else "pass",
        "gx, gy, gz, g00, g01, g02, g10, g11, g12, g20, g21, g22 = goal",
        *_goal_lines(robot, fold),
        "window = _inf",
        "it = 0",
        "while True:",
    ]
    straight, branches = _rotation_lines(position_only)
    chain = _in_radians(chain, n)
    values = [f"q{i} = v{i}*{to_user[i]!r}" for i in range(n) if _reads(chain, f"q{i}")]
    loop = fold.lines(
        values + chain + [f"e{k} = (g{'xyz'[k]} - p{k}) / {scale!r}" for k in range(3)] + straight
    )
    names = [*_STATE9.split(", "), *_GOAL9]
    loop += [line.format(**{name: fold.ref(name) for name in names}) for line in branches]
    loop += fold.lines(_measure_lines(picked, weights))
    loop += [
        f"if pos <= {pos2!r} and rot <= {rot2!r}: return {ret}, it, True",
        f"if it == max_iter: return {ret}, it, False",
        f"if it == checkpoint and pos + rot > limit: return {ret}, it, False",
        f"if give_up and it % {window} == 0:",
        f"    if sq > {gain!r} * window and sq > {floor!r}: return {ret}, it, False",
        "    window = sq",
        f"lam = {damping!r} * sq + (sq if sq < bias else bias)",
        "try:",
    ]
    solve = list(column_lines)
    jac, rhs_e = [], []
    for r, weight in zip(picked, weights, strict=True):
        if weight == 1.0:
            jac.append([columns[c][r] for c in range(n)])
            rhs_e.append(f"e{r}")
        else:
            solve += [f"J{r}_{c} = {columns[c][r]}*{float(weight)!r}" for c in range(n)]
            jac.append([f"J{r}_{c}" for c in range(n)])
            rhs_e.append(f"e{r}w")
    solve += _solve_lines(jac, rhs_e, n)
    solve = fold.lines(solve)
    loop += [f"    {line}" for line in solve]
    loop += [
        "except (ValueError, ZeroDivisionError, OverflowError):",
        f"    return {ret}, it, False  # not finite any more: a degenerate arm",
        "if free:",
    ]
    loop += [f"    v{i} = v{i} + d{i}" for i in range(n)]
    total = " + ".join(v) or "0.0"
    loop += [f"    t = {total}", f"    if t - t != 0.0: return {failed}", "else:"]
    for i in range(n):
        loop += [f"    {line}" for line in _clamp_lines(i, low[i], high[i], revolute[i])]
    clamped = " + ".join(f"w{i}" for i in range(n)) or "0.0"
    loop += [f"    t = {clamped}", f"    if t != t: return {failed}"]  # nan: not finite
    loop += [f"    v{i} = w{i}" for i in range(n)]
    loop.append("it += 1")
    body += [f"    {line}" for line in loop]
    head = "def descend(x, goal, max_iter, bias, give_up, free, checkpoint=-1, limit=0.0):\n"
    return head + "".join(f"    {line}\n" for line in body)


def compile_to_user(
    name: str, to_internal: Sequence[float], lower: Sequence[float], upper: Sequence[float]
) -> Callable:
    """``f(x) -> tuple``: joint values from internal units to the robot's,
    within its limits (the way back may round a limit a digit past it), as
    ``min(max(v / k, lower), upper)`` joint by joint, written out."""
    n = len(to_internal)
    lines = [f"{', '.join(f'v{i}' for i in range(n))}, = x" if n else "pass"]
    values = []
    for i, (k, lo, hi) in enumerate(zip(to_internal, lower, upper, strict=True)):
        lo_, hi_ = _literal(lo), _literal(hi)
        lines.append(f"a{i} = v{i} / {k!r}")
        values.append(f"{lo_} if a{i} < {lo_} else ({hi_} if a{i} > {hi_} else a{i})")
    lines.append(f"return ({''.join(f'{v}, ' for v in values)})")
    source = "def to_user(x):\n" + "".join(f"    {line}\n" for line in lines)
    namespace: dict = {"_inf": math.inf}
    exec(compile(source, f"<dhsim to_user: {name}>", "exec"), namespace)
    return namespace["to_user"]


def _half_turn(goal: list[float], state: tuple[float, ...]) -> tuple[float, float, float]:
    """The rotation error near a half turn (rare): numpy's, warnings kept quiet."""
    with np.errstate(all="ignore"):
        return rotation_error_floats(goal, state)


def compile_descent(robot: Robot, **plan) -> Callable:
    """:func:`descent_source` compiled (same arguments), folded when the
    folder can read the chain's lines."""
    try:
        source = descent_source(robot, **plan)
    except ValueError:  # a line the folder cannot read: the same code, unfolded
        source = descent_source(robot, **{**plan, "fold": False})
    namespace: dict = {
        "_cos": math.cos,
        "_sin": math.sin,
        "_sqrt": math.sqrt,
        "_atan2": math.atan2,
        "_inf": math.inf,
        "_turn": 2 * math.pi,
        "_half_turn": _half_turn,
    }
    exec(compile(source, f"<dhsim descent: {robot.name}>", "exec"), namespace)
    return namespace["descend"]

"""A written-out Cholesky factorisation of the smaller Gram matrix (JᵀJ or
JJᵀ) of a small flat Jacobian, generated once per size: the square root of
its determinant (:func:`root_gram_det`, the manipulability), in plain Python
floats, without numpy's per-call overhead. (The IK's damped step, which also
factors a Gram matrix, is written into each robot's descent by
:mod:`dhsim_tui.core.ik.step_codegen`.)
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable


def _gram_cholesky_lines(m: int, n: int) -> tuple[list[str], int]:
    """Straight-line Cholesky factor L of the smaller Gram matrix of a flat m×n
    ``jac`` (JᵀJ when n <= m, else JJᵀ): lines defining ``L{i}_{j}``, and the
    matrix's side."""
    names = [[f"j{r}_{c}" for c in range(n)] for r in range(m)]
    lines = [f"{', '.join(name for row in names for name in row)}, = jac"] if m and n else []
    side = min(m, n)

    def gram(i: int, j: int) -> str:
        if n <= m:
            return " + ".join(f"{names[r][i]}*{names[r][j]}" for r in range(m))
        return " + ".join(f"{names[i][c]}*{names[j][c]}" for c in range(n))

    for i in range(side):
        for j in range(i + 1):
            value = gram(i, j)
            value += "".join(f" - L{i}_{t}*L{j}_{t}" for t in range(j))
            if i == j:
                lines.append(f"L{i}_{i} = _sqrt({value})")
            else:
                lines.append(f"L{i}_{j} = ({value}) / L{j}_{j}")
    return lines, side


def _generated(name: str, lines: list[str], arguments: str) -> Callable:
    source = f"def {name}({arguments}):\n" + "".join(f"    {line}\n" for line in lines)
    namespace: dict = {"_sqrt": math.sqrt}
    exec(compile(source, f"<dhsim {name}>", "exec"), namespace)
    return namespace[name]


@functools.lru_cache(maxsize=64)
def root_gram_det(m: int, n: int) -> Callable:
    """``f(jac) -> sqrt det`` of the smaller Gram matrix of a flat m×n ``jac``:
    the product of its singular values, 0.0 when it is singular."""
    lines, side = _gram_cholesky_lines(m, n)
    guarded = []
    for line in lines:  # a pivot that is not positive: singular (or rounding of it)
        if line.startswith("L") and "_sqrt(" in line:
            head, value = line.split(" = _sqrt(", 1)
            guarded += [f"d = {value[:-1]}", "if d <= 0.0: return 0.0", f"{head} = _sqrt(d)"]
        else:
            guarded.append(line)
    guarded.append("return " + ("*".join(f"L{i}_{i}" for i in range(side)) or "1.0"))
    return _generated("root_gram_det", guarded, "jac")

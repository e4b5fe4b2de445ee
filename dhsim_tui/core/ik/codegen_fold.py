"""Constant folding for generated straight-line float code
(:mod:`dhsim_tui.core.ik.step_codegen`).

The compiled chain starts from a constant frame, its first axis is constant,
a tool's constant rotation has zeros in it, a Jacobian has constant entries:
much of the arithmetic a generated loop would redo each iteration has a
known answer. :class:`Folder` reads the lines in order, keeps every variable
whose value is a constant as that constant (its assignment disappears), and
writes the rest with those constants put in and folded: ``0.0*a`` and
``a + 0.0`` go, ``1.0*a`` is ``a``, a product of constants is computed (by
the same float operation Python would do at run time, so the same bits).

It assumes finite values (``0.0*a`` is ``0.0``) and ignores the sign of a
zero; a line it cannot read (anything but assignments, ``+=`` and ``;``) is
an error, not a silent pass-through.
"""

from __future__ import annotations

import ast
import math

_FUNCTIONS = {"_cos": math.cos, "_sin": math.sin, "_sqrt": math.sqrt, "_atan2": math.atan2}
_OPERATIONS = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
}


def _value(node: ast.expr) -> float | None:
    """A constant's value, None for anything else."""
    if isinstance(node, ast.Constant) and isinstance(node.value, int | float):
        return float(node.value)
    return None


def _constant(value: float) -> ast.expr | None:
    """A constant node, or None when the value has no literal (inf, nan)."""
    if not math.isfinite(value):
        return None
    return ast.Constant(value)


def _negate(node: ast.expr) -> ast.expr:
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        return node.operand
    value = _value(node)
    if value is not None:
        return ast.Constant(-value)
    return ast.UnaryOp(ast.USub(), node)


_SYMBOLS = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/"}


def _source(node: ast.expr) -> str:
    """The source of a folded expression, every operation in parentheses (the
    same order of evaluation; several times faster than ``ast.unparse``)."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Constant):
        text = repr(node.value)
        return f"({text})" if text.startswith("-") else text
    if isinstance(node, ast.BinOp):
        return f"({_source(node.left)} {_SYMBOLS[type(node.op)]} {_source(node.right)})"
    if isinstance(node, ast.UnaryOp):  # a negation: the only one folded lines keep
        return f"(-{_source(node.operand)})"
    if isinstance(node, ast.Call):
        return f"{_source(node.func)}({', '.join(_source(a) for a in node.args)})"
    raise ValueError(f"cannot write {ast.dump(node)}")


def _negated(node: ast.expr) -> ast.expr | None:
    """The operand of a negation, else None."""
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        return node.operand
    return None


def _cheap(node: ast.expr) -> bool:
    """A value read where it is used rather than kept in a variable of its own:
    a constant, a variable or its negation."""
    inner = _negated(node)
    return isinstance(inner if inner is not None else node, ast.Name | ast.Constant)


class Folder:
    """Folds lines in order, as single assignments: each value a line computes
    gets a variable of its own (``name__k``), a copy or a negation is read
    where it is used (a swap of axes costs nothing, ``c*x + s*(-y)`` is
    ``c*x - s*y``), a constant is put in, and an expression already computed
    is read again. Names in ``pinned`` keep their own name, for code the
    folder does not read."""

    def __init__(self, pinned: set[str] | frozenset[str] = frozenset(), fold: bool = True) -> None:
        self.values: dict[str, ast.expr] = {}  # name -> its value now
        self.pinned = set(pinned)
        #: False: every line as it is (for lines it cannot read)
        self.fold = fold
        self._count = 0
        self._seen: dict[str, str] = {}

    def ref(self, name: str) -> str:
        """``name``'s value as later code should read it (an expression)."""
        value = self.values.get(name)
        return name if value is None else _source(value)

    def lines(self, lines: list[str]) -> list[str]:
        """``lines``, folded."""
        if not self.fold:
            return list(lines)
        self._seen = {}  # code between two calls may set the names it read
        out: list[str] = []
        for line in lines:
            for statement in ast.parse(line).body:
                out += self._statement(statement)
        return out

    def _statement(self, node: ast.stmt) -> list[str]:
        if isinstance(node, ast.AugAssign) and isinstance(node.target, ast.Name):
            target = ast.Name(node.target.id, ast.Load())
            value = ast.BinOp(target, node.op, node.value)
            return self._assign([node.target.id], [value])
        if not isinstance(node, ast.Assign):
            raise ValueError(f"cannot fold {ast.unparse(node)!r}")
        lines = []
        for target in node.targets:  # a = b = value: each in turn
            if isinstance(target, ast.Name):
                lines += self._assign([target.id], [node.value])
            elif (
                isinstance(target, ast.Tuple)
                and isinstance(node.value, ast.Tuple)
                and len(target.elts) == len(node.value.elts)
                and all(isinstance(t, ast.Name) for t in target.elts)
            ):
                lines += self._assign([t.id for t in target.elts], node.value.elts)
            else:
                raise ValueError(f"cannot fold {ast.unparse(node)!r}")
        return lines

    def _fresh(self, name: str) -> str:
        self._count += 1
        return f"{name}__{self._count}"

    def _assign(self, names: list[str], values: list[ast.expr]) -> list[str]:
        folded = [self.expression(v) for v in values]  # all read before any is set
        targets, texts = [], []
        for name, value in zip(names, folded, strict=True):
            if name in self.pinned:
                targets.append(name)
                texts.append(_source(value))
                self.values[name] = ast.Name(name, ast.Load())
                continue
            if _cheap(value):
                self.values[name] = value
                continue
            inner = _negated(value)
            text = _source(value if inner is None else inner)
            known = self._seen.get(text)
            if known is None:
                known = self._seen[text] = self._fresh(name)
                targets.append(known)
                texts.append(text)
            read = ast.Name(known, ast.Load())
            self.values[name] = read if inner is None else ast.UnaryOp(ast.USub(), read)
        if not targets:
            return []
        return [f"{', '.join(targets)} = {', '.join(texts)}"]

    def expression(self, node: ast.expr) -> ast.expr:
        """``node`` with the known values put in and folded."""
        if isinstance(node, ast.Name):
            return self.values.get(node.id, ast.Name(node.id, ast.Load()))
        if isinstance(node, ast.Constant):
            return node
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return _negate(self.expression(node.operand))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.UAdd):
            return self.expression(node.operand)
        if isinstance(node, ast.BinOp) and type(node.op) in _OPERATIONS:
            return self._binary(node.op, self.expression(node.left), self.expression(node.right))
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and not node.keywords:
            args = [self.expression(a) for a in node.args]
            values = [_value(a) for a in args]
            function = _FUNCTIONS.get(node.func.id)
            if function is not None and all(v is not None for v in values):
                try:
                    folded = _constant(function(*values))
                except (ValueError, ZeroDivisionError, OverflowError):
                    folded = None
                if folded is not None:
                    return folded
            return ast.Call(ast.Name(node.func.id, ast.Load()), args, [])
        raise ValueError(f"cannot fold {ast.unparse(node)!r}")

    @staticmethod
    def _binary(op: ast.operator, left: ast.expr, right: ast.expr) -> ast.expr:
        a, b = _value(left), _value(right)
        if a is not None and b is not None:
            try:
                folded = _constant(_OPERATIONS[type(op)](a, b))
            except (ZeroDivisionError, OverflowError):
                folded = None
            if folded is not None:
                return folded
            return ast.BinOp(left, op, right)
        minus_a, minus_b = _negated(left), _negated(right)
        if isinstance(op, ast.Mult | ast.Div):
            if isinstance(op, ast.Mult):
                if a == 0.0 or b == 0.0:
                    return ast.Constant(0.0)
                if a in (1.0, -1.0):
                    return right if a == 1.0 else _negate(right)
            if b in (1.0, -1.0):
                return left if b == 1.0 else _negate(left)
            if minus_a is not None or minus_b is not None:  # (-a)*b = -(a*b), exactly
                product = ast.BinOp(
                    left if minus_a is None else minus_a, op, right if minus_b is None else minus_b
                )
                return product if (minus_a is None) == (minus_b is None) else _negate(product)
            return ast.BinOp(left, op, right)
        if isinstance(op, ast.Sub):  # a - b = a + (-b), exactly
            right = _negate(right)
            b, minus_b = _value(right), _negated(right)
        if a == 0.0:
            return right
        if b == 0.0:
            return left
        if minus_a is not None and minus_b is not None:
            return _negate(ast.BinOp(minus_a, ast.Add(), minus_b))
        if minus_b is not None:
            return ast.BinOp(left, ast.Sub(), minus_b)
        if minus_a is not None:
            return ast.BinOp(right, ast.Sub(), minus_a)
        return ast.BinOp(left, ast.Add(), right)

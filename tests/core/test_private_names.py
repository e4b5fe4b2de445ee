"""No module imports another module's ``_private`` name (issue 28).

A name that crosses a module boundary is public (no leading underscore); a
module that only its package should use may itself be private. Checked with
``ast`` over every module under ``dhsim_tui/``: ``from X import _name``
(absolute or relative) and ``X._name`` where ``X`` is another dhsim_tui
module bound by an import.
"""

from __future__ import annotations

import ast
from pathlib import Path

import dhsim_tui

PACKAGE = Path(dhsim_tui.__file__).parent

#: (importing module, "defining.module._name") pairs that may cross; each
#: needs a reason. None today.
ALLOWED: dict[tuple[str, str], str] = {}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _source(module: str, is_package: bool, node: ast.ImportFrom) -> str | None:
    """The absolute module a ``from ... import`` names."""
    if node.level == 0:
        return node.module
    base = module.split(".")
    if not is_package:
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


MODULES = {_module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


def _crossings(module: str, text: str, is_package: bool = False) -> list[tuple[int, str]]:
    """(line, "defining.module._name") for each private name ``module``'s
    source ``text`` takes from another dhsim_tui module."""
    tree = ast.parse(text)
    bound: dict[str, str] = {}  # local name -> the dhsim_tui module it is
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "dhsim_tui":
                    bound[alias.asname or "dhsim_tui"] = alias.name if alias.asname else "dhsim_tui"
        elif isinstance(node, ast.ImportFrom):
            source = _source(module, is_package, node)
            if not source or source.split(".")[0] != "dhsim_tui":
                continue
            for alias in node.names:
                full = f"{source}.{alias.name}"
                if full in MODULES:
                    bound[alias.asname or alias.name] = full
                if _private(alias.name) and source != module:
                    found.append((node.lineno, full))
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Attribute) and _private(node.attr)):
            continue
        chain = []
        value = node.value
        while isinstance(value, ast.Attribute):
            chain.append(value.attr)
            value = value.value
        if not isinstance(value, ast.Name) or value.id not in bound:
            continue
        target = ".".join([bound[value.id], *reversed(chain)])
        if target in MODULES and target != module:
            found.append((node.lineno, f"{target}.{node.attr}"))
    return sorted(found)


def test_the_walk_sees_the_package():
    assert "dhsim_tui.core.model.kinematics" in MODULES
    assert len(MODULES) > 100


def test_the_walk_finds_each_kind_of_crossing():
    text = (
        "import dhsim_tui.core.model.robot\n"
        "from dhsim_tui.core.model.kinematics import _rotate, forward\n"
        "from .robot import _private_thing\n"
        "from . import kinematics as k\n"
        "from dhsim_tui.core.model import units\n"
        "k._matrix, units._DEG, dhsim_tui.core.model.robot._hidden, _own, self._x\n"
    )
    found = [name for _, name in _crossings("dhsim_tui.core.model.text", text)]
    assert found == [
        "dhsim_tui.core.model.kinematics._rotate",
        "dhsim_tui.core.model.robot._private_thing",
        "dhsim_tui.core.model.kinematics._matrix",
        "dhsim_tui.core.model.robot._hidden",
        "dhsim_tui.core.model.units._DEG",
    ]


def test_no_module_imports_another_modules_private_name():
    found = [
        f"{path.relative_to(PACKAGE.parent)}:{line}: {name}"
        for module, path in MODULES.items()
        for line, name in _crossings(
            module, path.read_text(encoding="utf-8"), path.name == "__init__.py"
        )
        if (module, name) not in ALLOWED
    ]
    assert not found, "private names imported across modules:\n" + "\n".join(found)


def test_the_allow_list_has_reasons():
    assert all(reason.strip() for reason in ALLOWED.values())

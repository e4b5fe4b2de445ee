"""The core never loads a UI library; the CLI's scripting commands don't either."""

from __future__ import annotations

import ast
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from waiting import HANG

PACKAGE = Path(__file__).resolve().parents[2] / "dhsim_tui"
UI_LIBRARIES = ("textual", "plotext", "rich")


def _loaded_after(code: str) -> set[str]:
    script = code + "\nimport sys\nprint(' '.join(sorted(sys.modules)))"
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    ).stdout
    return {name.split(".")[0] for name in out.split()}


def test_core_imports_no_ui_library():
    loaded = _loaded_after(
        "import dhsim_tui.core as c\n"
        "r, _ = c.load_robot('puma560')\n"
        "r.kinematics.end_effector(r.home)\n"
        "c.save(r, 'saved.toml')\n"  # in the test's own empty working folder
    )
    assert not loaded & set(UI_LIBRARIES), loaded & set(UI_LIBRARIES)


def test_scene_imports_no_ui_library():
    loaded = _loaded_after(
        "import dhsim_tui.core as c, dhsim_tui.scene as s\n"
        "from dhsim_tui.scene.raster import rasterize\n"
        "r, _ = c.load_robot('puma560')\n"
        "w = s.build_wireframe(r, r.kinematics.frames(r.home))\n"
        "rasterize(s.project(w, s.VIEWS[0]), 40, 20)\n"
    )
    assert not loaded & set(UI_LIBRARIES), loaded & set(UI_LIBRARIES)


@pytest.mark.parametrize(
    ("layer", "allowed"), [("core", ()), ("scene", ()), ("render", ("plotext",))]
)
def test_layer_source_has_no_ui_imports(layer, allowed):
    """core and scene import no UI library; render (pictures as plain data)
    may use plotext, but not textual or rich."""
    for path in (PACKAGE / layer).rglob("*.py"):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module]
            for name in names:
                top = name.split(".")[0]
                assert top not in UI_LIBRARIES or top in allowed, f"{path.name} imports {name}"


# -- the core's modules import each other as a tree ------------------------------------

CORE = PACKAGE / "core"
#: core modules that still import inside a function, each to be fixed by its owner
#: (file name -> why); an entry must go once its module imports at the top
FUNCTION_IMPORTS_TO_FIX: dict[str, str] = {}
#: imports inside a function that are there on purpose: modules the simulator's
#: first frame does not need, loaded at their first use (issue 27: the closed
#: forms and the IK's generated code cost the start ~20 ms). (file, module) pairs
LAZY_IMPORTS = {
    ("ik/solutions.py", "dhsim_tui.core.ik"),  # from it: analytic, the closed forms
    ("ik/numerical_problem.py", "dhsim_tui.core.ik.step_codegen"),
    ("ik/numerical_descent.py", "dhsim_tui.core.ik.step_codegen"),
}


def _function_imports(tree: ast.AST, lazy: frozenset[str] = frozenset()) -> list[tuple[str, int]]:
    """(function name, line) of every import statement inside a function body
    (but those of a module in ``lazy``)."""
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda):
            for inner in ast.walk(node):
                if isinstance(inner, ast.ImportFrom) and inner.module in lazy:
                    continue
                if isinstance(inner, ast.Import | ast.ImportFrom):
                    found.append((getattr(node, "name", "<lambda>"), inner.lineno))
    return found


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


#: the core's own ``__init__``, which re-exports the names most callers need
FACADE = "(core facade)"


def _core_name(module: str, alias: str | None = None) -> str:
    """The core module an import loads, relative to ``dhsim_tui.core``
    (``ik.analytic``), or "" when it is not in the core. ``from P import m``
    names the submodule ``P.m`` when there is one, else the package ``P``."""
    if module != "dhsim_tui.core" and not module.startswith("dhsim_tui.core."):
        return ""
    tail = module.removeprefix("dhsim_tui.core").removeprefix(".")
    if alias is not None:
        dotted = f"{tail}.{alias}" if tail else alias
        if (CORE / (dotted.replace(".", "/") + ".py")).exists():
            return dotted
    return tail or FACADE


def _runtime_core_imports(tree: ast.Module) -> set[str]:
    """The core modules a module imports when it runs (not under TYPE_CHECKING)."""
    names: set[str] = set()
    pending: list[ast.stmt] = list(tree.body)
    while pending:
        node = pending.pop()
        if isinstance(node, ast.If) and _is_type_checking(node):
            pending.extend(node.orelse)
            continue
        if isinstance(node, ast.If | ast.Try | ast.With):
            for part in ("body", "orelse", "finalbody", "handlers"):
                pending.extend(getattr(node, part, []))
            continue
        if isinstance(node, ast.ExceptHandler):
            pending.extend(node.body)
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.update(_core_name(node.module, alias.name) for alias in node.names)
        elif isinstance(node, ast.Import):
            names.update(_core_name(alias.name) for alias in node.names)
    return names


def _core_modules() -> dict[str, ast.Module]:
    """Every core module by its dotted name below the core (``model.units``);
    a subpackage's ``__init__`` by the subpackage's name (``ik``)."""
    modules = {}
    for path in sorted(CORE.rglob("*.py")):
        parts = path.relative_to(CORE).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        modules[name or FACADE] = ast.parse(path.read_text(encoding="utf-8"), str(path))
    return modules


def test_core_modules_import_at_the_top():
    offenders, fixed = [], []
    for path in sorted(CORE.rglob("*.py")):
        name = str(path.relative_to(CORE))
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        lazy = frozenset(module for file, module in LAZY_IMPORTS if file == name)
        found = [f"{name}:{line} in {func}()" for func, line in _function_imports(tree, lazy)]
        if name in FUNCTION_IMPORTS_TO_FIX:
            fixed += [] if found else [name]
        else:
            offenders += found
    assert not offenders, "imports inside functions (dodging a cycle?): " + ", ".join(offenders)
    assert not fixed, f"fixed, so remove from FUNCTION_IMPORTS_TO_FIX: {fixed}"


def test_function_import_detector_finds_one():
    # the detector itself: an import inside a method is found, one at the top is not
    source = "import os\nclass A:\n    def f(self):\n        from x import y\n        return y\n"
    assert _function_imports(ast.parse(source)) == [("f", 4)]


def test_core_import_graph_has_no_cycle():
    modules = _core_modules()
    assert {"model.units", "ik.numerical", "files.robotfile", "interop.urdf"} <= set(modules)
    graph = {name: _runtime_core_imports(tree) & set(modules) for name, tree in modules.items()}
    # validation needs only the leaf units module
    assert "model.robot" not in graph["model.validation"]
    assert graph["model.units"] == set()
    # depth-first search for a back edge
    state: dict[str, str] = {}

    def visit(name: str, trail: list[str]) -> None:
        state[name] = "open"
        for child in sorted(graph[name]):
            if state.get(child) == "open":
                cycle = [*trail[trail.index(child) :], child] if child in trail else [name, child]
                raise AssertionError("import cycle: " + " -> ".join(cycle))
            if child not in state:
                visit(child, [*trail, child])
        state[name] = "done"

    for name in sorted(graph):
        if name not in state:
            visit(name, [name])


def test_the_simulator_starts_without_the_importers_and_exporters():
    """``dhsim`` loads the CLI and the app; the URDF/CSV readers, the exporters
    and the D-H conversion load when a command or key first needs them (each
    is tested where it is used). So do the closed forms of the IK and its
    generated code (issue 27; loaded at the start from issue 20 on, ~20 ms):
    the first Cartesian jog, linear move or ``dhsim ik`` loads them, see
    :func:`test_the_closed_forms_load_at_the_first_pose_solved`."""
    script = (
        "import dhsim_tui.cli.main, dhsim_tui.tui.app\nimport sys\n"
        "print(' '.join(sorted(sys.modules)))"
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    ).stdout.split()
    later = {
        "dhsim_tui.core.interop.importer",
        "dhsim_tui.core.interop.urdf",
        "dhsim_tui.core.interop.csv_import",
        "dhsim_tui.core.interop.export",
        "dhsim_tui.core.interop.convert",
        "xml.etree.ElementTree",
        "csv",
    }
    assert not later & set(out), later & set(out)


#: the IK's closed forms (ik.analytic and what only it imports) and generated code
CLOSED_FORMS = {
    f"dhsim_tui.core.ik.{name}"
    for name in (
        "analytic",
        "geometry",
        "parallel",
        "planar",
        "right_angle_wrist",
        "subproblems",
        "vectors",
        "wrist",
        "step_codegen",
        "codegen_fold",
    )
}


def test_the_closed_forms_load_at_the_first_pose_solved():
    """The nearest solution, every solution and the numerical solver work as
    before, from a start that had not loaded the closed forms."""
    script = (
        "import sys, numpy as np\n"
        "import dhsim_tui.cli.main, dhsim_tui.tui.app\n"
        "from dhsim_tui.core import load_robot\n"
        "from dhsim_tui.core.ik.nearest import inverse\n"
        "from dhsim_tui.core.ik.solutions import all_solutions\n"
        "print(' '.join(sorted(sys.modules)))\n"
        "r, _ = load_robot('puma560')\n"
        "q = (10.0, -20.0, 30.0, 40.0, 50.0, 60.0)\n"
        "pose = r.kinematics.pose(q)\n"
        "near = inverse(r, pose, r.home)\n"
        "every = all_solutions(r, pose)\n"
        "panda, _ = load_robot('panda')\n"
        "numerical = inverse(panda, panda.kinematics.pose(panda.home), panda.home)\n"
        "print(' '.join(sorted(sys.modules)))\n"
        "print(near.success, near.iterations, every.method, len(every.solutions),\n"
        "      any(np.allclose(s.q, q) for s in every.solutions), numerical.success)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    ).stdout.splitlines()
    before, after, answers = set(out[0].split()), set(out[1].split()), out[2].split()
    assert not CLOSED_FORMS & before, CLOSED_FORMS & before
    assert after >= CLOSED_FORMS, CLOSED_FORMS - after
    success, iterations, method, count, found, numerical = answers
    assert (success, iterations) == ("True", "0")  # the closed form answered
    assert method != "numerical" and int(count) >= 2 and found == "True"
    assert numerical == "True"


# -- the layers as import-linter contracts (pyproject.toml) ------------------------------

ROOT = PACKAGE.parent


def _lint_imports(cwd: Path, package_parent: Path) -> subprocess.CompletedProcess[str]:
    lint = Path(sys.executable).with_name("lint-imports")
    env = {**os.environ, "PYTHONPATH": str(package_parent), "COLUMNS": "250"}
    return subprocess.run(
        # the contracts in cwd's pyproject.toml (import-linter 2.15, the last for
        # Python 3.10, takes no path; later ones read the same file by default)
        [str(lint), "--no-cache", "--no-logo"],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=2 * HANG,  # a hang guard only
    )


def test_the_import_linter_contracts_are_kept():
    result = _lint_imports(ROOT, ROOT)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "5 kept, 0 broken" in result.stdout


@pytest.mark.parametrize(
    ("module", "line", "contract"),
    [
        ("core/model/units.py", "import dhsim_tui.scene", "Each layer imports only"),
        ("core/model/units.py", "import dhsim_tui.core.ik.numerical", "Each core subpackage"),
        ("core/files/atomicfile.py", "import dhsim_tui.core.interop.urdf", "Each core subpackage"),
        ("scene/clip.py", "import textual", "never import a UI library"),
        ("render/ticks.py", "import rich", "render may use plotext"),
        ("terminal/sgr.py", "import numpy", "knows nothing of robots"),
    ],
)
def test_the_contracts_catch_an_import_against_the_layers(tmp_path, module, line, contract):
    """The same contracts on a copy of the package with one bad import added."""
    shutil.copytree(PACKAGE, tmp_path / "dhsim_tui", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    target = tmp_path / "dhsim_tui" / module
    target.write_text(target.read_text(encoding="utf-8") + f"\n{line}  # noqa\n", encoding="utf-8")
    result = _lint_imports(tmp_path, tmp_path)
    assert result.returncode != 0, result.stdout
    broken = [row for row in result.stdout.splitlines() if row.endswith(" BROKEN")]
    # one bad import can break more than one contract (through what it pulls in)
    assert any(contract in row for row in broken), result.stdout

"""The core never loads a UI library; the CLI's scripting commands don't either."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "dhsim_tui"
UI_LIBRARIES = ("textual", "textual_plotext", "plotext", "rich")


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
        "c.save(r, __import__('tempfile').mktemp(suffix='.toml'))\n"
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


@pytest.mark.parametrize("layer", ["core", "scene"])
def test_layer_source_has_no_ui_imports(layer):
    for path in (PACKAGE / layer).rglob("*.py"):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module]
            for name in names:
                assert name.split(".")[0] not in UI_LIBRARIES, f"{path.name} imports {name}"

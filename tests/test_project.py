"""Project hygiene: ruff is clean, and CI runs exactly the README's test command."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name
from packaging.version import Version

import dhsim_tui

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]


def readme_commands() -> list[str]:
    block = re.search(r"```sh\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    assert block, "README has no set-up block"
    return [line for line in block.group(1).splitlines() if line and not line.startswith("#")]


def test_readme_has_exactly_two_setup_commands_and_ci_runs_the_second():
    commands = readme_commands()
    assert len(commands) == 2
    assert commands[0].endswith("dhsim")
    assert commands[1] in (ROOT / ".ci" / "run").read_text().splitlines()


@pytest.mark.parametrize("args", [["check", "."], ["format", "--check", "."]])
def test_ruff_is_clean(args):
    result = subprocess.run(
        [sys.executable, "-m", "ruff", *args], cwd=ROOT, capture_output=True, text=True
    )
    assert result.returncode == 0, result.stdout + result.stderr


# -- the package's metadata (issue 27 §6) ----------------------------------------------------

PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
REPOSITORY = "https://github.com/dhsim/dhsim-tui"


def declared(*extras: str) -> list[Requirement]:
    """The requirements pyproject.toml declares (the runtime ones, and ``extras``'),
    those whose marker holds on this Python."""
    project = PROJECT["project"]
    texts = list(project["dependencies"])
    for extra in extras:
        texts += project["optional-dependencies"][extra]
    found = [Requirement(text) for text in texts]
    return [r for r in found if r.marker is None or r.marker.evaluate({"extra": ""})]


def test_the_license_is_mit_in_spdx_form_with_its_file():
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert text.startswith("MIT License\n") and "Copyright (c) 2026 dhsim developers" in text
    assert 'THE SOFTWARE IS PROVIDED "AS IS"' in text
    assert PROJECT["project"]["license"] == "MIT"
    assert PROJECT["project"]["license-files"] == ["LICENSE"]
    assert "LICENSE" in PROJECT["tool"]["hatch"]["build"]["targets"]["sdist"]["include"]
    # hatchling reads PEP 639's license expression and license-files from 1.27 on
    (backend,) = PROJECT["build-system"]["requires"]
    assert Requirement(backend).specifier.contains("1.27") and not Requirement(
        backend
    ).specifier.contains("1.26")


def test_the_package_is_typed_and_the_wheel_takes_the_marker():
    marker = Path(dhsim_tui.__file__).parent / "py.typed"
    assert marker.is_file() and marker.parent == ROOT / "dhsim_tui"
    wheel = PROJECT["tool"]["hatch"]["build"]["targets"]["wheel"]
    # the wheel is the whole package folder, nothing left out
    assert wheel["packages"] == ["dhsim_tui"] and "exclude" not in wheel
    assert "exclude" not in PROJECT["tool"]["hatch"].get("build", {})


def test_the_version_is_given_in_one_place():
    assert "version" not in PROJECT["project"] and "version" in PROJECT["project"]["dynamic"]
    assert PROJECT["tool"]["hatch"]["version"]["path"] == "dhsim_tui/__init__.py"
    Version(dhsim_tui.__version__)  # a valid version
    given = [
        path.relative_to(ROOT).as_posix()
        for path in (ROOT / "dhsim_tui").rglob("*.py")
        if re.search(r"^__version__\s*=", path.read_text(encoding="utf-8"), re.M)
    ]
    assert given == ["dhsim_tui/__init__.py"]
    assert metadata.version("dhsim-tui") == dhsim_tui.__version__  # what pip installed


def test_the_urls_point_at_the_repository():
    urls = PROJECT["project"]["urls"]
    assert set(urls) == {"Homepage", "Documentation", "Issues"}
    assert urls["Homepage"] == REPOSITORY and urls["Issues"] == f"{REPOSITORY}/issues"
    assert urls["Documentation"].startswith(f"{REPOSITORY}/")


def test_the_readme_image_works_on_pypi_too():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    images = re.findall(r"!\[([^\]]*)\]\(([^)\s]+)\)", readme)
    assert images, "README has no image"
    raw = "https://raw.githubusercontent.com/dhsim/dhsim-tui/main/"
    for alt, url in images:
        assert len(alt.split()) >= 3, f"{url}: alt text says what it shows"
        assert url.startswith(raw), f"{url}: a relative link breaks on PyPI"
        assert (ROOT / url.removeprefix(raw)).is_file(), url


@pytest.mark.parametrize("requirement", declared("test"), ids=str)
def test_every_declared_floor_holds_for_the_installed_package(requirement):
    installed = metadata.version(requirement.name)
    assert requirement.specifier.contains(installed, prereleases=True), (
        f"{requirement}: {installed} is installed"
    )


def _floor(requirement: Requirement) -> Version | None:
    floors = [Version(s.version) for s in requirement.specifier if s.operator in (">=", "==")]
    return max(floors, default=None)


def test_no_floor_is_below_what_a_dependency_itself_needs():
    # e.g. textual 8.2.8 needs rich>=14.2.0, so rich>=13 was not a true floor
    ours = {canonicalize_name(r.name): r for r in declared()}
    for requirement in ours.values():
        for text in metadata.requires(requirement.name) or ():
            needed = Requirement(text)
            if needed.marker is not None and not needed.marker.evaluate({"extra": ""}):
                continue
            mine = ours.get(canonicalize_name(needed.name))
            if mine is None or _floor(needed) is None:
                continue
            assert _floor(mine) is not None and _floor(mine) >= _floor(needed), (
                f"{requirement.name} needs {needed}; pyproject says {mine}"
            )


def _imported_by_the_tests() -> set[str]:
    names: set[str] = set()
    for path in (ROOT / "tests").rglob("*.py"):
        if "__snapshots__" in path.parts:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                names.update(alias.name.split(".")[0] for alias in node.names)
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module.split(".")[0])
    return {name for name in names if name not in sys.stdlib_module_names}


def test_every_installed_package_the_tests_import_is_declared_and_nothing_unused():
    distributions = metadata.packages_distributions()
    wanted = {canonicalize_name(r.name) for r in declared("test")}
    imported = set()
    for name in _imported_by_the_tests():
        for distribution in distributions.get(name, ()):  # not installed: an optional tool
            imported.add(canonicalize_name(distribution))
    undeclared = imported - wanted - {canonicalize_name("dhsim-tui")}
    assert not undeclared, f"the tests import {sorted(undeclared)}: declare them in [test]"
    assert "ptyprocess" in wanted and "pexpect" not in wanted

"""Robot files with programs at the command line (issue 19): they load for
every command, a bad step is one line on stderr and exit status 2, and a
file the command line writes (``dhsim convert``) keeps the programs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dhsim_tui.cli.main import main
from dhsim_tui.core.files.library import load_robot
from dhsim_tui.core.files.robotfile import load

PUMA_FILE = Path(__file__).resolve().parents[2] / "robots" / "puma560.toml"


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def puma_with_step(tmp_path: Path, step: str, number: int = 3) -> Path:
    """The bundled Puma's file with its demo's step ``number`` replaced."""
    lines = PUMA_FILE.read_text(encoding="utf-8").splitlines(keepends=True)
    first = lines.index("demo = [\n") + 1
    lines[first + number - 1] = f"  {step},\n"
    path = tmp_path / "arm.toml"
    path.write_text("".join(lines), encoding="utf-8")
    return path


def test_check_and_fk_read_a_file_with_programs(capsys, tmp_path):
    path = puma_with_step(tmp_path, '{ move = "linear", to = "qn", speed = 100 }')
    code, out, err = run(capsys, "check", str(path))
    assert (code, err) == (0, "")
    assert out.startswith("ok  Puma 560: 6 joints")
    code, out, err = run(capsys, "fk", str(path), "--pose", "qn")
    assert code == 0 and "596.30" in out


@pytest.mark.parametrize(
    ("step", "number", "shown"),
    [
        ('{ move = "joint", to = "qm" }', 1, "programs.demo, step 1, to: no pose named 'qm'"),
        ("{ wait = 0.5, speed = 1 }", 3, "programs.demo, step 3, speed: a wait has no 'speed'"),
        ('{ move = "linear", to = [0, 45] }', 2, "programs.demo, step 2, to: expected 6 joint"),
        ('{ move = "linear", to = "qn", speed = -1 }', 4, "programs.demo, step 4, speed: speed"),
        ('{ move = "slide", to = "qn" }', 5, "programs.demo, step 5, move: the text 'slide'"),
    ],
)
def test_a_bad_step_is_one_line_and_status_2(capsys, tmp_path, step, number, shown):
    path = puma_with_step(tmp_path, step, number)
    for command in ("check", "fk"):
        code, out, err = run(capsys, command, str(path))
        assert (code, out) == (2, "")
        assert err.startswith(f"dhsim: error: {path}: {shown}")
        assert err.count("\n") == 1


def test_convert_keeps_the_programs_and_their_tool_poses(capsys, tmp_path):
    target = tmp_path / "modified.toml"
    argv = ("convert", "puma560", "--convention", "modified", "-o", str(target))
    code, _out, err = run(capsys, *argv)
    assert code == 0, err
    puma, converted = load_robot("puma560")[0], load(target)
    assert converted.convention == "modified"
    assert converted.programs == puma.programs
    for step in puma.program("demo").steps:  # each move's target is the same tool pose
        if not step.is_wait:
            q = puma.pose(step.to) if isinstance(step.to, str) else step.to
            assert np.allclose(converted.kinematics.pose(q), puma.kinematics.pose(q), atol=1e-6)

"""Saving a robot whose programs changed keeps the user's words (issue 19):
a line diff of the file before and after shows that only the lines of the
steps and programs that changed are touched, and every comment elsewhere,
and on unchanged programs, stays."""

from __future__ import annotations

import difflib
from dataclasses import replace
from pathlib import Path

import pytest

from dhsim_tui.core.files.robotfile import load, loads, save
from dhsim_tui.core.files.tomlparse import tomllib
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.program import Program, Step

ROBOTS_DIR = Path(__file__).resolve().parents[2] / "robots"

COMMENTED = """\
# Lab arm, with two programs (keep these notes)
name = "Lab arm"   # the students' name for it
units = "mm"

[poses]
ready = [0.0, 90, 100.0]   # ready to pick
low   = [10.0, -45.0, 0.0]

# what the arm does at the open day
[programs]
# the demo, as in the issue
demo = [
  { move = "joint", to = "ready" },                 # to a named pose
  { move = "linear", to = "low", speed = 250 },     # a straight line
  { move = "joint", to = [0, 45, 50], speed = 50 }, # half speed
  { wait = 0.5 },                                   # seconds
]
# a short one
nod = [{ move = "joint", to = "low" }, { wait = 1 }]   # one line

# ---- the joints ----
[[joints]]
theta = 0.0
d     = 300      # column height
a     = 0.0
alpha = 90.0
min = -170.0     # cable limit
max = 170.0

[[joints]]
theta = 0.0
d = 0.0
a = 400.0        # upper arm
alpha = 0.0
min = -90.0
max = 135.0

# quill (prismatic)
[[joints]]
type = "prismatic"
theta = 0.0
d = 100.0
a = 0.0
alpha = 0.0
min = 0.0
max = 200.0
"""


def edited(tmp_path: Path, text: str, edit) -> tuple[str, list[str], list[str]]:
    """Write ``text``, load it, apply ``edit``, save over it: the new text and
    the removed and added lines of a line diff."""
    path = tmp_path / "arm.toml"
    path.write_text(text, encoding="utf-8")
    robot = edit(load(path))
    save(robot, path)
    assert load(path) == robot
    new = path.read_text(encoding="utf-8")
    diff = list(difflib.ndiff(text.splitlines(), new.splitlines()))
    removed = [line[2:] for line in diff if line.startswith("- ")]
    added = [line[2:] for line in diff if line.startswith("+ ")]
    return new, removed, added


def comments(text: str) -> list[str]:
    return [line[line.index("#") :].strip() for line in text.splitlines() if "#" in line]


def with_steps(robot, name: str, steps) -> object:
    return editing.set_program(robot, Program(name, tuple(steps)))


def demo_steps(robot) -> list[Step]:
    return list(robot.program("demo").steps)


def test_adding_a_program_adds_its_lines_and_nothing_else(tmp_path):
    new, removed, added = edited(
        tmp_path,
        COMMENTED,
        lambda r: with_steps(r, "pick", [Step("joint", "low"), Step("wait", seconds=2.0)]),
    )
    assert removed == []
    assert added == [
        "pick = [",
        '  { move = "joint", to = "low" },',
        "  { wait = 2.0 },",
        "]",
    ]
    assert comments(new) == comments(COMMENTED)


def test_changing_a_step_rewrites_its_line_and_keeps_its_comment(tmp_path):
    def edit(robot):
        steps = demo_steps(robot)
        steps[1] = Step("linear", "low", 100.0)
        return with_steps(robot, "demo", steps)

    new, removed, added = edited(tmp_path, COMMENTED, edit)
    assert removed == ['  { move = "linear", to = "low", speed = 250 },     # a straight line']
    assert added == ['  { move = "linear", to = "low", speed = 100.0 },     # a straight line']
    assert comments(new) == comments(COMMENTED)


def test_a_step_that_changes_kind_rewrites_its_line_only(tmp_path):
    def edit(robot):
        steps = demo_steps(robot)
        steps[3] = Step("linear", (5.0, 6.0, 7.0), 20.0)  # a wait becomes a move
        steps[0] = Step("wait", seconds=3.0)  # and a move a wait
        return with_steps(robot, "demo", steps)

    new, removed, added = edited(tmp_path, COMMENTED, edit)
    assert len(removed) == len(added) == 2
    assert "  { wait = 3.0 },                 # to a named pose" in added
    assert '  { move = "linear", to = [5.0, 6.0, 7.0], speed = 20.0 },' in " ".join(added)
    assert comments(new) == comments(COMMENTED)


def test_inserting_and_deleting_steps_touch_only_their_lines(tmp_path):
    def insert(robot):
        steps = demo_steps(robot)
        steps.insert(2, Step("wait", seconds=1.5))
        return with_steps(robot, "demo", steps)

    new, removed, added = edited(tmp_path, COMMENTED, insert)
    assert (removed, added) == ([], ["  { wait = 1.5 },"])
    assert new.index("a straight line") < new.index("wait = 1.5") < new.index("half speed")

    def delete(robot):
        steps = demo_steps(robot)
        del steps[2]
        return with_steps(robot, "demo", steps)

    new, removed, added = edited(tmp_path, COMMENTED, delete)
    assert removed == ['  { move = "joint", to = [0, 45, 50], speed = 50 }, # half speed']
    assert added == []
    assert "# half speed" not in new
    assert comments(new) == [c for c in comments(COMMENTED) if c != "# half speed"]


def test_a_change_in_one_program_leaves_the_other_as_written(tmp_path):
    def edit(robot):
        return with_steps(robot, "nod", [Step("joint", "low"), Step("wait", seconds=4.0)])

    new, removed, added = edited(tmp_path, COMMENTED, edit)
    assert removed == ['nod = [{ move = "joint", to = "low" }, { wait = 1 }]   # one line']
    assert added == ['nod = [{ move = "joint", to = "low" }, { wait = 4.0 }]   # one line']
    demo = COMMENTED[COMMENTED.index("demo = [") : COMMENTED.index("# a short one")]
    assert demo in new  # the unchanged program, byte for byte, comments and all


def test_deleting_a_program_keeps_the_comments_around_it(tmp_path):
    new, removed, added = edited(tmp_path, COMMENTED, lambda r: editing.delete_program(r, "demo"))
    assert added == []
    assert removed == COMMENTED[COMMENTED.index("demo = [") :].splitlines()[:6]
    for comment in ("# what the arm does at the open day", "# a short one", "# one line"):
        assert comment in new


def test_emptying_and_reordering_programs(tmp_path):
    new, removed, added = edited(tmp_path, COMMENTED, lambda r: with_steps(r, "nod", []))
    assert removed == ['nod = [{ move = "joint", to = "low" }, { wait = 1 }]   # one line']
    assert added == ["nod = []   # one line"]

    def swap(robot):
        return replace(robot, programs=robot.programs[::-1])

    new, removed, added = edited(tmp_path, COMMENTED, swap)
    assert sorted(comments(new)) == sorted(comments(COMMENTED))
    assert new.index("nod = [") < new.index("demo = [")


def test_a_file_without_programs_gets_its_table_before_the_joints(tmp_path):
    start, end = COMMENTED.index("# what the arm"), COMMENTED.index("# ---- the joints")
    plain = COMMENTED[:start] + COMMENTED[end:]
    new, removed, added = edited(
        tmp_path, plain, lambda r: with_steps(r, "first", [Step("joint", "ready", 10.0)])
    )
    assert removed == []
    assert [line for line in added if line] == [
        "[programs]",
        "first = [",
        '  { move = "joint", to = "ready", speed = 10.0 },',
        "]",
    ]
    assert new.index("[programs]") < new.index("# ---- the joints") < new.index("[[joints]]")
    assert comments(new) == comments(plain)


def test_a_top_speed_is_one_line_added_or_removed(tmp_path):
    def fast(robot):
        joints = list(robot.joints)
        joints[1] = replace(joints[1], vmax=120.0)
        return replace(robot, joints=tuple(joints))

    new, removed, added = edited(tmp_path, COMMENTED, fast)
    assert (removed, added) == ([], ["vmax = 120.0"])
    assert new.index("upper arm") < new.index("vmax = 120.0") < new.index("# quill")
    assert loads(new).joints[1].vmax == 120.0

    def default(robot):
        joints = list(robot.joints)
        joints[1] = replace(joints[1], vmax=None)
        return replace(robot, joints=tuple(joints))

    again, removed, added = edited(tmp_path, new, default)
    assert (removed, added) == (["vmax = 120.0"], [])
    assert again == COMMENTED


def test_inserting_a_joint_changes_only_the_programs_own_joint_values(tmp_path):
    new, removed, added = edited(tmp_path, COMMENTED, lambda r: editing.insert_joint(r, 0))
    program_lines = [line for line in removed if "move" in line]
    assert program_lines == ['  { move = "joint", to = [0, 45, 50], speed = 50 }, # half speed']
    (line,) = [line for line in added if "move" in line]
    assert line.endswith("}, # half speed")
    step = tomllib.loads("x = " + line[: line.rindex(",")])["x"]
    assert step == {"move": "joint", "to": [0, 0, 45, 50], "speed": 50}
    assert comments(new) == comments(COMMENTED)


def test_steps_written_as_tables_of_an_array_are_edited_in_place(tmp_path):
    text = (
        'name = "aot"\n\n'
        "# program notes\n"
        '[[programs.go]]\nmove = "joint"   # first\nto = [10.0]\n\n'
        "[[programs.go]]\nwait = 1.0   # pause\n\n"
        "[[joints]]\ntheta = 0.0\nd = 0.0\na = 100.0\nalpha = 0.0\n"
    )

    def edit(robot):
        steps = list(robot.program("go").steps)
        steps[0] = Step("joint", (20.0,))
        return with_steps(robot, "go", steps)

    new, removed, added = edited(tmp_path, text, edit)
    assert (removed, added) == (["to = [10.0]"], ["to = [20.0]"])
    assert comments(new) == comments(text)


def test_the_bundled_demo_takes_a_new_step_as_one_line(tmp_path):
    original = (ROBOTS_DIR / "puma560.toml").read_text(encoding="utf-8")

    def edit(robot):
        steps = demo_steps(robot)
        return with_steps(robot, "demo", [*steps, Step("wait", seconds=1.0)])

    new, removed, added = edited(tmp_path, original, edit)
    assert (removed, added) == ([], ["  { wait = 1.0 },"])
    assert comments(new) == comments(original)


JOINT = "\n# the joint\n[[joints]]\ntheta = 0.0\nd = 0.0\na = 100.0\nalpha = 0.0\n"
#: the ways TOML can hold the same [programs] table, each with whole-line comments
LAYOUTS = {
    "table": '# top\nname = "x"\n\n# programs\n[programs]\ngo = [\n  { wait = 1 },\n]\n',
    "dotted": '# top\nname = "x"\n# programs\nprograms.go = [{ wait = 1 }]  # dotted\n',
    "inline": '# top\nname = "x"\n# programs\nprograms = { go = [{ wait = 1 }] }  # inline\n',
    "tables": '# top\nname = "x"\n\n# programs\n[[programs.go]]\nwait = 1.0  # w\n',
    "two tables": (
        '# top\nname = "x"\n\n# programs\n[[programs.go]]\nwait = 1.0  # w\n\n'
        "# second\n[[programs.b]]\nwait = 2.0\n"
    ),
    "header and tables": (
        '# top\nname = "x"\n\n[programs]\n# programs\n[[programs.go]]\nwait = 1.0  # w\n'
    ),
}
PROGRAM_EDITS = {
    "add": lambda r: with_steps(r, "new", [Step("joint", (5.0,)), Step("wait", seconds=2.0)]),
    "change": lambda r: with_steps(r, "go", [Step("wait", seconds=3.0)]),
    "insert": lambda r: with_steps(r, "go", [Step("joint", (1.0,)), *r.program("go").steps]),
    "delete": lambda r: editing.delete_program(r, "go"),
    "empty": lambda r: with_steps(r, "go", []),
}


@pytest.mark.parametrize("edit", PROGRAM_EDITS)
@pytest.mark.parametrize("layout", LAYOUTS)
def test_every_layout_of_programs_keeps_its_comments(tmp_path, layout, edit):
    text = LAYOUTS[layout] + JOINT
    new, _removed, _added = edited(tmp_path, text, PROGRAM_EDITS[edit])
    whole_line = [line for line in text.splitlines() if line.startswith("#")]
    assert [line for line in new.splitlines() if line.startswith("#")] == whole_line

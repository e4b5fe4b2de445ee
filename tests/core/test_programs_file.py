"""Programs and joint top speeds in robot files (issue 19): the ``[programs]``
table read strictly (every mistake named by program, step and field), written
one step a line, round trips on every bundled robot, and recovery files that
keep them.

The files read here are literal TOML text, and what ``dumps`` writes is read
back with Python's own TOML parser too, so a writer bug cannot hide a reader
bug.
"""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dhsim_tui.core.files import recovery
from dhsim_tui.core.files.library import bundled_names, load_robot
from dhsim_tui.core.files.robotfile import dumps, load, loads, save
from dhsim_tui.core.files.tomlparse import tomllib
from dhsim_tui.core.model.errors import DhsimError, RobotFileError
from dhsim_tui.core.model.program import Program, Step
from dhsim_tui.core.model.text import control_character

DOCS = Path(__file__).resolve().parents[2] / "docs" / "file-format.md"

#: a three-joint arm (R, R, P) with two poses and the issue's four kinds of step
ARM = """\
name = "Test arm"
units = "mm"

[poses]
ready = [0.0, 90.0, 100.0]
low = [10.0, -45.0, 0.0]

[programs]
demo = [
  { move = "joint", to = "ready" },
  { move = "linear", to = "low", speed = 250 },
  { move = "joint", to = [0, 45, 50], speed = 50 },
  { wait = 0.5 },
]

[[joints]]
theta = 0.0
d = 300.0
a = 0.0
alpha = 90.0
min = -170.0
max = 170.0

[[joints]]
theta = 0.0
d = 0.0
a = 400.0
alpha = 0.0
min = -90.0
max = 135.0
vmax = 45
amax = 180.5

[[joints]]
type = "prismatic"
theta = 0.0
d = 100.0
a = 0.0
alpha = 0.0
min = 0.0
max = 200.0
"""

DEMO_STEPS = (
    Step("joint", "ready"),
    Step("linear", "low", 250.0),
    Step("joint", (0.0, 45.0, 50.0), 50.0),
    Step("wait", seconds=0.5),
)


def with_step(text: str, step: str, number: int = 3) -> str:
    """``ARM`` with its demo's step ``number`` (1 to 4) replaced by ``step``."""
    lines = text.splitlines(keepends=True)
    first = lines.index("demo = [\n") + 1
    lines[first + number - 1] = f"  {step},\n"
    return "".join(lines)


def load_error(tmp_path: Path, text: str) -> str:
    path = tmp_path / "arm.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(RobotFileError) as info:
        load(path)
    message = str(info.value)
    assert message.startswith(f"{path}: ")
    assert "\n" not in message
    return message.removeprefix(f"{path}: ")


# -- reading -----------------------------------------------------------------------


def test_the_issues_program_loads_as_written():
    robot = loads(ARM)
    assert robot.program_names == ("demo",)
    assert robot.program("demo") == Program("demo", DEMO_STEPS)
    assert [(j.vmax, j.amax) for j in robot.joints] == [(None, None), (45.0, 180.5), (None, None)]


def test_steps_written_as_tables_of_an_array_mean_the_same():
    text = ARM.replace(
        ARM[ARM.index("[programs]") : ARM.index("[[joints]]")],
        '[[programs.demo]]\nmove = "joint"\nto = "ready"\n\n'
        '[[programs.demo]]\nmove = "linear"\nto = "low"\nspeed = 250\n\n'
        '[[programs.demo]]\nmove = "joint"\nto = [0, 45, 50]\nspeed = 50\n\n'
        "[[programs.demo]]\nwait = 0.5\n\n",
    )
    assert loads(text) == loads(ARM)


def test_a_file_without_programs_has_none_and_an_empty_program_is_kept():
    plain = ARM.replace(ARM[ARM.index("[programs]") : ARM.index("[[joints]]")], "")
    assert loads(plain).programs == ()
    empty = ARM.replace("demo = [", "idle = []\ndemo = [")
    assert loads(empty).programs == (Program("idle", ()), Program("demo", DEMO_STEPS))


# -- every mistake names the program, the step and the field -----------------------------

STEP_ERRORS = [
    # (step 3 replaced by, the message after the file name)
    (
        '{ move = "joint", to = "ready", sped = 50 }',
        "programs.demo, step 3, sped: unknown key (did you mean 'speed'?)",
    ),
    ('{ move = "joint", to = "ready", colour = 1 }', "programs.demo, step 3, colour: unknown key"),
    ('{ move = "joint", to = "redy" }', "programs.demo, step 3, to: no pose named 'redy'"),
    (
        '{ move = "joint", to = [0, 45] }',
        "programs.demo, step 3, to: expected 3 joint values (Th1, Th2, d3), got 2",
    ),
    (
        '{ move = "joint", to = [0, 45, 500] }',
        "programs.demo, step 3, to: d3 = 500 mm is outside its limits 0..200 mm",
    ),
    (
        '{ move = "joint", to = [0, "45", 50] }',
        "programs.demo, step 3, to[2]: expected a number, got the text '45'",
    ),
    (
        '{ move = "joint", to = 45 }',
        "programs.demo, step 3, to: expected a pose name in quotes or a list of joint values",
    ),
    (
        '{ move = "linear", to = "low", speed = -5 }',
        "programs.demo, step 3, speed: speed must be greater than 0, not -5",
    ),
    (
        '{ move = "linear", to = "low", speed = 0 }',
        "programs.demo, step 3, speed: speed must be greater than 0, not 0",
    ),
    (
        '{ move = "joint", to = "low", speed = 101 }',
        "programs.demo, step 3, speed: a joint move's speed is a percentage",
    ),
    (
        '{ move = "joint", to = "low", speed = "fast" }',
        "programs.demo, step 3, speed: expected a number, got the text 'fast'",
    ),
    (
        '{ move = "joint", to = "low", speed = nan }',
        "programs.demo, step 3, speed: NaN is not a number",
    ),
    (
        '{ move = "jump", to = "low" }',
        "programs.demo, step 3, move: the text 'jump' is not a move; a move is 'joint' or 'linear'",
    ),
    ('{ move = "jiont", to = "low" }', "programs.demo, step 3, move: the text 'jiont' is not a"),
    ('{ move = 1, to = "low" }', "programs.demo, step 3, move: the number 1 is not a move"),
    ('{ move = "wait", to = "low" }', "(a wait is written { wait = <seconds> })"),
    ('{ to = "low" }', "programs.demo, step 3, move: missing; a step is"),
    ('{ move = "linear" }', "programs.demo, step 3, to: missing; a step is"),
    ("{ wait = -1 }", "programs.demo, step 3, wait: -1 s is outside 0..3600 s"),
    ("{ wait = 3601 }", "programs.demo, step 3, wait: 3601 s is outside 0..3600 s"),
    ("{ wait = true }", "programs.demo, step 3, wait: expected a number, got the boolean true"),
    (
        '{ wait = 1, move = "joint" }',
        "programs.demo, step 3, move: a wait has no 'move'; a step is a move or a wait, not both",
    ),
    ("{ wiat = 1 }", "programs.demo, step 3, wiat: unknown key (did you mean 'wait'?)"),
    ('"ready"', "programs.demo, step 3: expected a step, { move ="),
    ("{}", "programs.demo, step 3, move: missing"),
]


@pytest.mark.parametrize(("step", "shown"), STEP_ERRORS, ids=[s for s, _ in STEP_ERRORS])
def test_a_bad_step_is_one_message_naming_program_step_and_field(tmp_path, step, shown):
    message = load_error(tmp_path, with_step(ARM, step))
    assert message.startswith("programs.demo, step 3")
    assert shown in message


def test_the_step_is_counted_from_one_wherever_it_is(tmp_path):
    for number in (1, 2, 4):
        message = load_error(tmp_path, with_step(ARM, '{ move = "joint", to = "nowhere" }', number))
        assert message.startswith(f"programs.demo, step {number}, to: no pose named 'nowhere'")


def test_the_program_is_named_when_another_one_is_wrong(tmp_path):
    text = ARM.replace(
        "demo = [", 'good = [{ wait = 1 }]\n"pick up" = [{ wait = 2, to = "x" }]\ndemo = [', 1
    )
    message = load_error(tmp_path, text)
    assert message.startswith("programs.pick up, step 1, to: a wait has no 'to'")


@pytest.mark.parametrize(
    ("programs", "shown"),
    [
        ("demo = 5", "programs.demo: expected an array of steps, like [{ move"),
        ("demo = { move = 1 }", "programs.demo: expected an array of steps"),
        ('"\\u001b[2J" = []', "programs.\\x1b[2J: a program name may not hold control characters"),
        ('"" = []', "programs: a program needs a non-empty name"),
        (f'"{"x" * 1001}" = []', "a program name has at most 1000 characters"),
    ],
)
def test_a_bad_program_is_named(tmp_path, programs, shown):
    text = ARM.replace("demo = [", f"{programs}\nother = [", 1)
    message = load_error(tmp_path, text)
    assert shown in message
    assert control_character(message) is None


def test_a_programs_key_that_is_not_a_table_is_refused(tmp_path):
    text = ARM.replace(ARM[ARM.index("[programs]") : ARM.index("[[joints]]")], "")
    text = text.replace('units = "mm"\n', 'units = "mm"\nprograms = 3\n')
    assert load_error(tmp_path, text).startswith("programs: expected a table of programs")


def test_a_misspelt_programs_table_is_an_unknown_key(tmp_path):
    message = load_error(tmp_path, ARM.replace("[programs]", "[program]"))
    assert message == "program: unknown key (did you mean 'programs'?)"


@pytest.mark.parametrize(
    ("line", "shown"),
    [
        ("vmax = -1", "joints[1].vmax: must be greater than 0 deg/s, not -1"),
        ("vmax = 0", "joints[1].vmax: must be greater than 0 deg/s, not 0"),
        ("amax = -2", "joints[1].amax: must be greater than 0 deg/s², not -2"),
        ('vmax = "fast"', "joints[1].vmax: expected a number, got the text 'fast'"),
        ("vmax = inf", "joints[1].vmax: inf is out of range"),
        ("vmx = 1", "joints[1].vmx: unknown key (did you mean 'vmax'?)"),
        ("amx = 1", "joints[1].amx: unknown key (did you mean 'amax'?)"),
    ],
)
def test_bad_joint_top_speeds_are_named(tmp_path, line, shown):
    text = ARM.replace("min = -170.0\n", f"min = -170.0\n{line}\n", 1)
    assert load_error(tmp_path, text).startswith(shown)


def test_a_prismatic_joints_top_speed_is_in_the_robots_unit(tmp_path):
    text = ARM.replace("max = 200.0\n", "max = 200.0\nvmax = -1\n")
    assert load_error(tmp_path, text) == "joints[3].vmax: must be greater than 0 mm/s, not -1"


def test_the_messages_quoted_in_the_docs_are_the_real_ones(tmp_path):
    """docs/file-format.md shows messages for the Puma; each is produced here."""
    puma = (Path(__file__).resolve().parents[2] / "robots" / "puma560.toml").read_text()
    start = puma.index("demo = [")
    end = puma.index("]\n", puma.index("demo = [")) + 2

    def message(*steps: str) -> str:
        text = puma[:start] + "demo = [\n" + "".join(f"  {s},\n" for s in steps) + "]\n"
        return load_error(tmp_path, text + puma[end:])

    ok, wait = '{ move = "joint", to = "qn" }', "{ wait = 1 }"
    produced = [
        message(ok, '{ move = "linear", to = "qn", spede = 3 }'),
        message('{ move = "joint", to = "redy" }'),
        message(ok, ok, '{ move = "joint", to = [0, 45, -90, 0, 45] }'),
        message(ok, ok, '{ move = "joint", to = [0, 250, -90, 0, 45, 0] }'),
        message(ok, '{ move = "linear", to = "qn", speed = -5 }'),
        message(ok, ok, '{ move = "joint", to = "qn", speed = 150 }'),
        message('{ move = "jump", to = "qn" }'),
        message(ok, wait, ok, "{ wait = -1 }"),
    ]
    docs = DOCS.read_text(encoding="utf-8")
    quoted = re.findall(r"^arm\.toml: (programs\..*)$", docs, flags=re.MULTILINE)
    assert quoted == produced


# -- writing -----------------------------------------------------------------------


def test_dumps_writes_each_step_on_its_line_before_the_joints():
    robot = loads(ARM)
    text = dumps(robot)
    section = text[text.index("[programs]") : text.index("[[joints]]")]
    assert section == (
        "[programs]\n"
        "demo = [\n"
        '  { move = "joint", to = "ready" },\n'
        '  { move = "linear", to = "low", speed = 250.0 },\n'
        '  { move = "joint", to = [0.0, 45.0, 50.0], speed = 50.0 },\n'
        "  { wait = 0.5 },\n"
        "]\n\n"
    )
    assert text.index("[poses]") < text.index("[programs]")
    joints = tomllib.loads(text)["joints"]
    assert [(j.get("vmax"), j.get("amax")) for j in joints] == [
        (None, None),
        (45.0, 180.5),
        (None, None),
    ]


def test_dumps_writes_no_programs_table_for_a_robot_without_programs():
    robot = replace(loads(ARM), programs=())
    assert "programs" not in dumps(robot)
    assert "programs" not in tomllib.loads(dumps(robot))


def test_dumps_quotes_a_program_name_that_is_not_a_bare_word():
    odd = 'pick "and" place é'
    robot = replace(loads(ARM), programs=(Program(odd, (Step("wait", seconds=1.0),)),))
    assert tomllib.loads(dumps(robot))["programs"] == {odd: [{"wait": 1.0}]}


def test_joints_written_inline_keep_the_programs_after_them():
    """tomli-w writes small joint tables inline at the top: programs follow."""
    planar = load_robot("planar2")[0]
    robot = replace(planar, programs=(Program("swing", (Step("joint", "elbow", 10.0),)),))
    text = dumps(robot)
    assert tomllib.loads(text)["programs"] == {
        "swing": [{"move": "joint", "to": "elbow", "speed": 10.0}]
    }
    assert loads(text) == robot


# -- round trips -------------------------------------------------------------------

BUNDLED = {name: load_robot(name)[0] for name in bundled_names()}
PROGRAM_NAMES = st.one_of(
    st.sampled_from(["demo", "pick and place", 'say "hi"', "Braço", "a.b", "[x]", "# not"]),
    st.text(min_size=1, max_size=12).filter(lambda s: s.strip() and control_character(s) is None),
)


@st.composite
def steps(draw, robot):
    move = draw(st.sampled_from(["joint", "linear", "wait"]))
    if move == "wait":  # six of the longest with six of the slowest moves: within the hour
        return Step("wait", seconds=draw(st.floats(0, 100)))
    if robot.poses and draw(st.booleans()):
        to = draw(st.sampled_from(robot.pose_names))
    else:
        to = tuple(draw(st.floats(j.min, j.max)) for j in robot.joints)
    low, top = (20.0, 100.0) if move == "joint" else (10.0, 1e6)
    speed = draw(st.one_of(st.none(), st.floats(low, top)))
    return Step(move, to, speed)


@st.composite
def robots_with_programs(draw):
    """A bundled robot's name, and the robot with random programs and top speeds."""
    name = draw(st.sampled_from(sorted(BUNDLED)))
    robot = BUNDLED[name]
    # top speeds and accelerations over the floors (program_timing), fast
    # enough that no drawn program passes the hour (the slow ones are refused:
    # tests/core/test_program_timing.py)
    rates = st.one_of(st.none(), st.floats(50.0, 1e6))
    joints = tuple(replace(j, vmax=draw(rates), amax=draw(rates)) for j in robot.joints)
    names = draw(st.lists(PROGRAM_NAMES, max_size=4, unique=True))
    programs = tuple(
        Program(name, tuple(draw(st.lists(steps(robot), max_size=6)))) for name in names
    )
    return name, replace(robot, joints=joints, programs=programs)


@pytest.mark.slow  # a long hypothesis run
@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(drawn=robots_with_programs())
def test_random_programs_on_the_bundled_robots_come_back_equal(drawn):
    _, robot = drawn
    text = dumps(robot)
    assert loads(text) == robot
    plain = tomllib.loads(text)  # Python's own parser reads what was meant
    assert list(plain.get("programs", {})) == list(robot.program_names)
    for program in robot.programs:
        rows = plain["programs"][program.name]
        assert [("wait" in row) for row in rows] == [s.is_wait for s in program.steps]
        assert [row.get("speed") for row in rows] == [
            None if s.is_wait else s.speed for s in program.steps
        ]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(drawn=robots_with_programs())
def test_random_programs_saved_over_a_bundled_file_keep_its_comments(drawn, tmp_path_factory):
    """The comment-keeping save (not the fresh document it falls back to)."""
    name, robot = drawn
    original = (Path(__file__).resolve().parents[2] / "robots" / f"{name}.toml").read_text()
    path = tmp_path_factory.mktemp("save") / f"{name}.toml"
    path.write_text(original, encoding="utf-8")
    save(robot, path)
    assert load(path) == robot
    text = path.read_text(encoding="utf-8")
    whole_line = [line.strip() for line in original.splitlines() if line.lstrip().startswith("#")]
    kept = [line.strip() for line in text.splitlines() if line.lstrip().startswith("#")]
    assert kept == whole_line


def test_every_bundled_robot_loads_and_the_puma_has_a_demo():
    for name in bundled_names():
        robot, _ = load_robot(name)
        assert loads(dumps(robot)) == robot
    puma = BUNDLED["puma560"]
    moves = {step.move for step in puma.program("demo").steps}
    assert {"joint", "linear"} <= moves


def test_recovery_files_keep_programs_and_top_speeds(tmp_path, monkeypatch):
    monkeypatch.setenv(recovery.RECOVERY_ENV, str(tmp_path / "recovery"))
    robot = loads(ARM)
    robot = replace(robot, programs=(*robot.programs, Program("b", (Step("wait", seconds=2.0),))))
    source = tmp_path / "arm.toml"
    recovery.write_recovery(robot, source)
    found = recovery.find_recovery(source)
    assert found is not None
    assert found.robot == robot
    assert found.robot.programs[1] == Program("b", (Step("wait", seconds=2.0),))
    assert found.robot.joints[1].vmax == 45.0


@pytest.mark.parametrize("name", ["a\x1b[2Jb", "x\u202ey", "n" * 1001])
def test_a_program_name_made_in_code_is_checked_as_a_pose_name(name):
    """Not only on load: the model refuses such a name however it is made
    (the simulator's panel shows it)."""
    robot = load_robot("puma560")[0]
    with pytest.raises(DhsimError) as caught:
        replace(robot, programs=(Program(name, (Step("joint", "qr"),)),))
    assert "program name" in str(caught.value)

"""Hostile imports cost little (issue 17, points 9 and 10).

A CSV or URDF built to waste time and memory is refused at the first fact
that decides (its size, the 33rd joint row, the first bad cell, the
1001st link, the 200 001st XML node, the 51st level of nesting), with one
short line. Memory is measured in a fresh interpreter (``ru_maxrss`` is the
peak resident size, so its growth over the import is what the import cost);
the bound is generous (100 MB) where a careless reader took 700 MB. How long
a refusal takes depends on how busy the machine is, so no test bounds it:
``bench/hostile_inputs.py`` times these files (1 s each, 0.5 s for the first bad cell).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tracemalloc
from pathlib import Path

import pytest
from waiting import HANG

from dhsim_tui.core.interop.csv_import import MAX_CSV_BYTES, MAX_POSES
from dhsim_tui.core.interop.importer import from_csv, from_urdf, import_file
from dhsim_tui.core.interop.urdf import MAX_URDF_BYTES, read_chain
from dhsim_tui.core.interop.urdf_xml import MAX_URDF_LINKS, MAX_URDF_NODES
from dhsim_tui.core.model.errors import DhsimError, TipNeeded

ROOT = Path(__file__).resolve().parents[2]
MEGABYTES = 100
#: a message quoting a file's text stays this short, whatever the file holds
SHORT = 400

MEASURE = """
import json, resource, sys
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.interop.importer import import_file
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
try:
    import_file(sys.argv[1])
    message = None
except DhsimError as exc:
    message = str(exc)
grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
print(json.dumps({"megabytes": grown / 1024, "message": message}))
"""


def _measured(path: Path) -> dict:
    """``import_file(path)`` in a fresh interpreter: megabytes grown, message."""
    done = subprocess.run(
        [sys.executable, "-c", MEASURE, str(path)],
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
        timeout=HANG,  # a hang guard only
    )
    return json.loads(done.stdout)


def _refused_in_little_memory(path: Path, *words: str) -> str:
    outcome = _measured(path)
    message = outcome["message"]
    assert message is not None, "imported"
    assert message.startswith(str(path)) and "\n" not in message and len(message) < SHORT
    for word in words:
        assert word in message, message
    assert outcome["megabytes"] < MEGABYTES, outcome
    return message


def _one_line(message: str) -> None:
    assert "\n" not in message and len(message) < SHORT, message


# -- CSV ---------------------------------------------------------------------------------


def test_a_million_row_csv_is_refused_by_its_size_unread(tmp_path):
    """The issue's case: 1,000,000 rows took 14.9 s and 718 MB to be refused."""
    path = tmp_path / "million.csv"
    path.write_text("theta,d,a,alpha\n" + "0,0,0,0\n" * 1_000_000)
    _refused_in_little_memory(path, "bytes is more than dhsim imports from a .csv file")


def test_a_csv_just_under_the_cap_stops_at_its_33rd_joint_row(tmp_path):
    rows = (MAX_CSV_BYTES - 100) // 8
    path = tmp_path / "long.csv"
    path.write_text("theta,d,a,alpha\n" + "0,0,0,0\n" * rows)
    assert path.stat().st_size <= MAX_CSV_BYTES
    _refused_in_little_memory(path, "line 34: more than 32 joint rows; a robot has 1 to 32 joints")


def test_the_first_bad_cell_decides_before_the_rest_is_read():
    text = "theta,d,a,alpha\n0,0,x,0\n" + "0,0,0,0\n" * 200_000
    tracing = tracemalloc.is_tracing()
    if not tracing:
        tracemalloc.start()
    tracemalloc.reset_peak()
    try:
        with pytest.raises(DhsimError, match=r"^arm\.csv: line 2: a: 'x' is not a number$"):
            from_csv(text, source="arm.csv")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        if not tracing:
            tracemalloc.stop()
    # the rest is never split into lines or rows: the peak is the reader's copy
    # of the text (io.StringIO: 4 bytes a character), where its 200,000 lines
    # as strings take 8 bytes a character and as CSV rows 16
    assert peak < 6 * len(text), peak


def test_a_csv_text_over_the_cap_is_refused_unread():
    text = "theta,d,a,alpha\n" + "0,0,0,0\n" * (MAX_CSV_BYTES // 8 + 1)
    with pytest.raises(DhsimError, match="characters is more than dhsim reads from a CSV"):
        from_csv(text, source="big.csv")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "".join(f'# pose "p{i}" = 0\n' for i in range(MAX_POSES + 1)),
            f"line {MAX_POSES + 1}: more than {MAX_POSES} named poses",
        ),
        ('# pose "wide" = ' + "0, " * 100_000 + "0\ntheta,d,a,alpha\n", "more than 32 numbers"),
        ("# base_xyz = " + "1, " * 100_000 + "1\n", "base_xyz: more than 3 numbers"),
        ("theta,d,a,alpha\n0,0," + "1" * 150_000 + ",0\n", "line 2: not a CSV row"),
        ("theta,d,a,alpha\n0,0," + "7" * 50_000 + ",0\n", "is too long to be a number"),
        ("theta,d,a,alpha\n0,0,0,0\n" + "0,0," + "x" * 50_000 + ",0\n", "line 3: a: 'xxxx"),
        ("type,theta,d,a,alpha\n" + "Q" * 50_000 + ",0,0,0,0\n", "is not R or P"),
        ("theta,d,a,alpha," + "z" * 50_000 + "\n", "column 5 'zzz"),
        ("theta (" + "g" * 50_000 + "),d,a,alpha\n0,0,0,0\n", "expected deg or rad"),
        ('# pose "' + "n" * 50_000 + '" = x\ntheta,d,a,alpha\n', "is not a number"),
        ("# base_z = " + "f" * 50_000 + "\ntheta,d,a,alpha\n0,0,0,0\n", "base_z: the text 'fff"),
        ("# units = " + "u" * 50_000 + "\ntheta,d,a,alpha\n0,0,0,0\n", "units 'uuu"),
        ('# pose "' + "p" * 5_000 + '" = 1, 2\ntheta,d,a,alpha\n0,0,0,0\n', "poses."),
    ],
)
def test_a_hostile_csv_line_is_one_short_message(text, message):
    with pytest.raises(DhsimError) as caught:
        from_csv(text, source="arm.csv")
    assert message in str(caught.value)
    _one_line(str(caught.value))


# -- URDF --------------------------------------------------------------------------------


def _chain_of(links: int) -> str:
    declared = "".join(f'<link name="l{i}"/>' for i in range(links))
    joints = "".join(
        f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
        '<origin xyz="0.1 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1"/></joint>'
        for i in range(1, links)
    )
    return f'<robot name="big">{declared}{joints}</robot>'


def test_a_urdf_of_ten_thousand_links_is_refused_at_the_1001st_link(tmp_path):
    path = tmp_path / "huge.urdf"
    path.write_text(_chain_of(10_000))
    assert path.stat().st_size < MAX_URDF_BYTES  # the link count decides, not the size
    _refused_in_little_memory(path, f"more than {MAX_URDF_LINKS} <link> elements")


def test_a_fifty_megabyte_urdf_is_refused_by_its_size_unread(tmp_path):
    path = tmp_path / "fifty.urdf"
    with path.open("wb") as handle:
        handle.truncate(50_000_000)  # sparse: its size is what counts
    _refused_in_little_memory(path, "50000000 bytes is more than dhsim imports from a .urdf file")


def test_a_urdf_of_many_small_elements_is_refused_while_streaming(tmp_path):
    path = tmp_path / "nodes.urdf"
    path.write_text('<robot name="r"><link name="a">' + "<b/>" * 900_000 + "</link></robot>")
    assert path.stat().st_size < MAX_URDF_BYTES
    _refused_in_little_memory(path, f"more than {MAX_URDF_NODES} XML elements and attributes")


def test_a_urdf_of_many_attributes_is_refused(tmp_path):
    path = tmp_path / "attributes.urdf"
    attributes = " ".join(f'a{i}=""' for i in range(350_000))
    path.write_text(f'<robot name="r"><link name="a" {attributes}/></robot>')
    assert path.stat().st_size < MAX_URDF_BYTES
    _refused_in_little_memory(path, "XML elements and attributes")


def test_deeply_nested_elements_are_refused(tmp_path):
    path = tmp_path / "deep.urdf"
    path.write_text('<robot name="r">' + "<a>" * 300_000 + "</a>" * 300_000 + "</robot>")
    _refused_in_little_memory(path, "nested more than 50 deep")


def test_a_chain_of_too_many_moving_joints_stops_before_reading_numbers():
    text = _chain_of(900).replace('<origin xyz="0.1 0 0"/>', '<origin xyz="nan 0 0"/>')
    with pytest.raises(DhsimError) as caught:
        read_chain(text, source="arm.urdf")
    message = str(caught.value)
    assert "has more than 32 moving joints; a robot has 1 to 32" in message
    assert "nan" not in message  # the numbers were never read
    _one_line(message)


def test_huge_names_are_cut_in_the_middle_in_messages():
    name = "x" * 500_000 + "END"
    text = f'<robot name="r"><link name="{name}"/><link name="{name}"/></robot>'
    with pytest.raises(DhsimError) as caught:
        read_chain(text, source="arm.urdf")
    message = str(caught.value)
    assert (
        "two links are named 'xxx" in message
        and "xxx … xxx" in message
        and message.endswith("xxxEND'")
    )
    _one_line(message)


def test_a_tree_of_many_leaves_lists_ten_and_counts_the_rest():
    leaves = "".join(
        f'<link name="leaf{i}"/><joint name="j{i}" type="fixed"><parent link="root"/>'
        f'<child link="leaf{i}"/></joint>'
        for i in range(900)
    )
    with pytest.raises(TipNeeded) as caught:
        read_chain(f'<robot name="r"><link name="root"/>{leaves}</robot>', source="t.urdf")
    assert len(caught.value.leaves) == 900  # all of them, to choose from
    message = str(caught.value)
    assert "'leaf9', ... (890 more)" in message
    _one_line(message)


def test_a_hostile_robot_name_is_cut_and_said_so():
    text = (
        f'<robot name="{"R" * 100_000}"><link name="a"/><link name="b"/>'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        '<limit lower="-1" upper="1"/></joint></robot>'
    )
    result = from_urdf(text, source="r.urdf")
    assert len(result.robot.name) == 200
    assert any("name is cut to 200 characters" in note for note in result.notes)
    assert all(len(line) < SHORT for line in result.header)


def test_entities_stay_refused_before_any_cap():
    """The caps come after the old guard: a DOCTYPE is still refused unexpanded."""
    text = '<!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]><robot name="&x;"/>'
    with pytest.raises(DhsimError, match="DOCTYPE"):
        read_chain(text)


def test_a_normal_import_is_unaffected(tmp_path):
    """The UR5 (a real, large-ish URDF) still imports, well inside every cap."""
    ur5 = ROOT / "tests" / "urdfs" / "ur5.urdf"
    assert import_file(ur5, tip="tool0").robot.dof == 6

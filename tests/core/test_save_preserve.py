"""Saving keeps the user's words and never overwrites what it did not read.

A commented robot file goes through edits and saves; a line diff shows that
only the changed values' lines changed. Saves refuse a file that changed on
disk since it was read, a read-only file (root included) and an owner they
cannot keep; they clean up after killed saves and keep a byte order mark.
"""

from __future__ import annotations

import difflib
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dhsim_tui.core.files import robotfile as robotfile_module
from dhsim_tui.core.files.robotfile import (
    FileChangedError,
    FileStamp,
    ReadOnlyError,
    dumps,
    load,
    load_with_stamp,
    loads,
    read_stamp,
    save,
)
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import DhsimError, RobotFileError

ROBOTS_DIR = Path(__file__).resolve().parents[2] / "robots"
BUNDLED_FILES = sorted(ROBOTS_DIR.glob("*.toml"))

COMMENTED = """\
# My lab arm -- hand written, please keep these notes!
#   measured 2024-03-01 with calipers

name   =   "Lab arm"     # what the students call it
units = "mm"
base_height = 100     # table top

# tool: a small gripper
[tool]
xyz = [0, 0, 50.0]   # fingertip
rpy = [ 0.0,  0.0, 0.0 ]

# saved poses
[poses]
ready = [0.0, 90, 100.0]   # ready to pick
low   = [10.0, -45.0, 0.0]

# ---- the joints ----
# shoulder
[[joints]]
theta = 0.0
d     = 300      # column height
a     = 0.0
alpha = 90.0
min = -170.0     # cable limit
max = 170.0

# elbow
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
d = 50.0
a = 0.0
alpha = 0.0
min = 0.0
max = 200.0

# end of file
"""

#: a robot file whose joints are one inline array (like the bundled Cobra 600)
INLINE = """\
name = "inline" # trailing
joints = [
    { theta = 0.0, d = 387.0, a = 325.0, alpha = 0.0 },  # first
    { theta = 0.0, d = 0.0, a = 275.0, alpha = 180.0 },
]
"""


def comments(text: str) -> list[str]:
    """Every comment in ``text`` (whole-line and trailing), in order."""
    return [line[line.index("#") :].strip() for line in text.splitlines() if "#" in line]


def edited(tmp_path: Path, text: str, edit) -> tuple[str, list[str], list[str]]:
    """Write ``text``, load it, apply ``edit``, save over it. Returns the new
    text and the removed and added lines of a line diff."""
    path = tmp_path / "arm.toml"
    path.write_text(text, encoding="utf-8")
    robot = edit(load(path))
    save(robot, path)
    assert load(path) == robot
    new = path.read_text(encoding="utf-8")
    diff = list(difflib.ndiff(text.splitlines(), new.splitlines()))
    removed = [line[2:] for line in diff if line.startswith("- ")]
    added = [line[2:] for line in diff if line.startswith("+ ")]
    assert [p.name for p in tmp_path.iterdir()] == ["arm.toml"]  # no temporary file left
    return new, removed, added


# -- style preservation ------------------------------------------------------------


@pytest.mark.parametrize("path", BUNDLED_FILES, ids=lambda p: p.stem)
def test_saving_an_unchanged_robot_keeps_the_bytes(tmp_path, path):
    target = tmp_path / path.name
    shutil.copy(path, target)
    save(load(target), target)
    assert target.read_bytes() == path.read_bytes()


def test_saving_an_unchanged_commented_robot_keeps_the_bytes(tmp_path):
    new, removed, added = edited(tmp_path, COMMENTED, lambda robot: robot)
    assert new == COMMENTED
    assert removed == added == []


def test_changing_one_joint_value_changes_one_line(tmp_path):
    new, removed, added = edited(
        tmp_path, COMMENTED, lambda r: editing.set_joint_field(r, 1, "a", 410.5)
    )
    assert removed == ["a = 400.0        # upper arm"]
    assert added == ["a = 410.5        # upper arm"]
    assert comments(new) == comments(COMMENTED)


def test_unchanged_numbers_keep_their_spelling(tmp_path):
    # the integers 100, 300, 0, 90 and the odd spacing stay as the user wrote them
    new, removed, added = edited(
        tmp_path, COMMENTED, lambda r: editing.set_joint_field(r, 2, "max", 250.0)
    )
    assert (removed, added) == (["max = 200.0"], ["max = 250.0"])
    for line in ("base_height = 100     # table top", "xyz = [0, 0, 50.0]   # fingertip"):
        assert line in new.splitlines()


def test_a_changed_integer_is_written_as_its_exact_value(tmp_path):
    _new, removed, added = edited(tmp_path, COMMENTED, lambda r: editing.set_base_height(r, 120.25))
    assert (removed, added) == (
        ["base_height = 100     # table top"],
        ["base_height = 120.25     # table top"],
    )


def test_adding_a_pose_adds_one_line(tmp_path):
    new, removed, added = edited(
        tmp_path, COMMENTED, lambda r: editing.set_pose(r, "side", (45.0, 10.0, 20.0))
    )
    assert removed == []
    assert added == ["side = [45.0, 10.0, 20.0]"]
    lines = new.splitlines()
    assert lines.index("side = [45.0, 10.0, 20.0]") == lines.index("low   = [10.0, -45.0, 0.0]") + 1


def test_adding_a_pose_with_an_awkward_name_adds_one_line(tmp_path):
    name = 'pick "A" \\ near.bin'
    _new, removed, added = edited(
        tmp_path, COMMENTED, lambda r: editing.set_pose(r, name, (45.0, 10.0, 20.0))
    )
    assert removed == [] and len(added) == 1
    assert load(tmp_path / "arm.toml").pose(name) == (45.0, 10.0, 20.0)


def test_replacing_a_pose_changes_its_line_and_keeps_its_comment(tmp_path):
    _new, removed, added = edited(
        tmp_path, COMMENTED, lambda r: editing.set_pose(r, "ready", (0.0, 80.0, 100.0))
    )
    assert removed == ["ready = [0.0, 90, 100.0]   # ready to pick"]
    assert added == ["ready = [0.0, 80.0, 100.0]   # ready to pick"]


def test_deleting_a_pose_removes_its_line_only(tmp_path):
    _new, removed, added = edited(tmp_path, COMMENTED, lambda r: editing.delete_pose(r, "low"))
    assert (removed, added) == (["low   = [10.0, -45.0, 0.0]"], [])


def test_a_pose_deleted_and_added_again_moves_to_the_end_alone(tmp_path):
    def edit(robot):
        robot = editing.delete_pose(robot, "ready")
        return editing.set_pose(robot, "ready", (0.0, 0.0, 0.0))

    _new, removed, added = edited(tmp_path, COMMENTED, edit)
    assert removed == ["ready = [0.0, 90, 100.0]   # ready to pick"]
    assert added == ["ready = [0.0, 0.0, 0.0]   # ready to pick"]
    assert load(tmp_path / "arm.toml").pose_names == ("low", "ready")


def test_the_files_key_order_is_kept(tmp_path):
    text = "[[joints]]\nalpha = 0.0\na = 1.0\nd = 0.0\ntheta = 0.0\n"
    text = 'units = "cm"  # first\nname = "odd order"\n' + text
    _new, removed, added = edited(tmp_path, text, lambda r: editing.set_joint_field(r, 0, "a", 2.0))
    assert (removed, added) == (["a = 1.0"], ["a = 2.0"])


def test_the_first_pose_creates_a_poses_table_before_the_joints(tmp_path):
    text = COMMENTED.replace(
        "# saved poses\n[poses]\nready = [0.0, 90, 100.0]   # ready to pick\n"
        "low   = [10.0, -45.0, 0.0]\n\n",
        "",
    )
    assert "[poses]" not in text
    new, removed, added = edited(
        tmp_path, text, lambda r: editing.set_pose(r, "home", (0.0, 0.0, 50.0))
    )
    assert removed == []
    assert [line for line in added if line] == ["[poses]", "home = [0.0, 0.0, 50.0]"]
    lines = new.splitlines()
    assert lines.index("[poses]") < lines.index("# ---- the joints ----")


def test_inserting_a_joint_adds_its_table_and_one_value_per_pose(tmp_path):
    new, removed, added = edited(tmp_path, COMMENTED, lambda r: editing.insert_joint(r, 1))
    assert removed == ["ready = [0.0, 90, 100.0]   # ready to pick", "low   = [10.0, -45.0, 0.0]"]
    assert added[:2] == [
        "ready = [0.0, 90, 0.0, 100.0]   # ready to pick",
        "low   = [10.0, -45.0, 0.0, 0.0]",
    ]
    assert added[2] == "[[joints]]" and all("#" not in line for line in added[2:])
    assert comments(new) == comments(COMMENTED)
    robot = load(tmp_path / "arm.toml")
    assert robot.dof == 4 and robot.joints[2] == editing.Joint()


def test_deleting_a_joint_removes_its_table_and_keeps_the_other_comments(tmp_path):
    new, removed, added = edited(tmp_path, COMMENTED, lambda r: editing.delete_joint(r, 1))
    assert "a = 400.0        # upper arm" in removed
    assert [line for line in added if line] == [
        "ready = [0.0, 100.0]   # ready to pick",
        "low   = [10.0, 0.0]",
    ]
    assert [c for c in comments(COMMENTED) if c != "# upper arm"] == comments(new)


def test_moving_a_joint_keeps_every_comment_and_every_line(tmp_path):
    new, _removed, _added = edited(tmp_path, COMMENTED, lambda r: editing.move_joint(r, 1, 1))
    assert sorted(comments(new)) == sorted(comments(COMMENTED))
    # the elbow's table moved whole, with the comment above it
    elbow = "# elbow\n[[joints]]\ntheta = 0.0\nd = 0.0\na = 400.0        # upper arm\n"
    assert elbow in new
    assert new.index("# quill (prismatic)") < new.index("# elbow")
    assert sorted(line for line in new.splitlines() if line) == sorted(
        line
        for line in COMMENTED.replace("[0.0, 90, 100.0]", "[0.0, 100.0, 90.0]")
        .replace("[10.0, -45.0, 0.0]", "[10.0, 0.0, -45.0]")
        .splitlines()
        if line
    )


def test_changing_units_changes_every_length_and_keeps_every_comment(tmp_path):
    new, _removed, added = edited(tmp_path, COMMENTED, lambda r: editing.set_units(r, "m"))
    assert comments(new) == comments(COMMENTED)
    assert len(new.splitlines()) == len(COMMENTED.splitlines())
    assert added == [
        'units = "m"',
        "base_height = 0.1     # table top",
        "xyz = [0, 0, 0.05]   # fingertip",
        "ready = [0.0, 90, 0.1]   # ready to pick",
        "d     = 0.3      # column height",
        "a = 0.4        # upper arm",
        "d = 0.05",
        "max = 0.2",
    ]


def test_keys_left_out_stay_out_and_a_changed_default_is_added_in_its_place(tmp_path):
    # no convention, base_z, base_x, type or limits in this file
    new, removed, added = edited(
        tmp_path, COMMENTED, lambda r: editing.set_convention(r, "modified")
    )
    assert (removed, added) == ([], ['convention = "modified"'])
    lines = new.splitlines()
    assert lines.index('convention = "modified"') == lines.index('units = "mm"') + 1
    text = "name = 'x'\n[[joints]]\ntheta = 10\nd = 0.0\na = 1\nalpha = 0.0\n"
    new, removed, added = edited(tmp_path, text, lambda r: editing.toggle_type(r, 0))
    assert (removed, added) == ([], ['type = "prismatic"'])  # limits: still the default


def test_inline_array_of_joints_changes_one_row(tmp_path):
    _new, removed, added = edited(
        tmp_path, INLINE, lambda r: editing.set_joint_field(r, 1, "d", 12.5)
    )
    assert removed == ["    { theta = 0.0, d = 0.0, a = 275.0, alpha = 180.0 },"]
    assert added == ["    { theta = 0.0, d = 12.5, a = 275.0, alpha = 180.0 },"]
    _new, removed, added = edited(tmp_path, INLINE, lambda r: editing.insert_joint(r, 1))
    assert removed == [] and len(added) == 1 and added[0].startswith("    { ")


# -- zero offsets are not written ------------------------------------------------------


@pytest.mark.parametrize("path", BUNDLED_FILES, ids=lambda p: p.stem)
def test_editing_joint_1s_theta_changes_one_line_and_writes_no_offset(tmp_path, path):
    # the README: offsets are written only when they are not zero. Joint 1 of
    # planar2 is equal to joint 2: the edited row is changed where it is, not
    # dropped and written anew with every key (offset = 0.0 among them).
    text = path.read_text(encoding="utf-8")

    def edit(robot):
        return editing.set_joint_field(robot, 0, "theta", robot.joints[0].theta + 1.0)

    new, removed, added = edited(tmp_path, text, edit)
    assert len(removed) == len(added) == 1, (removed, added)
    assert "theta" in removed[0] and "offset" not in added[0]
    assert comments(new) == comments(text)


@pytest.mark.parametrize("path", BUNDLED_FILES, ids=lambda p: p.stem)
def test_a_new_joint_is_written_like_its_neighbours_without_a_zero_offset(tmp_path, path):
    text = path.read_text(encoding="utf-8")
    new, _removed, added = edited(tmp_path, text, lambda r: editing.insert_joint(r, 0))
    assert not any("offset" in line for line in added), added
    assert comments(new) == comments(text)
    if "[[joints]]" in text:  # the new table has the keys its neighbours have
        assert "[[joints]]" in added and 'type = "revolute"' in added


def test_an_offset_the_file_has_stays_when_it_becomes_zero(tmp_path):
    # the user's line is kept, set to 0 (deleting it would drop its comment)
    text = COMMENTED.replace("max = 135.0\n", "max = 135.0\noffset = 5.0   # zero mark\n", 1)
    _new, removed, added = edited(
        tmp_path, text, lambda r: editing.set_joint_field(r, 1, "offset", 0.0)
    )
    assert (removed, added) == (["offset = 5.0   # zero mark"], ["offset = 0.0   # zero mark"])
    assert load(tmp_path / "arm.toml").joints[1].offset == 0.0


def test_windows_line_ends_stay_windows_line_ends(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_bytes(COMMENTED.replace("\n", "\r\n").encode("utf-8"))
    robot = editing.set_pose(editing.insert_joint(load(path), 1), "side", (1.0, 2.0, 3.0, 4.0))
    save(robot, path)
    raw = path.read_bytes()
    assert raw.count(b"\n") == raw.count(b"\r\n") > len(COMMENTED.splitlines())
    assert load(path) == robot
    assert comments(raw.decode("utf-8")) == comments(COMMENTED)


def test_save_as_starts_from_the_given_text(tmp_path):
    robot = editing.set_joint_field(loads(COMMENTED), 0, "d", 310.0)
    target = tmp_path / "copy.toml"
    save(robot, target, base_text=COMMENTED)
    assert load(target) == robot
    diff = [line for line in difflib.ndiff(COMMENTED.splitlines(), target.read_text().splitlines())]
    assert [line for line in diff if line[:2] in ("- ", "+ ")] == [
        "- d     = 300      # column height",
        "+ d     = 310.0      # column height",
    ]


def test_saving_over_a_toml_file_that_is_not_a_robot_keeps_its_comments(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text('# notes\ncolour = "red"  # why not\n', encoding="utf-8")
    robot = loads(COMMENTED)
    save(robot, path)
    assert load(path) == robot
    assert path.read_text(encoding="utf-8").startswith("# notes\n")


def test_a_file_that_is_not_toml_is_replaced_by_a_fresh_document(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_bytes(b"# notes\nthis is = = not toml\n\xff")
    robot = loads(COMMENTED)
    save(robot, path)
    assert path.read_text(encoding="utf-8") == dumps(robot)
    path.write_bytes(b"# notes\nthis is = = not toml\n")
    save(robot, path, base_text=INLINE)  # then the given text is the starting point
    assert path.read_text(encoding="utf-8").startswith('name = "Lab arm" # trailing\n')
    assert load(path) == robot


def test_a_wrong_update_is_never_written(tmp_path, monkeypatch):
    # whatever the style-preserving update produces is parsed before the
    # rename; if it does not read back as the robot, a fresh document is written
    path = tmp_path / "arm.toml"
    path.write_text(COMMENTED, encoding="utf-8")
    robot = editing.set_joint_field(load(path), 1, "a", 410.5)
    monkeypatch.setattr(robotfile_module, "update_text", lambda *args: COMMENTED)
    save(robot, path)
    assert load(path) == robot
    assert path.read_text(encoding="utf-8") == dumps(robot)

    def broken(*args):
        raise RecursionError("tomlkit went too deep")

    monkeypatch.setattr(robotfile_module, "update_text", broken)
    save(editing.set_joint_field(robot, 1, "a", 420.0), path)
    assert load(path).joints[1].a == 420.0


def test_saving_through_a_symlink_keeps_the_link_and_the_comments(tmp_path):
    real = tmp_path / "real.toml"
    real.write_text(COMMENTED, encoding="utf-8")
    link = tmp_path / "link.toml"
    link.symlink_to(real)
    robot, stamp = load_with_stamp(link)
    assert stamp.path == real.resolve()
    new = save(editing.set_joint_field(robot, 1, "a", 410.5), link, expect=stamp)
    assert link.is_symlink() and new.path == real.resolve()
    assert "a = 410.5        # upper arm" in real.read_text(encoding="utf-8")


# -- never overwrite what was not read -----------------------------------------------


def test_stamps_name_the_real_file_and_its_bytes(tmp_path):
    path = tmp_path / "arm.toml"
    assert read_stamp(path) is None
    path.write_text(COMMENTED, encoding="utf-8")
    robot, stamp = load_with_stamp(path)
    assert robot == load(path)
    assert stamp == read_stamp(path)
    assert stamp.size == len(COMMENTED.encode()) and len(stamp.digest) == 64
    written = save(editing.set_base_height(robot, 5.0), path, expect=stamp)
    assert written == read_stamp(path) != stamp
    assert isinstance(written, FileStamp) and written.path == path.resolve()


def test_an_external_change_of_the_same_size_and_time_is_detected(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(COMMENTED, encoding="utf-8")
    robot, stamp = load_with_stamp(path)
    before = path.stat()
    external = COMMENTED.replace("upper arm", "UPPER ARM")
    assert len(external) == len(COMMENTED)
    path.write_text(external, encoding="utf-8")
    os.utime(path, ns=(before.st_atime_ns, before.st_mtime_ns))
    assert (path.stat().st_size, path.stat().st_mtime_ns) == (stamp.size, stamp.mtime_ns)
    with pytest.raises(FileChangedError) as info:
        save(editing.set_base_height(robot, 5.0), path, expect=stamp)
    assert "changed on disk since it was opened" in str(info.value)
    assert str(path) in str(info.value)
    assert path.read_text(encoding="utf-8") == external
    assert [p.name for p in tmp_path.iterdir()] == ["arm.toml"]


def test_a_removed_file_or_a_new_one_is_a_change_too(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(COMMENTED, encoding="utf-8")
    robot, stamp = load_with_stamp(path)
    path.unlink()
    with pytest.raises(FileChangedError, match="changed on disk"):
        save(robot, path, expect=stamp)
    assert not path.exists()
    save(robot, path, expect=None)  # the file must not exist yet: it does not
    with pytest.raises(FileChangedError, match="changed on disk"):
        save(robot, path, expect=None)
    save(robot, path)  # no expectation: today's behaviour


def test_a_read_only_file_is_refused_even_for_root(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(COMMENTED, encoding="utf-8")
    robot = editing.set_base_height(load(path), 5.0)
    path.chmod(0o444)
    with pytest.raises(ReadOnlyError) as info:
        save(robot, path)
    message = str(info.value)
    assert str(path) in message and "read-only" in message and "another name" in message
    assert isinstance(info.value, RobotFileError)
    assert path.read_text(encoding="utf-8") == COMMENTED
    assert path.stat().st_mode & 0o777 == 0o444
    assert [p.name for p in tmp_path.iterdir()] == ["arm.toml"]


def test_a_file_os_access_says_is_not_writable_is_refused(tmp_path, monkeypatch):
    path = tmp_path / "arm.toml"
    path.write_text(COMMENTED, encoding="utf-8")
    robot = load(path)
    monkeypatch.setattr(os, "access", lambda *args, **kwargs: False)
    with pytest.raises(ReadOnlyError):
        save(robot, path)
    assert path.read_text(encoding="utf-8") == COMMENTED


@pytest.mark.skipif(os.geteuid() != 0, reason="only root can give a file away")
def test_owner_group_and_mode_are_kept(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(COMMENTED, encoding="utf-8")
    os.chown(path, 12345, 12346)
    path.chmod(0o640)
    save(editing.set_base_height(load(path), 5.0), path)
    info = path.stat()
    assert (info.st_uid, info.st_gid, info.st_mode & 0o7777) == (12345, 12346, 0o640)
    assert load(path).base_height == 5.0


@pytest.mark.skipif(os.geteuid() != 0, reason="needs root to act as another user")
def test_an_owner_that_cannot_be_kept_is_refused():
    # root's file, writable by all, saved by "nobody": the save would hand the
    # file to nobody, so it is refused and the file stays as it was
    folder = Path(tempfile.mkdtemp())
    try:
        folder.chmod(0o777)
        path = folder / "arm.toml"
        path.write_text(COMMENTED, encoding="utf-8")
        path.chmod(0o666)
        robot = editing.set_base_height(load(path), 5.0)
        os.seteuid(65534)
        try:
            with pytest.raises(RobotFileError) as info:
                save(robot, path)
        finally:
            os.seteuid(0)
        assert "owner" in str(info.value) and str(path) in str(info.value)
        assert path.read_text(encoding="utf-8") == COMMENTED
        assert path.stat().st_uid == 0
        assert [p.name for p in folder.iterdir()] == ["arm.toml"]
    finally:
        shutil.rmtree(folder)


def _dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_temporary_files_of_killed_saves_are_removed(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(COMMENTED, encoding="utf-8")
    dead = tmp_path / f".arm.toml.{_dead_pid()}.k2x9q_ab.tmp"
    old = tmp_path / f".arm.toml.{os.getpid()}.zzzzzzzz.tmp"
    live = tmp_path / f".arm.toml.{os.getpid()}.yyyyyyyy.tmp"
    others = [
        tmp_path / f".other.toml.{_dead_pid()}.abcdefgh.tmp",
        tmp_path / "arm.toml.bak",
        tmp_path / ".arm.toml.notapid.abcdefgh.tmp",
        tmp_path / f".arm.toml.{_dead_pid()}.abcdefgh.tmp.keep",
    ]
    for file in (dead, old, live, *others):
        file.write_text("half a robot", encoding="utf-8")
    two_hours_ago = time.time() - 7200
    os.utime(old, (two_hours_ago, two_hours_ago))
    load_with_stamp(path)
    assert not dead.exists() and not old.exists()
    assert live.exists() and all(file.exists() for file in others)
    live.unlink()
    dead.write_text("half a robot", encoding="utf-8")
    save(load(path), path)
    assert not dead.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["arm.toml", *(file.name for file in others)]
    )


def test_temporary_file_is_named_after_the_target_and_the_process(tmp_path, monkeypatch):
    names = []
    real_replace = os.replace

    def replace(src, dst):
        names.append(Path(src).name)
        return real_replace(src, dst)

    monkeypatch.setattr(os, "replace", replace)
    save(loads(COMMENTED), tmp_path / "arm.toml")
    assert re.fullmatch(rf"\.arm\.toml\.{os.getpid()}\.[a-z0-9_]+\.tmp", names[0])


# -- byte order mark and control characters -----------------------------------------------


def test_a_byte_order_mark_is_accepted_and_kept(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_bytes(b"\xef\xbb\xbf" + COMMENTED.encode("utf-8"))
    robot = load(path)
    assert robot == loads(COMMENTED)
    assert loads("\ufeff" + COMMENTED) == robot
    save(editing.set_joint_field(robot, 1, "a", 410.5), path)
    raw = path.read_bytes()
    assert raw.startswith(b"\xef\xbb\xbf") and not raw.startswith(b"\xef\xbb\xbf" * 2)
    assert "# upper arm" in raw.decode("utf-8")
    assert load(path).joints[1].a == 410.5


def test_a_file_without_a_byte_order_mark_gets_none(tmp_path):
    path = tmp_path / "arm.toml"
    save(loads(COMMENTED), path)
    assert not path.read_bytes().startswith(b"\xef\xbb\xbf")


@pytest.mark.parametrize(
    ("text", "shown"),
    [
        ('"\\u001b[2J" = 1\n', "\\x1b[2J: unknown key"),
        ('nmae = "x"\n"\\u202e" = 1\n', "nmae: unknown key (did you mean 'name'?)"),
        (
            'name = "x"\njoints = [{theta = 0, d = 0, a = 0, alpha = 0}]\n'
            '[poses]\n"\\u001b]0;evil\\u0007" = "up"\n',
            "poses.\\x1b]0;evil\\x07",
        ),
        (
            'name = "x"\njoints = [{theta = 0, d = 0, a = 0, alpha = 0}]\n'
            '[tool]\n"x\\u009by" = 1\n',
            "tool.x\\x9by: unknown key",
        ),
        (
            'name = "x"\n[[joints]]\ntheta = 0.0\nd = 0.0\na = 0.0\nalpha = 0.0\n"\\u202e" = 1\n',
            "joints[1].\\u202e: unknown key",
        ),
    ],
)
def test_file_content_in_messages_is_escaped(tmp_path, text, shown):
    path = tmp_path / "arm.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(RobotFileError) as info:
        load(path)
    message = str(info.value)
    assert shown in message
    assert not any(ord(c) < 32 or 0x7F <= ord(c) < 0xA0 or c == "\u202e" for c in message)


# -- random edits of the bundled robots ---------------------------------------------------

EDITS = st.one_of(
    st.tuples(
        st.just("field"),
        st.integers(0, 31),
        st.sampled_from(editing.JOINT_FIELDS),
        st.one_of(
            st.integers(-400, 400).map(float),
            st.floats(-400, 400, allow_nan=False).map(lambda v: round(v, 3)),
            st.floats(-400, 400, allow_nan=False),
        ),
    ),
    st.tuples(st.just("toggle"), st.integers(0, 31)),
    st.tuples(st.just("insert"), st.integers(-1, 31)),
    st.tuples(st.just("delete"), st.integers(0, 31)),
    st.tuples(st.just("move"), st.integers(0, 31), st.sampled_from((-1, 1))),
    st.tuples(st.just("units"), st.sampled_from(("mm", "cm", "m", "in"))),
    st.tuples(st.just("convention"), st.sampled_from(("standard", "modified"))),
    st.tuples(st.just("height"), st.floats(0, 2000, allow_nan=False)),
    st.tuples(st.just("pose"), st.sampled_from(("new", "qz", "up", "home 2", "qn"))),
    st.tuples(st.just("unpose"), st.sampled_from(("qz", "qr", "qn", "up", "new"))),
    st.tuples(st.just("tool"), st.floats(-100, 100, allow_nan=False)),
    st.tuples(st.just("name"), st.sampled_from(("Arm", 'Quote " arm', "Bra\u00e7o"))),
)


def apply_edit(robot, edit):
    kind, *args = edit
    index = args[0] % robot.dof if args and isinstance(args[0], int) else 0
    actions = {
        "field": lambda: editing.set_joint_field(robot, index, args[1], args[2]),
        "toggle": lambda: editing.toggle_type(robot, index),
        "insert": lambda: editing.insert_joint(robot, min(args[0], robot.dof - 1)),
        "delete": lambda: editing.delete_joint(robot, index),
        "move": lambda: editing.move_joint(robot, index, args[1]),
        "units": lambda: editing.set_units(robot, args[0]),
        "convention": lambda: editing.set_convention(robot, args[0]),
        "height": lambda: editing.set_base_height(robot, args[0]),
        "pose": lambda: editing.set_pose(robot, args[0], robot.home),
        "unpose": lambda: editing.delete_pose(robot, args[0]),
        "tool": lambda: editing.set_tool(robot, xyz=(0.0, args[0], 1.5)),
        "name": lambda: editing.set_name(robot, args[0]),
    }
    try:
        return actions[kind]()
    except DhsimError:
        return robot  # an edit the editor would refuse


@settings(max_examples=60, deadline=None, database=None, derandomize=True)
@given(
    source=st.sampled_from(BUNDLED_FILES),
    edits=st.lists(EDITS, min_size=1, max_size=6),
    saves=st.integers(1, 3),
)
def test_random_edits_of_bundled_robots_keep_every_comment(source, edits, saves):
    with tempfile.TemporaryDirectory() as folder:
        check_random_edits(Path(folder), source, edits, saves)


def check_random_edits(tmp_path: Path, source: Path, edits: list, saves: int) -> None:
    target = tmp_path / source.name
    shutil.copy(source, target)
    robot = load(target)
    original = source.read_text(encoding="utf-8")
    whole_line = [line.strip() for line in original.splitlines() if line.lstrip().startswith("#")]
    chunks = [edits[i::saves] for i in range(saves)]
    for chunk in chunks:
        for edit in chunk:
            robot = apply_edit(robot, edit)
        save(robot, target)
        assert load(target) == robot
    text = target.read_text(encoding="utf-8")
    kept = [line.strip() for line in text.splitlines() if line.lstrip().startswith("#")]
    assert kept == whole_line
    for name, _ in robot.poses:  # a pose that survived keeps its trailing comment
        for line in original.splitlines():
            if line.startswith(f"{name} = ") and "#" in line:
                assert line[line.index("#") :] in text
    assert sorted(p.name for p in tmp_path.iterdir()) == [source.name]

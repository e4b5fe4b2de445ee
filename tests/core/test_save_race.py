"""A change made on disk while dhsim saves is never lost.

A save writes a temporary file and renames it over the robot file. Anything
that changes the file in between (an in-place write, another editor's rename,
a deletion, a symbolic link swapped in), and a symbolic link made or pointed
elsewhere since the file was read (even at the same bytes), is reported as a
change on disk (``FileChangedError``, which the UI asks about): the file is
left as the other program made it, with no temporary file and no lock file
behind. Two dhsim processes saving one file never lose each other's saves.

The outside change is made from ``os.fsync`` of the temporary file, which any
atomic save calls between writing the temporary file and renaming it; real
writers run as separate processes. Waits are on conditions (``HANG`` only
turns a hang into a failure).
"""

from __future__ import annotations

import os
import select
import shutil
import subprocess
import sys
import tempfile
import threading
from collections.abc import Callable
from pathlib import Path

import pytest
from waiting import HANG, wait_until

from dhsim_tui.core.files import atomicfile
from dhsim_tui.core.files.robotfile import (
    FileChangedError,
    load,
    load_with_stamp,
    read_stamp,
    save,
)
from dhsim_tui.core.model import editing
from dhsim_tui.core.model.errors import RobotFileError

ROOT = Path(__file__).resolve().parents[2]

TEXT = """\
# a robot file another program also edits: keep this comment
name = "arm"
units = "mm"
base_height = 0

[[joints]]
theta = 0.0
d = 0.0
a = 100.0  # upper arm
alpha = 0.0

[[joints]]
theta = 0.0
d = 0.0
a = 50.0
alpha = 0.0
"""

#: what the writer processes write: the same robot, a counter in base_height
WRITTEN = TEXT.replace("base_height = 0", "base_height = {n}  # written elsewhere")


def temporary_files(path: Path) -> list[Path]:
    return [
        p
        for p in path.parent.iterdir()
        if p.name.startswith(f".{path.name}.") and p.suffix == ".tmp"
    ]


def while_saving(monkeypatch, path: Path, action: Callable[[], None], times: int = 1) -> list:
    """Run ``action`` while a save's temporary file of ``path`` exists (after it
    is written and fsynced, before the rename): at most ``times`` saves."""
    real_fsync = os.fsync
    done: list[str] = []

    def fsync(fd: int) -> None:
        real_fsync(fd)
        for temp in temporary_files(path):
            if temp.name not in done and len(done) < times:
                done.append(temp.name)
                action()

    monkeypatch.setattr(os, "fsync", fsync)
    return done


def names(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


@pytest.fixture
def arm(tmp_path: Path) -> Path:
    path = tmp_path / "arm.toml"
    path.write_text(TEXT, encoding="utf-8")
    return path


# -- (a) one outside change between the temporary file and the rename ------------------


def write_in_place(path: Path) -> None:
    path.write_text(WRITTEN.format(n=7), encoding="utf-8")


def rename_over(path: Path) -> None:  # how most editors save
    other = path.with_name("other-editor.tmp")
    other.write_text(WRITTEN.format(n=7), encoding="utf-8")
    os.replace(other, path)


@pytest.mark.parametrize("change", [write_in_place, rename_over], ids=["in place", "renamed"])
def test_a_change_made_while_the_temporary_file_exists_is_kept_and_reported(
    arm, monkeypatch, change
):
    robot, stamp = load_with_stamp(arm)
    done = while_saving(monkeypatch, arm, lambda: change(arm))
    with pytest.raises(FileChangedError) as info:
        save(editing.set_base_height(robot, 5.0), arm, expect=stamp)
    assert done, "the outside change was made during the save"
    message = str(info.value)
    assert str(arm) in message and "changed on disk since it was opened" in message
    assert "while it was being saved" in message
    assert arm.read_text(encoding="utf-8") == WRITTEN.format(n=7)  # the change is kept
    assert names(arm.parent) == ["arm.toml"]  # no temporary file, no lock file
    # what "overwrite" does once asked: the file as it is now is expected
    save(editing.set_base_height(robot, 5.0), arm, expect=read_stamp(arm))
    assert load(arm).base_height == 5.0 and names(arm.parent) == ["arm.toml"]


def test_a_file_deleted_while_saving_is_reported_and_not_brought_back(arm, monkeypatch):
    robot, stamp = load_with_stamp(arm)
    while_saving(monkeypatch, arm, arm.unlink)
    with pytest.raises(FileChangedError, match="gone"):
        save(editing.set_base_height(robot, 5.0), arm, expect=stamp)
    assert names(arm.parent) == []


def test_a_file_made_while_a_new_one_is_saved_is_reported_and_kept(tmp_path, monkeypatch):
    path = tmp_path / "new.toml"
    robot = editing.new_robot("new", 2)
    while_saving(monkeypatch, path, lambda: path.write_text(TEXT, encoding="utf-8"))
    with pytest.raises(FileChangedError, match="changed on disk"):
        save(robot, path, expect=None)  # None: the file must not exist
    assert path.read_text(encoding="utf-8") == TEXT
    assert names(tmp_path) == ["new.toml"]


def test_saving_without_a_check_still_overwrites(arm, monkeypatch):
    # expect=... (``--force``): no check, today's behaviour; the lock is still taken
    robot = load(arm)
    while_saving(monkeypatch, arm, lambda: write_in_place(arm))
    save(editing.set_base_height(robot, 5.0), arm)
    assert load(arm).base_height == 5.0 and names(arm.parent) == ["arm.toml"]


# -- (b) real concurrent writers, 25 saves ------------------------------------------------

#: writes the file in place, over and over, while dhsim's temporary file
#: exists; prints the last number it wrote once the temporary file is gone
HAMMER = """
import os, sys, time
from pathlib import Path
path, stop = Path(sys.argv[1]), Path(sys.argv[2])
text = sys.stdin.read()
prefix = "." + path.name + "."
def saving():
    return any(n.startswith(prefix) and n.endswith(".tmp") for n in os.listdir(path.parent))
n = 0
print("ready", flush=True)
while not stop.exists():
    if not saving():
        time.sleep(0.0005)
        continue
    while saving():
        n += 1
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(text.format(n=n))
    print(n, flush=True)
"""


def read_line(process: subprocess.Popen) -> str:
    """The writer's next line (waits on the pipe, HANG at most)."""
    ready, _, _ = select.select([process.stdout], [], [], HANG)
    assert ready, f"hung: waited {HANG:g} s for the writer"
    return process.stdout.readline().strip()


def test_a_writer_hammering_the_file_during_25_saves_is_never_overwritten(arm, monkeypatch):
    """The campaign's case: a writer that changes the file while dhsim's
    temporary file exists. Every save reports the change; the writer's last
    content is what the file holds each time."""
    stop = arm.with_name("stop")
    writer = subprocess.Popen(
        [sys.executable, "-c", HAMMER, str(arm), str(stop)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        writer.stdin.write(WRITTEN)
        writer.stdin.close()
        assert read_line(writer) == "ready"
        loaded: list[bytes] = []

        def written_meanwhile() -> None:  # the save waits until the writer wrote
            wait_until(lambda: arm.read_bytes() != loaded[-1], "the writer's change")

        while_saving(monkeypatch, arm, written_meanwhile, times=25)
        for attempt in range(25):
            robot, stamp = load_with_stamp(arm)
            loaded.append(arm.read_bytes())
            mine = editing.set_name(editing.set_base_height(robot, 999.0), f"mine {attempt}")
            with pytest.raises(FileChangedError, match="changed on disk"):
                save(mine, arm, expect=stamp)
            last = int(read_line(writer))  # the writer is idle again
            assert arm.read_text(encoding="utf-8") == WRITTEN.format(n=last)
            assert names(arm.parent) == ["arm.toml"]
    finally:
        stop.touch()
        writer.wait(HANG)
    assert writer.returncode == 0


#: another dhsim: adds 1 to base_height with a checked save, until told to stop;
#: prints how many of its saves were written
OTHER_DHSIM = """
import sys
from pathlib import Path
from dhsim_tui.core.files.robotfile import FileChangedError, load_with_stamp, save
from dhsim_tui.core.model import editing
path, stop = Path(sys.argv[1]), Path(sys.argv[2])
written = 0
print("ready", flush=True)
while not stop.exists():
    robot, stamp = load_with_stamp(path)
    try:
        save(editing.set_base_height(robot, robot.base_height + 1), path, expect=stamp)
        written += 1
    except FileChangedError:
        pass
print(written, flush=True)
"""


def test_two_dhsims_saving_one_file_never_lose_a_save(arm):
    """Both add 1 to the file's base height, as fast as they can: the file
    ends up counting every save either reported as written."""
    stop = arm.with_name("stop")
    other = subprocess.Popen(
        [sys.executable, "-c", OTHER_DHSIM, str(arm), str(stop)],
        stdout=subprocess.PIPE,
        text=True,
        cwd=ROOT,
        env={
            **os.environ,
            "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
        },
    )
    written = reported = 0
    try:
        assert read_line(other) == "ready"
        while written + reported < 25:
            robot, stamp = load_with_stamp(arm)
            try:
                save(editing.set_base_height(robot, robot.base_height + 1), arm, expect=stamp)
                written += 1
            except FileChangedError:
                reported += 1
    finally:
        stop.touch()
        theirs = int(read_line(other))
        other.wait(HANG)
    assert other.returncode == 0
    assert load(arm).base_height == written + theirs  # no save lost
    assert "# a robot file another program also edits" in arm.read_text(encoding="utf-8")
    assert names(arm.parent) == ["arm.toml", "stop"]  # no lock file, no temporary file


# -- (c) symbolic links: another file, even with the same bytes ---------------------------


def test_a_symlink_swapped_in_after_loading_is_a_change_even_to_the_same_bytes(arm):
    robot, stamp = load_with_stamp(arm)
    copy = arm.with_name("copy.toml")
    shutil.copyfile(arm, copy)
    arm.unlink()
    arm.symlink_to(copy.name)
    assert arm.read_bytes() == copy.read_bytes() and read_stamp(arm).digest == stamp.digest
    with pytest.raises(FileChangedError) as info:
        save(editing.set_base_height(robot, 5.0), arm, expect=stamp)
    assert "another file" in str(info.value) and "symbolic link" in str(info.value)
    assert arm.is_symlink() and copy.read_text(encoding="utf-8") == TEXT
    assert names(arm.parent) == ["arm.toml", "copy.toml"]


def test_a_symlink_pointed_elsewhere_or_replaced_is_a_change(tmp_path):
    one, two = tmp_path / "one.toml", tmp_path / "two.toml"
    one.write_text(TEXT, encoding="utf-8")
    two.write_text(TEXT, encoding="utf-8")
    link = tmp_path / "link.toml"
    link.symlink_to(one.name)
    robot, stamp = load_with_stamp(link)
    link.unlink()
    link.symlink_to(two.name)  # the same bytes, another file
    with pytest.raises(FileChangedError, match="another file"):
        save(editing.set_base_height(robot, 5.0), link, expect=stamp)
    link.unlink()
    shutil.copyfile(one, link)  # no link any more: a copy of the same bytes
    with pytest.raises(FileChangedError, match="another file"):
        save(editing.set_base_height(robot, 5.0), link, expect=stamp)
    assert one.read_text(encoding="utf-8") == two.read_text(encoding="utf-8") == TEXT
    assert link.read_text(encoding="utf-8") == TEXT and not link.is_symlink()
    # through an unchanged link, a save still writes the file it points to
    relinked = tmp_path / "relinked.toml"
    relinked.symlink_to(one.name)
    robot, stamp = load_with_stamp(relinked)
    save(editing.set_base_height(robot, 5.0), relinked, expect=stamp)
    assert relinked.is_symlink() and load(one).base_height == 5.0


def test_a_symlink_swapped_in_while_saving_is_reported_and_kept(arm, monkeypatch):
    robot, stamp = load_with_stamp(arm)
    copy = arm.with_name("copy.toml")
    shutil.copyfile(arm, copy)

    def swap() -> None:
        link = arm.with_name("link.tmp")
        link.symlink_to(copy.name)
        os.replace(link, arm)

    while_saving(monkeypatch, arm, swap)
    with pytest.raises(FileChangedError, match="while it was being saved"):
        save(editing.set_base_height(robot, 5.0), arm, expect=stamp)
    assert arm.is_symlink() and os.readlink(arm) == "copy.toml"
    assert copy.read_text(encoding="utf-8") == TEXT
    assert names(arm.parent) == ["arm.toml", "copy.toml"]


# -- (d) the lock: taken, waited for, never left behind ------------------------------------


def test_a_lock_file_left_by_a_killed_save_is_used_and_removed(arm):
    stale = atomicfile.lock_path(arm)
    assert stale.name == ".arm.toml.dhsim-lock"
    stale.touch()
    save(editing.set_base_height(load(arm), 5.0), arm)
    assert names(arm.parent) == ["arm.toml"]


def test_a_non_empty_file_of_the_lock_files_name_is_never_removed(arm):
    mine = atomicfile.lock_path(arm)
    mine.write_text("not dhsim's", encoding="utf-8")
    save(editing.set_base_height(load(arm), 5.0), arm)
    assert mine.read_text(encoding="utf-8") == "not dhsim's"


def test_a_save_waits_for_another_dhsims_lock(arm):
    robot = editing.set_base_height(load(arm), 5.0)
    errors: list[BaseException] = []

    def saving() -> None:
        try:
            save(robot, arm)
        except BaseException as exc:  # reported below
            errors.append(exc)

    with atomicfile.locked(arm):  # another dhsim in the middle of its save
        assert atomicfile.lock_path(arm).exists()
        thread = threading.Thread(target=saving)
        thread.start()
        wait_until(lambda: temporary_files(arm), "the save's temporary file")
        assert load(arm).base_height == 0  # it waits: nothing renamed yet
    thread.join(HANG)
    assert not thread.is_alive() and not errors
    assert load(arm).base_height == 5.0 and names(arm.parent) == ["arm.toml"]


def test_a_lock_held_too_long_is_a_clear_error_and_nothing_is_written(arm, monkeypatch):
    monkeypatch.setattr(atomicfile, "LOCK_WAIT_SECONDS", 0.0)
    with atomicfile.locked(arm):
        with pytest.raises(RobotFileError) as info:
            save(editing.set_base_height(load(arm), 5.0), arm)
        assert "another dhsim is saving this file" in str(info.value)
        assert str(arm) in str(info.value)
        assert names(arm.parent) == [".arm.toml.dhsim-lock", "arm.toml"]  # the holder's
    assert arm.read_text(encoding="utf-8") == TEXT and names(arm.parent) == ["arm.toml"]


def test_a_failed_rename_leaves_no_lock_and_no_temporary_file(arm, monkeypatch):
    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(os, "replace", refuse)  # what a read-only folder does to the rename
    robot, stamp = load_with_stamp(arm)
    with pytest.raises(RobotFileError) as info:
        save(editing.set_base_height(robot, 5.0), arm, expect=stamp)
    assert "cannot save: permission denied" in str(info.value)
    assert arm.read_text(encoding="utf-8") == TEXT and names(arm.parent) == ["arm.toml"]


def test_a_read_only_folder_is_refused_as_before_and_left_clean():
    folder = Path(tempfile.mkdtemp())
    try:
        path = folder / "arm.toml"
        path.write_text(TEXT, encoding="utf-8")
        path.chmod(0o666)
        folder.chmod(0o555)
        robot, stamp = load_with_stamp(path)
        as_root = os.geteuid() == 0
        if as_root:
            os.seteuid(65534)  # root may write anywhere: "nobody" may not
        try:
            with pytest.raises(RobotFileError) as info:
                save(editing.set_base_height(robot, 5.0), path, expect=stamp)
        finally:
            if as_root:
                os.seteuid(0)
        assert str(path) in str(info.value) and "permission denied" in str(info.value)
        assert path.read_text(encoding="utf-8") == TEXT and names(folder) == ["arm.toml"]
    finally:
        folder.chmod(0o755)
        shutil.rmtree(folder)

"""ondisk: the one atomic writer every file goes through, and the bounded reader.

Modes are checked under a umask the test sets (so a wrong mode cannot pass by chance), the
folder's fsync by the descriptors ``os.fsync`` is given, crash safety by a write that fails
half-way (a file-size limit in a child process: the kernel refuses the write, as on a full
disk) and by an exception inside the ``with`` block.
"""

from __future__ import annotations

import os
import re
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from ondisk import (
    AtomicFile,
    TargetError,
    atomic_path,
    check_target,
    read_bounded,
    write_atomically,
)

ROOT = Path(__file__).resolve().parents[2]


def _with_umask(mask: int, action):
    old = os.umask(mask)
    try:
        return action()
    finally:
        os.umask(old)


def _leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


@pytest.mark.parametrize("mask, mode", [(0o022, 0o644), (0o027, 0o640), (0o077, 0o600),
                                        (0o002, 0o664)])
def test_a_new_file_gets_the_mode_open_would_give(tmp_path: Path, mask: int, mode: int):
    target = tmp_path / "new.txt"
    _with_umask(mask, lambda: write_atomically(target, "x\n"))
    assert stat.S_IMODE(target.stat().st_mode) == mode
    assert target.read_text() == "x\n"


@pytest.mark.parametrize("mode", [0o600, 0o640, 0o755, 0o444])
def test_an_existing_file_keeps_its_mode(tmp_path: Path, mode: int):
    target = tmp_path / "kept.txt"
    target.write_text("old")
    target.chmod(mode)
    _with_umask(0o077, lambda: write_atomically(target, b"new"))
    assert stat.S_IMODE(target.stat().st_mode) == mode
    assert target.read_bytes() == b"new"


def test_set_id_bits_are_not_carried_to_new_content(tmp_path: Path):
    target = tmp_path / "tool"
    target.write_text("old")
    target.chmod(0o4755)
    write_atomically(target, "new")
    assert stat.S_IMODE(target.stat().st_mode) == 0o755


def test_the_file_and_then_its_folder_are_fsynced(tmp_path: Path, monkeypatch):
    synced: list[str] = []
    real_fsync = os.fsync

    def recording_fsync(fd: int) -> None:
        synced.append(os.readlink(f"/proc/self/fd/{fd}"))
        real_fsync(fd)

    monkeypatch.setattr(os, "fsync", recording_fsync)
    target = tmp_path / "data.json"
    write_atomically(target, "{}")
    assert len(synced) == 2
    assert re.fullmatch(rf"{re.escape(str(tmp_path))}/\.data\.json\.[0-9a-f]{{8}}\.tmp",
                        synced[0])  # the content, before the rename
    assert synced[1] == str(tmp_path)  # the rename, after it


def test_an_exception_inside_the_block_leaves_the_old_file_and_no_temporary(tmp_path: Path):
    target = tmp_path / "state.txt"
    target.write_text("old")
    with pytest.raises(RuntimeError), AtomicFile(target) as file:
        file.write("half of the new")
        raise RuntimeError("crash")
    assert target.read_text() == "old"
    assert _leftovers(tmp_path) == []


def test_a_write_the_kernel_refuses_leaves_the_old_file_whole(tmp_path: Path):
    target = tmp_path / "state.txt"
    target.write_text("old content\n")
    script = (
        "import resource, signal, sys\n"
        "from ondisk import write_atomically\n"
        "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
        "resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))\n"
        "try:\n"
        "    write_atomically(sys.argv[1], 'y' * 100_000)\n"
        "except OSError as error:\n"
        "    print(error.strerror)\n")
    result = subprocess.run([sys.executable, "-c", script, str(target)], capture_output=True,
                            text=True, timeout=60)
    assert result.stdout.strip() == "File too large", result.stderr
    assert target.read_text() == "old content\n"
    assert _leftovers(tmp_path) == []


def _fifo(path: Path) -> Path:
    os.mkfifo(path)
    return path


def _device(path: Path) -> Path:
    if os.geteuid() != 0:
        pytest.skip("making a device node needs root")
    os.mknod(path, 0o666 | stat.S_IFCHR, os.makedev(1, 7))  # the kernel's "full" device
    return path


def _folder(path: Path) -> Path:
    path.mkdir()
    return path


@pytest.mark.parametrize("make", [_fifo, _device, _folder])
def test_a_fifo_a_device_or_a_folder_is_refused_and_left_as_it_is(tmp_path: Path, make):
    target = make(tmp_path / "target")
    kind = stat.S_IFMT(target.lstat().st_mode)
    with pytest.raises(TargetError, match=f"^{re.escape(str(target))} exists and is not a "
                                          "regular file$"):
        write_atomically(target, "x")
    assert stat.S_IFMT(target.lstat().st_mode) == kind
    assert _leftovers(tmp_path) == []


@pytest.mark.parametrize("dangling", [False, True])
def test_a_symbolic_link_is_neither_written_through_nor_replaced(tmp_path: Path,
                                                                 dangling: bool):
    victim = tmp_path / "victim.txt"
    if not dangling:
        victim.write_text("precious")
    link = tmp_path / "save.pl"
    link.symlink_to(victim)
    with pytest.raises(TargetError, match=f"is a symbolic link \\(to {re.escape(str(victim))}"):
        write_atomically(link, "overwritten")
    assert link.is_symlink()
    assert victim.exists() is not dangling
    if not dangling:
        assert victim.read_text() == "precious"


def test_a_link_put_in_place_while_writing_is_refused_at_commit(tmp_path: Path):
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    target = tmp_path / "trace.txt"
    file = AtomicFile(target)
    file.write("line\n")
    target.symlink_to(victim)
    with pytest.raises(TargetError, match="symbolic link"):
        file.commit()
    assert victim.read_text() == "precious" and target.is_symlink()
    assert _leftovers(tmp_path) == []


def test_a_writer_that_wants_a_name_gets_one_with_the_suffix_and_its_file_is_put_in_place(
        tmp_path: Path):
    target = tmp_path / "run.mp4"
    target.write_bytes(b"old video")
    target.chmod(0o640)
    with atomic_path(target) as partial:
        assert partial.parent == tmp_path and partial.name.startswith(".run.mp4.")
        assert partial.suffix == ".mp4" and partial.exists()
        with open(partial, "wb") as stream:  # as ffmpeg does: by name, truncating
            stream.write(b"new video")
        assert target.read_bytes() == b"old video"
    assert target.read_bytes() == b"new video"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640
    assert _leftovers(tmp_path) == []


def test_a_writer_by_name_that_fails_leaves_the_old_file(tmp_path: Path):
    target = tmp_path / "run.mp4"
    target.write_bytes(b"old video")
    with pytest.raises(RuntimeError), atomic_path(target) as partial:
        partial.write_bytes(b"half")
        raise RuntimeError("ffmpeg died")
    assert target.read_bytes() == b"old video" and _leftovers(tmp_path) == []
    victim = tmp_path / "victim"
    victim.write_text("precious")
    link = tmp_path / "link.mp4"
    link.symlink_to(victim)
    with pytest.raises(TargetError, match="symbolic link"), atomic_path(link):
        pass
    assert victim.read_text() == "precious"


def test_a_missing_folder_is_made_and_a_file_in_the_way_is_a_clear_error(tmp_path: Path):
    assert write_atomically(tmp_path / "a" / "b" / "c.txt", "x") == tmp_path / "a/b/c.txt"
    (tmp_path / "blocker").write_text("a file")
    with pytest.raises(TargetError, match="cannot create the folder .*blocker"):
        check_target(tmp_path / "blocker" / "sub" / "c.txt")


def test_importing_the_writers_never_touches_the_umask():
    script = (
        "import os\n"
        "calls = []\n"
        "real = os.umask\n"
        "os.umask = lambda mask: calls.append(mask) or real(mask)\n"
        "import ondisk, goalagent.beliefs, goalagent.trace, goalagent.eis.envs.support\n"
        "import behaviours.learners.persist, behaviours.learners.known_objects\n"
        "import robot.reproduce.framework.documents, robot.reproduce.framework.runner\n"
        "import robot.affordance\n"
        "from ondisk import write_atomically\n"
        "import tempfile, pathlib\n"
        "with tempfile.TemporaryDirectory() as folder:\n"
        "    write_atomically(pathlib.Path(folder) / 'f', 'x')\n"
        "print(calls)\n")
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            timeout=120, cwd=ROOT)
    assert result.stdout.strip() == "[]", result.stderr


def test_no_module_writes_a_file_in_place_by_itself():
    """One writer: no temporary files, renames or umask games outside ondisk."""
    pattern = re.compile(r"os\.replace|os\.rename|mkstemp|NamedTemporaryFile|os\.umask|"
                         r"\.write_text\(|\.write_bytes\(|cv2\.imwrite")
    found = []
    for package in ("goalagent", "sim", "behaviours", "robot", "scripts"):
        for path in sorted((ROOT / package).rglob("*.py")):
            for number, line in enumerate(path.read_text().splitlines(), 1):
                if pattern.search(line):
                    found.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()}")
    assert found == []


@pytest.mark.parametrize("make, says", [(_fifo, "a FIFO, not a regular file"),
                                        (_folder, "a directory, not a regular file")])
def test_the_bounded_reader_refuses_what_is_not_a_regular_file(tmp_path: Path, make, says):
    target = make(tmp_path / "input")
    with pytest.raises(OSError, match=says):
        read_bounded(target, 100)


def test_the_bounded_reader_reads_at_most_its_limit(tmp_path: Path):
    target = tmp_path / "input"
    target.write_bytes(b"x" * 101)
    assert read_bounded(target, 101) == b"x" * 101
    with pytest.raises(OSError, match="101 bytes: larger than the 100 bytes accepted"):
        read_bounded(target, 100)
    with pytest.raises(OSError, match="grew past the 100 bytes"):  # says size 0, holds more
        read_bounded("/proc/self/maps", 100)

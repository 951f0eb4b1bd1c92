"""A save cut by a signal's stop at any point: the file is the old one or the new one, whole,
the stop comes out as itself (not turned into another error), and no descriptor is closed
twice (a second close hits whatever file took the number: the run's next save then failed
with EBADF and the stop was lost). A stop that lands just after ``os.open`` returns the
folder's descriptor for its fsync leaks that one descriptor (nothing in Python hands it over
in one step); the run it stops is ending, so only closing twice is a fault."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from ondisk import write_atomically
from tests.interrupt_points import Stop, interrupt_at

OLD, NEW = "old\n", "new content\n" * 500


def open_descriptors() -> dict[str, str]:
    """The process's open descriptors and what each names."""
    found = {}
    for name in os.listdir("/proc/self/fd"):
        try:
            found[name] = os.readlink(f"/proc/self/fd/{name}")
        except FileNotFoundError:  # the descriptor listdir itself used
            continue
    return found


@pytest.mark.parametrize("data", [NEW, NEW.encode()], ids=["text", "bytes"])
def test_a_stop_at_any_point_of_a_save_leaves_a_whole_file_and_every_descriptor(
        tmp_path: Path, data: str | bytes) -> None:
    target = tmp_path / "saved.pl"
    before = open_descriptors()
    point = 0
    while True:
        point += 1
        target.write_text(OLD)
        with interrupt_at(point, ("ondisk/atomic.py",)) as seen:
            try:
                write_atomically(target, data)
            except Stop:
                pass
        assert target.read_text() in (OLD, NEW), point
        assert open_descriptors().items() >= before.items(), point
        if seen[0] < point:  # the save ran to its end before this point
            break
    assert point > 50  # every opcode of the save was a point: the walk covered it
    assert target.read_text() == NEW

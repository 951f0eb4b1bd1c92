"""Reading a whole file that may be hostile: only a regular file, only up to a limit.

A path given by a user may name ``/dev/zero`` (endless), a FIFO (blocks until a writer comes),
a folder or a file of gigabytes; each is refused before anything is read, with a reason a
person can act on.
"""

from __future__ import annotations

import os
import stat

from ondisk.atomic import file_kind

_READ_CHUNK = 1 << 20


def read_bounded(path: str | os.PathLike[str], limit: int) -> bytes:
    """The bytes of ``path`` if it is a regular file of at most ``limit`` bytes.

    The file is opened without blocking (a FIFO would wait for a writer) and checked on the
    open descriptor, so a device, FIFO, socket or folder is refused before anything is read,
    and at most ``limit + 1`` bytes are ever read (a file growing meanwhile is caught).
    Raises ``OSError`` (``FileNotFoundError`` for a missing file) with a readable message.
    """
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise OSError(f"{file_kind(info.st_mode)}, not a regular file")
        if info.st_size > limit:
            raise OSError(f"{info.st_size} bytes: larger than the {limit} bytes accepted")
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(fd, min(limit + 1 - size, _READ_CHUNK))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        if size > limit:
            raise OSError(f"grew past the {limit} bytes accepted while being read")
        return b"".join(chunks)
    finally:
        os.close(fd)

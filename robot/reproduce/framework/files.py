"""Every file the workbench writes (pages, plots, JSON, cache entries) is written atomically:
all or nothing, even when the run is killed mid-write."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

_UMASK = os.umask(0)
os.umask(_UMASK)


def write_atomically(path: Path, data: bytes) -> Path:
    """A temporary file in the same folder, fsync, then os.replace: all or nothing. The file
    gets the permissions a plainly created one would (mkstemp makes it owner-only)."""
    fd, temporary = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        os.chmod(temporary, 0o666 & ~_UMASK)
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return path

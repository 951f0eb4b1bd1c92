"""The user's cache: where goalagent keeps what it can rebuild, and reading back only what the
user's own processes could have put there.

Some of what is kept runs code when it is loaded (a pickle, as a ``.pyc`` does), so a cached
file is read only when it and its folder belong to the running user and nobody else may write
either: a file planted by another account, or in a folder another account may write, is
treated as missing and rebuilt.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from ondisk.bounded import read_bounded


def cache_folder() -> Path:
    """``$XDG_CACHE_HOME/goalagent`` (``~/.cache/goalagent`` when the variable is unset or
    empty, as the XDG base-directory specification says)."""
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "goalagent"


def _only_ours(info: os.stat_result) -> bool:
    """Owned by this process's user, and writable by no group or other account."""
    return (info.st_uid == os.geteuid()
            and not info.st_mode & (stat.S_IWGRP | stat.S_IWOTH))


def read_own(path: Path, limit: int) -> bytes | None:
    """The bytes of the cached file ``path`` (a regular file of at most ``limit`` bytes), or
    None when it is missing, unreadable, a link, too large, or not only the user's (see the
    module's docstring). The checks are made on the path before it is opened; only the user
    can swap what they looked at, since nobody else may write the folder."""
    try:
        folder = os.lstat(path.parent)
        own = os.lstat(path)
    except OSError:
        return None
    if not (stat.S_ISDIR(folder.st_mode) and _only_ours(folder)
            and stat.S_ISREG(own.st_mode) and _only_ours(own)):
        return None
    try:
        return read_bounded(path, limit)
    except OSError:
        return None


def make_cache_folder(folder: Path) -> None:
    """Creates ``folder`` (and its parents) for the user alone, if it does not exist."""
    folder.mkdir(mode=0o700, parents=True, exist_ok=True)

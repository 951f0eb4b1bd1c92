"""The user's cache folder: where goalagent keeps what it learns or computes between runs
(the robot's models and known objects, the reproductions' finished seeds)."""

from __future__ import annotations

import os
from pathlib import Path


def cache_folder() -> Path:
    """``$XDG_CACHE_HOME/goalagent`` (``~/.cache/goalagent`` when the variable is unset or
    empty, as the XDG base-directory specification says)."""
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "goalagent"

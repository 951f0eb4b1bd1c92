"""Where the robot application keeps what it learns between runs (under XDG_CACHE_HOME)."""

from __future__ import annotations

import os
from pathlib import Path


def cache_dir() -> Path:
    """``$XDG_CACHE_HOME/goalagent`` (``~/.cache/goalagent`` by default)."""
    return Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "goalagent"


def default_model_path() -> Path:
    """Learned effect models Ĥ (chapter 6) unless the garbage environment's ``models`` says."""
    return cache_dir() / "affordance-models.json"


def default_objects_path() -> Path:
    """The known-object database (chapter 5) unless the environment's ``objects`` says."""
    return cache_dir() / "known-objects.json"

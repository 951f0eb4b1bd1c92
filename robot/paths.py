"""Where the robot application keeps what it learns between runs (under XDG_CACHE_HOME)."""

from __future__ import annotations

from pathlib import Path

from ondisk.cache import cache_folder


def default_model_path() -> Path:
    """Learned effect models Ĥ (chapter 6) unless the garbage environment's ``models`` says."""
    return cache_folder() / "affordance-models.json"


def default_objects_path() -> Path:
    """The known-object database (chapter 5) unless the environment's ``objects`` says."""
    return cache_folder() / "known-objects.json"

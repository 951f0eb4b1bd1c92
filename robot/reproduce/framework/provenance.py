"""Where a seed's result came from: the package and its git commit, the Python, MuJoCo and
SWI-Prolog versions, the numerical libraries, the platform. Collected once per process, in
the process that ran the seed (a Ray worker on another node reports its own)."""

from __future__ import annotations

import functools
import hashlib
import platform
import shutil
import subprocess
from importlib import metadata
from pathlib import Path

from pydantic import BaseModel, ConfigDict

ROOT = Path(__file__).resolve().parents[3]
CODE = ("goalagent", "behaviours", "sim", "robot", "agents", "pyproject.toml")
"""What makes a commit ``+dirty`` when changed: the code, not the pages a run writes."""


@functools.cache
def code_fingerprint() -> str:
    """A hash of the code's files (``CODE`` under ``ROOT``, compiled files aside): a cached
    seed made by other code is not this code's result, whether or not the change was
    committed (the git commit does not see uncommitted edits)."""
    digest = hashlib.sha256()
    for name in CODE:
        top = ROOT / name
        if top.is_file():
            files = [top]
        else:
            files = sorted(path for path in top.rglob("*")
                           if path.is_file() and "__pycache__" not in path.parts)
        for path in files:
            digest.update(path.relative_to(ROOT).as_posix().encode() + b"\0")
            digest.update(path.read_bytes() + b"\0")
    return digest.hexdigest()


class Provenance(BaseModel):
    """Versions and platform of the process that ran a seed."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    goalagent: str | None
    git_commit: str | None
    """The commit of the source tree, ``+dirty`` when its code (not its docs or results) had
    uncommitted changes; None outside a git checkout."""
    python: str
    mujoco: str | None
    swi_prolog: str | None
    numpy: str | None
    scipy: str | None
    scikit_learn: str | None
    platform: str


@functools.cache
def current() -> Provenance:
    """This process's provenance."""
    return Provenance(goalagent=_version("goalagent"), git_commit=_commit(),
                      python=platform.python_version(), mujoco=_version("mujoco"),
                      swi_prolog=_swipl(), numpy=_version("numpy"), scipy=_version("scipy"),
                      scikit_learn=_version("scikit-learn"), platform=platform.platform())


def _version(distribution: str) -> str | None:
    try:
        return metadata.version(distribution)
    except metadata.PackageNotFoundError:
        return None


def _run(command: list[str]) -> str | None:
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=30, cwd=ROOT)
    except (OSError, subprocess.SubprocessError):
        return None
    return done.stdout.strip() if done.returncode == 0 else None


def _commit() -> str | None:
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        return None
    commit = _run(["git", "rev-parse", "HEAD"])
    if commit is None:
        return None
    changes = _run(["git", "status", "--porcelain", "--untracked-files=no", "--", *CODE])
    return commit + ("+dirty" if changes else "")


def _swipl() -> str | None:
    """``swipl --version``'s number (``SWI-Prolog version 9.0.4 for x86_64-linux``)."""
    text = _run(["swipl", "--version"]) if shutil.which("swipl") else None
    words = (text or "").split()
    return words[2] if len(words) > 2 and words[1] == "version" else None

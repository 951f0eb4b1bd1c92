"""Saving learners as versioned JSON, written atomically; unreadable files give clear errors.

A file holds ``{"format": FORMAT, "version": VERSION, "kind": ..., "params": ..., "state":
...}``. JSON rather than pickle: a saved model is data a user may inspect or hand on, and
loading one must never run code.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

__all__ = [
    "FORMAT", "VERSION", "LearnerFileError", "json_params", "read_learner", "write_learner",
    "write_text_atomically",
]

FORMAT = "goalagent-learner"
VERSION = 1


class LearnerFileError(ValueError):
    """A file that cannot be read as a saved learner of the expected kind."""


def write_learner(path: str | os.PathLike[str], kind: str, params: dict, state: dict) -> Path:
    """Write atomically (see ``write_text_atomically``)."""
    text = json.dumps({"format": FORMAT, "version": VERSION, "kind": kind,
                       "params": params, "state": state}, indent=1)
    return write_text_atomically(path, text)


def write_text_atomically(path: str | os.PathLike[str], text: str) -> Path:
    """A temporary file in the same folder, fsync, then ``os.replace``: all or nothing."""
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp_name = tempfile.mkstemp(prefix=f".{target.name}.", dir=target.parent)
    try:
        umask = os.umask(0)
        os.umask(umask)
        os.fchmod(fd, 0o666 & ~umask)  # mkstemp makes 0600; a saved file is an ordinary file
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp_name, target)
    except BaseException:
        Path(tmp_name).unlink(missing_ok=True)
        raise
    return target


def read_learner(path: str | os.PathLike[str], kind: str) -> tuple[dict, dict]:
    """(params, state) of a saved learner of ``kind``, or LearnerFileError naming the file."""
    source = Path(path)
    try:
        data = json.loads(source.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise LearnerFileError(f"cannot read learner file {str(source)!r}: {exc}") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise LearnerFileError(f"{str(source)!r} is not a goalagent learner file")
    if data.get("version") != VERSION:
        raise LearnerFileError(f"learner file {str(source)!r} has version "
                               f"{data.get('version')!r}; this goalagent reads version {VERSION}")
    if data.get("kind") != kind:
        raise LearnerFileError(f"learner file {str(source)!r} holds a {data.get('kind')!r}, "
                               f"not a {kind!r}")
    params, state = data.get("params"), data.get("state")
    if not isinstance(params, dict) or not isinstance(state, dict):
        raise LearnerFileError(f"learner file {str(source)!r} lacks its params or state")
    return params, state


def json_params(estimator: object) -> dict:
    """An estimator's ``get_params()`` fit for JSON: a generator ``random_state`` becomes None.

    (Tuples become lists on writing; loaders turn them back where it matters.)
    """
    params = dict(estimator.get_params(deep=False))  # type: ignore[attr-defined]
    if "random_state" in params and not isinstance(params["random_state"], (int, type(None))):
        params["random_state"] = None
    return params

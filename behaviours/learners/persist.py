"""Saving learners as versioned JSON, written atomically; unreadable files give clear errors.

A file holds ``{"format": FORMAT, "version": VERSION, "kind": ..., "params": ..., "state":
...}``. JSON rather than pickle: a saved model is data a user may inspect or hand on, and
loading one must never run code. Every JSON store of behaviours (learners, effect models,
known objects) is read through :func:`read_json`: only a regular file of at most
``MAX_STORE_BYTES`` is read, and a malformed one is an error at its ``file:line:col``.
(goalagent has the same guard for program files; behaviours may not import goalagent.)
"""

from __future__ import annotations

import json
import os
import stat
from pathlib import Path

from behaviours.learners.schemas import SchemaError, check
from ondisk import write_atomically

__all__ = [
    "FORMAT", "MAX_STORE_BYTES", "VERSION", "LearnerFileError", "StoreFileError",
    "check_store", "json_params", "read_json", "read_learner", "read_store", "write_learner",
    "write_text_atomically",
]

FORMAT = "goalagent-learner"
VERSION = 1
MAX_STORE_BYTES = 64 * 2**20
"""Largest JSON store read (a model or learner file is a few kB to a few MB)."""


class StoreFileError(ValueError):
    """A JSON store that cannot be read: not a regular file, too large, or not JSON."""


def read_json(path: str | os.PathLike[str], what: str) -> object:
    """The JSON value in ``path`` (``what`` names the kind of file in messages).

    The file is opened without blocking and checked on the open descriptor, so a device,
    FIFO or directory is refused before anything is read, and at most MAX_STORE_BYTES + 1
    bytes are read. Malformed JSON (also nesting too deep, or a number too long to convert)
    is a StoreFileError at ``file:line:col``; ``NaN`` and ``Infinity`` are refused too."""
    where = str(path)
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
        try:
            info = os.fstat(fd)
            if not stat.S_ISREG(info.st_mode):
                raise StoreFileError(f"cannot read {what} {where!r}: not a regular file")
            if info.st_size > MAX_STORE_BYTES:
                raise StoreFileError(f"cannot read {what} {where!r}: {info.st_size} bytes, "
                                     f"more than the {MAX_STORE_BYTES} accepted")
            with os.fdopen(os.dup(fd), "rb") as stream:
                data = stream.read(MAX_STORE_BYTES + 1)
        finally:
            os.close(fd)
        if len(data) > MAX_STORE_BYTES:
            raise StoreFileError(f"cannot read {what} {where!r}: it grew past the "
                                 f"{MAX_STORE_BYTES} bytes accepted")
        return json.loads(data.decode("utf-8"), parse_constant=_not_a_json_number)
    except json.JSONDecodeError as exc:
        raise StoreFileError(f"cannot read {what} {where}:{exc.lineno}:{exc.colno}: not JSON: "
                             f"{exc.msg}") from None
    except UnicodeDecodeError as exc:
        raise StoreFileError(f"cannot read {what} {where!r}: not UTF-8 text (byte "
                             f"{exc.start})") from None
    except RecursionError:
        raise StoreFileError(f"cannot read {what} {where!r}: JSON nested too deeply") from None
    except (OSError, ValueError) as exc:  # ValueError: e.g. an integer of 5,000 digits
        if isinstance(exc, StoreFileError):
            raise
        reason = getattr(exc, "strerror", None) or exc
        raise StoreFileError(f"cannot read {what} {where!r}: {reason}") from None


def _not_a_json_number(name: str) -> object:
    """``NaN``, ``Infinity`` and ``-Infinity``, which Python's json reads, are not JSON."""
    raise ValueError(f"{name} is not a JSON number")


class LearnerFileError(ValueError):
    """A file that cannot be read as a saved learner of the expected kind."""


def write_learner(path: str | os.PathLike[str], kind: str, params: dict, state: dict) -> Path:
    """Write atomically (see ``write_text_atomically``)."""
    text = json.dumps({"format": FORMAT, "version": VERSION, "kind": kind,
                       "params": params, "state": state}, indent=1)
    return write_text_atomically(path, text)


def write_text_atomically(path: str | os.PathLike[str], text: str) -> Path:
    """Replace ``path`` by ``text`` all or nothing, also after kill -9 or a power cut
    (``ondisk.write_atomically``: the file keeps its mode; a link, device, FIFO or folder
    is refused, never replaced)."""
    return write_atomically(path, text)


def read_store(path: str | os.PathLike[str], what: str, format_: str, version: int,
               error: type[ValueError]) -> dict:
    """The JSON object of a versioned store (``read_json``) whose ``format`` and ``version``
    identify it as a ``what`` this goalagent reads, or ``error`` naming the file."""
    where = str(path)
    try:
        data = read_json(path, what)
    except StoreFileError as exc:
        raise error(str(exc)) from None
    if not isinstance(data, dict) or data.get("format") != format_:
        raise error(f"{where!r} is not a goalagent {what}")
    if data.get("version") != version:
        raise error(f"{what} {where!r} has version {data.get('version')!r}; this goalagent "
                    f"reads version {version}")
    return data


def check_store(data: dict, schema: str, path: str | os.PathLike[str], what: str,
                error: type[ValueError]) -> None:
    """``data`` checked against ``schemas/SCHEMA.schema.json``, or ``error`` naming the file
    and the path of the first bad field."""
    try:
        check(data, schema)
    except SchemaError as exc:
        raise error(f"{what} {str(path)!r}: {exc}") from None


def read_learner(path: str | os.PathLike[str], kind: str) -> tuple[dict, dict]:
    """(params, state) of a saved learner of ``kind``, or LearnerFileError naming the file:
    the format, version and kind identify the file, then the kind's JSON Schema
    (``schemas/KIND.schema.json``) checks every field, naming the first bad one."""
    data = read_store(path, "learner file", FORMAT, VERSION, LearnerFileError)
    if data.get("kind") != kind:
        raise LearnerFileError(f"learner file {str(path)!r} holds a {data.get('kind')!r}, "
                               f"not a {kind!r}")
    check_store(data, kind, path, "learner file", LearnerFileError)
    return data["params"], data["state"]


def json_params(estimator: object) -> dict:
    """An estimator's ``get_params()`` fit for JSON: a generator ``random_state`` becomes None.

    (Tuples become lists on writing; loaders turn them back where it matters.)
    """
    params = dict(estimator.get_params(deep=False))  # type: ignore[attr-defined]
    if "random_state" in params and not isinstance(params["random_state"], (int, type(None))):
        params["random_state"] = None
    return params

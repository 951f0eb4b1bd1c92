"""Finished (config, seed) results on disk, one file each, written atomically as soon as the
seed finishes: a reproduction or sweep that is interrupted (Ctrl-C, a killed process, a lost
node) resumes from them and never runs a finished seed again. An entry that cannot be read
back as the study's result is reported with its path and run again, never used; an entry
made by other code (``code_fingerprint``: any change to the code's files since) is stale and
run again."""

from __future__ import annotations

import json
from pathlib import Path

from pydantic import ValidationError

from ondisk import write_atomically
from ondisk.cache import cache_folder
from robot.reproduce.framework.provenance import Provenance, code_fingerprint
from robot.reproduce.framework.tasks import SCHEMA_VERSION, Finished, Task


class CorruptEntry(ValueError):
    """A cache entry that is not a finished result of its task."""

    def __init__(self, path: Path, reason: str) -> None:
        super().__init__(f"corrupt cache entry {path}: {reason}")
        self.path = path


def default_folder() -> Path:
    """``$XDG_CACHE_HOME/goalagent/reproduce`` (``~/.cache/...`` without the variable)."""
    return cache_folder() / "reproduce"


class StaleEntry(ValueError):
    """A cache entry of this config and seed made by code that has changed since."""


class Cache:
    """The entries under ``folder``: ``STUDY/KEY-seedN.json``."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder

    def path(self, task: Task) -> Path:
        return self.folder / task.study.name / f"{task.key[:24]}-seed{task.seed}.json"

    def load(self, task: Task) -> Finished | None:
        """The task's finished result, None if there is none; CorruptEntry if the entry does
        not hold it, StaleEntry if other code made it."""
        path = self.path(task)
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            return None
        except (OSError, UnicodeDecodeError) as error:
            raise CorruptEntry(path, str(error)) from None
        try:
            entry = json.loads(text)
            if not isinstance(entry, dict):
                raise CorruptEntry(path, "not a JSON object")
            if entry.get("schema_version") != SCHEMA_VERSION or entry.get("key") != task.key:
                raise CorruptEntry(path, "it is not this study's config and seed")
            result = task.study.result.model_validate(entry["result"])
            provenance = Provenance.model_validate(entry["provenance"])
            seconds = float(entry["seconds"])
        except json.JSONDecodeError as error:
            raise CorruptEntry(path, f"not JSON ({error})") from None
        except ValidationError as error:
            first = error.errors()[0]
            where = ".".join(str(part) for part in first["loc"])
            raise CorruptEntry(path, f"{where}: {first['msg']}") from None
        except (KeyError, TypeError, ValueError) as error:
            if isinstance(error, CorruptEntry):
                raise
            raise CorruptEntry(path, f"{type(error).__name__}: {error}") from None
        if entry.get("code") != code_fingerprint():
            raise StaleEntry(path)
        return Finished(task, result, seconds, provenance)

    def store(self, finished: Finished) -> Path:
        """Write the entry atomically."""
        task = finished.task
        path = self.path(task)
        path.parent.mkdir(parents=True, exist_ok=True)
        entry = {"schema_version": SCHEMA_VERSION, "study": task.study.name, "seed": task.seed,
                 "key": task.key, "code": code_fingerprint(),
                 "config": task.config.model_dump(mode="json"),
                 "seconds": finished.seconds,
                 "provenance": finished.provenance.model_dump(mode="json"),
                 "result": finished.result.model_dump(mode="json")}
        return write_atomically(path, json.dumps(entry, allow_nan=False).encode())

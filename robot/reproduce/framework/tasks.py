"""One unit of work, a (config, seed) of a study, and what running it gives: the typed result,
the seconds it took and the provenance of the process that ran it. ``execute`` is what every
backend calls, in this process, a pool worker or a Ray worker."""

from __future__ import annotations

import hashlib
import json
import time
from collections.abc import Callable
from dataclasses import dataclass

from pydantic import ValidationError

from robot.reproduce.framework.provenance import Provenance, current
from robot.reproduce.framework.study import SeedResult, Study, StudyConfig

SCHEMA_VERSION = 2
"""The version of every JSON the workbench writes (documents and cache entries). Version 1
was the untyped ``{summary, seeds}`` of the first ``goalagent reproduce``."""


class ReproductionFailed(RuntimeError):
    """A seed's run raised, or returned something that is not the study's result type."""


@dataclass(frozen=True)
class Task:
    """A study's config and one seed."""

    study: Study
    config: StudyConfig
    seed: int

    @property
    def key(self) -> str:
        """What identifies the task's result: the study, the schema, every config value and
        the seed (the cache's file name)."""
        text = json.dumps([self.study.name, SCHEMA_VERSION, self.config.model_dump(mode="json"),
                           self.seed], sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(text.encode()).hexdigest()


@dataclass(frozen=True)
class Finished:
    """A task's result, how long it took and where it ran."""

    task: Task
    result: SeedResult
    seconds: float
    provenance: Provenance


def execute(task: Task, progress: Callable[[float], None]) -> Finished:
    """Run one task; an exception or a result of the wrong type becomes ReproductionFailed
    naming the study and the seed."""
    study, started = task.study, time.perf_counter()
    try:
        result = study.run(task.config, task.seed, progress)
    except Exception as error:
        raise ReproductionFailed(f"{study.name}: seed {task.seed} failed: "
                                 f"{type(error).__name__}: {error}") from None
    if not isinstance(result, study.result):
        raise ReproductionFailed(f"{study.name}: seed {task.seed} returned "
                                 f"{type(result).__name__}, not {study.result.__name__}")
    try:
        json.dumps(result.model_dump(mode="json"), allow_nan=False)
    except (TypeError, ValueError, ValidationError) as error:
        raise ReproductionFailed(f"{study.name}: seed {task.seed}'s result is not plain "
                                 f"JSON ({error})") from None
    return Finished(task, result, round(time.perf_counter() - started, 3), current())

"""The JSON a reproduction or a sweep writes, typed and versioned (``schema_version``): the
full config, the provenance of the processes that ran the seeds, every seed's result and
seconds, and the statistics. The same seeds on the local pool or on Ray give the same
document but for the seconds."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, ValidationError

from ondisk import write_atomically
from robot.reproduce.framework.provenance import Provenance
from robot.reproduce.framework.statistics import Summary
from robot.reproduce.framework.study import SeedResult, Study
from robot.reproduce.framework.tasks import SCHEMA_VERSION, Finished


class DocumentError(ValueError):
    """A JSON that is not a document of this schema (the message names the file)."""


class Frozen(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid")


class SeedRecord(Frozen):
    """One seed: its result, the seconds it took, and which provenance ran it."""

    seed: int
    seconds: float
    provenance: int
    """Index into the document's ``provenance`` list."""
    result: dict[str, Any]


class ReproductionDocument(Frozen):
    """``NAME.json``."""

    schema_version: Literal[2]
    kind: Literal["reproduction"]
    study: str
    description: str
    command: str
    config: dict[str, Any]
    provenance: list[Provenance]
    seeds: list[SeedRecord]
    summary: Summary

    def results(self, study: Study) -> list[SeedResult]:
        """The seeds' results as the study's typed results."""
        return [study.result.model_validate(record.result) for record in self.seeds]


class SweepCell(Frozen):
    """One combination of the grid's values."""

    values: dict[str, Any]
    config: dict[str, Any]
    seeds: list[SeedRecord]
    summary: Summary


class SweepDocument(Frozen):
    """``NAME-sweep-KEYS.json``."""

    schema_version: Literal[2]
    kind: Literal["sweep"]
    study: str
    description: str
    command: str
    config: dict[str, Any]
    """The config every cell starts from (its grid keys then set per cell)."""
    grid: dict[str, list[Any]]
    provenance: list[Provenance]
    cells: list[SweepCell]


def records(finished: Sequence[Finished],
            provenance: list[Provenance]) -> list[SeedRecord]:
    """The seeds in seed order; each provenance is added to ``provenance`` once."""
    out = []
    for item in sorted(finished, key=lambda f: f.task.seed):
        if item.provenance not in provenance:
            provenance.append(item.provenance)
        out.append(SeedRecord(seed=item.task.seed, seconds=item.seconds,
                              provenance=provenance.index(item.provenance),
                              result=item.result.model_dump(mode="json")))
    return out


def write(document: ReproductionDocument | SweepDocument, path: Path) -> Path:
    """The document as indented JSON, written atomically."""
    text = json.dumps(document.model_dump(mode="json"), indent=1, allow_nan=False,
                      ensure_ascii=False)
    return write_atomically(path, text.encode())


def read(path: Path) -> ReproductionDocument | SweepDocument:
    """A document from ``path``; DocumentError with the file and the reason otherwise."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
        raise DocumentError(f"{path}: cannot read it: {error}") from None
    if not isinstance(data, dict):
        raise DocumentError(f"{path}: not a reproduction's JSON (no object)")
    version = data.get("schema_version")
    if version != SCHEMA_VERSION:
        raise DocumentError(f"{path}: schema version {version or 1}, this goalagent reads "
                            f"version {SCHEMA_VERSION}: run the reproduction again")
    model = SweepDocument if data.get("kind") == "sweep" else ReproductionDocument
    try:
        return model.model_validate(data)
    except ValidationError as error:
        first = error.errors()[0]
        where = ".".join(str(part) for part in first["loc"])
        raise DocumentError(f"{path}: {where}: {first['msg']}") from None

"""``goalagent sweep``: a study over a grid of parameter values, one cell per combination,
every cell's seeds in one pool (so two cores, or a cluster, stay busy across cells), then
``NAME-sweep-KEYS.json``, a markdown table of the headline metrics and the claims' verdicts
per cell, and a plot of each headline metric against the swept parameter."""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from pydantic import ValidationError
from rich.console import Console

from ondisk import write_atomically
from robot.reproduce.framework import documents
from robot.reproduce.framework.backends import Backend
from robot.reproduce.framework.cache import Cache
from robot.reproduce.framework.documents import DocumentError, SweepCell, SweepDocument
from robot.reproduce.framework.pages import cell_label, sweep_page
from robot.reproduce.framework.plots import SweepLine, render_sweep
from robot.reproduce.framework.provenance import Provenance
from robot.reproduce.framework.runner import Tally, command_line, run_tasks
from robot.reproduce.framework.settings import SettingError
from robot.reproduce.framework.statistics import summarize
from robot.reproduce.framework.study import Metric, SeedResult, Study, StudyConfig
from robot.reproduce.framework.tasks import SCHEMA_VERSION, Task

HEADLINE_DEFAULT = 4
"""Metrics a sweep reports when the study names no headline ones: its first few."""


@dataclass(frozen=True)
class SweepOutcome:
    """What a sweep measured and where it wrote it."""

    document: SweepDocument
    files: list[Path]
    tally: Tally = Tally()


def stem(study: Study, keys: Sequence[str]) -> str:
    """``xcs-mux-sweep-N`` for a grid over N (``-sweep-N-p_hash`` over two keys)."""
    return f"{study.name}-sweep-{'-'.join(keys)}"


def cells(study: Study, base: StudyConfig,
          grid: dict[str, list[object]]) -> list[tuple[dict[str, object], StudyConfig]]:
    """Every combination of the grid's values, as (values, config); SettingError when a
    combination is not a valid config."""
    found = []
    for combination in itertools.product(*grid.values()):
        values = dict(zip(grid, combination, strict=True))
        try:
            config = study.config.model_validate({**base.model_dump(), **values})
        except ValidationError as error:
            raise SettingError(f"--grid cell {cell_label(values)}: "
                               f"{error.errors()[0]['msg']}") from None
        found.append((values, config))
    return found


def sweep(study: Study, base: StudyConfig, grid: dict[str, list[object]], seeds: Sequence[int],
          backend: Backend, out: Path, *, cache: Cache | None = None,
          console: Console | None = None, fresh: bool = False) -> SweepOutcome:
    """Run every cell's seeds in one pool and write the sweep's outputs into ``out``."""
    combinations = cells(study, base, grid)
    tasks = [Task(study, config, seed) for _, config in combinations for seed in seeds]
    finished, tally = run_tasks(tasks, backend, cache, console, fresh)
    provenance: list[Provenance] = []
    built = []
    for index, (values, config) in enumerate(combinations):
        records = documents.records(finished[index * len(seeds):(index + 1) * len(seeds)],
                                    provenance)
        built.append(_cell(study, config, values, records))
    document = SweepDocument(
        schema_version=SCHEMA_VERSION, kind="sweep", study=study.name,
        description=study.description,
        command=command_line(study, base, seeds, verb="sweep", grid=grid),
        config=base.model_dump(mode="json"), grid=_plain_grid(grid), provenance=provenance,
        cells=built)
    return SweepOutcome(document, write_sweep(study, document, out), tally)


def _plain_grid(grid: dict[str, list[object]]) -> dict[str, list[object]]:
    return {key: [list(v) if isinstance(v, tuple) else v for v in values]
            for key, values in grid.items()}


def _cell(study: Study, config: StudyConfig, values: dict,
          records: Sequence[documents.SeedRecord]) -> SweepCell:
    results = [study.result.model_validate(record.result) for record in records]
    summary = summarize(study.metrics(config), study.claims(config), results)
    dumped = config.model_dump(mode="json")
    return SweepCell(values={key: dumped[key] for key in values}, config=dumped,
                     seeds=list(records), summary=summary)


def headline(study: Study, document: SweepDocument) -> list[str]:
    """The metric keys the sweep reports: the study's headline ones, else its first few."""
    keys = [row.key for row in document.cells[0].summary.metrics]
    return [key for key in study.headline if key in keys] or keys[:HEADLINE_DEFAULT]


def write_sweep(study: Study, document: SweepDocument, out: Path) -> list[Path]:
    """A plot per headline metric, the page and the JSON, each written atomically."""
    out.mkdir(parents=True, exist_ok=True)
    name = stem(study, list(document.grid))
    # each cell's metrics and typed seed results, made once for all the plots
    measured = [(study.metrics(study.config.model_validate(cell.config)),
                 [study.result.model_validate(record.result) for record in cell.seeds])
                for cell in document.cells]
    files = [write_atomically(out / plot_file(study, document, key),
                              _plot(study, document, key, measured))
             for key in headline(study, document)]
    files.append(write_atomically(out / f"{name}.md", page(study, document).encode()))
    files.append(documents.write(document, out / f"{name}.json"))
    return files


def plot_file(study: Study, document: SweepDocument, key: str) -> str:
    """``NAME-sweep-KEYS-METRIC.png``: the plot of the headline metric ``key``."""
    return f"{stem(study, list(document.grid))}-{key.replace('.', '-')}.png"


def page(study: Study, document: SweepDocument) -> str:
    """``NAME-sweep-KEYS.md`` of the document, as the study's current code writes it."""
    keys = headline(study, document)
    return sweep_page(study, document, keys, [plot_file(study, document, key) for key in keys],
                      study.config.model_validate(document.config))


def _plot(study: Study, document: SweepDocument, key: str,
          measured: Sequence[tuple[Sequence[Metric], Sequence[SeedResult]]]) -> bytes:
    """``key`` against the grid's first parameter, one line per value of the others;
    ``measured`` holds each cell's metrics and typed seed results, in the cells' order."""
    first, *others = document.grid
    values = document.grid[first]
    lines = []
    for rest in itertools.product(*(document.grid[other] for other in others)):
        fixed = dict(zip(others, rest, strict=True))
        chosen = [(cell, metrics, results)
                  for cell, (metrics, results) in zip(document.cells, measured, strict=True)
                  if all(cell.values[k] == v for k, v in fixed.items())]
        points, means, intervals = [], [], []
        for cell, metrics, results in chosen:
            metric = next(m for m in metrics if m.key == key)
            points.append([float(v) for v in map(metric.value, results) if v is not None])
            row = next(row for row in cell.summary.metrics if row.key == key)
            means.append(row.mean)
            intervals.append(row.ci)
        lines.append(SweepLine(cell_label(fixed) or key, points, means, intervals))
    row = next(row for row in document.cells[0].summary.metrics if row.key == key)
    return render_sweep(f"{study.name}: {row.label}", first, values, key, lines, row.reference)


def replot(study: Study, out: Path) -> list[SweepOutcome]:
    """Every ``NAME-sweep-*.json`` in ``out`` drawn again (statistics included), nothing run."""
    outcomes = []
    for path in sorted(out.glob(f"{study.name}-sweep-*.json")):
        old = documents.read(path)
        if not isinstance(old, SweepDocument) or old.study != study.name:
            raise DocumentError(f"{path}: not a sweep of {study.name}")
        document = restated(study, old)
        outcomes.append(SweepOutcome(document, write_sweep(study, document, out)))
    return outcomes


def restated(study: Study, old: SweepDocument) -> SweepDocument:
    """``old`` with every cell's statistics computed again from its seeds by this code."""
    rebuilt = [_cell(study, study.config.model_validate(cell.config), cell.values, cell.seeds)
               for cell in old.cells]
    return old.model_copy(update={"cells": rebuilt})

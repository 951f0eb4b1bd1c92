"""Running a study: its (config, seed) tasks, each taken from the cache when it finished
before and otherwise run on the backend and cached the moment it finishes; then the
statistics, ``NAME.json``, ``NAME.md`` and the figures, each written atomically. Also
``--replot`` (the outputs again from NAME.json, nothing run) and ``merge`` (shards run
elsewhere, one document)."""

from __future__ import annotations

import shlex
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

from ondisk import write_atomically
from robot.reproduce.framework import documents
from robot.reproduce.framework.backends import Backend
from robot.reproduce.framework.cache import Cache, CorruptEntry, StaleEntry
from robot.reproduce.framework.documents import DocumentError, ReproductionDocument, SeedRecord
from robot.reproduce.framework.pages import reproduction_page
from robot.reproduce.framework.plots import Figure, render_figure
from robot.reproduce.framework.provenance import Provenance
from robot.reproduce.framework.settings import format_value
from robot.reproduce.framework.statistics import summarize
from robot.reproduce.framework.study import Study, StudyConfig
from robot.reproduce.framework.tasks import SCHEMA_VERSION, Finished, Task


@dataclass(frozen=True)
class Tally:
    """How a run got its seeds."""

    computed: int = 0
    cached: int = 0
    recomputed_corrupt: int = 0
    recomputed_stale: int = 0


@dataclass(frozen=True)
class Outcome:
    """What a reproduction measured and where it wrote it."""

    document: ReproductionDocument
    files: list[Path]
    tally: Tally = Tally()


def command_line(study: Study, config: StudyConfig, seeds: Sequence[int],
                 verb: str = "reproduce", grid: dict[str, list] | None = None) -> str:
    """The command that runs this again: the study, the seeds, every value not the default
    (one command per run of consecutive seeds, when merged shards left gaps)."""
    ordered = sorted(seeds)
    if ordered != list(range(ordered[0], ordered[0] + len(ordered))):
        breaks = [i for i in range(1, len(ordered)) if ordered[i] != ordered[i - 1] + 1]
        runs = [ordered[a:b] for a, b in zip([0, *breaks], [*breaks, len(ordered)], strict=True)]
        return "; ".join(command_line(study, config, run, verb, grid) for run in runs)
    words = ["goalagent", verb, study.name]
    for key, values in (grid or {}).items():
        words += ["--grid", f"{key}=" + ",".join(format_value(v) for v in values)]
    words += ["--seeds", str(len(ordered))]
    if ordered[0] != 0:
        words += ["--seed-offset", str(ordered[0])]
    defaults = study.default_config().model_dump(mode="json")
    for key, value in config.model_dump(mode="json").items():
        if value != defaults[key] and key not in (grid or {}):
            words += ["--set", f"{key}={format_value(value)}"]
    return shlex.join(words)


def run_tasks(tasks: Sequence[Task], backend: Backend, cache: Cache | None,
              console: Console | None, fresh: bool = False) -> tuple[list[Finished], Tally]:
    """Every task's finished result, in task order: from the cache (unless ``fresh``) or run
    on ``backend``, each cached as it finishes. A corrupt cache entry is reported and run."""
    found: dict[int, Finished] = {}
    corrupt = stale = 0
    for index, task in enumerate(tasks):
        if cache is None or fresh:
            break
        try:
            hit = cache.load(task)
        except CorruptEntry as error:
            corrupt += 1
            if console is not None:
                console.print(f"warning: {escape(str(error))}; running seed {task.seed} again")
            continue
        except StaleEntry:
            stale += 1
            continue
        if hit is not None:
            found[index] = hit
    missing = [index for index in range(len(tasks)) if index not in found]
    if console is not None and stale:
        console.print(f"{stale} cached seed{'s' if stale > 1 else ''} of this config came from "
                      "code that has changed since: running again", markup=False)
    if console is not None and cache is not None and found:
        console.print(f"{len(found)} of {len(tasks)} seeds from the cache {cache.folder}",
                      markup=False)
    with _Bar(console, len(tasks), len(found), tasks[0].study.name) as show:
        def finished(position: int, done: Finished) -> None:
            found[missing[position]] = done
            if cache is not None:
                cache.store(done)
            show(position, 1.0)

        if missing:
            backend.run([tasks[index] for index in missing], show, finished)
    tally = Tally(computed=len(missing), cached=len(tasks) - len(missing),
                  recomputed_corrupt=corrupt, recomputed_stale=stale)
    return [found[index] for index in range(len(tasks))], tally


class _Bar:
    """A progress bar over the tasks (seeds done, fractions included); nothing without a
    console."""

    def __init__(self, console: Console | None, total: int, done: int, name: str) -> None:
        columns = (TextColumn("{task.description}"), BarColumn(),
                   TextColumn("{task.completed:.1f}/{task.total:.0f} seeds"),
                   TimeElapsedColumn(), TimeRemainingColumn())
        self.progress = Progress(*columns, console=console, disable=console is None)
        self.task = self.progress.add_task(escape(name), total=total, completed=done)
        self.base = done
        self.fractions: dict[int, float] = {}

    def __enter__(self) -> Callable[[int, float], None]:
        self.progress.__enter__()
        return self.show

    def __exit__(self, *exc: object) -> None:
        self.progress.__exit__(*exc)

    def show(self, position: int, fraction: float) -> None:
        self.fractions[position] = min(max(fraction, self.fractions.get(position, 0.0)), 1.0)
        self.progress.update(self.task, completed=self.base + sum(self.fractions.values()))


def document(study: Study, config: StudyConfig, seeds: Sequence[SeedRecord],
             provenance: list[Provenance], command: str) -> ReproductionDocument:
    """The reproduction's document: the seeds with the statistics over them."""
    results = [study.result.model_validate(record.result) for record in seeds]
    summary = summarize(study.metrics(config), study.claims(config), results)
    return ReproductionDocument(
        schema_version=SCHEMA_VERSION, kind="reproduction", study=study.name,
        description=study.description, command=command,
        config=config.model_dump(mode="json"), provenance=provenance, seeds=list(seeds),
        summary=summary)


def reproduce(study: Study, config: StudyConfig, seeds: Sequence[int], backend: Backend,
              out: Path, *, cache: Cache | None = None, console: Console | None = None,
              fresh: bool = False) -> Outcome:
    """Run ``seeds`` of ``config`` and write the outputs into ``out`` (created if missing)."""
    if not seeds:
        raise ValueError("no seeds to run")
    finished, tally = run_tasks([Task(study, config, seed) for seed in seeds], backend, cache,
                                console, fresh)
    provenance: list[Provenance] = []
    records = documents.records(finished, provenance)
    built = document(study, config, records, provenance, command_line(study, config, seeds))
    return Outcome(built, write_reproduction(study, built, out), tally)


def write_reproduction(study: Study, built: ReproductionDocument, out: Path) -> list[Path]:
    """The figures, NAME.md and NAME.json, each written atomically."""
    config = study.config.model_validate(built.config)
    results = built.results(study)
    out.mkdir(parents=True, exist_ok=True)
    files = [write_atomically(out / figure_file(study, figure),
                              render_figure(figure, len(results)))
             for figure in study.figures(config, results)]
    files.append(write_atomically(out / f"{study.name}.md", page(study, built).encode()))
    files.append(documents.write(built, out / f"{study.name}.json"))
    return files


def figure_file(study: Study, figure: Figure) -> str:
    """``NAME-STEM.png``."""
    return f"{study.name}-{figure.stem}.png"


def page(study: Study, built: ReproductionDocument) -> str:
    """NAME.md of the document, as the study's current code writes it."""
    config = study.config.model_validate(built.config)
    results = built.results(study)
    return reproduction_page(study, built, [figure_file(study, figure) for figure
                                            in study.figures(config, results)],
                             study.listings(config, results))


def load(study: Study, path: Path) -> ReproductionDocument:
    """The study's document at ``path`` (DocumentError when it is another study's)."""
    found = documents.read(path)
    if not isinstance(found, ReproductionDocument) or found.study != study.name:
        raise DocumentError(f"{path}: not a reproduction of {study.name}")
    return found


def replot(study: Study, out: Path) -> Outcome:
    """NAME.md, the figures, the statistics and NAME.json again from ``out``/NAME.json, as the
    study's current code draws them (nothing is run)."""
    old = load(study, out / f"{study.name}.json")
    config = _config(study, old.config, out / f"{study.name}.json")
    rebuilt = document(study, config, old.seeds, list(old.provenance), old.command)
    return Outcome(rebuilt, write_reproduction(study, rebuilt, out))


def _config(study: Study, values: dict, path: Path) -> StudyConfig:
    from pydantic import ValidationError

    try:
        return study.config.model_validate(values)
    except ValidationError as error:
        raise DocumentError(f"{path}: its config does not fit {study.name}'s: "
                            f"{error.errors()[0]['msg']}") from None


def merge(study: Study, paths: Sequence[Path], out: Path) -> Outcome:
    """One document from shards of the same study and config run elsewhere: their seeds
    (each once; a seed in two shards must have the same result), with the statistics."""
    shards = [load(study, path) for path in paths]
    first = shards[0]
    for path, shard in zip(paths[1:], shards[1:], strict=True):
        if shard.config != first.config:
            raise DocumentError(f"{path}: another config than {paths[0]}; only shards of one "
                                "config merge")
    provenance: list[Provenance] = []
    seeds: dict[int, SeedRecord] = {}
    for path, shard in zip(paths, shards, strict=True):
        for record in shard.seeds:
            origin = shard.provenance[record.provenance]
            if origin not in provenance:
                provenance.append(origin)
            moved = record.model_copy(update={"provenance": provenance.index(origin)})
            if record.seed in seeds and seeds[record.seed].result != record.result:
                raise DocumentError(f"{path}: seed {record.seed} has another result than in "
                                    "an earlier shard")
            seeds.setdefault(record.seed, moved)
    config = _config(study, first.config, paths[0])
    ordered = [seeds[seed] for seed in sorted(seeds)]
    built = document(study, config, ordered, provenance,
                     command_line(study, config, sorted(seeds)))
    return Outcome(built, write_reproduction(study, built, out))

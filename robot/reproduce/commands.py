"""``goalagent reproduce`` and ``goalagent sweep``: the workbench's command line. Everything a
user can get wrong (a study, a key, a value, a grid, a cluster address, a shard) is one
``error:`` line and exit 2; a seed that fails is exit 1; Ctrl-C is exit 130, with every
finished seed cached for the next run of the same command."""

from __future__ import annotations

import os
import signal
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table
from rich.text import Text

from goalagent.console import err_console, user_error

Seeds = Annotated[int | None, typer.Option(
    help="Number of seeds (default: the study's, 10 for most; 2 with --quick).",
    show_default=False)]
SeedOffset = Annotated[int, typer.Option(
    help="First seed: run seeds S .. S+K-1 (shards run elsewhere; see reproduce merge).")]
Out = Annotated[Path, typer.Option(help="Folder for the JSON, the markdown and the figures.")]
Jobs = Annotated[int | None, typer.Option(
    help="Seeds run in parallel processes on this machine (default: the number of CPUs).",
    show_default=False)]
Quick = Annotated[bool, typer.Option(
    "--quick", help="A small run: the study's quick values (and 2 seeds).")]
Sets = Annotated[list[str] | None, typer.Option(
    "--set", help="KEY=VALUE: a parameter of the study's config (repeatable; --params lists "
                  "them).", show_default=False)]
Ray = Annotated[str | None, typer.Option(
    "--ray", help="Run each (config, seed) as a task on the Ray cluster at ADDRESS ('auto' or "
                  "HOST:PORT) instead of local processes.", show_default=False)]
CacheFolder = Annotated[Path | None, typer.Option(
    "--cache", help="Folder of finished (config, seed) results: a rerun resumes from it "
                    "(default: ~/.cache/goalagent/reproduce).", show_default=False)]
Fresh = Annotated[bool, typer.Option(
    "--fresh", help="Run every seed again (the cache is written, not read).")]


def reproduce(
    name: Annotated[str | None, typer.Argument(
        help="Which study (see --list), or 'merge' followed by shards' NAME.json files.",
        show_default=False)] = None,
    shards: Annotated[list[Path] | None, typer.Argument(
        help="With 'merge': the shards' JSON files.", show_default=False)] = None,
    seeds: Seeds = None,
    seed_offset: SeedOffset = 0,
    out: Out = Path("results"),
    jobs: Jobs = None,
    scale: Annotated[float | None, typer.Option(
        help="Run size in (0, 1] (the same as --set scale=X).", show_default=False)] = None,
    quick: Quick = False,
    set_: Sets = None,
    list_: Annotated[bool, typer.Option(
        "--list", help="List the studies, one line each, and stop.")] = False,
    params: Annotated[bool, typer.Option(
        "--params", help="List the study's parameters: value, default and meaning.")] = False,
    replot: Annotated[bool, typer.Option(
        "--replot", help="Redraw NAME.md, the statistics and the figures from --out's "
                         "NAME.json, run nothing.")] = False,
    ray: Ray = None,
    cache: CacheFolder = None,
    fresh: Fresh = False,
) -> None:
    """Run a study of the thesis's results over seeds: NAME.json (config, provenance, every
    seed, statistics), NAME.md (measured beside the reference with 95% CIs, each claim's test
    and verdict) and PNG figures in --out."""
    from robot.reproduce.framework import runner

    with _user_errors():
        if list_:
            _list()
            return
        if name is None:
            raise user_error("name a study (goalagent reproduce --list shows them)")
        if name == "merge":
            _merge(shards or [], out)
            return
        if shards:
            raise user_error(f"unexpected arguments after {name}: "
                             f"{' '.join(str(path) for path in shards)}")
        study = _study(name)
        if params:
            _parameters(study)
            return
        if replot:
            _report(runner.replot(study, out))
            return
        settings = [*(set_ or []), *([f"scale={scale}"] if scale is not None else [])]
        config = _config(study, quick, settings)
        seed_list = _seeds(study, seeds, seed_offset, quick)
        _check_out(out)
        backend = _backend(ray, jobs)
        outcome = _interruptible(lambda: runner.reproduce(
            study, config, seed_list, backend, out, cache=_cache(cache),
            console=err_console, fresh=fresh))
        _report(outcome)


def sweep(
    name: Annotated[str, typer.Argument(help="Which study (see reproduce --list).")],
    grid: Annotated[list[str] | None, typer.Option(
        "--grid", help="KEY=V1,V2,...: the values of one parameter (repeatable: one cell per "
                       "combination).", show_default=False)] = None,
    seeds: Seeds = None,
    seed_offset: SeedOffset = 0,
    out: Out = Path("results"),
    jobs: Jobs = None,
    quick: Quick = False,
    set_: Sets = None,
    replot: Annotated[bool, typer.Option(
        "--replot", help="Redraw every NAME-sweep-*.json in --out, run nothing.")] = False,
    ray: Ray = None,
    cache: CacheFolder = None,
    fresh: Fresh = False,
) -> None:
    """Run a study over a grid of parameter values, every cell's seeds in one pool:
    NAME-sweep-KEYS.json, a markdown table of the headline metrics and each claim's verdict
    per cell, and a plot of each headline metric against the swept parameter."""
    from robot.reproduce.framework import sweeps
    from robot.reproduce.framework.settings import parse_grid

    with _user_errors():
        study = _study(name)
        if replot:
            outcomes = sweeps.replot(study, out)
            if not outcomes:
                raise user_error(f"no {study.name}-sweep-*.json in {out}")
            for outcome in outcomes:
                _wrote(outcome.files)
            return
        config = _config(study, quick, set_ or [])
        parsed = parse_grid(study, config, grid or [])
        seed_list = _seeds(study, seeds, seed_offset, quick)
        _check_out(out)
        backend = _backend(ray, jobs)
        outcome = _interruptible(lambda: sweeps.sweep(
            study, config, parsed, seed_list, backend, out, cache=_cache(cache),
            console=err_console, fresh=fresh))
        _tally(outcome.tally)
        _wrote(outcome.files)


@contextmanager
def _user_errors() -> Iterator[None]:
    """The workbench's errors as the command line reports them."""
    from robot.reproduce.framework.cluster import ClusterError
    from robot.reproduce.framework.documents import DocumentError
    from robot.reproduce.framework.registry import UnknownStudy
    from robot.reproduce.framework.settings import SettingError
    from robot.reproduce.framework.tasks import ReproductionFailed

    try:
        yield
    except (UnknownStudy, SettingError, ClusterError, DocumentError) as error:
        raise user_error(str(error)) from None
    except ReproductionFailed as error:
        err_console.print(f"error: {error}", markup=False)
        raise typer.Exit(code=1) from None


def _interruptible(run):
    """Run; on Ctrl-C say that the finished seeds are cached, and exit 130. (Ctrl-C is taken
    back from goalagent/launcher.py's stop-at-once handler for the run, so it can be said.)"""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        return run()
    except KeyboardInterrupt:
        err_console.print("interrupted: every seed that finished is cached; run the same "
                          "command again to go on from there", markup=False)
        raise typer.Exit(code=130) from None
    finally:
        signal.signal(signal.SIGINT, previous)


def _study(name: str):
    from robot.reproduce.framework.registry import find

    return find(name)


def _config(study, quick: bool, settings: list[str]):
    from robot.reproduce.framework.settings import apply

    base = study.quick_config() if quick else study.default_config()
    return apply(study, base, settings)


def _seeds(study, seeds: int | None, offset: int, quick: bool) -> list[int]:
    count = seeds if seeds is not None else 2 if quick else study.default_seeds
    if count < 1:
        raise user_error(f"--seeds must be at least 1, got {count}")
    if offset < 0:
        raise user_error(f"--seed-offset must be at least 0, got {offset}")
    return list(range(offset, offset + count))


def _check_out(out: Path) -> None:
    if out.exists() and not out.is_dir():
        raise user_error(f"--out {out} exists and is not a folder")


def _backend(ray: str | None, jobs: int | None):
    from robot.reproduce.framework.backends import LocalBackend
    from robot.reproduce.framework.cluster import RayBackend

    if ray is not None:
        if jobs is not None:
            raise user_error("--jobs is for local processes; with --ray the cluster's CPUs "
                             "decide")
        backend = RayBackend(ray)
        backend.connect()  # a cluster that cannot be joined is said before anything runs
        return backend
    count = jobs if jobs is not None else os.cpu_count() or 1
    if count < 1:
        raise user_error(f"--jobs must be at least 1, got {count}")
    return LocalBackend(count)


def _cache(folder: Path | None):
    from robot.reproduce.framework.cache import Cache, default_folder

    folder = folder or default_folder()
    if folder.exists() and not folder.is_dir():
        raise user_error(f"--cache {folder} exists and is not a folder")
    return Cache(folder)


def _list() -> None:
    from robot.reproduce.framework.registry import registered

    studies = registered()
    width = max((len(study.name) for study in studies), default=0)
    for study in studies:
        err_console.print(f"{study.name:<{width}}  {study.description}", markup=False)


def _parameters(study) -> None:
    from robot.reproduce.framework.settings import format_value

    table = Table("parameter", "default", "quick", "meaning", title=Text(study.name))
    quick = study.quick_config().model_dump(mode="json")
    for key, value in study.default_config().model_dump(mode="json").items():
        table.add_row(Text(key), Text(format_value(value)),
                      Text("" if quick[key] == value else format_value(quick[key])),
                      Text(study.config.describe(key)))
    err_console.print(table)


def _merge(shards: list[Path], out: Path) -> None:
    from robot.reproduce.framework import runner
    from robot.reproduce.framework.documents import read

    if len(shards) < 2:
        raise user_error("reproduce merge needs two or more shards' NAME.json files")
    first = read(shards[0])
    _report(runner.merge(_study(first.study), shards, out))


def _report(outcome) -> None:
    """The measured table, each claim's verdict, and where the files went."""
    from robot.reproduce.framework.pages import METRIC_HEADERS, metric_rows
    from robot.reproduce.framework.statistics import reading

    summary = outcome.document.summary
    table = Table(*METRIC_HEADERS)
    for row in metric_rows(summary):
        table.add_row(*(Text(cell) for cell in row))
    err_console.print(table)
    for comparison in summary.comparisons:
        err_console.print(Text(f"claim: {comparison.claim}\n  {reading(comparison)}"))
    _tally(outcome.tally)
    _wrote(outcome.files)


def _tally(tally) -> None:
    if tally.cached or tally.computed:
        err_console.print(f"seeds run: {tally.computed}, from the cache: {tally.cached}"
                          + (f" ({tally.recomputed_corrupt} corrupt entries run again)"
                             if tally.recomputed_corrupt else "")
                          + (f" ({tally.recomputed_stale} made by changed code run again)"
                             if tally.recomputed_stale else ""), markup=False)


def _wrote(files: list[Path]) -> None:
    err_console.print("wrote " + ", ".join(str(path) for path in files), markup=False)

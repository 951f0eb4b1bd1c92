"""Running a reproduction: its seeds in parallel processes under a progress bar, then
``NAME.json`` (``summary`` and ``seeds``), ``NAME.md`` and the figures, each file written
atomically."""

from __future__ import annotations

import json
import multiprocessing
import os
import queue
import shlex
import sys
import time
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from dataclasses import dataclass
from pathlib import Path

from rich.console import Console
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

from ondisk import write_atomically
from robot.reproduce.framework import Comparison, Reproduction, SeedResult
from robot.reproduce.report import markdown, render_figure

PROGRESS_STEP = 0.01
"""A seed reports its progress to the bar at most once per this fraction of its run."""


class ReproductionFailed(RuntimeError):
    """A seed's run raised, or returned something that is not a JSON object."""


@dataclass(frozen=True)
class Outcome:
    """What a run measured and where it wrote it."""

    summary: dict
    seeds: list[SeedResult]
    comparisons: list[Comparison]
    files: list[Path]


def run(reproduction: Reproduction, *, seeds: int, scale: float, jobs: int, out: Path,
        console: Console | None = None, command: str | None = None) -> Outcome:
    """Run seeds 0 .. seeds-1 at ``scale`` on ``jobs`` processes (1: in this process) and
    write the outputs into ``out`` (created if missing)."""
    if seeds < 1 or jobs < 1 or not 0.0 < scale <= 1.0:
        raise ValueError("seeds and jobs must be at least 1 and scale in (0, 1]")
    results = run_seeds(reproduction, list(range(seeds)), scale, jobs, console)
    command = command or shlex.join(["goalagent", "reproduce", *sys.argv[2:]])
    return write_outputs(reproduction, results, scale, out, command)


def replot(reproduction: Reproduction, out: Path) -> Outcome:
    """Rewrite NAME.md, the figures and the summary from the seeds in ``out``/NAME.json, as
    the reproduction's current code draws them (nothing is run again)."""
    path = out / f"{reproduction.name}.json"
    try:
        document = json.loads(path.read_text(encoding="utf-8"))
        seeds, scale, command = document["seeds"], document["scale"], document["command"]
    except (OSError, UnicodeDecodeError, json.JSONDecodeError, KeyError, TypeError) as error:
        raise ReproductionFailed(f"cannot replot from {path}: {error}") from None
    if not isinstance(seeds, list) or not seeds or not all(isinstance(s, dict) for s in seeds):
        raise ReproductionFailed(f"cannot replot from {path}: it holds no seeds")
    return write_outputs(reproduction, seeds, scale, out, command)


def write_outputs(reproduction: Reproduction, results: list[SeedResult], scale: float,
                  out: Path, command: str) -> Outcome:
    """The figures, NAME.md and NAME.json (summary and seeds), each written atomically."""
    summary = reproduction.summarize(results)
    comparisons = reproduction.compare(summary, results)
    figures = reproduction.figures(results)
    out.mkdir(parents=True, exist_ok=True)
    files = []
    for figure in figures:
        path = out / f"{reproduction.name}-{figure.stem}.png"
        write_atomically(path, render_figure(figure, len(results)))
        files.append(path)
    listings = reproduction.listings(summary, results) if reproduction.listings else ""
    page = markdown(reproduction, comparisons, [p.name for p in files], len(results), scale,
                    command, listings)
    files.append(write_atomically(out / f"{reproduction.name}.md", page.encode()))
    document = {"name": reproduction.name, "description": reproduction.description,
                "command": command, "scale": scale, "summary": summary, "seeds": results}
    text = json.dumps(document, indent=1, allow_nan=False)
    files.append(write_atomically(out / f"{reproduction.name}.json", text.encode()))
    return Outcome(summary, results, comparisons, files)


def run_seeds(reproduction: Reproduction, seeds: list[int], scale: float, jobs: int,
              console: Console | None) -> list[SeedResult]:
    """Each seed's result, in seed order; the bar counts seeds, advanced by their reports."""
    columns = (TextColumn("{task.description}"), BarColumn(),
               TextColumn("{task.completed:.1f}/{task.total:.0f} seeds"), TimeElapsedColumn(),
               TimeRemainingColumn())
    with Progress(*columns, console=console, transient=False,
                  disable=console is None) as bar:
        task = bar.add_task(reproduction.name, total=len(seeds))
        done = dict.fromkeys(seeds, 0.0)

        def show(seed: int, fraction: float) -> None:
            done[seed] = min(max(fraction, done[seed]), 1.0)
            bar.update(task, completed=sum(done.values()))

        if jobs == 1:
            results = {}
            for seed in seeds:
                result = _call(reproduction, seed, scale,
                               lambda fraction, seed=seed: show(seed, fraction))
                results[seed] = _checked(reproduction, seed, result)
                show(seed, 1.0)
        else:
            results = _in_processes(reproduction, seeds, scale, jobs, show)
    return [results[seed] for seed in seeds]


def _in_processes(reproduction: Reproduction, seeds: list[int], scale: float, jobs: int,
                  show: Callable[[int, float], None]) -> dict[int, SeedResult]:
    """Run the seeds in fresh ("spawn") processes: the parent may hold SWI-Prolog, threads
    (the progress bar) or a GL context, none of which survive a fork."""
    context = multiprocessing.get_context("spawn")
    reports = context.Queue()
    results: dict[int, SeedResult] = {}
    with ProcessPoolExecutor(min(jobs, len(seeds)), mp_context=context,
                             initializer=_start_worker, initargs=(reports,)) as pool:
        futures: dict[Future, int] = {
            pool.submit(_run_seed_in_worker, reproduction, seed, scale): seed for seed in seeds}
        pending = set(futures)
        try:
            while pending:
                finished, pending = wait(pending, timeout=0.25, return_when=FIRST_COMPLETED)
                _drain(reports, show)
                for future in finished:
                    seed = futures[future]
                    results[seed] = _checked(reproduction, seed, future.result())
                    show(seed, 1.0)
        except BaseException:
            for future in pending:
                future.cancel()
            raise
    return results


def _drain(reports: multiprocessing.Queue, show: Callable[[int, float], None]) -> None:
    while True:
        try:
            seed, fraction = reports.get_nowait()
        except queue.Empty:
            return
        show(seed, fraction)


_REPORTS: multiprocessing.Queue | None = None


def _start_worker(reports: multiprocessing.Queue) -> None:
    global _REPORTS
    _REPORTS = reports
    os.environ.setdefault("MUJOCO_GL", "egl")


def _run_seed_in_worker(reproduction: Reproduction, seed: int, scale: float) -> SeedResult:
    def report(fraction: float) -> None:
        if _REPORTS is not None:
            _REPORTS.put((seed, fraction))

    return _call(reproduction, seed, scale, report)


def _call(reproduction: Reproduction, seed: int, scale: float,
          report: Callable[[float], None]) -> object:
    """One seed's run; an exception becomes ReproductionFailed naming the seed."""
    try:
        return reproduction.run_seed(seed, scale, _Throttled(report))
    except Exception as error:
        raise ReproductionFailed(f"{reproduction.name}: seed {seed} failed: "
                                 f"{type(error).__name__}: {error}") from None


class _Throttled:
    """Pass a progress report on only when it moved by PROGRESS_STEP or 1 s has passed."""

    def __init__(self, report: Callable[[float], None]) -> None:
        self._report = report
        self._last = 0.0
        self._when = time.monotonic()

    def __call__(self, fraction: float) -> None:
        now = time.monotonic()
        if fraction - self._last >= PROGRESS_STEP or now - self._when >= 1.0:
            self._last, self._when = fraction, now
            self._report(fraction)


def _checked(reproduction: Reproduction, seed: int, result: object) -> SeedResult:
    if not isinstance(result, dict):
        raise ReproductionFailed(f"{reproduction.name}: seed {seed} returned "
                                 f"{type(result).__name__}, not a dict")
    try:
        json.dumps(result, allow_nan=False)
    except (TypeError, ValueError) as error:
        raise ReproductionFailed(f"{reproduction.name}: seed {seed}'s result is not plain "
                                 f"JSON ({error})") from None
    return result

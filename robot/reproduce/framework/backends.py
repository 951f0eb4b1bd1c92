"""Where tasks run: in this process (``--jobs 1``) or in a pool of fresh processes on this
machine (``--jobs N``); ``robot.reproduce.framework.cluster`` runs them on a Ray cluster. Every
backend hands each finished task to ``finished`` as soon as it is done (the runner caches it
there), so an interrupted run loses no finished seed."""

from __future__ import annotations

import multiprocessing
import os
import queue
import time
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Protocol

from robot.reproduce.framework.tasks import Finished, ReproductionFailed, Task, execute

PROGRESS_STEP = 0.01
"""A seed reports its progress at most once per this fraction of its run (or once a second)."""
RETRIES = 3
"""How often a task whose worker process died (killed, out of memory) is run again."""

Report = Callable[[int, float], None]
"""(index of the task, fraction of it done)."""
Done = Callable[[int, Finished], None]
"""(index of the task, its finished result)."""


class Backend(Protocol):
    """Runs tasks, reporting progress and each finished task as it comes."""

    def run(self, tasks: Sequence[Task], report: Report, finished: Done) -> None: ...


class Throttled:
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


class LocalBackend:
    """``jobs`` processes on this machine; one job runs the tasks in this process."""

    def __init__(self, jobs: int) -> None:
        if jobs < 1:
            raise ValueError(f"jobs must be at least 1, got {jobs}")
        self.jobs = jobs

    def run(self, tasks: Sequence[Task], report: Report, finished: Done) -> None:
        if self.jobs == 1 or len(tasks) == 1:
            for index, task in enumerate(tasks):
                done = execute(task, Throttled(lambda f, index=index: report(index, f)))
                finished(index, done)
            return
        pending = dict(enumerate(tasks))
        for attempt in range(RETRIES + 1):
            try:
                self._in_processes(pending, report, finished)
                return
            except BrokenProcessPool:
                if attempt == RETRIES:
                    raise ReproductionFailed(
                        f"a worker process died {RETRIES + 1} times (killed, or out of "
                        f"memory); seeds left: {sorted(t.seed for t in pending.values())}"
                    ) from None

    def _in_processes(self, pending: dict[int, Task], report: Report, finished: Done) -> None:
        """Run ``pending`` in fresh ("spawn") processes, deleting each task from it when it is
        finished: the parent may hold SWI-Prolog, threads (the progress bar) or a GL context,
        none of which survive a fork."""
        context = multiprocessing.get_context("spawn")
        reports = context.Queue()
        with ProcessPoolExecutor(min(self.jobs, len(pending)), mp_context=context,
                                 initializer=_start_worker, initargs=(reports,)) as pool:
            futures: dict[Future, int] = {pool.submit(_run_in_worker, index, task): index
                                          for index, task in pending.items()}
            waiting = set(futures)
            try:
                while waiting:
                    done, waiting = wait(waiting, timeout=0.25, return_when=FIRST_COMPLETED)
                    _drain(reports, report)
                    for future in done:
                        index = futures[future]
                        result = future.result()
                        del pending[index]
                        finished(index, result)
            except BaseException:
                for future in waiting:
                    future.cancel()
                raise


def _drain(reports: multiprocessing.Queue, report: Report) -> None:
    while True:
        try:
            index, fraction = reports.get_nowait()
        except queue.Empty:
            return
        report(index, fraction)


_REPORTS: multiprocessing.Queue | None = None


def _start_worker(reports: multiprocessing.Queue) -> None:
    global _REPORTS
    _REPORTS = reports
    os.environ.setdefault("MUJOCO_GL", "egl")


def _run_in_worker(index: int, task: Task) -> Finished:
    def report(fraction: float) -> None:
        if _REPORTS is not None:
            _REPORTS.put((index, fraction))

    return execute(task, Throttled(report))

"""Wilson's experimental protocol for XCS on the multiplexer and in woods (Wilson 1995).

Explore and exploit problems alternate. An explore problem learns (random actions among
those advocated); an exploit problem acts greedily and learns nothing, and is what the curves
measure: the fraction correct, or the steps to food, over the last 50 exploit problems,
plotted against the number of explore problems, with the population size in
macro-classifiers beside it.
"""

from __future__ import annotations

import functools
from collections import deque
from collections.abc import Callable, Mapping

import numpy as np

from behaviours.learners.xcs import XCS
from robot.reproduce.framework import Figure, Metric, Panel, Reference, SeedResult, Series
from robot.reproduce.studies.common.lcs_problems import Woods

WINDOW = 50
"""Exploit problems in the moving performance measure (Wilson 1995)."""
RECORD_EVERY = 50
"""Explore problems between two points of a curve."""
REWARD = 1000.0


class MuxRun(SeedResult):
    """XCS on one multiplexer: the curves and where they ended."""

    problems: list[int]
    accuracy: list[float]
    macro_classifiers: list[int]
    final_accuracy: float
    problems_to_99: int | None
    """The explore problem from which the last 50 exploit problems stayed all right."""
    first_at_99: int | None
    """The first explore problem at which they were all right."""
    final_macro_classifiers: int


class WoodsRun(SeedResult):
    """XCS in one woods map: the curves, where they ended, and the map's optimum."""

    problems: list[int]
    steps: list[float]
    macro_classifiers: list[int]
    final_steps: float
    final_macro_classifiers: int
    optimum: float


def explore_problems(full: int, scale: float) -> int:
    """``full`` explore problems scaled, at least 100."""
    return max(100, round(full * scale))


def environment_rng(seed: int) -> np.random.Generator:
    """The problems' random stream, independent of the learner's (both from ``seed``)."""
    return np.random.default_rng([seed, 0x5EED])


def multiplexer_experiment(address_bits: int, problems: int, params: Mapping[str, object],
                           seed: int, progress: Callable[[float], None]) -> MuxRun:
    """XCS on the (address_bits + 2**address_bits)-bit multiplexer, reward 1000 when right."""
    length = address_bits + 2 ** address_bits
    rng = environment_rng(seed)
    xcs = XCS(2, random_state=seed, **params)
    window: deque[bool] = deque(maxlen=WINDOW)
    curve: dict[str, list] = {"problems": [], "accuracy": [], "macro_classifiers": []}
    first_perfect = stays_perfect = None
    for problem in range(1, problems + 1):
        for explore in (True, False):
            state = format(int(rng.integers(2 ** length)), f"0{length}b")
            answer = int(state[address_bits + int(state[:address_bits], 2)])
            action = xcs.act(state, explore=explore)
            xcs.reward(REWARD if action == answer else 0.0, done=True)
        window.append(action == answer)
        accuracy = sum(window) / len(window)
        if len(window) == WINDOW and accuracy >= 0.99:
            first_perfect = first_perfect or problem
            stays_perfect = stays_perfect or problem
        else:
            stays_perfect = None
        if problem % RECORD_EVERY == 0:
            curve["problems"].append(problem)
            curve["accuracy"].append(accuracy)
            curve["macro_classifiers"].append(xcs.macro_count)
            progress(problem / problems)
    return MuxRun(**curve, final_accuracy=sum(window) / len(window),
                  problems_to_99=stays_perfect, first_at_99=first_perfect,
                  final_macro_classifiers=xcs.macro_count)


def woods_experiment(rows: tuple[str, ...], codes: dict[str, str], problems: int,
                     params: Mapping[str, object], seed: int,
                     progress: Callable[[float], None], step_limit: int) -> WoodsRun:
    """XCS as Wilson's animat in a woods map: each problem starts on a random blank cell and
    ends at food (reward 1000) or after ``step_limit`` steps."""
    world = Woods(rows, codes, environment_rng(seed))
    xcs = XCS(8, random_state=seed, **params)
    window: deque[int] = deque(maxlen=WINDOW)
    curve: dict[str, list] = {"problems": [], "steps": [], "macro_classifiers": []}
    for problem in range(1, problems + 1):
        _trial(xcs, world, explore=True, step_limit=step_limit)
        window.append(_trial(xcs, world, explore=False, step_limit=step_limit))
        if problem % RECORD_EVERY == 0:
            curve["problems"].append(problem)
            curve["steps"].append(sum(window) / len(window))
            curve["macro_classifiers"].append(xcs.macro_count)
            progress(problem / problems)
    return WoodsRun(**curve, final_steps=sum(window) / len(window),
                    final_macro_classifiers=xcs.macro_count, optimum=world.optimal_steps())


def _trial(xcs: XCS, world: Woods, explore: bool, step_limit: int) -> int:
    """One problem; returns its number of steps."""
    state = world.reset()
    for step in range(1, step_limit + 1):
        state, reward, done = world.step(xcs.act(state, explore=explore))
        xcs.reward(reward, done)
        if done:
            return step
    xcs.end_trial()
    return step_limit


def first_at_or_below(run: WoodsRun, level: float) -> int | None:
    """The first recorded problem count whose steps are at or below ``level``."""
    return next((p for p, v in zip(run.problems, run.steps, strict=True) if v <= level), None)


def curve_panels(runs: Mapping[str, list[MuxRun] | list[WoodsRun]], ylabel: str,
                 references: list[Reference],
                 ylim: tuple[float, float] | None) -> list[Panel]:
    """Two panels over explore problems: the performance curve (fraction correct or steps to
    food) and the population size, one series per labelled set of seeds."""
    def values(run: MuxRun | WoodsRun) -> list[float]:
        return run.accuracy if isinstance(run, MuxRun) else run.steps

    series = [(label, seeds[0].problems, seeds) for label, seeds in runs.items()]
    return [Panel("explore problems", ylabel,
                  [Series(label, x, [values(run) for run in seeds]) for label, x, seeds in series],
                  references, ylim=ylim),
            Panel("explore problems", "population size (macro-classifiers)",
                  [Series(label, x, [run.macro_classifiers for run in seeds])
                   for label, x, seeds in series])]


def woods_figure(runs: Mapping[str, list[WoodsRun]], stem: str, title: str,
                 references: list[Reference], ylim: tuple[float, float] | None) -> Figure:
    """Steps to food and population size, with ``references`` and the map's optimum."""
    optimum = next(iter(runs.values()))[0].optimum
    return Figure(stem, title, curve_panels(
        runs, "steps to food (last 50 exploit problems)",
        [*references, Reference(optimum, f"optimum {optimum:.2f}")], ylim))


@functools.cache
def map_optimum(rows: tuple[str, ...], codes: tuple[tuple[str, str], ...]) -> float:
    """The mean shortest number of steps to food over a map's blank cells."""
    return Woods(rows, dict(codes), environment_rng(0)).optimal_steps()


def woods_metrics(key: str, label: str, run: Callable[[SeedResult], WoodsRun],
                  optimum: float, reference: tuple[float, str] | None,
                  near: float) -> list[Metric]:
    """A woods run's rows: steps to food at the end (beside ``reference``, if any, and the
    optimum), whether a seed ended at ``near`` steps or fewer, the explore problems until it
    first got there, the population size."""
    rows = [Metric(f"{key}.final_steps", f"{label}: steps to food, last 50 exploit problems, "
                   "at the end", lambda s: run(s).final_steps, *(reference or (None, "")))]
    rows += [
        Metric(f"{key}.final_steps_over_optimum", f"{label}: the same against the optimum",
               lambda s: run(s).final_steps, optimum, "shortest paths over the map"),
        Metric(f"{key}.near_optimal_at_end", f"{label}: seeds at {near:g} steps or fewer at "
               "the end", lambda s: float(run(s).final_steps <= near)),
        Metric(f"{key}.problems_to_near", f"{label}: explore problems until {near:g} steps or "
               "fewer", lambda s: first_at_or_below(run(s), near)),
        Metric(f"{key}.macro_classifiers", f"{label}: macro-classifiers at the end",
               lambda s: run(s).final_macro_classifiers),
    ]
    return rows

"""What the chapter-3 and Appendix-A studies share: one XCS experiment in a task world (its
typed record), the learned rules as a Table 3.2 / 7.2 listing, movability by majority over
seeds, per-seed windows over trials, curves.

Imports of MuJoCo and the behaviours happen inside ``opened_world`` and ``experiment``
(``goalagent reproduce --list`` imports every study module and must stay light).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from typing import Annotated, Literal

from pydantic import Field

from robot.reproduce.framework import Reading, SeedResult
from robot.reproduce.studies.common.xcs import Table71, xcs_keywords

MODES = ("truth", "camera")
RULE_COLUMNS = ("id", "condition", "action", "prediction", "error", "fitness", "set_size",
                "experience", "numerosity")
Rule = tuple[int, str, str, float, float, float, float, int, int]
"""A macro-classifier as a row of ``RULE_COLUMNS``."""
Movability = tuple[str, str, int]
"""(object code, action code, effect): Table 3.3's rows."""


FilterScope = Literal["choice", "choice_and_value"]


class TrialConfig(Table71):
    """Table 7.1's XCS run in trials that alternate exploring and exploiting."""

    learn_in_exploit: Annotated[bool, Reading(
        "App. A, Performance Component: \"learning happens only in explore mode while "
        "evaluation happens in exploit mode\"; Algorithm 2 (§3.3.4) credits [M]_aj at every "
        "step (lines 12-14), making no difference between the two.")] = False
    """Whether exploit trials update XCS too (eqs 7.1-7.7 on [A]-1 and [A], no GA): false is
    App. A's explicit statement, true Algorithm 2's loop taken literally."""


class TaskConfig(TrialConfig):
    """Table 7.1's XCS in a chapter-3 task."""

    trials: Annotated[int, Field(ge=4)] = 20
    """Trials of an experiment, odd ones exploring, even ones exploiting (§3.5.7: 20; scaled
    to an even number, at least 4)."""
    n_step: Annotated[int, Field(ge=1)] = 10
    """Actions per trial at most (§3.5.7's n_step)."""
    filter_scope: Annotated[FilterScope, Reading(
        "Algorithm 2 (§3.3.4): form [M] (line 3), compute the prediction of every action "
        "(3.8, line 4), filter by (3.10) (lines 5-7), select by (3.9) (line 8): the filter "
        "acts on the choice only; App. A's eq. 7.2 takes max_i P(a_i) over the prediction "
        "array.")] = "choice"
    """Where affordance-based XCS's filter (eq. 3.10) applies: `choice` (Algorithm 2: covering
    and eq. 7.2's max range over every applicable action) or `choice_and_value` (the filtered
    actions are also left out of covering and of eq. 7.2's max; this code's earlier
    reading)."""

    def scaled_trials(self) -> int:
        return even_trials(self.trials, self.scale, 4)


class NavigationConfig(TaskConfig):
    """A chapter-3 task config whose navigation trials start where §3.5.7 says."""

    start: Annotated[Literal["anywhere", "right_lane"], Reading(
        "§3.5.7: \"The NAO was allowed to start from anywhere on one side of the area\"; "
        "§3.5.8 reckons the chance after the exchange for a start facing the unmovable "
        "box.")] = "anywhere"
    """Where each trial starts: `anywhere` draws one of the four lanes (0.15 m apart, each
    facing a box) per trial from the seed; `right_lane` starts every trial in the right-most
    lane, facing the right box (this code's earlier setting)."""


class TaskRun(SeedResult):
    """One experiment, trial by trial, with the learned table and rules."""

    payoff: list[float]
    steps: list[int]
    success: list[int]
    explore: list[int]
    first_action: list[str | None]
    movability: list[Movability]
    rules: list[Rule]
    starts: list[float] | None = None
    """Navigation: the lane (y, m) each trial started in."""


@contextmanager
def opened_world(task_name: str) -> Iterator[object]:
    """The world of ``task_name``, built once for all the experiments of a seed, then closed."""
    from sim.headless import use_headless_rendering

    use_headless_rendering()
    if task_name == "navigation":
        from sim.navigation import NavigationWorld as World
    elif task_name == "stacking":
        from sim.stacking import StackingWorld as World
    else:
        from sim.search import SearchWorld as World
    world = World()
    try:
        yield world
    finally:
        world.close()


def even_trials(full: int, scale: float, minimum: int) -> int:
    """``full`` trials scaled by ``scale`` and rounded to an even number (explore and exploit
    trials alternate), at least ``minimum``."""
    return max(minimum, 2 * round(full * scale / 2))


def experiment(world: object, task_name: str, mode: str, method: str, seed: int,
               trials: int, change_after: int, config: TrialConfig, n_step: int,
               task_options: Mapping[str, object] | None = None,
               **options: bool | str) -> TaskRun:
    """One experiment of ``trials`` alternating trials in ``world``; the world changes after
    ``change_after`` (boxes exchanged, target moved). ``task_options`` go to the task (start,
    push_needs_object), ``options`` to the learner. Per-trial payoff, steps, success and
    mode, the first action of each trial, the learned table and rules."""
    from behaviours.blob_grid import make_grid_perception
    from behaviours.object_state import make_object_perception
    from behaviours.xcs_tasks import NavigationTask, SearchTask, StackingTask
    from behaviours.xcs_trials import make_learner, run_experiment

    extra = dict(task_options or {})
    if task_name == "navigation":
        task = NavigationTask(world, make_object_perception(mode, task_name),  # type: ignore
                              exchange_after=change_after, seed=seed, **extra)
    elif task_name == "stacking":
        task = StackingTask(world, make_object_perception(mode, task_name),  # type: ignore
                            **extra)
    else:
        task = SearchTask(world, make_grid_perception(mode),  # type: ignore[arg-type]
                          move_after=change_after, **extra)
    if isinstance(config, TaskConfig):
        options = {"filter_scope": config.filter_scope, **options}
    learner = make_learner(task.actions, method, seed, **xcs_keywords(config),
                           learn_in_exploit=config.learn_in_exploit, **options)
    records = run_experiment(task, learner, trials=trials, n_step=n_step)
    starts = ([task.start_lane(t) for t in range(trials)]
              if isinstance(task, NavigationTask) else None)
    return TaskRun(
        payoff=[r.payoff for r in records], steps=[r.steps for r in records],
        success=[int(r.success) for r in records], explore=[int(r.explore) for r in records],
        first_action=[task.names[r.actions[0]] if r.actions else None for r in records],
        movability=[tuple(t) for t in learner.table.triples()],
        rules=rule_listing(learner.learner.classifiers(), task.actions), starts=starts)


def rule_listing(classifiers: Sequence, actions: Sequence[str]) -> list[Rule]:
    """Every macro-classifier as a row of ``RULE_COLUMNS``; the id is its place in the
    population, which grows by appending (so larger ids came later, as in Table 3.2)."""
    return [(index + 1, c.condition, actions[c.action], round(c.prediction, 1),
             round(c.error, 1), round(c.fitness, 2), round(c.action_set_size, 1),
             c.experience, c.numerosity) for index, c in enumerate(classifiers)]


def experienced_rules(rules: Sequence[Rule], count: int) -> list[Rule]:
    """The ``count`` most experienced rules, listed in id order (Table 3.2 shows such a set)."""
    experience = RULE_COLUMNS.index("experience")
    top = sorted(rules, key=lambda row: (-row[experience], row[0]))[:count]
    return sorted(top, key=lambda row: row[0])


def majority_movability(tables: Sequence[Sequence[Movability]]) -> list[Movability]:
    """Per (object, action) met in any seed, the effect most seeds learned (ties to
    "unmoved"), in order of first appearance."""
    order: list[tuple[str, str]] = []
    votes: dict[tuple[str, str], Counter] = {}
    for table in tables:
        for obj, action, effect in table:
            key = (obj, action)
            if key not in votes:
                order.append(key)
                votes[key] = Counter()
            votes[key][effect] += 1
    return [(*key, max(sorted(votes[key]), key=lambda e: (votes[key][e], -e))) for key in order]


def knows(run: TaskRun, row: Movability) -> float:
    """1 when the run's table holds exactly the triple ``row``, else 0."""
    return float(tuple(row) in {tuple(t) for t in run.movability})


def window(run: TaskRun, values: Sequence[float], start: int, stop: int,
           exploit_only: bool = False) -> float | None:
    """The run's mean of ``values`` over trials start..stop-1 (0-based; only exploit trials
    with ``exploit_only``); None when there are none."""
    chosen = [values[t] for t in range(start, stop) if not exploit_only or not run.explore[t]]
    return sum(chosen) / len(chosen) if chosen else None


def identical(runs: Mapping[str, TaskRun], other: Mapping[str, TaskRun]) -> float:
    """1 when every paired experiment had, trial by trial, the same payoff and steps (the
    camera perceived the same states as the truth throughout), else 0."""
    return float(all(runs[key].payoff == other[key].payoff
                     and runs[key].steps == other[key].steps for key in runs))


def per_trial(runs: Sequence[TaskRun], key: str) -> list[list[float]]:
    """One list per seed of ``key`` over the trials (the Series layout)."""
    return [[float(v) for v in getattr(run, key)] for run in runs]

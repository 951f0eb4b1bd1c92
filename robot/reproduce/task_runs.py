"""What the chapter-3 and Appendix-A reproductions share: one XCS experiment in a task world,
the learned rules as a Table 3.2 / 7.2 listing, movability by majority over seeds, curves.

Imports of MuJoCo and the behaviours happen inside ``opened_world`` and ``experiment``
(``goalagent reproduce --list`` imports every reproduction module and must stay light).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator, Sequence
from contextlib import contextmanager

from robot.reproduce.framework import mean_and_std

TASKS = ("navigation", "stacking", "search")
MODES = ("truth", "camera")
RULE_COLUMNS = ("id", "condition", "action", "prediction", "error", "fitness", "set_size",
                "experience", "numerosity")


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
               trials: int, change_after: int) -> dict:
    """One experiment of ``trials`` alternating trials in ``world``; the world changes after
    ``change_after`` (boxes exchanged, target moved). Per-trial payoff, steps, success and
    mode, the first action of each trial, the learned table and rules."""
    from behaviours.blob_grid import make_grid_perception
    from behaviours.object_state import make_object_perception
    from behaviours.xcs_tasks import NavigationTask, SearchTask, StackingTask
    from behaviours.xcs_trials import N_STEP, SEARCH_STEPS, make_learner, run_experiment

    options: dict[str, bool] = {}
    n_step = N_STEP
    if task_name == "navigation":
        task = NavigationTask(world, make_object_perception(mode, task_name),  # type: ignore
                              exchange_after=change_after)
    elif task_name == "stacking":
        task = StackingTask(world, make_object_perception(mode, task_name))  # type: ignore
    else:
        task = SearchTask(world, make_grid_perception(mode),  # type: ignore[arg-type]
                          move_after=change_after)
        options, n_step = {"consistent_actions": True}, SEARCH_STEPS
    learner = make_learner(task.actions, method, seed, **options)
    records = run_experiment(task, learner, trials=trials, n_step=n_step)
    return {
        "payoff": [r.payoff for r in records],
        "steps": [r.steps for r in records],
        "success": [int(r.success) for r in records],
        "explore": [int(r.explore) for r in records],
        "first_action": [task.names[r.actions[0]] if r.actions else None for r in records],
        "movability": [list(t) for t in learner.table.triples()],
        "rules": rule_listing(learner.learner.classifiers(), task.actions),
    }


def rule_listing(classifiers: Sequence, actions: Sequence[str]) -> list[list]:
    """Every macro-classifier as a row of ``RULE_COLUMNS``; the id is its place in the
    population, which grows by appending (so larger ids came later, as in Table 3.2)."""
    return [[index + 1, c.condition, actions[c.action], round(c.prediction, 1),
             round(c.error, 1), round(c.fitness, 2), round(c.action_set_size, 1),
             c.experience, c.numerosity] for index, c in enumerate(classifiers)]


def experienced_rules(rules: list[list], count: int) -> list[list]:
    """The ``count`` most experienced rules, listed in id order (Table 3.2 shows such a set)."""
    experience = RULE_COLUMNS.index("experience")
    top = sorted(rules, key=lambda row: (-row[experience], row[0]))[:count]
    return sorted(top, key=lambda row: row[0])


def majority_movability(tables: Sequence[Sequence[Sequence]]) -> list[list]:
    """[object, action, effect] rows: per pair met in any seed, the effect most seeds learned
    (ties to "unmoved"), in order of first appearance; with how many seeds knew the pair."""
    order: list[tuple[str, str]] = []
    votes: dict[tuple[str, str], Counter] = {}
    for table in tables:
        for obj, action, effect in table:
            key = (obj, action)
            if key not in votes:
                order.append(key)
                votes[key] = Counter()
            votes[key][effect] += 1
    rows = []
    for key in order:
        counts = votes[key]
        effect = max(sorted(counts), key=lambda e: (counts[e], -e))
        rows.append([key[0], key[1], effect])
    return rows


def seeds_with(tables: Sequence[Sequence[Sequence]], row: Sequence) -> float:
    """Fraction of seeds whose table holds exactly the triple ``row``."""
    return sum(any(list(t) == list(row) for t in table) for table in tables) / len(tables)


def per_trial(runs: Sequence[dict], key: str) -> list[list[float]]:
    """One list per seed of ``key`` over the trials (the Series layout)."""
    return [[float(v) for v in run[key]] for run in runs]


def window_mean(runs: Sequence[dict], key: str, start: int, stop: int,
                exploit_only: bool = False) -> tuple[float | None, float | None]:
    """Mean and sd over seeds of each seed's mean of ``key`` in trials start..stop-1 (0-based)."""
    values = []
    for run in runs:
        chosen = [run[key][t] for t in range(start, stop)
                  if not exploit_only or not run["explore"][t]]
        values.append(sum(chosen) / len(chosen) if chosen else None)
    return mean_and_std(values)


def identical_runs(pairs: Sequence[tuple[dict, dict]]) -> float:
    """Fraction of (truth, camera) experiment pairs whose every trial had the same actions'
    outcome: the same payoff and steps (the camera perceived the same states throughout)."""
    same = [a["payoff"] == b["payoff"] and a["steps"] == b["steps"] for a, b in pairs]
    return sum(same) / len(same)

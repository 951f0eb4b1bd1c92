"""One source of truth (issue 31): the XCS trials and Algorithm 3 give identical results
whether they drive a task directly or through its Gymnasium environment (``robot.gym.adapters``),
for the same seed, on every task."""

from __future__ import annotations

import gymnasium
import numpy as np
import pytest

from robot.gym.adapters import EnvContact, EnvTask


def direct_task(task_name: str, mode: str, change_after: int):
    from behaviours.blob_grid import make_grid_perception
    from behaviours.object_state import make_object_perception
    from behaviours.xcs_tasks import NavigationTask, SearchTask, StackingTask
    from sim.navigation import NavigationWorld
    from sim.search import SearchWorld
    from sim.stacking import StackingWorld

    if task_name == "navigation":
        return NavigationTask(NavigationWorld(), make_object_perception(mode, task_name),
                              exchange_after=change_after)
    if task_name == "stacking":
        return StackingTask(StackingWorld(), make_object_perception(mode, task_name))
    return SearchTask(SearchWorld(), make_grid_perception(mode), move_after=change_after)


def experiment(task, method: str, seed: int, trials: int, n_step: int, **options) -> tuple:
    from behaviours.xcs_trials import make_learner, run_experiment

    learner = make_learner(task.actions, method, seed, **options)
    records = run_experiment(task, learner, trials=trials, n_step=n_step)
    return records, learner.table.triples(), [tuple(c) for c in learner.learner.classifiers()]


@pytest.mark.parametrize(("task_name", "env_id", "method", "mode", "options"), [
    ("navigation", "Navigation", "affordance_xcs", "truth", {}),
    ("navigation", "Navigation", "standard_xcs", "camera", {}),
    ("stacking", "Stacking", "affordance_xcs", "truth", {}),
    ("search", "HeadSearch", "standard_xcs", "truth", {"consistent_actions": True}),
])
def test_xcs_experiments_are_identical_through_the_gymnasium_environment(
        task_name, env_id, method, mode, options):
    trials, change_after = 6, 3
    n_step = 20 if task_name == "search" else 10
    change = {"search": "move_after", "stacking": None}.get(task_name, "exchange_after")
    kwargs = {"perception": mode, **({change: change_after} if change else {})}
    env = gymnasium.make(f"goalagent/{env_id}-v0", **kwargs)
    through_gym = experiment(EnvTask(env, seed=7), method, 7, trials, n_step, **options)
    direct = experiment(direct_task(task_name, mode, change_after), method, 7, trials, n_step,
                        **options)
    assert through_gym == direct
    records = through_gym[0]
    assert len({r.payoff for r in records}) > 1 or task_name == "search"  # not all alike
    env.close()


def test_algorithm_3_is_identical_through_the_gymnasium_environment():
    from behaviours.contact import PartContact
    from behaviours.learners.exploration import ActiveExplorer
    from sim.world import GarbageWorld

    def explorer() -> ActiveExplorer:
        return ActiveExplorer(mode="active", n_max=24, n_random=20, random_state=3, stop=False)

    direct = PartContact(GarbageWorld("o1", seed=3), "lid", dims=1).start()
    env = gymnasium.make("goalagent/CanOpening-v0", can="o1", part="lid", dims=1)
    through_gym = explorer().explore(EnvContact(env, seed=3).start()).history_
    history = explorer().explore(direct).history_
    for field in ("states", "actions", "effects", "predictions", "rewards", "td_errors"):
        assert np.array_equal(getattr(through_gym, field), getattr(history, field)), field
    assert through_gym.states.max() > 0.01  # it did open the lid
    env.close()


def test_navigation_trials_start_in_the_same_drawn_lanes_through_the_environment():
    """``start="anywhere"`` (§3.5.7): the environment draws each trial's lane from the
    experiment's seed as the task does, so the runs stay identical."""
    from behaviours.object_state import make_object_perception
    from behaviours.xcs_tasks import NavigationTask
    from sim.navigation import NavigationWorld

    env = gymnasium.make("goalagent/Navigation-v0", exchange_after=3, start="anywhere")
    through_gym = experiment(EnvTask(env, seed=7), "affordance_xcs", 7, 6, 10)
    task = NavigationTask(NavigationWorld(), make_object_perception("truth", "navigation"),
                          exchange_after=3, start="anywhere", seed=7)
    assert len({task.start_lane(trial) for trial in range(6)}) > 1
    assert through_gym == experiment(task, "affordance_xcs", 7, 6, 10)
    env.close()

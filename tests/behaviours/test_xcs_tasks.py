"""The XCS tasks: rewards 3.14 / 3.15 / App. A on hand values, the eq. 3.10 filter, task steps."""

from __future__ import annotations

import pytest

from behaviours.blob_grid import make_grid_perception
from behaviours.learners.affordance_table import AffordanceTable
from behaviours.learners.affordance_xcs import AffordanceXCS
from behaviours.object_state import make_object_perception
from behaviours.xcs_tasks import (
    GOAL_REWARD,
    PUNISHMENT,
    NavigationTask,
    SearchTask,
    StackingTask,
    navigation_reward,
    search_reward,
    stacking_reward,
)
from sim.navigation import NavigationWorld
from sim.search import SearchWorld
from sim.stacking import StackingWorld

LEFT, AHEAD, RIGHT, PUSH = range(4)
STAND, SQUAT, BOX, FOAM = range(4)


def test_eq_3_14_goal_first_then_punishment_for_too_little_progress():
    assert navigation_reward(distance=0.0, progress=0.15) == GOAL_REWARD
    assert navigation_reward(distance=0.01, progress=0.0) == GOAL_REWARD
    assert navigation_reward(distance=0.30, progress=0.02) == PUNISHMENT
    assert navigation_reward(distance=0.30, progress=0.0) == PUNISHMENT  # a sideways step
    assert navigation_reward(distance=0.30, progress=0.15) == 0.0


def test_eq_3_15_and_the_search_reward():
    assert stacking_reward(stacked=True, chose=False) == 1000.0
    assert stacking_reward(stacked=False, chose=True) == -100.0
    assert stacking_reward(stacked=False, chose=False) == 0.0
    assert search_reward("000010000") == 1000.0
    assert search_reward("110110000") == 1000.0
    assert search_reward("100000000") == 0.0


class _Unused:
    """A learner slot ``allowed`` never calls (it only consults the table)."""


def test_eq_3_10_filter_allows_every_action_but_those_with_an_undesired_effect():
    table = AffordanceTable()
    table.update("1100", "010", 0)
    table.update("1001", "010", 1)
    filtered = AffordanceXCS(_Unused(), ("000", "001", "011", "010"), table)  # type: ignore
    assert filtered.allowed("1100") == {LEFT, AHEAD, RIGHT}
    assert filtered.allowed("1001") is None  # nothing undesired known: no restriction
    assert filtered.allowed(None) is None  # nothing in front
    baseline = AffordanceXCS(_Unused(), filtered.actions, table, use_affordances=False)  # type: ignore
    assert baseline.allowed("1100") is None
    for action in ("000", "001", "011"):
        table.update("1100", action, 0)
    assert filtered.allowed("1100") is None  # all filtered: the filter is dropped


@pytest.fixture(scope="module")
def navigation():
    world = NavigationWorld()
    yield NavigationTask(world, make_object_perception("truth", "navigation"), exchange_after=1)
    world.close()


def test_pushing_the_fixed_box_is_punished_and_unmoved(navigation):
    view = navigation.reset(1)  # from trial 1 on the boxes are exchanged
    assert view.obj == "1100"
    outcome, after = navigation.perform(PUSH)
    assert (outcome.reward, outcome.effect, outcome.done) == (PUNISHMENT, 0, False)
    assert after == view


def test_pushing_the_movable_box_three_times_reaches_the_destination(navigation):
    view = navigation.reset(0)
    assert view.obj == "1001"
    rewards, effects = [], []
    for _ in range(3):
        outcome, view = navigation.perform(PUSH)
        rewards.append(outcome.reward)
        effects.append(outcome.effect)
    assert rewards == [0.0, 0.0, GOAL_REWARD] and effects == [1, 1, 1]
    assert outcome.done and outcome.success


def test_stepping_off_the_table_ends_the_trial_without_success(navigation):
    navigation.reset(0)
    outcome, _ = navigation.perform(RIGHT)
    assert outcome.done and not outcome.success and outcome.reward == PUNISHMENT
    assert outcome.effect is None  # walking teaches no affordance


def test_stacking_task_rewards_choices_pushes_and_the_stack():
    world = StackingWorld()
    task = StackingTask(world, make_object_perception("truth", "stacking"))
    try:
        assert task.reset(0).obj is None
        outcome, view = task.perform(FOAM)
        assert outcome.reward == PUNISHMENT and view.obj == "0010" and outcome.effect is None
        outcome, _ = task.perform(STAND)
        assert (outcome.reward, outcome.effect) == (0.0, 0)
        outcome, view = task.perform(SQUAT)
        assert (outcome.reward, outcome.effect, view.obj) == (0.0, 1, None)
        task.perform(BOX)
        outcome, _ = task.perform(STAND)
        assert (outcome.reward, outcome.effect, outcome.done) == (GOAL_REWARD, 1, True)
    finally:
        world.close()


def test_search_task_finds_the_target_and_it_moves_after_the_first_trials():
    world = SearchWorld()
    task = SearchTask(world, make_grid_perception("truth"), move_after=1)
    try:
        task.reset(0)
        outcomes = [task.perform(task.actions.index(a))[0] for a in ("11", "11", "00", "00")]
        assert [o.reward for o in outcomes] == [0.0, 0.0, 0.0, GOAL_REWARD] and outcomes[-1].done
        task.reset(1)  # the target has moved to the right
        outcomes = [task.perform(task.actions.index("01"))[0] for _ in range(3)]
        assert [o.done for o in outcomes] == [False, False, True]
    finally:
        world.close()

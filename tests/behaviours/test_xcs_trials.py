"""Algorithm 2 through the real XCS (eq. 3.10 via ``allowed``) and the trial / experiment loop."""

from __future__ import annotations

import pytest

from behaviours.object_state import make_object_perception
from behaviours.xcs_tasks import NAVIGATION_ACTIONS, NavigationTask
from behaviours.xcs_trials import TABLE_7_1, make_learner, run_experiment, run_trial
from sim.navigation import NavigationWorld

ACTIONS = tuple(NAVIGATION_ACTIONS)
PUSH = ACTIONS.index("010")
FACING_RED = "11000001"


def _knows_red_is_fixed(method: str, seed: int = 0):
    learner = make_learner(ACTIONS, method, seed)
    learner.table.update("1100", "010", 0)
    return learner


@pytest.mark.parametrize("explore", [True, False])
def test_affordance_xcs_never_pushes_what_the_table_says_does_not_move(explore):
    learner = _knows_red_is_fixed("affordance_xcs")
    for _ in range(150):
        assert learner.act(FACING_RED, "1100", explore) != PUSH
        learner.reward(-100.0, True)


def test_standard_xcs_keeps_pushing_the_fixed_box_now_and_then():
    learner = _knows_red_is_fixed("standard_xcs")
    chosen = []
    for _ in range(150):
        chosen.append(learner.act(FACING_RED, "1100", True))
        learner.reward(-100.0, True)
    assert chosen.count(PUSH) > 10


def test_covering_still_offers_the_allowed_actions_on_an_unseen_state():
    learner = _knows_red_is_fixed("affordance_xcs")
    prediction = learner.learner.prediction_array(FACING_RED)
    assert all(p != p for p in prediction)  # nothing advocates anything yet: all NaN
    assert learner.act(FACING_RED, "1100", explore=False) in {0, 1, 2}


def test_table_7_1_parameters_reach_xcs_and_unknown_methods_are_refused():
    learner = make_learner(ACTIONS, "affordance_xcs", seed=3)
    params = learner.learner.get_params()
    assert {k: params[k] for k in TABLE_7_1} == TABLE_7_1
    assert params["random_state"] == 3
    with pytest.raises(ValueError, match="unknown method 'q_learning'"):
        make_learner(ACTIONS, "q_learning", 0)


@pytest.fixture(scope="module")
def world():
    w = NavigationWorld()
    yield w
    w.close()


def test_a_trial_sums_its_rewards_and_stops_at_the_step_limit(world):
    task = NavigationTask(world, make_object_perception("truth", "navigation"))
    learner = make_learner(task.actions, "standard_xcs", seed=1)
    record = run_trial(task, learner, trial=0, explore=True, n_step=3)
    assert 1 <= record.steps <= 3 and len(record.actions) == record.steps
    assert record.trial == 1 and record.explore
    assert record.payoff % 100 == 0 and record.payoff <= 1000
    if record.steps == 3 and not record.success:
        assert record.payoff >= -300  # each step costs at most 100 (eq. 3.14)


def test_an_experiment_alternates_explore_and_exploit_and_learns_movability(world):
    task = NavigationTask(world, make_object_perception("truth", "navigation"),
                          exchange_after=3)
    learner = make_learner(task.actions, "affordance_xcs", seed=0)
    records = run_experiment(task, learner, trials=6)
    assert [r.explore for r in records] == [True, False] * 3
    assert [r.trial for r in records] == list(range(1, 7))
    for obj, action, effect in learner.table.triples():
        assert action == "010"  # only pushes teach affordances
        assert effect == {"1001": 1, "1100": 0}[obj]
    with pytest.raises(ValueError, match="at least one trial"):
        run_experiment(task, learner, trials=0)

"""XCS equations on hand-built populations against values computed by hand (thesis App. A).

Eq. 3.8 (prediction array), 3.9 (greedy choice), 7.1 (prediction), 7.2 (multi-step payoff),
7.3 (GA trigger), 7.4 (error), 7.5-7.7 (fitness from relative accuracy), the action-set size
estimate, experience, numerosity and time stamps.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from behaviours.learners.xcs import XCS
from tests.xcs_helpers import by_condition, cl, make


def test_prediction_array_is_the_fitness_weighted_mean_per_action_eq_3_8():
    xcs = make([cl("0#1", 0, prediction=100.0, fitness=0.2),
                cl("##1", 0, prediction=400.0, fitness=0.6),
                cl("0##", 1, prediction=900.0, fitness=0.5),
                cl("1##", 2, prediction=50.0, fitness=0.9)], n_actions=4)
    array = xcs.prediction_array("011")
    assert array[0] == pytest.approx((100 * 0.2 + 400 * 0.6) / (0.2 + 0.6))
    assert array[1] == pytest.approx(900.0)
    assert math.isnan(array[2])  # its only classifier does not match 011
    assert math.isnan(array[3])  # nobody advocates action 3
    assert len(xcs.classifiers()) == 4  # a query covers nothing


def test_exploit_takes_the_best_prediction_eq_3_9_and_the_best_allowed_one():
    records = [cl("##", 0, prediction=300.0), cl("##", 1, prediction=700.0),
               cl("##", 2, prediction=500.0)]
    xcs = make(records, n_actions=3)
    assert xcs.act("10", explore=False) == 1
    xcs.reward(0.0, done=True)
    assert xcs.act("10", explore=False, allowed={0, 2}) == 2
    xcs.reward(0.0, done=True)
    assert by_condition(xcs)[("##", 1)].experience == 0  # exploit problems learn nothing
    assert xcs.time_ == 0


def test_widrow_hoff_updates_of_prediction_and_error_with_separate_rates_eq_7_1_7_4_7_5():
    xcs = make([cl("##", 0, prediction=500.0, error=100.0, fitness=0.5, experience=10)],
               beta_p=0.5, beta_e=0.25, beta_f=0.1, beta=0.2)
    assert xcs.act("01", explore=True, allowed={0}) == 0
    xcs.reward(1000.0, done=True)
    (after,) = xcs.classifiers()
    prediction = 500 + 0.5 * (1000 - 500)  # eq. 7.1
    assert after.prediction == pytest.approx(prediction)
    assert after.error == pytest.approx(100 + 0.25 * (abs(1000 - prediction) - 100))  # eq. 7.4
    assert after.fitness == pytest.approx(0.5 + 0.1 * (1.0 - 0.5))  # eq. 7.5, kappa' = 1 alone
    assert after.experience == 11
    assert after.action_set_size == pytest.approx(1.0)


def test_a_new_classifier_averages_its_first_payoffs_before_1_over_beta_updates():
    xcs = make([cl("##", 0, prediction=10.0, error=0.0, experience=0)], beta=0.2)
    for reward, expected_prediction, expected_error in (
            (600.0, 600.0, 0.0),  # exp 1: p = P, error |P - p| = 0
            (300.0, 450.0, 75.0),  # exp 2: p += (P - p) / 2; error += (|P - p| - error) / 2
            (0.0, 300.0, 150.0)):  # exp 3: mean of 600, 300, 0; error += (300 - 75) / 3
        xcs.act("11", explore=True, allowed={0})
        xcs.reward(reward, done=True)
        (after,) = xcs.classifiers()
        assert after.prediction == pytest.approx(expected_prediction)
        assert after.error == pytest.approx(expected_error)


def test_fitness_moves_towards_relative_accuracy_eq_7_5_to_7_7():
    xcs = make([cl("0#", 0, prediction=1000.0, error=5.0, fitness=0.2, experience=100,
                   numerosity=2),
                cl("##", 0, prediction=1000.0, error=20.0, fitness=0.2, experience=100)],
               beta=0.2, epsilon_0=10.0, alpha=0.1, nu=5.0)
    xcs.act("01", explore=True, allowed={0})
    xcs.reward(1000.0, done=True)
    after = by_condition(xcs)
    error_accurate, error_inaccurate = 5.0 * 0.8, 20.0 * 0.8  # eq. 7.4 with P = p
    assert after[("0#", 0)].error == pytest.approx(error_accurate)
    assert after[("##", 0)].error == pytest.approx(error_inaccurate)
    kappa_accurate = 1.0  # eq. 7.6: error below epsilon_0
    kappa_inaccurate = 0.1 * (error_inaccurate / 10.0) ** -5.0
    total = kappa_accurate * 2 + kappa_inaccurate * 1  # eq. 7.7 weighs by numerosity
    assert after[("0#", 0)].fitness == pytest.approx(0.2 + 0.2 * (2 * kappa_accurate / total
                                                                  - 0.2))
    assert after[("##", 0)].fitness == pytest.approx(0.2 + 0.2 * (kappa_inaccurate / total
                                                                  - 0.2))


def test_action_set_size_estimate_tracks_the_numerosity_of_the_action_set():
    xcs = make([cl("##", 0, experience=50, numerosity=3, action_set_size=10.0),
                cl("0#", 0, experience=50, numerosity=2, action_set_size=1.0),
                cl("1#", 0, experience=50, numerosity=4, action_set_size=1.0)], beta=0.2)
    xcs.act("01", explore=True, allowed={0})
    xcs.reward(0.0, done=True)
    after = by_condition(xcs)
    assert after[("##", 0)].action_set_size == pytest.approx(10 + 0.2 * (5 - 10))
    assert after[("0#", 0)].action_set_size == pytest.approx(1 + 0.2 * (5 - 1))
    assert after[("1#", 0)].action_set_size == pytest.approx(1.0)  # not in [A]
    assert after[("1#", 0)].experience == 50


def test_multi_step_payoff_is_reward_plus_discounted_max_of_next_prediction_array_eq_7_2():
    records = [cl("0#", 0, prediction=100.0, fitness=1.0, experience=100),
               cl("0#", 1, prediction=50.0, fitness=1.0, experience=100),
               cl("1#", 0, prediction=400.0, fitness=1.0, experience=100),
               cl("1#", 1, prediction=800.0, fitness=1.0, experience=100)]
    for allowed, best_next in ((None, 800.0), ({0}, 400.0)):
        xcs = make(records, gamma=0.71, beta=0.2)
        first = xcs.act("01", explore=True)
        xcs.reward(5.0, done=False)
        untouched = by_condition(xcs)[("0#", first)]
        assert untouched.experience == 100  # [A]-1 waits for the next state
        second = xcs.act("10", explore=True, allowed=allowed)
        payoff = 5.0 + 0.71 * best_next  # eq. 7.2, max over the allowed actions
        previous = by_condition(xcs)[("0#", first)]
        assert previous.prediction == pytest.approx(records[first].prediction
                                                    + 0.2 * (payoff - records[first].prediction))
        assert previous.experience == 101
        xcs.reward(1000.0, done=True)  # last step of the trial: [A] gets P = r
        last = by_condition(xcs)[("1#", second)]
        start = records[2 + second].prediction
        assert last.prediction == pytest.approx(start + 0.2 * (1000.0 - start))


def test_a_trial_cut_short_leaves_the_last_action_set_unrewarded():
    xcs = make([cl("##", 0, prediction=100.0, experience=100)])
    xcs.act("00", explore=True, allowed={0})
    xcs.reward(0.0, done=False)
    xcs.end_trial()
    xcs.act("11", explore=True, allowed={0})  # a new trial: no bootstrapping into it
    (after,) = xcs.classifiers()
    assert after.experience == 100 and after.prediction == 100.0


def test_ga_runs_when_the_numerosity_weighted_mean_time_stamp_is_older_than_theta_ga_eq_7_3():
    records = [cl("0#", 0, fitness=0.5, numerosity=3, time_stamp=0),
               cl("##", 0, fitness=0.5, numerosity=1, time_stamp=8)]
    xcs = make(records, theta_ga=10, time=11, chi=0.0, mu=0.0)
    xcs.act("01", explore=True, allowed={0})  # t = 12: 12 - (0*3 + 8*1)/4 = 10, not > 10
    xcs.reward(0.0, done=True)
    assert xcs.micro_count == 4
    assert [c.time_stamp for c in xcs.classifiers()] == [0, 8]
    xcs.act("01", explore=True, allowed={0})  # t = 13: 11 > 10, the GA runs
    xcs.reward(0.0, done=True)
    assert xcs.micro_count == 6  # two offspring, copies of their parents (no crossover,
    assert xcs.macro_count == 2  # no mutation) joining them as numerosity
    assert [c.time_stamp for c in xcs.classifiers()] == [13, 13]


def test_time_counts_explore_steps_and_stamps_covering_classifiers():
    xcs = XCS(2, random_state=3)
    xcs.act("0101", explore=False)
    xcs.reward(0.0, done=True)
    assert xcs.time_ == 0
    for _ in range(3):
        xcs.act("0101", explore=True)
        xcs.reward(0.0, done=True)
    assert xcs.time_ == 3
    xcs.act("1111", explore=True)
    stamps = {c.time_stamp for c in xcs.classifiers() if all(
        symbol in ("1", "#") for symbol in c.condition)}
    assert 4 in stamps


def test_numerosity_experience_and_records_are_consistent_after_learning():
    xcs = XCS(2, N=50, random_state=1)
    rng = np.random.default_rng(0)
    for _ in range(300):
        state = "".join(rng.choice(["0", "1"], size=4))
        action = xcs.act(state, explore=True)
        xcs.reward(1000.0 if action == int(state[0]) else 0.0, done=True)
    records = xcs.classifiers()
    assert sum(c.numerosity for c in records) == xcs.micro_count <= 50
    assert len(records) == xcs.macro_count
    assert len({(c.condition, c.action) for c in records}) == len(records)
    assert all(c.numerosity >= 1 and c.experience >= 0 and c.fitness > 0 for c in records)
    assert all(0 <= c.time_stamp <= xcs.time_ for c in records)



def test_action_sets_deleted_before_their_payoff_arrives_are_skipped_quietly():
    xcs = XCS(4, N=12, theta_ga=0, random_state=0)  # deletion after almost every step
    rng = np.random.default_rng(0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for step in range(3000):
            xcs.act(rng.integers(0, 2, 6), explore=True)
            xcs.reward(float(rng.integers(0, 2)) * 100.0, done=step % 7 == 6)
    assert xcs.micro_count <= 12

"""XCS rule discovery on hand-built populations: covering, the GA's operators and offspring,
GA and action-set subsumption, and deletion by action-set size and fitness."""

from __future__ import annotations

import numpy as np
import pytest

from behaviours.learners.xcs import XCS
from behaviours.learners.xcs_discovery import (
    mutate_action,
    mutate_condition,
    run_ga,
    two_point_crossover,
)
from behaviours.learners.xcs_params import Settings
from behaviours.learners.xcs_population import condition_masks, condition_text, more_general
from tests.xcs_helpers import by_condition, cl, make


def settings(n_actions: int = 2, **changes) -> Settings:
    return Settings.resolve("XCS", XCS(n_actions, **changes).get_params())


def state(text: str) -> int:
    return condition_masks(text)[1]


# -- covering ----------------------------------------------------------------------------------

def test_covering_creates_one_classifier_per_missing_action_with_initial_values():
    xcs = XCS(3, random_state=0, p_hash=0.0, prediction_init=7.0, error_init=2.0,
              fitness_init=0.05)
    action = xcs.act("0110", explore=True)
    records = xcs.classifiers()
    assert sorted(c.action for c in records) == [0, 1, 2]
    assert all(c.condition == "0110" for c in records)  # p_hash 0: the state itself
    assert all((c.prediction, c.error, c.fitness, c.experience, c.numerosity,
                c.action_set_size, c.time_stamp) == (7.0, 2.0, 0.05, 0, 1, 1.0, 1)
               for c in records)
    assert action in (0, 1, 2)


def test_covering_with_p_hash_one_makes_fully_general_conditions():
    xcs = XCS(2, random_state=0, p_hash=1.0)
    xcs.act("0110", explore=False)
    assert {c.condition for c in xcs.classifiers()} == {"####"}


def test_covering_draws_hashes_at_the_rate_p_hash():
    xcs = XCS(1, N=5000, random_state=0, p_hash=0.33)
    rng = np.random.default_rng(1)
    for _ in range(400):
        xcs.act("".join(rng.choice(["0", "1"], size=24)), explore=False)
    conditions = "".join(c.condition for c in xcs.classifiers())
    assert conditions.count("#") / len(conditions) == pytest.approx(0.33, abs=0.02)


def test_when_every_advocated_action_is_filtered_out_covering_makes_an_allowed_one():
    xcs = make([cl("##", 0, prediction=900.0, fitness=1.0)], n_actions=3)
    action = xcs.act("01", explore=False, allowed={2})
    assert action == 2
    covered = by_condition(xcs)
    assert [key for key in covered if key[1] == 2] and not [k for k in covered if k[1] == 1]
    assert covered[("##", 0)].numerosity == 1


def test_covering_keeps_the_population_within_n():
    xcs = XCS(4, N=6, random_state=0)
    rng = np.random.default_rng(2)
    for _ in range(50):
        xcs.act("".join(rng.choice(["0", "1"], size=8)), explore=False)
        assert xcs.micro_count <= 6


# -- GA operators ------------------------------------------------------------------------------

def test_two_point_crossover_exchanges_the_positions_from_start_to_stop():
    first, second = two_point_crossover(condition_masks("0#1#01"), condition_masks("1100#1"), 1,
                                        4)
    assert (condition_text(*first, 6), condition_text(*second, 6)) == ("010001", "1#1##1")
    unchanged = two_point_crossover(condition_masks("0#1#01"), condition_masks("1100#1"), 3, 3)
    assert [condition_text(*c, 6) for c in unchanged] == ["0#1#01", "1100#1"]


def test_niche_mutation_keeps_the_condition_matching_the_state():
    mutated = mutate_condition(condition_masks("0#1#"), [0, 1, 3], state("0110"))
    assert condition_text(*mutated, 4) == "#110"  # 0 -> #, # -> 1 and # -> 0 from the state
    assert mutate_condition(condition_masks("0#1#"), [], state("0110")) == condition_masks("0#1#")


def test_action_mutation_picks_another_action_uniformly():
    three = settings(n_actions=3, mu=0.5)
    assert mutate_action(1, 0.6, 0.1, three) == 1  # draw >= mu: no mutation
    assert [mutate_action(1, 0.2, choice, three) for choice in (0.1, 0.6)] == [0, 2]
    assert [mutate_action(0, 0.2, choice, three) for choice in (0.1, 0.6)] == [1, 2]
    assert mutate_action(0, 0.0, 0.9, settings(n_actions=1, mu=1.0)) == 0


def test_offspring_of_crossover_average_their_parents_and_lose_nine_tenths_of_fitness():
    parents = [cl("0#", 0, prediction=100.0, error=4.0, fitness=0.4, numerosity=2,
                  action_set_size=3.0, time_stamp=7),
               cl("#1", 0, prediction=300.0, error=8.0, fitness=0.3, action_set_size=5.0,
                  time_stamp=7)]
    seen_offspring = False
    for seed in range(30):
        xcs = make(parents, n_actions=1)
        population = xcs.population_
        run_ga(population, np.array([0, 1]), population.fitness[:2], state("01"),
               settings(n_actions=1, chi=1.0, mu=0.0, ga_subsumption=False),
               np.random.default_rng(seed))
        for child in by_condition(xcs).values():
            if child.condition in ("0#", "#1"):
                continue
            seen_offspring = True  # "01" or "##": a real exchange between the two parents
            assert child.prediction == pytest.approx(200.0)
            assert child.error == pytest.approx(6.0)
            assert child.fitness * child.numerosity == pytest.approx(
                child.numerosity * 0.1 * (0.4 / 2 + 0.3 / 1) / 2)
            assert child.experience == 0 and child.time_stamp == 7
    assert seen_offspring


def test_offspring_without_crossover_copy_one_parent_with_a_tenth_of_its_micro_fitness():
    xcs = make([cl("##", 0, prediction=600.0, error=3.0, fitness=0.9, numerosity=3,
                   experience=40, action_set_size=4.0, time_stamp=2)], n_actions=1)
    run_ga(xcs.population_, np.array([0]), xcs.population_.fitness[:1], state("10"),
           settings(n_actions=1, chi=0.0, mu=1.0, ga_subsumption=False),
           np.random.default_rng(0))
    child = by_condition(xcs)[("10", 0)]  # mu = 1: every # became the state's bit
    assert child.numerosity == 2  # both offspring are the same classifier
    assert (child.prediction, child.error, child.experience) == (600.0, 3.0, 0)
    assert child.fitness == pytest.approx(0.1 * 0.9 / 3)
    assert (child.action_set_size, child.time_stamp) == (4.0, 2)


# -- subsumption -------------------------------------------------------------------------------

def test_is_more_general_needs_strictly_more_hashes_and_agreement():
    general = condition_masks("1#0#")
    others = ["1#0#", "110#", "1100", "0#0#", "1#00", "##0#", "1#1#"]
    assert [more_general(general, condition_masks(text)) for text in others] == [
        False, True, True, False, True, False, False]


def test_ga_subsumption_gives_an_accurate_experienced_parent_its_more_specific_offspring():
    accurate = cl("##", 0, prediction=1000.0, error=0.0, fitness=1.0, experience=50)
    xcs = make([accurate], n_actions=1, theta_ga=0, chi=0.0, mu=1.0, ga_subsumption=True)
    xcs.act("01", explore=True)
    xcs.reward(1000.0, done=True)
    assert [(c.condition, c.numerosity) for c in xcs.classifiers()] == [("##", 3)]
    inexperienced = accurate._replace(experience=5)  # theta_sub = 20 not reached
    xcs = make([inexperienced], n_actions=1, theta_ga=0, chi=0.0, mu=1.0, ga_subsumption=True)
    xcs.act("01", explore=True)
    xcs.reward(1000.0, done=True)
    assert {(c.condition, c.numerosity) for c in xcs.classifiers()} == {("##", 1), ("01", 2)}


def test_action_set_subsumption_folds_more_specific_classifiers_into_the_most_general():
    records = [cl("1#", 0, prediction=1000.0, fitness=0.5, experience=30, numerosity=2),
               cl("11", 0, prediction=1000.0, fitness=0.5, experience=30, numerosity=3),
               cl("#1", 0, prediction=1000.0, error=50.0, fitness=0.5, experience=30),
               cl("11", 1, prediction=0.0, fitness=0.5, experience=30)]
    xcs = make(records, action_set_subsumption=True)
    xcs.act("11", explore=True, allowed={0})
    xcs.reward(1000.0, done=True)
    after = by_condition(xcs)
    assert set(after) == {("1#", 0), ("#1", 0), ("11", 1)}  # "#1" is too inaccurate to subsume
    assert after[("1#", 0)].numerosity == 5
    assert xcs.micro_count == 7


# -- deletion ----------------------------------------------------------------------------------

def test_deletion_votes_by_action_set_size_and_low_fitness():
    records = [cl("0#", 0, fitness=0.5, experience=5, action_set_size=2.0),  # vote 2
               cl("1#", 0, fitness=0.02, experience=30, numerosity=2),  # 2 * 0.205 / 0.01 = 41
               cl("##", 1, fitness=0.3, experience=30, action_set_size=3.0)]  # vote 3
    for uniform, victim in ((0.01, "0#"), (2.1 / 46, "1#"), (42.9 / 46, "1#"), (0.99, "##")):
        xcs = make(records, theta_del=20, delta=0.1)
        xcs.population_.delete_one(uniform, theta_del=20, delta=0.1)
        left = {c.condition: c.numerosity for c in xcs.classifiers()}
        expected = {"0#": 1, "1#": 2, "##": 1}
        expected[victim] -= 1
        assert left == {name: n for name, n in expected.items() if n}, uniform
        assert xcs.micro_count == 3


@pytest.mark.parametrize(("size_limit", "removed"), [(9, 2), (10, 1), (11, 0)])
def test_repeated_deletion_matches_single_deletions_and_stops_at_n(size_limit, removed):
    # "0#" holds most of the fitness and of the votes: once it goes, the mean fitness falls
    # from 7.3 / 11 to 1.3 / 10 and "1#" and "##" are no longer weak
    records = [cl("0#", 0, fitness=6.0, experience=5, action_set_size=20.0),
               cl("1#", 0, fitness=0.1, experience=30, numerosity=2),
               cl("##", 1, fitness=0.3, experience=30, numerosity=5),
               cl("01", 1, fitness=0.9, experience=40, numerosity=3)]
    for seed in range(20):
        repeated, single = make(records), make(records)
        rng, draws = np.random.default_rng(seed), np.random.default_rng(seed)
        repeated.population_.delete_over(size_limit, 2, rng, theta_del=20, delta=0.1)
        for _ in range(removed):
            single.population_.delete_one(draws.random(), theta_del=20, delta=0.1)
        assert repeated.classifiers() == single.classifiers()
        assert repeated.micro_count == 11 - removed
        assert rng.random() == draws.random()  # one draw per removal, none beyond N


def test_a_weak_classifier_whose_fitness_underflowed_to_0_is_deleted_without_an_error():
    # only rewards near the float range underflow a fitness; its raised vote is then numpy's
    # x / 0 (inf), on the wheel as before, not a ZeroDivisionError of the float path
    population = make([cl("0#", 0, fitness=1.0, experience=30),
                       cl("##", 1, fitness=1.0, experience=30)]).population_
    population.fitness[0] = 0.0
    with np.errstate(all="ignore"):
        population.delete_one(0.5, theta_del=20, delta=0.1)
    assert population.micro_count == 1


def test_the_ga_deletes_down_to_n_after_inserting_offspring():
    xcs = make([cl("##", 0, fitness=0.5, numerosity=4, experience=10)], n_actions=2, N=4,
               theta_ga=0, mu=0.5)
    xcs.act("10", explore=True, allowed={0})
    xcs.reward(10.0, done=True)
    assert xcs.micro_count == 4

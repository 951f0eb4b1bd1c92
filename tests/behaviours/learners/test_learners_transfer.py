"""Algorithms 4, 5 and 6 (thesis ch. 5) on the hand-made objects of tests/synthetic_cans.py."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.base import clone

from behaviours.learners.baseline import PartBasedLearner
from behaviours.learners.known_objects import KnownObject
from behaviours.learners.part_models import OpeningGoal
from behaviours.learners.similarity import PartSimilarity, fit_similarity, rank_sources
from behaviours.learners.transfer import TransferLearner, gradient_step
from tests.synthetic_cans import (
    BODY,
    HANDLE,
    HANDLE_CAN,
    LID,
    LOW_LID,
    PEDAL,
    SyntheticCan,
    Working,
    thesis_cans,
)


def learned(names: list[str], seed: int = 0) -> list[KnownObject]:
    """The known objects after learning ``names`` in order, each with transfer from the rest."""
    cans, known = thesis_cans(seed=seed), []
    for name in names:
        learner = TransferLearner(database=list(known), random_state=seed).fit(cans[name])
        known.append(KnownObject.learned(name, learner))
    return known


# ---------------------------------------------------------------- Algorithm 4
def test_baseline_explores_every_pair_and_stops_dead_pairs_after_three():
    can = thesis_cans()["o1"]
    learner = PartBasedLearner(random_state=0).fit(can)
    assert set(learner.models_) == {(p, a) for p in ("lid", "body") for a in can.actions}
    counts = {pair: model.n_samples_ for pair, model in learner.models_.items()}
    # the effective pair: all n = 5 samples, and the goal-directed action's sample joins them
    assert counts.pop(("lid", "extend_arm")) == 5 + 1
    assert set(counts.values()) == {3}  # the 11 dead pairs settle (5.19) after three
    # 5 + 11 * 3 exploratory actions and one goal-directed action with θ* (5.12)
    assert learner.n_actions_ == len(can.calls) == 39
    assert learner.trials_[-1].purpose == "exploit" and learner.trials_[-1].reached
    assert (learner.functional_.part, learner.functional_.action) == ("lid", "extend_arm")
    # θ* aims at s_o^g + δ1 = 0.13 m: ĝ = 1.2 θ, ĥ = 0.93 e_ψ is short of that at 0.1, so θ*
    # is the smallest θ within δ2 of the largest displacement
    assert learner.functional_.theta == pytest.approx((0.12 - 0.002) / 1.2)
    assert len(learner.data_) == 39 and learner.data_[0].obj == "o1"


def test_baseline_on_a_three_part_can_and_with_noise():
    learner = PartBasedLearner(random_state=3).fit(thesis_cans()["o5"])
    assert learner.n_actions_ == 17 * 3 + 5 + 1
    assert (learner.functional_.part, learner.functional_.action) == ("handle", "contract_arm")
    noisy = PartBasedLearner(random_state=3).fit(thesis_cans(noise=0.002, seed=1)["o2"])
    assert (noisy.functional_.part, noisy.functional_.action) == ("handle", "lift_up")
    assert noisy.n_actions_ <= 3 * 6 * 5 + 3


def test_baseline_that_finds_nothing_reports_no_functional_pair():
    stuck = SyntheticCan("stuck", {"lid": LID, "body": BODY}, {("lid", "body")}, {})
    learner = PartBasedLearner(max_checks=2, random_state=0).fit(stuck)
    assert learner.functional_ is None
    assert learner.n_actions_ == 12 * 3 + 2


def test_learner_parameters_are_checked():
    can = thesis_cans()["o1"]
    for params, message in (({"n": 0}, "'n' parameter"), ({"n_min": 1}, "n_min"),
                            ({"settle_tol": -1.0}, "settle_tol"), ({"delta2": 0}, "delta2"),
                            ({"max_checks": 1.5}, "max_checks")):
        with pytest.raises(ValueError, match=message):
            PartBasedLearner(**params).fit(can)
    with pytest.raises(ValueError, match="consistency_tol"):
        TransferLearner(consistency_tol=0).fit(can)
    with pytest.raises(ValueError, match="KnownObject"):
        TransferLearner(database=["o1"]).fit(can)
    assert can.calls == []  # nothing was done to the object
    assert clone(TransferLearner(n=4)).get_params()["n"] == 4


# ---------------------------------------------------------------- Algorithm 5
def test_part_similarity_groups_by_nearest_known_parts_and_flags_novel_ones():
    similarity = PartSimilarity().fit([LID, BODY, HANDLE, LOW_LID], ["lid", "body", "handle",
                                                                    "lid"])
    assert list(similarity.predict([LID, (0.0019, 0.4444, 1.0), HANDLE])) == [
        "lid", "lid", "handle"]
    assert similarity.group(PEDAL) is None  # far from every known part
    assert similarity.distance(LID, BODY) == pytest.approx(np.hypot(2.6, 0.0643))
    with pytest.raises(ValueError, match="X has 2 features, but PartSimilarity is expecting 3"):
        similarity.predict([(1.0, 2.0)])
    with pytest.raises(ValueError, match="3 values each"):
        PartSimilarity().fit([(1.0, 2.0)], ["lid"])
    unweighted = PartSimilarity(weights=None, max_distance=None).fit([LID, PEDAL], ["a", "b"])
    assert list(unweighted.predict([(0.0, 0.4, 1.0), (5.0, 5.0, 5.0)])) == ["a", "b"]
    with pytest.raises(ValueError, match="not fitted"):
        PartSimilarity().predict([LID])


def test_source_ranking_follows_table_5_4():
    goal, cans = OpeningGoal(), thesis_cans()
    known = learned(["o1", "o2"])
    ranked = rank_sources(known, cans["o3"].perceive(), goal)
    assert [c.known.name for c in ranked] == ["o1"]  # o3 has no handle: o2 is not relevant
    assert (ranked[0].rehearsal.part, ranked[0].rehearsal.action) == ("lid", "extend_arm")
    ranked = rank_sources(known, cans["o4"].perceive(), goal)
    assert [c.known.name for c in ranked] == ["o2", "o1"]  # o2 shares all three relations
    assert [c.shared_relations for c in ranked] == [3, 1]
    assert ranked[0].target_part == "handle"
    # o5: o2 and o4 share every relation; the tie goes to the object known first
    ranked = rank_sources(learned(["o1", "o2", "o3", "o4"]), cans["o5"].perceive(), goal)
    assert [c.known.name for c in ranked] == ["o2", "o4", "o1", "o3"]
    assert [c.shared_relations for c in ranked] == [3, 3, 1, 1]
    ranked = rank_sources(learned(["o1", "o3", "o4", "o2"]), cans["o5"].perceive(), goal)
    assert [c.known.name for c in ranked][:2] == ["o4", "o2"]
    assert rank_sources([], cans["o5"].perceive(), goal) == []
    assert fit_similarity([]) is None


# ---------------------------------------------------------------- Algorithm 6
def test_direct_success_o3_after_o1_takes_one_action():
    can = thesis_cans()["o3"]
    learner = TransferLearner(database=learned(["o1"]), random_state=0).fit(can)
    assert (learner.source_, learner.branch_, learner.n_actions_) == ("o1", "direct", 1)
    trial = learner.trials_[0]
    assert (trial.part, trial.action, trial.purpose) == ("lid", "extend_arm", "transfer")
    assert trial.state_after >= 0.1


def test_gradient_steps_when_the_source_needs_less_motion():
    # the source o4 opens 0.13 m at θ ≈ 0.042; o2's handle needs θ >= 0.052 (line 13)
    known = [k for k in learned(["o1", "o2", "o3", "o4"]) if k.name == "o4"]
    learner = TransferLearner(database=known, random_state=0).fit(thesis_cans()["o2"])
    assert (learner.source_, learner.branch_) == ("o4", "gradient")
    thetas = [t.theta for t in learner.trials_]
    assert [t.purpose for t in learner.trials_] == ["transfer", "gradient"]
    assert thetas[1] > thetas[0]
    assert not learner.trials_[0].reached and learner.trials_[1].reached


def test_gradient_step_is_clipped_to_theta_and_stops_at_the_bound():
    source = learned(["o1", "o2"])[1].models[("handle", "lift_up")]
    goal = OpeningGoal()
    step = gradient_step(0.03, source, 0.05, goal, (0.0, 0.1))
    # the missing 0.13 - 0.05 m over ĥ's slope, then over ĝ's slope
    assert step == pytest.approx(0.03 + 0.08 / source.h_slope_ / source.g_slope_)
    assert gradient_step(0.09, source, 0.0, goal, (0.0, 0.1)) == 0.1
    assert gradient_step(0.1, source, 0.0, goal, (0.0, 0.1)) is None


def test_an_inconsistent_action_type_is_found_o5_after_o2():
    known = learned(["o1", "o2"])
    learner = TransferLearner(database=known, random_state=0).fit(thesis_cans()["o5"])
    assert (learner.source_, learner.branch_) == ("o2", "other_action")
    assert (learner.functional_.part, learner.functional_.action) == ("handle", "contract_arm")
    lifts = [t for t in learner.trials_ if t.action == "lift_up"]
    assert lifts and all(t.part_displacement == 0 for t in lifts)
    assert learner.trials_[-1].purpose == "consistency"
    assert learner.n_actions_ < PartBasedLearner(random_state=0).fit(
        thesis_cans()["o5"]).n_actions_


def test_another_part_of_the_source_leads_to_the_goal():
    # looks like o2, but the lid is pushed open and the handle is a dummy
    decoy = SyntheticCan("decoy", {"lid": LOW_LID, "body": BODY, "handle": HANDLE},
                         HANDLE_CAN, {("lid", "extend_arm"): Working(1.2, 0.93)})
    learner = TransferLearner(database=learned(["o1", "o2"])[1:], random_state=0).fit(decoy)
    assert (learner.source_, learner.branch_) == ("o2", "other_part")
    assert learner.similar_parts_[:2] == ["handle", "lid"]
    assert learner.functional_.part == "lid"
    consistency = [t for t in learner.trials_ if t.purpose == "consistency"]
    assert {t.action for t in consistency if t.part == "handle"} == set(decoy.actions) - {
        "lift_up"}


def test_novel_parts_fall_back_to_algorithm_4():
    pedal_can = SyntheticCan("pedal", {"lid": LID, "body": BODY, "pedal": PEDAL},
                             {("lid", "body"), ("lid", "pedal"), ("body", "pedal")},
                             {("pedal", "sweep_down"): Working(0.5, 3.0)})
    learner = TransferLearner(database=learned(["o1"]), random_state=0).fit(pedal_can)
    assert (learner.source_, learner.branch_) == ("o1", "fallback")
    assert learner.similar_parts_ == ["lid", "body"]
    assert learner.functional_.part == "pedal" and learner.functional_.action == "sweep_down"
    baseline = PartBasedLearner(random_state=0).fit(pedal_can)
    assert learner.n_actions_ < baseline.n_actions_


def test_the_fallback_explores_every_novel_pair_first_without_stop_at_goal():
    """Algorithm 6's line 31 is Algorithm 4: as printed it explores every pair of the novel
    part (6 action types, the working one n = 5 times, the others until dead at 3) and then
    acts with 5.11/5.12; stop_at_goal ends it at the first action that opens the can."""
    pedal_can = SyntheticCan("pedal", {"lid": LID, "body": BODY, "pedal": PEDAL},
                             {("lid", "body"), ("lid", "pedal"), ("body", "pedal")},
                             {("pedal", "sweep_down"): Working(0.5, 3.0)})
    runs = {stop: TransferLearner(database=learned(["o1"]), stop_at_goal=stop,
                                  random_state=0).fit(pedal_can)
            for stop in (True, False)}
    assert runs[True].branch_ == runs[False].branch_ == "fallback"
    on_pedal = {stop: [t for t in run.trials_ if t.part == "pedal"]
                for stop, run in runs.items()}
    assert on_pedal[True][-1].reached and len(on_pedal[True]) < len(on_pedal[False])
    explored = {t.action for t in on_pedal[False] if t.purpose == "explore"}
    assert explored == set(pedal_can.actions) and on_pedal[False][-1].purpose == "exploit"
    assert runs[False].functional_.part == "pedal"


def test_other_parts_false_stops_after_the_source_s_functional_part():
    """Lines 2-23 only: o1's push on the lid, then one try of every other action there; the
    body (o1's other part) and the novel pedal are left to the caller."""
    pedal_can = SyntheticCan("pedal", {"lid": LID, "body": BODY, "pedal": PEDAL},
                             {("lid", "body"), ("lid", "pedal"), ("body", "pedal")},
                             {("pedal", "sweep_down"): Working(0.5, 3.0)})
    learner = TransferLearner(database=learned(["o1"]), other_parts=False,
                              random_state=0).fit(pedal_can)
    assert (learner.source_, learner.branch_, learner.functional_) == ("o1", "failed", None)
    assert learner.similar_parts_ == ["lid"]
    assert {t.part for t in learner.trials_} == {"lid"}
    assert {t.action for t in learner.trials_} == set(pedal_can.actions)
    whole = TransferLearner(database=learned(["o1"]), random_state=0).fit(pedal_can)
    assert [t.theta for t in whole.trials_[:len(learner.trials_)]] == [
        t.theta for t in learner.trials_]  # the same start as Algorithm 6 in full


def test_without_a_source_transfer_is_algorithm_4():
    can = thesis_cans()["o1"]
    learner = TransferLearner(database=learned(["o2"]), random_state=5).fit(can)
    baseline = PartBasedLearner(random_state=5).fit(thesis_cans()["o1"])
    assert (learner.source_, learner.branch_) == (None, "no_source")
    assert learner.n_actions_ == baseline.n_actions_
    assert [t.theta for t in learner.trials_] == [t.theta for t in baseline.trials_]


def test_transfer_that_finds_nothing_says_so():
    stuck = SyntheticCan("stuck", {"lid": LID, "body": BODY}, {("lid", "body")}, {})
    learner = TransferLearner(database=learned(["o1"]), random_state=0).fit(stuck)
    assert (learner.branch_, learner.functional_) == ("failed", None)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_table_5_4_on_the_synthetic_cans(seed: int):
    cans, known, rows = thesis_cans(noise=0.002, seed=seed), [], {}
    for name, can in cans.items():
        baseline = PartBasedLearner(random_state=seed).fit(thesis_cans(0.002, seed)[name])
        learner = TransferLearner(database=list(known), random_state=seed).fit(can)
        known.append(KnownObject.learned(name, learner))
        rows[name] = (baseline.n_actions_, learner.n_actions_, learner.source_)
        assert (learner.functional_.part, learner.functional_.action) in can.working
    assert [rows[o][2] for o in rows] == [None, "o1", "o1", "o2", "o2"]
    assert all(rows[o][1] < rows[o][0] for o in ("o2", "o3", "o4", "o5"))
    assert rows["o3"][1] <= 3

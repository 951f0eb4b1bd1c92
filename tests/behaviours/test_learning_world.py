"""``learn_in_world`` on the simulated o1 can (real MuJoCo): the lid is pushed open, not swept."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from behaviours.learners.effect_models import ModelStore
from behaviours.learning import (
    AffordanceBehaviours,
    AffordanceEvidence,
    LearningModeUnavailable,
    learn_in_world,
    verify_effect,
)
from behaviours.perception import Observation
from behaviours.skills import SkillError, perform_skill
from sim.world import GarbageWorld

DELTA = 0.1
"""Thesis §6.4.1: the lid counts as opened beyond 0.1 m."""


@pytest.fixture(scope="module")
def world() -> GarbageWorld:
    w = GarbageWorld("o1", seed=0)
    yield w
    w.close()


def test_extend_arm_on_the_lid_is_learned_and_verified(world: GarbageWorld, tmp_path: Path) -> None:
    world.reset("o1", seed=0)
    store = ModelStore(tmp_path / "effects.json")
    result = learn_in_world(
        world, part="lid", action="extend_arm", delta=DELTA, n_max=8, random_state=1, store=store
    )
    assert result.evidence == AffordanceEvidence("lid", "extend_arm", "opened", 0, 0, 0.3)
    assert result.e_max >= DELTA and result.theta_max == 0.1
    assert 4 <= result.samples <= 8
    assert result.model.effect_.max() >= DELTA  # the samples really opened the lid
    assert world.opening() == pytest.approx(0.0, abs=1e-3)  # the can is left as found
    # rule 6.12 goes on with θ_max (6.13): the observed effect verifies the affordance
    observed = perform_skill(world, "extend_arm", "lid", result.theta_max).effect
    verified = verify_effect(
        obj="lid", action="extend_arm", effect_name="opened", observed_effect=observed, delta=DELTA
    )
    assert verified == AffordanceEvidence("lid", "extend_arm", "opened", 1, 1, 1)
    stored = ModelStore(tmp_path / "effects.json").get(("o1", "lid", "extend_arm"))
    assert stored is not None and stored.model.n_samples_ == result.samples


def test_sweeping_the_lid_is_predicted_ineffective(world: GarbageWorld) -> None:
    world.reset("o1", seed=0)
    result = learn_in_world(
        world, part="lid", action="sweep_left", delta=DELTA, n_max=6, random_state=2
    )
    assert result.evidence == AffordanceEvidence("lid", "sweep_left", "opened", 0, 0, 0.05)
    assert result.e_max < DELTA


def test_refusals_leave_the_world_untouched(world: GarbageWorld) -> None:
    world.reset("o1", seed=0)
    world.set_opening(0.05)
    before = world.state()
    with pytest.raises(SkillError, match="no part 'handle'"):
        learn_in_world(world, part="handle", action="lift_up", delta=DELTA, n_max=5, random_state=0)
    with pytest.raises(ValueError, match="unknown learning mode 'curious'"):
        learn_in_world(
            world,
            part="lid",
            action="extend_arm",
            mode="curious",
            delta=DELTA,
            n_max=5,
            random_state=0,
        )
    assert world.state() == before


def test_active_learning_finds_the_push_and_rejects_the_sweep(world: GarbageWorld) -> None:
    """Algorithm 3 over θ: at least N + 1 = 21 tries, e_max from the forward model (6.8)."""
    world.reset("o1", seed=0)
    push = learn_in_world(world, part="lid", action="extend_arm", mode="active", delta=DELTA,
                          n_max=5, random_state=0)
    assert push.evidence == AffordanceEvidence("lid", "extend_arm", "opened", 0, 0, 0.3)
    assert push.e_max >= DELTA and push.theta_max > 0.05
    assert 21 <= push.samples <= 100 and push.settled
    assert push.model.n_samples_ == push.samples  # the store keeps the line through them
    sweep = learn_in_world(world, part="lid", action="sweep_left", mode="active", delta=DELTA,
                           n_max=5, random_state=0, active_n_max=30)
    assert sweep.evidence.rel == 0.05 and sweep.e_max < DELTA and sweep.samples <= 30
    assert world.opening() < 1e-3  # every try started from, and ended at, the closed can


class DoubledOpening:
    """Reads the true opening at twice its size, to trace where the effects come from."""

    def observe(self, world: GarbageWorld) -> Observation:
        return Observation(parts={}, above=(), opening=2 * world.opening())


def test_effects_come_from_the_given_perception(world: GarbageWorld) -> None:
    options = dict(part="lid", action="extend_arm", delta=DELTA, n_max=4, random_state=3)
    world.reset("o1", seed=0)
    truth = learn_in_world(world, **options)
    world.reset("o1", seed=0)
    seen = learn_in_world(world, perception=DoubledOpening(), **options)
    assert np.array_equal(seen.model.theta_, truth.model.theta_)
    assert seen.model.effect_ == pytest.approx(2 * truth.model.effect_, abs=1e-6)


def test_default_n_min_does_not_settle_on_three_lucky_samples(world: GarbageWorld) -> None:
    """o3, seed 8: three short pushes look settled at n_min = 3 and miss the working action."""
    options = dict(part="lid", action="extend_arm", delta=DELTA, n_max=10, random_state=8)
    world.reset("o3", seed=0)
    hasty = learn_in_world(world, n_min=3, **options)
    world.reset("o3", seed=0)
    default = learn_in_world(world, **options)
    assert hasty.samples == 3 and hasty.evidence.rel == 0.05
    assert default.samples >= 4 and default.evidence.rel == 0.3


def test_behaviours_learn_apply_and_carry_theta_to_another_can(
    world: GarbageWorld, tmp_path: Path
) -> None:
    """Experiment 1 then 2 in miniature: learned on o1, the lid push fails on o2's lid."""
    world.reset("o1", seed=0)
    robot = AffordanceBehaviours(world, store=ModelStore(tmp_path / "effects.json"), seed=4)
    assert robot.theta_for("lid", "extend_arm") == 0.1  # nothing learned: the largest θ
    learned = robot.learn("lid", "extend_arm")
    assert learned.evidence.rel == 0.3
    used = robot.apply("lid", "extend_arm")
    assert used.theta == learned.theta_max
    assert used.evidence == AffordanceEvidence("lid", "extend_arm", "opened", 1, 1, 1)
    assert world.opening() >= DELTA

    world.reset("o2", seed=0)
    later = AffordanceBehaviours(world, store=ModelStore(tmp_path / "effects.json"))
    assert later.theta_for("lid", "extend_arm") == learned.theta_max  # o1's model
    failed = later.apply("lid", "extend_arm")
    assert failed.evidence == AffordanceEvidence("lid", "extend_arm", "opened", 1, 0, 0)
    with pytest.raises(LearningModeUnavailable, match="whole-object behaviour"):
        later.learn("handle", "lift_up", mode="transfer")


def test_behaviours_are_reproducible_under_a_seed(world: GarbageWorld) -> None:
    runs = []
    for _ in range(2):
        world.reset("o1", seed=0)
        robot = AffordanceBehaviours(world, seed=9, n_max=5)
        runs.append(
            [robot.learn("lid", a).model.theta_.tolist() for a in ("extend_arm", "lift_up")]
        )
    assert runs[0] == runs[1]
    assert runs[0][0] != runs[0][1]  # one generator feeds successive explorations

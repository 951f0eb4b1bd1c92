"""The chapter-5 learners on the simulated cans (real MuJoCo): Table 5.4's o1 -> o3 transfer."""

from __future__ import annotations

import pytest

from behaviours.learners.baseline import PartBasedLearner
from behaviours.learners.known_objects import KnownObject
from behaviours.learners.transfer import TransferLearner
from behaviours.part_learning import CanUnderTest
from behaviours.perception import make_perception
from sim.world import GarbageWorld


@pytest.fixture(scope="module")
def world() -> GarbageWorld:
    made = GarbageWorld("o1", seed=0)
    yield made
    made.close()


def test_the_can_under_test_perceives_parts_and_resets_before_each_action(world):
    world.reset("o2", seed=0)
    can = CanUnderTest(world, make_perception("truth"))
    view = can.perceive()
    assert set(view.parts) == {"body", "lid", "handle"}
    assert view.above == {("lid", "body"), ("lid", "handle"), ("handle", "body")}
    assert view.state == pytest.approx(0.0, abs=1e-3)
    lifted = can.perform("handle", "lift_up", 0.08)
    assert lifted.part_displacement > 0.03 and lifted.effect > 0.1
    again = can.perform("handle", "lift_up", 0.08)  # from the closed can again, same result
    assert again.state_before == pytest.approx(0.0, abs=1e-3)
    assert again.effect == pytest.approx(lifted.effect, abs=0.01)
    pushed = can.perform("lid", "extend_arm", 0.1)
    assert pushed.part_displacement < 0.005 and pushed.effect < 0.005
    assert can.performed == 3
    can.restore()
    assert world.opening() == pytest.approx(0.0, abs=1e-3)


@pytest.mark.parametrize("mode", ["truth", "camera"])
def test_o3_after_o1_needs_at_most_three_actions(world, mode):
    perception = make_perception(mode)
    world.reset("o1", seed=0)
    first = PartBasedLearner(random_state=0).fit(CanUnderTest(world, perception))
    assert (first.functional_.part, first.functional_.action) == ("lid", "extend_arm")
    assert first.n_actions_ == 2 * 6 * 3 - 3 + 5 + 1  # dead pairs stop after three samples
    world.reset("o3", seed=0)
    target = CanUnderTest(world, perception)
    learner = TransferLearner(database=[KnownObject.learned("o1", first)],
                              random_state=0).fit(target)
    assert learner.source_ == "o1"
    assert (learner.functional_.part, learner.functional_.action) == ("lid", "extend_arm")
    assert learner.n_actions_ == target.performed <= 3

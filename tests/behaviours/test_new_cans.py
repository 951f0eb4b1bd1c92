"""The two mechanisms beyond the thesis's cans, in MuJoCo physics: a sliding lid and a pedal."""

from __future__ import annotations

import pytest

from behaviours.perception import CameraPerception, TruthPerception
from behaviours.skills import THETA_BOUNDS, perform_skill
from sim.canfile import find_can
from sim.world import GarbageWorld


@pytest.fixture(scope="module")
def world() -> GarbageWorld:
    made = GarbageWorld(find_can("slide"), seed=0)
    yield made
    made.close()


@pytest.mark.parametrize(("can", "part", "action"), [("slide", "lid", "sweep_left"),
                                                     ("pedal", "pedal", "sweep_down")])
def test_only_the_functional_pair_opens_the_new_cans(world, can, part, action):
    spec = find_can(can)
    assert spec.functional == (part, action)
    world.reset(spec, seed=0)
    assert world.can == can and world.parts == spec.parts
    assert world.opening() == pytest.approx(0.0, abs=1e-3)
    opened = perform_skill(world, action, part, 0.1)
    assert opened.effect >= 0.1 and opened.part_displacement > 0.02
    for other_part in spec.parts:
        for other in THETA_BOUNDS:
            if (other_part, other) == (part, action):
                continue
            world.reset(spec, seed=0)
            result = perform_skill(world, other, other_part, 0.1)
            assert result.effect < 0.01, (other_part, other, result)


def test_the_sliding_lid_opens_with_the_sweep_and_stays(world):
    world.reset(find_can("slide"), seed=0)
    small = perform_skill(world, "sweep_left", "lid", 0.05)
    assert 0.04 < small.effect < 0.08
    bigger = perform_skill(world, "sweep_left", "lid", 0.05)  # from where it was left
    assert bigger.opening_after > small.opening_after + 0.03


@pytest.mark.parametrize("can", ["slide", "pedal"])
def test_camera_measures_the_new_cans_openings(world, can):
    world.reset(find_can(can), seed=0)
    camera, truth = CameraPerception(), TruthPerception()
    seen = camera.observe(world)
    assert set(seen.parts) == set(world.parts)
    assert seen.opening == pytest.approx(0.0, abs=0.005)
    for width in (0.03, 0.06, 0.1, 0.14):
        world.set_opening(width)
        assert world.opening() == pytest.approx(width, abs=1e-4)
        assert camera.observe(world).opening == pytest.approx(width, abs=0.015)
        assert truth.observe(world).opening == pytest.approx(width, abs=1e-4)

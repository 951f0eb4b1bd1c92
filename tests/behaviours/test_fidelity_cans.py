"""Cans as the thesis measured them (Table 5.3): non-functional parts that move a little, in
the can files; sensor noise on what chapter 5 measures."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from behaviours.perception import NoisyPerception, make_perception
from behaviours.skills import perform_skill
from sim.canfile import CanFileError, find_can, parse_can
from sim.world import GarbageWorld
from tests.sim.test_canfile import GOOD

MOVING = {"o2": [("handle", "extend_arm"), ("handle", "contract_arm")],
          "o3": [("body", "extend_arm")],
          "o5": [("handle", "sweep_left"), ("handle", "lift_up"), ("lid", "extend_arm")]}
"""Table 5.3's non-functional pairs that moved their part."""


@pytest.mark.parametrize("can", sorted(MOVING))
def test_table_5_3s_non_functional_parts_move_without_opening_the_can(can):
    world = GarbageWorld(find_can(can), seed=0)
    try:
        for part, action in MOVING[can]:
            world.set_opening(0.0)
            result = perform_skill(world, action, part, 0.08)
            assert result.part_displacement >= 0.015, (part, action)
            assert abs(result.effect) < 0.002, (part, action)  # nothing opens
            world.set_opening(0.0)  # and set_opening puts the part back
            assert all(abs(world.data.joint(name).qpos[0]) < 1e-12
                       for name in world.spec.give_joints)
        part, action = world.spec.functional  # the functional pair still opens the can
        assert perform_skill(world, action, part, 0.08).effect > 0.1
    finally:
        world.close()


def test_a_can_file_gives_parts_play_and_a_slide():
    spec = parse_can(GOOD + "give:\n  handle:\n    axes: [x, z]\n    travel: 0.02\n"
                     "  can:\n    slide: 0.03\n")
    assert (spec.handle_play, spec.play_travel, spec.can_slide) == (("x", "z"), 0.02, 0.03)
    assert spec.give_joints == ("can_slide", "handle_play_x", "handle_play_z")
    assert find_can("o1").give_joints == ()


@pytest.mark.parametrize(("give", "where", "message"), [
    ("give:\n  handle:\n    axes: [w]\n    travel: 0.02\n", "16:12", "'w' is not one of"),
    ("give:\n  can:\n    slide: 0.5\n", "16:12", "0.5 is greater than the maximum"),
    ("give:\n  handle:\n    axes: [x]\n", "16:5", "'travel' is missing"),
])
def test_a_broken_give_section_is_a_located_error(give, where, message):
    with pytest.raises(CanFileError, match=f"mine.yaml:{where}: .*{message}"):
        parse_can(GOOD + give, "mine.yaml")


def test_a_push_lid_can_has_no_handle_to_give_play_to(tmp_path: Path):
    text = Path(find_can("o1").source).read_text()
    with pytest.raises(CanFileError, match="o1.yaml:.*a push_lid can has no handle"):
        parse_can(text + "give:\n  handle:\n    axes: [x]\n    travel: 0.02\n", "o1.yaml")


def test_sensor_noise_perturbs_the_opening_and_part_positions_reproducibly():
    world = GarbageWorld(find_can("o2"), seed=0)
    try:
        exact = make_perception("truth")
        assert make_perception("truth", sigma=0.0).__class__ is exact.__class__
        seen = [NoisyPerception(exact, 0.01, [4, 2]).observe(world) for _ in range(2)]
        assert seen[0] == seen[1]  # the same stream, the same noise
        draws = NoisyPerception(exact, 0.01, 7)
        openings = [draws.observe(world).opening for _ in range(400)]
        truth = exact.observe(world)
        assert np.mean(openings) == pytest.approx(truth.opening, abs=0.002)
        assert np.std(openings) == pytest.approx(0.01, rel=0.15)
        moved = draws.observe(world).parts["handle"].centre
        shift = np.hypot(*np.subtract(moved, truth.parts["handle"].centre)) * truth.scale
        assert 0 < shift < 0.05
        with pytest.raises(ValueError, match="sigma must be a finite number >= 0"):
            NoisyPerception(exact, -1.0)
    finally:
        world.close()

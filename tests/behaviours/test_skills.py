"""Motor skills on the five cans (real MuJoCo): Table 5.3-like effects, refusals, the ball."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from behaviours.skills import (
    ACTION_TYPES,
    DropResult,
    SkillError,
    ball_within_reach,
    drop_ball,
    grasp_ball,
    perform_skill,
)
from sim.canfile import find_can, parse_can
from sim.scene import WALL
from sim.world import CANS, GarbageWorld
from tests.can_files import HIGH_STEEP_HANDLE

GOAL = 0.1
"""Thesis goal width (m)."""
THETAS = (0.02, 0.04, 0.06, 0.08, 0.1)


@pytest.fixture(scope="module")
def world() -> GarbageWorld:
    """One world reused (and reset) across this module's tests."""
    w = GarbageWorld("o1", seed=0)
    yield w
    w.close()


def _opening_after(world: GarbageWorld, can: str, part: str, action: str, theta: float) -> float:
    """Opening left by one skill on a freshly reset can."""
    world.reset(can, seed=0)
    return perform_skill(world, action, part, theta).opening_after


@pytest.mark.parametrize("can", sorted(CANS))
def test_functional_pair_opens_the_can_and_grows_with_theta(world: GarbageWorld, can: str) -> None:
    """The functional part/action passes the goal at some θ <= 0.1 and pushes further open more."""
    part, action = CANS[can].functional
    openings = [_opening_after(world, can, part, action, t) for t in THETAS]
    assert max(openings) > GOAL, openings
    assert all(b >= a - 2e-3 for a, b in zip(openings, openings[1:], strict=False)), openings
    assert openings[0] < GOAL, "the smallest move should not already open the can"


@pytest.mark.parametrize("can", sorted(CANS))
def test_every_other_pair_stays_below_the_goal_at_max_theta(world: GarbageWorld, can: str) -> None:
    """Non-functional part/action pairs leave the can (nearly) closed even at θ = 0.1."""
    functional = CANS[can].functional
    for part in CANS[can].parts:
        for action in ACTION_TYPES:
            if (part, action) == functional:
                continue
            opening = _opening_after(world, can, part, action, 0.1)
            assert opening < GOAL, f"{can}: {action} on {part} opened {opening:.3f} m"


def _theta_to_open(world: GarbageWorld, can: str) -> float:
    """Smallest θ of a 1 cm grid whose functional skill reaches the goal width."""
    part, action = CANS[can].functional
    for theta in np.arange(0.01, 0.101, 0.01):
        if _opening_after(world, can, part, action, float(theta)) > GOAL:
            return float(theta)
    raise AssertionError(f"{can} never opens")


def test_similar_cans_need_different_parameters(world: GarbageWorld) -> None:
    """o3 is pushed like o1 but further; o4 is lifted like o2 but by a different amount."""
    assert _theta_to_open(world, "o3") - _theta_to_open(world, "o1") >= 0.015
    assert abs(_theta_to_open(world, "o4") - _theta_to_open(world, "o2")) >= 0.01


def test_o5_handle_is_pulled_not_lifted(world: GarbageWorld) -> None:
    """Pulling o5's handle back opens it; lifting it does nothing."""
    assert _opening_after(world, "o5", "handle", "contract_arm", 0.1) > GOAL
    assert _opening_after(world, "o5", "handle", "lift_up", 0.1) < 0.01


def test_result_reports_part_and_object_effects(world: GarbageWorld) -> None:
    """eq. 5.15 displacement of the part and eq. 5.3 change of opening, both consistent."""
    world.reset("o2", seed=0)
    r = perform_skill(world, "lift_up", "handle", np.float32(0.06))  # any real number type
    assert (r.action, r.part) == ("lift_up", "handle")
    assert type(r.theta) is float and r.theta == pytest.approx(0.06)
    assert r.effect == pytest.approx(r.opening_after - r.opening_before)
    assert r.opening_before < 1e-3 and r.effect > 0.05
    assert 0.04 < r.part_displacement < 0.06  # the handle rose by about θ minus the approach gap
    body = perform_skill(world, "extend_arm", "body", 0.1)
    assert body.part_displacement < 1e-3 and abs(body.effect) < 2e-3


def test_opening_stays_put_after_the_skill(world: GarbageWorld) -> None:
    """The hand has gone home; the lid does not fall back over simulated seconds."""
    for can in ("o1", "o4"):
        world.reset(can, seed=0)
        part, action = CANS[can].functional
        after = perform_skill(world, action, part, 0.08).opening_after
        world.step(2500)
        assert world.opening() == pytest.approx(after, abs=2e-3), can


def test_skills_are_deterministic_under_a_seed(world: GarbageWorld) -> None:
    """The same sequence from the same seed gives identical results and states."""
    def run() -> tuple:
        world.reset("o3", seed=5)
        results = (perform_skill(world, "extend_arm", "lid", 0.05),
                   perform_skill(world, "sweep_left", "body", 0.03))
        return results, world.state()

    assert run() == run()


@pytest.mark.parametrize("args, message", [
    (("lift_up", "handle", 0.05), "no part 'handle'.*body, lid"),
    (("extend_arm", "lid", 0.0), "out of bounds"),
    (("extend_arm", "lid", 0.1001), "out of bounds"),
    (("extend_arm", "lid", -0.02), "out of bounds"),
    (("extend_arm", "lid", float("nan")), "out of bounds"),
    (("extend_arm", "lid", True), "must be a number"),
    (("extend_arm", "lid", "far"), "must be a number"),
    (("push", "lid", 0.05), "unknown action 'push'"),
])
def test_refused_requests_leave_the_world_unchanged(world: GarbageWorld, args, message) -> None:
    """SkillError (a ValueError) names the problem; nothing was simulated."""
    world.reset("o1", seed=0)
    world.move_arm(0.02, -0.01, 0.0)
    before, steps, qpos = world.state(), world.steps, world.data.qpos.copy()
    with pytest.raises(SkillError, match=message):
        perform_skill(world, *args)
    assert world.state() == before and world.steps == steps
    assert np.array_equal(world.data.qpos, qpos)


@pytest.mark.parametrize("can", ["o1", "o5", "slide", "pedal"])
def test_ball_goes_in_only_when_the_can_is_open(world: GarbageWorld, can: str) -> None:
    """Dropped at a closed lid the ball is stopped at the can and stays outside; after opening
    the can it falls in, whether the lid lifts (o1, o5, pedal) or slides aside (slide)."""
    spec = find_can(can)
    world.reset(spec, seed=0)
    assert grasp_ball(world) and world.state().holding_ball
    assert drop_ball(world) == DropResult(landed=False, blocked=True)
    s = world.state()
    assert not s.holding_ball and not s.ball_in_can
    assert ball_within_reach(world)  # it can be picked up again

    world.reset(spec, seed=0)
    assert grasp_ball(world)
    part, action = spec.functional
    assert perform_skill(world, action, part, 0.1).opening_after > GOAL
    assert drop_ball(world) == DropResult(landed=True, blocked=False)
    s = world.state()
    assert s.ball_in_can and not s.holding_ball
    assert not ball_within_reach(world)


def test_the_ball_is_carried_over_a_handle_lifted_above_the_rim(world: GarbageWorld) -> None:
    """A handle high on the front, lifted the whole 0.1 m, stands over the rim where the
    ball goes in: the ball is carried over it and lands (it was stopped there, issue 32)."""
    world.reset(parse_can(HIGH_STEEP_HANDLE, "high_lift.yaml"), seed=0)
    assert grasp_ball(world)
    assert perform_skill(world, "lift_up", "handle", 0.1).opening_after > GOAL
    handle = world.model.geom("marker_handle").id
    top = world.data.geom_xpos[handle][2] + world.model.geom_size[handle][2]
    assert top > world.spec.rim + 0.02  # the bar stands in the ball's way over the rim
    assert drop_ball(world) == DropResult(landed=True, blocked=False)


def test_a_sliding_lid_uncovers_one_side_of_the_rim(world: GarbageWorld) -> None:
    """The ball is carried in over the uncovered side: the middle of the free stretch."""
    world.reset(find_can("slide"), seed=0)
    assert world.free_rim_y() == 0.0
    world.set_opening(0.1)
    inner = world.spec.width / 2 - WALL
    # the lid slid 0.1 m to the left: the free stretch runs from the right wall to 0.1 m
    # past it, less the wall the lid's edge had to clear first
    assert world.free_rim_y() == pytest.approx(-(inner - (0.1 - WALL) / 2), abs=1e-3)
    world.reset("o1", seed=0)
    world.set_opening(0.1)
    assert world.free_rim_y() == 0.0  # a lid that lifts leaves the middle open


def test_drop_without_ball_does_nothing(world: GarbageWorld) -> None:
    """No ball in hand: drop_ball reports neither a landing nor a block and the arm does not
    move."""
    world.reset("o2", seed=0)
    steps = world.steps
    assert drop_ball(world) == DropResult(landed=False, blocked=False)
    assert world.steps == steps


def test_a_held_ball_does_not_change_what_skills_do(world: GarbageWorld) -> None:
    """Carrying the ball (tucked in the hand) leaves the affordance effects as they were."""
    world.reset("o1", seed=0)
    free = perform_skill(world, "extend_arm", "lid", 0.04)
    world.reset("o1", seed=0)
    assert grasp_ball(world)
    held = perform_skill(world, "extend_arm", "lid", 0.04)
    assert dataclasses.astuple(held) == pytest.approx(dataclasses.astuple(free), abs=3e-3)


@pytest.mark.parametrize("can, part, action", [
    ("o1", "lid", "sweep_down"), ("o3", "lid", "sweep_down"),
    ("o2", "handle", "sweep_down"), ("o5", "handle", "extend_arm"),
])
def test_an_open_can_can_be_closed_again(world: GarbageWorld, can: str, part: str,
                                         action: str) -> None:
    """Pressing a push lid down, pushing a lift handle down or a pull handle in closes the can."""
    world.reset(can, seed=0)
    fpart, faction = CANS[can].functional
    assert perform_skill(world, faction, fpart, 0.08).opening_after > GOAL
    assert perform_skill(world, action, part, 0.1).opening_after < 0.01

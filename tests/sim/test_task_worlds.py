"""The chapter-3 and Appendix-A worlds: what the physics does to boxes, foams, lift and head."""

from __future__ import annotations

import numpy as np
import pytest

from sim.navigation import D_WALK, DESTINATION_X, START_LANE, NavigationWorld
from sim.search import BOUNDARY, HEAD_STEP, SearchWorld
from sim.stacking import TABLE_TOP, StackingWorld


@pytest.fixture(scope="module")
def nav():
    world = NavigationWorld()
    yield world
    world.close()


@pytest.fixture(scope="module")
def stacking():
    world = StackingWorld()
    yield world
    world.close()


def _box(world: NavigationWorld, name: str) -> np.ndarray:
    return np.array(world.box_state(name).pos)


def test_the_fixed_box_really_does_not_move_when_pushed(nav):
    nav.reset(exchanged=True)  # the fixed box stands in front of the robot
    before, robot = _box(nav, "fixed"), nav.robot_pos
    for _ in range(3):
        assert nav.push() is False
    assert np.linalg.norm(_box(nav, "fixed") - before) < 1e-3
    assert nav.robot_pos[0] - robot[0] < 0.03  # only the 2 cm gap was closed


def test_the_movable_box_slides_a_step_per_push_and_the_robot_reaches_the_destination(nav):
    nav.reset(exchanged=False)
    start = _box(nav, "movable")
    assert nav.push() is True
    assert 0.11 < _box(nav, "movable")[0] - start[0] < D_WALK + 0.01
    nav.push()
    assert nav.distance_to_destination() > 0.05
    nav.push()
    assert nav.distance_to_destination() < 0.05 and nav.robot_pos[0] > DESTINATION_X - 0.05


def test_walking_ahead_into_a_box_stops_at_it_without_pushing(nav):
    nav.reset(exchanged=False)
    box, x = _box(nav, "movable"), nav.robot_pos[0]
    assert nav.walk("ahead") is False
    assert nav.robot_pos[0] - x < 0.03
    assert np.linalg.norm(_box(nav, "movable") - box) < 0.01


def test_walking_sideways_changes_lane_and_off_the_edge_the_robot_falls(nav):
    nav.reset(exchanged=False)
    assert nav.walk("left") is True
    assert nav.robot_pos[1] == pytest.approx(START_LANE + D_WALK, abs=3e-3)
    assert not nav.fallen
    nav.reset()
    nav.walk("right")  # the robot starts in the right-most lane
    assert nav.fallen and nav.robot_pos[2] < TABLE_TOP - 0.05


def test_exchanging_swaps_the_boxes_and_unknown_directions_are_refused(nav):
    nav.reset(exchanged=False)
    assert nav.box_state("fixed").pos[1] > 0 > nav.box_state("movable").pos[1]
    nav.reset(exchanged=True)
    assert nav.box_state("fixed").pos[1] < 0 < nav.box_state("movable").pos[1]
    with pytest.raises(ValueError, match="unknown direction 'back'"):
        nav.walk("back")


def test_a_standing_push_passes_over_the_low_foam_and_a_squatting_push_moves_it(stacking):
    stacking.reset()
    assert stacking.choose("foam")
    foam = stacking.state().in_front
    before = stacking.data.body(foam).xpos.copy()
    stacking.push("stand")
    assert np.linalg.norm(stacking.data.body(foam).xpos - before) < 1e-3
    stacking.push("squat")
    state = stacking.state()
    assert state.in_front is None and state.stacked_objects == (foam,)
    assert state.stack_height == pytest.approx(0.12, abs=0.005) and not state.stacked


def test_three_foams_or_the_high_box_make_a_stack_as_high_as_the_table(stacking):
    stacking.reset()
    for _ in range(3):
        stacking.choose("foam")
        stacking.push("squat")
    state = stacking.state()
    assert len(state.stacked_objects) == 3 and state.stacked
    assert stacking.stack_top() == pytest.approx(TABLE_TOP, abs=0.015)
    stacking.reset()
    stacking.choose("box")
    stacking.push("stand")
    state = stacking.state()
    assert state.stacked_objects == ("box",) and state.stacked


def test_choosing_again_gives_the_standing_object_back(stacking):
    stacking.reset()
    stacking.choose("foam")
    stacking.choose("box")
    assert stacking.state().in_front == "box"
    assert stacking.data.body("foam1").xpos[2] < TABLE_TOP  # back with the operator
    with pytest.raises(ValueError, match="unknown object kind 'cup'"):
        stacking.choose("cup")
    with pytest.raises(ValueError, match="unknown pose 'kneel'"):
        stacking.push("kneel")


def test_the_head_turns_a_tenth_of_a_radian_and_resets_past_the_boundary():
    world = SearchWorld()
    try:
        assert world.look("left")
        assert world.head == pytest.approx((HEAD_STEP, 0.0), abs=3e-3)
        world.look("down")
        assert world.head == pytest.approx((HEAD_STEP, HEAD_STEP), abs=3e-3)
        world.rest()
        for _ in range(round(BOUNDARY / HEAD_STEP)):
            assert world.look("up")
        assert world.look("up") is False
        assert world.head == pytest.approx((0.0, 0.0), abs=3e-3)
        with pytest.raises(ValueError, match="unknown head move 'spin'"):
            world.look("spin")
        with pytest.raises(ValueError, match="unknown place 'attic'"):
            world.place_target("attic")
    finally:
        world.close()

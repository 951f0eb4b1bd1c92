"""The 8-bit object state (eqs. 3.11-3.13) and the 9-bit search grid: encoding, camera vs truth."""

from __future__ import annotations

from collections import deque

import numpy as np
import pytest

from behaviours.blob_grid import centre_seen, grid_bits, make_grid_perception
from behaviours.object_state import (
    ENCODINGS,
    ObjectState,
    SeenMarker,
    encode,
    height_above_table,
    make_object_perception,
    push_effect,
)
from sim.navigation import NavigationWorld
from sim.search import BOUNDARY, HEAD_STEP, SearchWorld
from sim.stacking import StackingWorld

NAV = ENCODINGS["navigation"]


def test_eq_3_11_height_is_camera_height_over_table_less_the_drop_to_the_marker():
    assert height_above_table(marker_z=0.62, camera_z=0.85, table_top=0.40) == pytest.approx(0.22)
    assert height_above_table(marker_z=0.52, camera_z=0.85, table_top=0.40) == pytest.approx(0.12)


def test_the_object_in_front_gives_height_colour_and_location_bits():
    high_blue = SeenMarker("blue", (0.245, -0.15, 0.62), 0.22)
    low_green = SeenMarker("green", (0.40, 0.15, 0.52), 0.12)
    state = encode([high_blue, low_green], np.array([0.10, -0.225, 0.4]), NAV)
    assert state.bits == "1001" + "0001" and state.front == high_blue
    # in the left lane the low green one is in front, two rows further on, in the left bin
    state = encode([high_blue, low_green], np.array([0.10, 0.225, 0.4]), NAV)
    assert state.object_bits == "0010" and state.location_bits == "0110"
    # nothing within reach: o = 0000 and the spot ahead of the robot
    assert encode([], np.array([0.10, -0.075, 0.4]), NAV).bits == "0000" + "0001"


def test_push_effect_is_displacement_thresholded_and_a_vanished_object_moved():
    box = SeenMarker("red", (0.245, -0.15, 0.62), 0.22)
    before = ObjectState("11000001", box, (box,))
    nudged = SeenMarker("red", (0.265, -0.15, 0.62), 0.22)
    assert push_effect(before, ObjectState("11000001", nudged, (nudged,))) == 0
    pushed = SeenMarker("red", (0.39, -0.15, 0.62), 0.22)
    assert push_effect(before, ObjectState("11000101", pushed, (pushed,))) == 1
    assert push_effect(before, ObjectState("00000001", None, ())) == 1
    assert push_effect(ObjectState("00000001", None, ()), before) is None


def _agree(world, task: str) -> str:
    camera = make_object_perception("camera", task).observe(world)
    truth = make_object_perception("truth", task).observe(world)
    assert camera.bits == truth.bits
    assert np.linalg.norm(np.subtract(camera.front.position, truth.front.position)) < 0.01 \
        if truth.front else camera.front is None
    return truth.bits


def test_camera_agrees_with_truth_in_the_navigation_world():
    world = NavigationWorld()
    try:
        seen = [_agree(world, "navigation")]
        for _ in range(3):
            world.push()
            seen.append(_agree(world, "navigation"))
        assert seen == ["10010001", "10010101", "10011001", "10011101"]
        world.reset(exchanged=True)
        assert _agree(world, "navigation") == "11000001"  # the red box is in front now
        world.walk("left")
        world.walk("left")
        assert _agree(world, "navigation") == "10010010"  # the blue one, on the left
    finally:
        world.close()


def test_camera_agrees_with_truth_in_the_stacking_world():
    world = StackingWorld()
    try:
        assert _agree(world, "stacking") == "00000010"
        world.choose("foam")
        assert _agree(world, "stacking") == "00100010"
        world.push("squat")  # onto the lift: not on the table any more
        assert _agree(world, "stacking") == "00000010"
        world.choose("box")
        assert _agree(world, "stacking") == "10010010"
    finally:
        world.close()


def test_grid_bits_read_the_ninths_row_by_row_as_in_fig_7_2():
    mask = np.zeros((240, 320), np.uint8)
    mask[10:30, 10:40] = 255
    assert grid_bits(mask) == "100000000"
    mask[60:120, 60:150] = 255  # spills over into the three neighbours
    assert grid_bits(mask) == "110110000" and centre_seen(grid_bits(mask))
    few = np.zeros((240, 320), np.uint8)
    few[100:101, 150:153] = 255  # three pixels: noise, not a blob
    assert grid_bits(few) == "000000000"


def test_camera_grid_agrees_with_truth_over_the_head_poses():
    world = SearchWorld()
    camera, truth = make_grid_perception("camera"), make_grid_perception("truth")
    try:
        for place in ("up_left", "right"):
            world.place_target(place)
            for yaw in np.arange(-BOUNDARY, BOUNDARY + 1e-9, 2 * HEAD_STEP):
                for pitch in np.arange(-BOUNDARY, BOUNDARY + 1e-9, 2 * HEAD_STEP):
                    world.turn_to(float(yaw), float(pitch))
                    assert camera.observe(world) == truth.observe(world), (place, yaw, pitch)
    finally:
        world.close()


@pytest.mark.parametrize(("place", "steps"), [("up_left", 4), ("right", 3)])
def test_the_target_needs_as_many_looks_as_in_appendix_a(place, steps):
    world = SearchWorld(place)
    truth = make_grid_perception("truth")
    moves = list(SearchWorld.MOVES.values())
    try:
        queue, seen = deque([((0, 0), 0)]), {(0, 0)}
        while queue:
            (yaw, pitch), depth = queue.popleft()
            world.turn_to(yaw * HEAD_STEP, pitch * HEAD_STEP)
            if centre_seen(truth.observe(world)):
                break
            for dy, dp in moves:
                nxt = (yaw + dy, pitch + dp)
                if max(map(abs, nxt)) * HEAD_STEP <= BOUNDARY and nxt not in seen:
                    seen.add(nxt)
                    queue.append((nxt, depth + 1))
        assert depth == steps
    finally:
        world.close()


def test_unknown_modes_and_tasks_are_clear_errors():
    with pytest.raises(ValueError, match="use camera or truth"):
        make_object_perception("sonar", "navigation")
    with pytest.raises(ValueError, match="unknown task 'cooking'"):
        make_object_perception("truth", "cooking")
    with pytest.raises(ValueError, match="use camera or truth"):
        make_grid_perception("sonar")

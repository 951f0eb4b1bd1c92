"""GarbageWorld against real MuJoCo: scenes, arm, truth, rendering, recording, determinism."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from sim.scene import ARM_RANGE, CANS, HOME, asset_path, build_mjcf
from sim.world import GarbageWorld

MARKER_HSV = {  # OpenCV HSV ranges of the marker colours (red wraps around hue 0)
    "body": [((0, 120, 60), (8, 255, 255)), ((172, 120, 60), (179, 255, 255))],
    "lid": [((105, 120, 60), (130, 255, 255))],
    "handle": [((45, 120, 60), (80, 255, 255))],
}


def _pixels(image: np.ndarray, part: str) -> int:
    """Number of pixels in the marker colour of ``part``."""
    hsv = cv2.cvtColor(image, cv2.COLOR_RGB2HSV)
    mask = np.zeros(hsv.shape[:2], np.uint8)
    for lo, hi in MARKER_HSV[part]:
        mask |= cv2.inRange(hsv, np.array(lo, np.uint8), np.array(hi, np.uint8))
    return int(np.count_nonzero(mask))


def _dark(image: np.ndarray) -> int:
    """Number of near-black pixels (the can's interior)."""
    return int(np.count_nonzero(cv2.cvtColor(image, cv2.COLOR_RGB2HSV)[:, :, 2] <= 40))


@pytest.fixture(scope="module")
def world() -> GarbageWorld:
    """One world reused (and reset) across this module's tests."""
    w = GarbageWorld("o1", seed=0)
    yield w
    w.close()


@pytest.mark.parametrize("can", sorted(CANS))
def test_committed_assets_match_the_generator(can: str) -> None:
    """sim/assets/<can>.xml is exactly what the generator writes (run python -m sim.scene)."""
    assert asset_path(can).read_text() == build_mjcf(can)


def test_unknown_can_and_bad_image_size_are_clear_errors() -> None:
    """User mistakes name what is allowed instead of failing deep inside MuJoCo."""
    with pytest.raises(ValueError, match="unknown can 'o9'.*o1"):
        GarbageWorld("o9")
    with pytest.raises(ValueError, match="image size"):
        GarbageWorld("o1", width=0)
    with pytest.raises(ValueError, match="seed must be an integer"):
        GarbageWorld("o1", seed="x")  # type: ignore[arg-type]


@pytest.mark.parametrize("can", sorted(CANS))
def test_render_shows_the_markers_of_the_can_and_dark_only_when_open(
        world: GarbageWorld, can: str) -> None:
    """Each part's marker colour is visible, absent parts' colours are not, dark = open."""
    world.reset(can, seed=0)
    closed = world.render()
    assert closed.shape == (240, 320, 3) and closed.dtype == np.uint8
    for part in ("body", "lid", "handle"):
        if part in world.parts:
            assert _pixels(closed, part) > 30, f"{can}: {part} marker not visible"
        else:
            assert _pixels(closed, part) == 0
    assert _dark(closed) == 0
    world.set_opening(0.12)
    assert world.opening() == pytest.approx(0.12, abs=1e-6)
    opened = world.render()
    assert _dark(opened) > 500
    for part in world.parts:
        assert _pixels(opened, part) > 30, f"{can}: {part} marker hidden when open"


def test_camera_model_projects_markers_onto_their_colour(world: GarbageWorld) -> None:
    """camera_intrinsics().project puts each marker centre on a pixel of its colour."""
    world.reset("o2", seed=0)
    image = world.render()
    cam = world.camera_intrinsics()
    assert (cam.width, cam.height) == (320, 240)
    for part, ps in world.state().parts.items():
        u, v = cam.project([ps.pos])[0]
        patch = image[int(round(v)) - 1:int(round(v)) + 2, int(round(u)) - 1:int(round(u)) + 2]
        assert _pixels(patch, part) >= 5, part
    with pytest.raises(ValueError, match="unknown camera 'nose'.*head"):
        world.render("nose")


def test_state_reports_closed_lid_ball_on_table_hand_home(world: GarbageWorld) -> None:
    """Right after reset: closed lid, ball on the table (not held, not in the can), hand home."""
    world.reset("o4", seed=3)
    s = world.state()
    assert s.opening < 1e-3 and abs(s.lid_angle) < 1e-2
    assert set(s.parts) == {"body", "lid", "handle"}
    assert not s.holding_ball and not s.ball_in_can
    assert s.ball_pos[2] == pytest.approx(0.40 + 0.025, abs=2e-3)
    assert np.allclose(s.effector_pos, HOME, atol=2e-3)
    assert s.parts["lid"].size == pytest.approx((0.002, 0.05, 0.02))


def test_arm_moves_in_cartesian_space_and_stays_in_its_box(world: GarbageWorld) -> None:
    """Relative moves arrive; targets outside the reachable box are clipped to it."""
    world.reset("o1", seed=0)
    start = world.effector_pos
    assert world.move_arm(0.05, -0.03, -0.04)
    assert np.allclose(world.effector_pos, start + [0.05, -0.03, -0.04], atol=3e-3)
    world.move_arm_to([5.0, -5.0, 5.0])
    lo = np.array([b[0] for b in ARM_RANGE])
    hi = np.array([b[1] for b in ARM_RANGE])
    assert np.all(world.effector_pos >= lo - 0.01) and np.all(world.effector_pos <= hi + 0.01)
    with pytest.raises(ValueError, match="three finite numbers"):
        world.move_arm_to([0.0, float("nan"), 0.0])


def test_lid_stays_where_it_was_left(world: GarbageWorld) -> None:
    """Hinge friction holds an open lid (and its geared handle) against gravity."""
    for can in ("o1", "o5"):
        world.reset(can, seed=0)
        world.set_opening(0.11)
        world.step(3000)  # six simulated seconds
        assert world.opening() == pytest.approx(0.11, abs=2e-3), can


def test_a_held_lid_follows_the_hand_both_ways_and_stays_when_released(
        world: GarbageWorld) -> None:
    """hold(): a ball joint where the hand touches; pulling back closes what pushing opened."""
    world.reset("o1", seed=0)
    face = world.state().parts["lid"].pos
    world.move_arm_to([-0.12, face[1], face[2]])
    with pytest.raises(ValueError, match="must be within 0.01 m to take hold"):
        world.hold("lid")
    world.move_arm_to([face[0] - 0.017, face[1], face[2]])
    world.hold("lid")
    assert world.held_part == "lid"
    with pytest.raises(ValueError, match="already holds the lid"):
        world.hold("lid")
    for _ in range(6):
        world.move_arm(0.0, 0.0, 0.01)
    opened = world.opening()
    assert opened > 0.03
    for _ in range(3):
        world.move_arm(0.0, 0.0, -0.01)
    assert 0.005 < world.opening() < opened - 0.015  # moving back closes it again
    world.release()
    assert world.held_part is None
    left = world.opening()
    world.move_arm(-0.05, 0.0, 0.0)
    world.step(1000)
    assert world.opening() == pytest.approx(left, abs=2e-3)  # friction keeps it there
    world.reset(seed=0)
    assert world.held_part is None and world.opening() < 1e-3


def test_a_sliding_hold_slides_over_the_lid_face_and_still_pulls_it_shut(
        world: GarbageWorld) -> None:
    """hold(sliding=True): only the distance to the face is kept, so a push forward turns the
    lid while the hand slides down its face (a ball joint would drag the hand up the lid's
    arc instead); pulling back closes the lid again; release restores the ball-joint hold."""
    world.reset("o1", seed=0)
    face = world.state().parts["lid"].pos
    world.move_arm_to([face[0] - 0.017, face[1], face[2]])
    world.arm_stiffness = 15000.0
    world.hold("lid", sliding=True)
    start = world.effector_pos
    world.move_arm(0.01, 0.0, 0.0)
    moved = world.effector_pos - start
    assert moved[0] > 0.007 and abs(moved[2]) < 0.002  # forward, not up
    assert world.opening() > 0.02
    world.move_arm(-0.012, 0.0, 0.0)
    assert world.opening() < 0.005
    world.release()
    assert world.held_part is None
    world.arm_stiffness = 3000.0
    world.reset(seed=0)
    world.move_arm_to([face[0] - 0.017, face[1], face[2]])
    world.hold("lid")
    start = world.effector_pos
    world.move_arm(0.01, 0.0, 0.0)
    moved = world.effector_pos - start
    assert moved[0] < 0.004 and moved[2] > moved[0]  # the ball joint follows the lid's arc
    world.release()


def test_arm_stiffness_is_reset_and_checked(world: GarbageWorld) -> None:
    world.reset("o1", seed=0)
    assert world.arm_stiffness == 3000.0
    world.arm_stiffness = 12000.0
    assert world.arm_stiffness == 12000.0
    world.reset(seed=0)
    assert world.arm_stiffness == 3000.0
    for bad in (0.0, -1.0, float("nan"), "stiff"):
        with pytest.raises(ValueError, match="arm stiffness must be a positive number"):
            world.arm_stiffness = bad  # type: ignore[assignment]


def test_hold_refuses_parts_the_can_cannot_hold(world: GarbageWorld) -> None:
    world.reset("o1", seed=0)
    with pytest.raises(ValueError, match="no part 'handle' to hold; it has lid"):
        world.hold("handle")
    with pytest.raises(ValueError, match="no part 'body' to hold"):
        world.hold("body")


def test_gap_corners_span_the_opening(world: GarbageWorld) -> None:
    world.reset("o5", seed=0)
    world.set_opening(0.1)
    corners = world.gap_corners()
    assert corners.shape == (4, 3)
    assert np.linalg.norm(corners[2] - corners[1]) == pytest.approx(0.1, abs=0.01)
    assert corners[1, 1] - corners[0, 1] == pytest.approx(world.spec.width - 2 * 0.008)
    world.set_opening(0.0)


def test_set_opening_refuses_impossible_widths(world: GarbageWorld) -> None:
    """Openings beyond what the hinge allows are refused and the lid is left closed."""
    world.reset("o1", seed=0)
    with pytest.raises(ValueError, match="outside"):
        world.set_opening(2.0)
    assert world.opening() < 1e-3


def test_reset_is_deterministic_under_a_seed(world: GarbageWorld) -> None:
    """Same seed, same world; another seed moves the ball a little."""
    world.reset("o3", seed=7)
    first = world.state()
    world.move_arm(0.0, 0.0, -0.05)
    world.reset(seed=7)
    assert world.state() == first
    world.reset(seed=8)
    assert world.state().ball_pos != first.ball_pos


def test_record_writes_an_mp4(world: GarbageWorld, tmp_path) -> None:
    """Everything simulated inside record() ends up as frames of an mp4."""
    import imageio.v2 as imageio

    world.reset("o1", seed=0)
    out = tmp_path / "run.mp4"
    with world.record(out):
        world.move_arm(0.05, 0.0, 0.0)
        world.step(250)  # half a simulated second more
        simulated = world.data.time
        world.reset(seed=0)  # time restarts; the video goes on
        world.step(250)
        simulated += world.data.time
    reader = imageio.get_reader(str(out))
    frames = [f for f in reader]
    reader.close()
    assert abs(len(frames) - simulated * 25) <= 3
    assert frames[0].shape == (240, 320, 3)

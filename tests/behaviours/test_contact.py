"""Chapter 4's continuous interface: the hand holds the lid or handle and moves in small steps."""

from __future__ import annotations

import numpy as np
import pytest

from behaviours.contact import CONTACT_CAMERA, CONTACT_STIFFNESS, REACH, PartContact
from behaviours.learners.exploration import ContinuousWorld
from behaviours.perception import CameraPerception
from sim.scene import ARM_KP, HOME
from sim.world import GarbageWorld


@pytest.fixture(scope="module")
def world() -> GarbageWorld:
    made = GarbageWorld("o1")
    yield made
    made.close()


def run(contact: PartContact, moves: list[list[float]]) -> list[float]:
    """s_o before and after each move."""
    states = [contact.observe()]
    states += [contact.step(np.array(move)) for move in moves]
    return states


def test_pushing_the_lid_opens_it_fully_and_pulling_back_closes_it(world: GarbageWorld) -> None:
    """Thesis §4.6 / Table 4.1: about six pushes open the lid fully (s_o ~0.13 of the image),
    the arm then fully stretched and the state stable; contracting closes it again."""
    world.reset("o1", seed=0)
    with PartContact(world, "lid") as contact:
        assert isinstance(contact, ContinuousWorld) and world.held_part == "lid"
        assert contact.action_bounds == [(-0.01, 0.01)]
        assert world.arm_stiffness == CONTACT_STIFFNESS
        start = world.effector_pos
        states = run(contact, [[0.01]] * 14 + [[-0.01]] * 10)
        assert world.effector_pos[0] - start[0] <= REACH[0][1] + 0.002
    opening, closing = np.diff(states[:15]), np.diff(states[14:])
    assert states[0] == 0.0 and 0.11 < states[8] < 0.15
    assert opening[0] > 0.02 and np.all(np.abs(opening[8:]) < 0.01)  # then no more effect
    assert np.all(opening >= -1e-3) and np.all(closing <= 1e-3)  # e_o = s'_o − s_o (4.20)
    assert states[22] == states[-1] == 0.0  # closed within eight steps, and stays closed
    assert world.held_part is None and np.allclose(world.effector_pos, HOME, atol=3e-3)
    assert world.arm_stiffness == ARM_KP


def test_pulling_the_handle_opens_it_until_the_arm_is_contracted(world: GarbageWorld) -> None:
    world.reset("o5", seed=0)
    with PartContact(world, "handle", dims=3) as contact:
        assert contact.action_bounds == [(-0.01, 0.01)] * 3
        states = run(contact, [[-0.01, 0.0, -0.005]] * 9 + [[0.01, 0.0, 0.0]] * 8)
    assert np.all(np.diff(states[:7]) > 0.01) and 0.11 < states[6] < 0.15
    # fully contracted: pulling on only takes up the handle's vertical play (o5's give, Table
    # 5.3: its handle moves when lifted), a small fraction of the opening
    assert abs(states[9] - states[6]) < 0.02 * states[6]
    assert states[-1] < 0.003
    assert world.opening() < 0.01  # the can stays as the hand left it


@pytest.mark.parametrize(("can", "part", "opens"), [("o1", "lid", 0.01), ("o5", "handle", -0.01)])
def test_the_close_camera_agrees_with_ground_truth_along_a_run(
        world: GarbageWorld, can: str, part: str, opens: float) -> None:
    """s_o (eq. 4.19) from the rendered ``close`` frame and from the projected gap."""
    world.reset(can, seed=0)
    camera = CameraPerception(CONTACT_CAMERA)
    with PartContact(world, part) as contact:
        for move in [opens] * 7 + [-opens] * 3:
            truth = contact.step(np.array([move]))
            assert abs(camera.observe(world).opening_area - truth) <= 0.002 + 0.05 * truth


@pytest.mark.parametrize(
    ("move", "message"),
    [([0.02], "out of bounds"), ([float("nan")], "finite number"), ([0.01, 0.0], "1 finite")],
)
def test_bad_actions_are_refused_and_leave_the_world_unchanged(
        world: GarbageWorld, move: list[float], message: str) -> None:
    world.reset("o1", seed=0)
    with PartContact(world, "lid") as contact:
        contact.step(np.array([0.01]))
        before = (world.opening(), tuple(world.effector_pos))
        with pytest.raises(ValueError, match=message):
            contact.step(np.array(move))
        assert (world.opening(), tuple(world.effector_pos)) == before


def test_misuse_is_a_clear_error(world: GarbageWorld) -> None:
    world.reset("o1", seed=0)
    with pytest.raises(ValueError, match="has no part 'handle'"):
        PartContact(world, "handle")
    with pytest.raises(ValueError, match="dims must be 1"):
        PartContact(world, "lid", dims=2)
    with pytest.raises(ValueError, match="does not hold the lid; call start first"):
        PartContact(world, "lid").step(np.array([0.01]))

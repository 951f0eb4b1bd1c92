"""Camera perception agrees with the simulator's truth; parts are recognised across cans."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from sklearn.neighbors import KNeighborsClassifier

from behaviours.perception import make_perception
from sim.scene import CANS
from sim.world import GarbageWorld

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def worlds():
    made = {can: GarbageWorld(can) for can in sorted(CANS)}
    yield made
    for world in made.values():
        world.close()


@pytest.mark.parametrize("can", sorted(CANS))
def test_camera_and_truth_agree_over_a_sweep_of_openings(worlds, can):
    world = worlds[can]
    camera, truth = make_perception("camera"), make_perception("truth")
    for opening in (0.0, 0.02, 0.05, 0.08, 0.11, 0.14):
        world.set_opening(opening)
        seen, true = camera.observe(world), truth.observe(world)
        assert abs(seen.opening - true.opening) <= 0.01, (can, opening, seen.opening)
        assert sorted(seen.parts) == sorted(true.parts) == sorted(world.parts)
        assert seen.above == true.above
    world.set_opening(0.0)


def test_parts_of_a_held_out_can_are_recognised_by_their_descriptors(worlds):
    camera = make_perception("camera")
    seen = {can: camera.observe(world).parts for can, world in worlds.items()}
    for held_out in sorted(CANS):
        train = [(part.descriptor(), name) for can, parts in seen.items() if can != held_out
                 for name, part in parts.items()]
        features = np.array([d for d, _ in train])
        scale = features.std(axis=0)
        model = KNeighborsClassifier(n_neighbors=1).fit(features / scale, [n for _, n in train])
        for name, part in seen[held_out].items():
            assert model.predict([part.descriptor() / scale])[0] == name, (held_out, name)


def test_unknown_perception_mode_is_a_clear_error():
    with pytest.raises(ValueError, match="use camera or truth"):
        make_perception("sonar")


def test_snapshot_command_writes_an_annotated_png(tmp_path):
    out = tmp_path / "frame.png"
    result = subprocess.run([sys.executable, "-m", "goalagent", "snapshot", "--can", "o2",
                             "--out", str(out), "--opening", "0.08"],
                            capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert "parts body, handle, lid, opening 0.08" in result.stderr
    assert out.stat().st_size > 5_000

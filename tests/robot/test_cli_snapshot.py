"""The ``goalagent snapshot`` command (perception itself is tested in test_perception.py)."""

from __future__ import annotations

import cv2

from robot.snapshot import SCALE
from tests.conftest import cli

# robot/snapshot.py's box colours (RGB): none of them occurs in a rendered can frame
BOXES = {"body": (255, 255, 0), "lid": (0, 255, 255), "handle": (255, 0, 255)}


def test_snapshot_command_writes_an_annotated_png(tmp_path):
    out = tmp_path / "frame.png"
    result = cli("snapshot", "--can", "o2", "--out", str(out), "--opening", "0.08")
    assert result.exit_code == 0, result.stderr
    assert "parts body, handle, lid, opening 0.08" in result.stderr
    image = cv2.cvtColor(cv2.imread(str(out)), cv2.COLOR_BGR2RGB)
    assert image.shape == (240 * SCALE, 320 * SCALE, 3)  # the 320x240 head frame, enlarged
    for part, colour in BOXES.items():  # each perceived part is boxed in its colour
        assert (image == colour).all(axis=2).sum() >= 20, part

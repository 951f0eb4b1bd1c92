"""Head-camera snapshot with each perceived part boxed and labelled and the opening written on.

Backs ``goalagent snapshot --can o1 --out frame.png``: one look at what the robot's camera
perception makes of a can, to check markers, descriptors and the opening by eye.
"""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from behaviours.perception import BODY_MARKER_LENGTH, Observation, observe_image

_BOX_COLOURS: dict[str, tuple[int, int, int]] = {
    "body": (255, 255, 0),
    "lid": (0, 255, 255),
    "handle": (255, 0, 255),
}
_TEXT = (255, 255, 255)


def annotate(image: np.ndarray, obs: Observation) -> np.ndarray:
    """A copy of an RGB frame with the parts' rotated boxes, labels and the opening drawn."""
    out = np.ascontiguousarray(image.copy())
    font = cv2.FONT_HERSHEY_SIMPLEX
    for name, part in sorted(obs.parts.items()):
        colour = _BOX_COLOURS.get(name, _TEXT)
        corners = np.array(part.corners, dtype=np.float32).round().astype(np.int32)
        cv2.polylines(out, [corners], isClosed=True, color=colour, thickness=1)
        x, y, _, _ = part.bbox
        label = f"{name} r{part.rectangleness:.2f} s{part.squareness:.2f}"
        cv2.putText(out, label, (x, max(10, y - 3)), font, 0.33, colour, 1, cv2.LINE_AA)
    text = f"opening {obs.opening:.3f} m"
    cv2.rectangle(out, (0, 0), (8 + 7 * len(text), 16), (0, 0, 0), -1)
    cv2.putText(out, text, (4, 12), font, 0.4, _TEXT, 1, cv2.LINE_AA)
    return out


def render_snapshot(can: str, out: Path, seed: int = 0,
                    opening: float | None = None) -> Observation:
    """Render can's head-camera view (opened ``opening`` m first, if given), perceive it and
    save the annotated frame as PNG."""
    from sim.world import GarbageWorld

    out = Path(out)
    if out.suffix.lower() != ".png":
        raise ValueError(f"snapshot output must be a .png file, got {str(out)!r}")
    world = GarbageWorld(can=can, seed=seed)
    try:
        if opening is not None:
            world.set_opening(opening)
        image = world.render("head")
    finally:
        world.close()
    obs = observe_image(image, BODY_MARKER_LENGTH)
    out.parent.mkdir(parents=True, exist_ok=True)
    if not cv2.imwrite(str(out), cv2.cvtColor(annotate(image, obs), cv2.COLOR_RGB2BGR)):
        raise OSError(f"could not write snapshot to {str(out)!r}")
    return obs

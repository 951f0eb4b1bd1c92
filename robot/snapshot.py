"""Head-camera snapshot with each perceived part boxed and labelled and the opening written on.

Backs ``goalagent snapshot --can o1 --out frame.png`` (or ``goalagent robot snapshot``): one
look at what the robot's camera perception makes of a can, to check markers, descriptors and
the opening by eye. Perception runs on the 320x240 frame the robot uses; the picture is drawn
at ``SCALE`` times that size so the labels are legible.
"""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from behaviours.perception import Observation, dark_region, observe_image
from ondisk import write_atomically
from sim.canspec import CanSpec

SCALE = 2
"""The annotated PNG is this many times the camera frame's size (nearest-neighbour)."""
_BOX_COLOURS: dict[str, tuple[int, int, int]] = {
    "body": (255, 255, 0),
    "lid": (0, 255, 255),
    "handle": (255, 0, 255),
}
_DARK_BOX = (255, 140, 0)
_TEXT = (255, 255, 255)
_FONT = cv2.FONT_HERSHEY_SIMPLEX


def annotate(image: np.ndarray, obs: Observation) -> np.ndarray:
    """An enlarged copy of an RGB frame with parts boxed and labelled and the opening written."""
    out = cv2.resize(image, None, fx=SCALE, fy=SCALE, interpolation=cv2.INTER_NEAREST)
    for name, part in sorted(obs.parts.items()):
        colour = _BOX_COLOURS.get(name, _TEXT)
        corners = (np.array(part.corners, dtype=np.float32) + 0.5) * SCALE
        cv2.polylines(out, [corners.round().astype(np.int32)], isClosed=True, color=colour,
                      thickness=1, lineType=cv2.LINE_AA)
        x, y, w, _ = part.bbox
        label = f"{name}  a{part.area:.4f} r{part.rectangleness:.2f} s{part.squareness:.2f}"
        _label(out, label, (SCALE * (x + w) + 6, SCALE * y + 10), colour)
    gap = dark_region(cv2.cvtColor(image, cv2.COLOR_RGB2HSV))
    if gap is not None and obs.opening > 0:
        x, y, w, h = (SCALE * v for v in gap)
        cv2.rectangle(out, (x, y), (x + w - 1, y + h - 1), _DARK_BOX, 1)
        _label(out, "gap", (x + w + 6, y + h // 2 + 4), _DARK_BOX)
    _label(out, f"opening {obs.opening:.3f} m", (6, 18), _TEXT, size=0.55)
    return out


def _label(image: np.ndarray, text: str, origin: tuple[int, int],
           colour: tuple[int, int, int], size: float = 0.42) -> None:
    """Write text on a black backing box so it reads on any background."""
    (w, h), base = cv2.getTextSize(text, _FONT, size, 1)
    x = min(max(0, origin[0]), image.shape[1] - w - 2)
    y = min(max(h + 2, origin[1]), image.shape[0] - base - 2)
    cv2.rectangle(image, (x - 2, y - h - 3), (x + w + 2, y + base), (0, 0, 0), -1)
    cv2.putText(image, text, (x, y), _FONT, size, colour, 1, cv2.LINE_AA)


def render_snapshot(can: str | CanSpec, out: Path, seed: int = 0,
                    opening: float | None = None) -> Observation:
    """Render ``can``'s head camera (opened ``opening`` m first, if given), perceive the frame
    and save it annotated as a PNG; user mistakes (unknown can, bad opening, a path that is
    not a writable .png) raise ``ValueError`` saying so."""
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
    obs = observe_image(image)
    encoded, png = cv2.imencode(".png", cv2.cvtColor(annotate(image, obs), cv2.COLOR_RGB2BGR))
    if not encoded:
        raise ValueError("could not encode the snapshot as PNG")
    try:
        write_atomically(out, png.tobytes())
    except OSError as err:
        raise ValueError(f"could not write the snapshot to {str(out)!r}: "
                         f"{err.strerror or err}") from None
    return obs

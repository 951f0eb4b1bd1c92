"""Perception of garbage cans: colour markers to parts, shape descriptors and opening width.

The camera pipeline follows thesis §5.3.1 and §5.6.1: the head-camera frame is converted to
HSV, each marker colour (body red, lid blue, handle green) is segmented, the largest connected
component of a colour is that part's blob, bounded by a minimum-area (rotated) rectangle, and
described by Table 5.1 (area, rectangleness, squareness). The opening is the height of the
dark interior's bounding box scaled to metres by the known marker size (eq. 5.14).
``TruthPerception`` builds the same ``Observation`` from the simulator's ground truth, so tests
and fast experiments can swap one for the other.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import cv2
import numpy as np

if TYPE_CHECKING:
    from sim.world import GarbageWorld

PART_COLOURS: dict[str, str] = {"body": "red", "lid": "blue", "handle": "green"}
"""Which marker colour identifies which part (the rendering convention of sim/world.py)."""

# HSV ranges in OpenCV units (H 0..179, S and V 0..255); red wraps around hue 0.
_HSV_RANGES: dict[str, tuple[tuple[tuple[int, int, int], tuple[int, int, int]], ...]] = {
    "red": (((0, 120, 60), (8, 255, 255)), ((172, 120, 60), (179, 255, 255))),
    "blue": (((105, 120, 60), (130, 255, 255)),),
    "green": (((45, 120, 60), (80, 255, 255)),),
    "dark": (((0, 0, 0), (179, 255, 40)),),
}
MIN_BLOB_PIXELS = 12
"""Components smaller than this are noise (anti-aliased edges, specks), not parts."""


@dataclass(frozen=True)
class PartObservation:
    """One perceived part: its Table 5.1 shape descriptors and where it is in the image."""

    name: str
    area: float
    rectangleness: float
    squareness: float
    centre: tuple[float, float]
    bbox: tuple[int, int, int, int]
    corners: tuple[tuple[float, float], ...] = ()

    def descriptor(self) -> np.ndarray:
        """The (area, rectangleness, squareness) feature vector used to compare parts."""
        return np.array([self.area, self.rectangleness, self.squareness], dtype=float)


@dataclass(frozen=True)
class Observation:
    """What the robot sees of a can: its parts, which part is above which, the opening (m)."""

    parts: dict[str, PartObservation]
    above: tuple[tuple[str, str], ...]
    opening: float


class Perception(Protocol):
    """Anything that turns the current world into an ``Observation``."""

    def observe(self, world: GarbageWorld) -> Observation:
        """Perceive the world as it is now."""
        ...


def colour_mask(hsv: np.ndarray, colour: str) -> np.ndarray:
    """Binary mask (uint8 0/255) of the pixels of one named colour in an HSV image."""
    mask = np.zeros(hsv.shape[:2], dtype=np.uint8)
    for low, high in _HSV_RANGES[colour]:
        mask |= cv2.inRange(hsv, np.array(low, np.uint8), np.array(high, np.uint8))
    return mask


def largest_blob(mask: np.ndarray) -> np.ndarray | None:
    """Mask of the largest connected component (8-connected), or None if all are specks."""
    count, labels, stats, _ = cv2.connectedComponentsWithStats(mask, connectivity=8)
    if count <= 1:
        return None
    best = 1 + int(np.argmax(stats[1:, cv2.CC_STAT_AREA]))
    if stats[best, cv2.CC_STAT_AREA] < MIN_BLOB_PIXELS:
        return None
    return np.where(labels == best, 255, 0).astype(np.uint8)


def describe_blob(name: str, blob: np.ndarray) -> PartObservation:
    """Table 5.1 descriptors of a blob mask, bounded by its minimum-area rotated rectangle."""
    height, width = blob.shape[:2]
    points = cv2.findNonZero(blob)
    pixels = float(len(points))
    (cx, cy), (rw, rh), angle = cv2.minAreaRect(points)
    # minAreaRect measures between pixel centres; each side spans one more pixel.
    rw, rh = rw + 1.0, rh + 1.0
    corners = cv2.boxPoints(((cx, cy), (rw, rh), angle))
    x, y, w, h = cv2.boundingRect(points)
    return PartObservation(
        name=name,
        area=pixels / float(width * height),
        rectangleness=min(rw, rh) / max(rw, rh),
        squareness=min(1.0, pixels / (rw * rh)),
        centre=(float(cx), float(cy)),
        bbox=(int(x), int(y), int(w), int(h)),
        corners=tuple((float(px), float(py)) for px, py in corners),
    )


def above_relations(
    parts: dict[str, PartObservation], margin: float = 2.0
) -> tuple[tuple[str, str], ...]:
    """Pairs (p1, p2) where p1's centre is higher in the image than p2's by over margin px."""
    names = sorted(parts)
    return tuple(
        (p1, p2)
        for p1 in names
        for p2 in names
        if p1 != p2 and parts[p1].centre[1] + margin < parts[p2].centre[1]
    )


def marker_scale(marker: PartObservation, marker_length: float) -> float:
    """Metres per pixel (alpha of eq. 5.14) from a marker's long side of known length."""
    (ax, ay), (bx, by), (cx, cy) = marker.corners[:3]
    long_side = max(np.hypot(bx - ax, by - ay), np.hypot(cx - bx, cy - by))
    return marker_length / float(long_side)


def opening_height(image_hsv: np.ndarray) -> int:
    """Height in pixels of the bounding box of the dark interior (0 when none is visible)."""
    blob = largest_blob(colour_mask(image_hsv, "dark"))
    if blob is None:
        return 0
    return int(cv2.boundingRect(cv2.findNonZero(blob))[3])


def observe_image(image: np.ndarray, marker_length: float) -> Observation:
    """Perceive an RGB frame: parts by marker colour, relations, and opening (eq. 5.14)."""
    hsv = cv2.cvtColor(image, cv2.COLOR_RGB2HSV)
    parts: dict[str, PartObservation] = {}
    for part, colour in PART_COLOURS.items():
        blob = largest_blob(colour_mask(hsv, colour))
        if blob is not None:
            parts[part] = describe_blob(part, blob)
    reference = parts.get("body") or parts.get("lid")
    height = opening_height(hsv)
    opening = 0.0
    if reference is not None and height > 0:
        opening = height * marker_scale(reference, marker_length)
    return Observation(parts=parts, above=above_relations(parts), opening=opening)


BODY_MARKER_LENGTH = 0.08
"""Long side (m) of the body marker, the scale of eq. 5.14 (sim.scene.MARKER_SIZE["body"])."""


class CameraPerception:
    """Perceive through the head camera: render a frame and run the OpenCV pipeline."""

    def observe(self, world: GarbageWorld) -> Observation:
        return observe_image(world.render("head"), BODY_MARKER_LENGTH)


class TruthPerception:
    """The same ``Observation`` from the simulator: every part's marker projected through the
    head camera's model (so descriptors compare with the camera's), the true opening."""

    def observe(self, world: GarbageWorld) -> Observation:
        camera = world.camera_intrinsics("head")
        state = world.state()
        image_area = float(camera.width * camera.height)
        parts: dict[str, PartObservation] = {}
        for name, part in state.parts.items():
            corners = camera.project(_marker_corners(part.pos, part.quat, part.size))
            (cx, cy), (rw, rh), _ = cv2.minAreaRect(corners.astype(np.float32))
            polygon = float(cv2.contourArea(corners.astype(np.float32)))
            x, y, w, h = cv2.boundingRect(corners.round().astype(np.int32))
            parts[name] = PartObservation(
                name=name,
                area=polygon / image_area,
                rectangleness=min(rw, rh) / max(rw, rh),
                squareness=min(1.0, polygon / (rw * rh)),
                centre=(float(cx), float(cy)),
                bbox=(int(x), int(y), int(w), int(h)),
                corners=tuple((float(u), float(v)) for u, v in corners),
            )
        return Observation(parts=parts, above=above_relations(parts), opening=state.opening)


def _marker_corners(pos: tuple[float, ...], quat: tuple[float, ...],
                    size: tuple[float, ...]) -> np.ndarray:
    """World coordinates of a flat marker's four corners (its thin axis is local x)."""
    w, x, y, z = quat
    rotation = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])
    half_w, half_h = size[1] / 2, size[2] / 2
    local = np.array([[0, -half_w, -half_h], [0, half_w, -half_h],
                      [0, half_w, half_h], [0, -half_w, half_h]])
    return np.asarray(pos) + local @ rotation.T


PERCEPTION_MODES = {"camera": CameraPerception, "truth": TruthPerception}


def make_perception(mode: str) -> Perception:
    """The perception for a mode name: ``camera`` or ``truth``."""
    if mode not in PERCEPTION_MODES:
        raise ValueError(f"unknown perception mode {mode!r}; use camera or truth")
    return PERCEPTION_MODES[mode]()

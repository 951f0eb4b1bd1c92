"""Perception of garbage cans: colour markers to parts, shape descriptors and opening width.

The camera pipeline follows thesis §5.3.1 and §5.6.1: the head-camera frame is converted to
HSV, each marker colour (body red, lid blue, handle green) is segmented, the largest connected
component of a colour is that part's blob, bounded by a minimum-area (rotated) rectangle, and
described by Table 5.1 (area, rectangleness, squareness). The opening is the height of the
dark interior's bounding box scaled to metres by the known marker size (eq. 5.14); chapter 4's
state s_o is that box's share of the image (eq. 4.19).
``CameraPerception`` runs that pipeline on the world's rendered head-camera frame;
``TruthPerception`` builds the same ``Observation`` from the simulator's ground truth (marker
boxes projected through the camera model, so descriptors are comparable), so tests and fast
experiments can swap one for the other (``make_perception("camera" | "truth")``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Protocol

import cv2
import numpy as np

from sim.canspec import MARKER_SIZE

if TYPE_CHECKING:
    from sim.world import GarbageWorld

PART_COLOURS: dict[str, str] = {"body": "red", "lid": "blue", "handle": "green",
                                 "pedal": "magenta"}
"""Which marker colour identifies which part (the rendering convention of sim/world.py)."""

# HSV ranges in OpenCV units (H 0..179, S and V 0..255); red wraps around hue 0.
_HSV_RANGES: dict[str, tuple[tuple[tuple[int, int, int], tuple[int, int, int]], ...]] = {
    "red": (((0, 120, 60), (8, 255, 255)), ((172, 120, 60), (179, 255, 255))),
    "blue": (((105, 120, 60), (130, 255, 255)),),
    "green": (((45, 120, 60), (80, 255, 255)),),
    "magenta": (((140, 120, 60), (165, 255, 255)),),
    "dark": (((0, 0, 0), (179, 255, 40)),),
}
MIN_BLOB_PIXELS = 12
"""Components smaller than this are noise (anti-aliased edges, specks), not parts."""
DARK_BRIDGE = 5
"""Dark bands up to DARK_BRIDGE - 2 px apart vertically count as one dark region."""
_BRIDGE_KERNEL = np.ones((DARK_BRIDGE, 1), dtype=np.uint8)
SCALE_MARKERS: dict[str, float] = {"body": MARKER_SIZE["body"][0], "lid": MARKER_SIZE["lid"][0]}
"""Markers whose long side (m) scales pixels to metres, in order of preference (eq. 5.14).

The body marker comes first: its horizontal width is not foreshortened by the camera's pitch
and lies at the rim's depth, so it measures the opening within ~5 mm; the lid is a fallback.
"""
SIDE_GAP_OFFSET = 0.01
"""A dark gap whose centre lies this far (m) beside the can's centre line is a side gap."""
ABOVE_MARGIN_M = 0.005
"""Height difference (m) over which one part counts as above another in ground truth."""
DESCRIPTOR_WEIGHTS = np.array([1000.0, 1.0, 1.0])
"""Weights putting (area, rectangleness, squareness) on like ranges for distances between parts.

Area is a fraction of the image (~0.001..0.01 for a marker), the ratios lie in 0..1: area in
per-mille weighs as much as the ratios. (Standardising by the spread instead over-weights
squareness, which is ~1 for every marker, so a one-pixel jag would decide the nearest part.)
"""


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

    def features(self) -> np.ndarray:
        """The descriptor weighted by ``DESCRIPTOR_WEIGHTS``, for nearest-part comparisons."""
        return self.descriptor() * DESCRIPTOR_WEIGHTS


@dataclass(frozen=True)
class Observation:
    """What the robot sees of a can: its parts, which part is above which, the opening (m)."""

    parts: dict[str, PartObservation]
    above: tuple[tuple[str, str], ...]
    opening: float
    scale: float = 0.0
    """Metres per pixel (alpha of eq. 5.14) from the first scale marker seen; 0 if none."""
    opening_area: float = 0.0
    """s_o of eq. 4.19: the dark opening's bounding box as a fraction of the image (0..1)."""


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


def dark_region(image_hsv: np.ndarray) -> tuple[int, int, int, int] | None:
    """Bounding box (x, y, w, h) of the largest dark (interior) blob, or None if none is seen.

    A closing with a vertical ``DARK_BRIDGE``-pixel kernel first joins dark bands split by a
    thin lighter line (a steep lid's underside above the interior, with the back rim's edge
    between them), so the gap is measured whole.
    """
    mask = cv2.morphologyEx(colour_mask(image_hsv, "dark"), cv2.MORPH_CLOSE, _BRIDGE_KERNEL)
    blob = largest_blob(mask)
    if blob is None:
        return None
    x, y, w, h = cv2.boundingRect(cv2.findNonZero(blob))
    return int(x), int(y), int(w), int(h)


def observe_image(
    image: np.ndarray, scale_markers: Mapping[str, float] = SCALE_MARKERS
) -> Observation:
    """Perceive an RGB frame: parts by marker colour, relations, and opening (eq. 5.14).

    ``scale_markers`` maps part names to their marker's long side in metres; the first one
    seen scales the dark region's pixel height to metres (no marker seen: opening 0).
    """
    if image.ndim != 3 or image.shape[2] != 3 or image.dtype != np.uint8:
        raise ValueError(f"expected an RGB uint8 image (H, W, 3), got {image.dtype} "
                         f"{image.shape}")
    hsv = cv2.cvtColor(image, cv2.COLOR_RGB2HSV)
    parts: dict[str, PartObservation] = {}
    for part, colour in PART_COLOURS.items():
        blob = largest_blob(colour_mask(hsv, colour))
        if blob is not None:
            parts[part] = describe_blob(part, blob)
    scale = _scale(parts, scale_markers)
    box = dark_region(hsv)
    opening = gap_pixels(box, parts, scale) * scale if scale > 0 else 0.0
    area = 0.0 if box is None else box[2] * box[3] / float(image.shape[0] * image.shape[1])
    return Observation(parts=parts, above=above_relations(parts), opening=opening, scale=scale,
                       opening_area=area)


def gap_pixels(box: tuple[int, int, int, int] | None, parts: Mapping[str, PartObservation],
               scale: float) -> int:
    """The dark box's extent in pixels that measures the opening (eq. 5.14).

    A hinged lid opens a gap in front of it, centred on the can: its height is the opening,
    as in the thesis. A lid that slides sideways opens a gap beside it, off the can's centre
    line (the body marker's): there its width is the opening.
    """
    if box is None:
        return 0
    x, _, width, height = box
    body = parts.get("body")
    if body is not None and scale > 0 and abs(x + width / 2 - body.centre[0]) * scale > (
            SIDE_GAP_OFFSET):
        return width
    return height


def _scale(parts: Mapping[str, PartObservation], scale_markers: Mapping[str, float]) -> float:
    """Metres per pixel from the first of ``scale_markers`` among ``parts`` (0 if none is)."""
    reference = next((p for p in scale_markers if p in parts), None)
    return 0.0 if reference is None else marker_scale(parts[reference], scale_markers[reference])


def part_displacement(before: Observation, after: Observation, part: str) -> float:
    """How far (m) ``part``'s centre moved between two observations (eq. 5.15).

    The pixel distance between the part's box centres times alpha (the earlier observation's
    metres per pixel); a part missing from either observation, or no scale, is an error.
    """
    missing = [name for name, obs in (("before", before), ("after", after))
               if part not in obs.parts]
    if missing:
        raise ValueError(f"part {part!r} was not seen {' and '.join(missing)} the action")
    if before.scale <= 0:
        raise ValueError("no scale marker was seen before the action: cannot convert pixels "
                         "to metres")
    (x0, y0), (x1, y1) = before.parts[part].centre, after.parts[part].centre
    return before.scale * float(np.hypot(x1 - x0, y1 - y0))


class CameraPerception:
    """Perceive by rendering a camera of the world and running the OpenCV pipeline on it.

    The opening agrees with ground truth within 0.01 m from 0 to 0.20 m on every can (tested).
    Wider, a tall lid's front edge lies well behind the rim, where the body marker's scale
    no longer holds: o3 reads 0.024 m short at 0.25 m.
    """

    def __init__(self, camera: str = "head"):
        """Use ``camera`` (the head camera by default)."""
        self.camera = camera

    def observe(self, world: GarbageWorld) -> Observation:
        """Render the camera now and perceive the frame (opening scaled by the body marker)."""
        return observe_image(world.render(self.camera))


class TruthPerception:
    """Perceive from ground truth: the can's parts, its real opening, projected marker shapes.

    Each marker box of the model is projected through the camera's pinhole model and filled
    as a polygon, then described exactly like a camera blob, so descriptors are comparable
    with ``CameraPerception``'s; ``above`` compares true marker heights; the opening is
    ``world.state().opening``; the opening's image area (eq. 4.19) is the bounding box of the
    projected gap (``GarbageWorld.gap_corners``). No rendering, so it is fast and needs no GL
    context.
    """

    def __init__(self, camera: str = "head"):
        """Project into ``camera`` (the head camera by default)."""
        self.camera = camera

    def observe(self, world: GarbageWorld) -> Observation:
        """The ideal observation of the world as it is now."""
        state = world.state()
        camera = world.camera_intrinsics(self.camera)
        parts: dict[str, PartObservation] = {}
        for name in world.parts:
            geom = world.model.geom(f"marker_{name}").id
            centre = world.data.geom_xpos[geom]
            axes = world.data.geom_xmat[geom].reshape(3, 3)
            corners = centre + (BOX_CORNERS * world.model.geom_size[geom]) @ axes.T
            blob = filled_hull(camera.project(corners), camera.width, camera.height)
            if blob is not None:
                parts[name] = describe_blob(name, blob)
        heights = {name: state.parts[name].pos[2] for name in parts}
        above = tuple(
            (p1, p2)
            for p1 in sorted(parts)
            for p2 in sorted(parts)
            if p1 != p2 and heights[p1] > heights[p2] + ABOVE_MARGIN_M
        )
        corners = camera.project(world.gap_corners())
        gap = filled_hull(corners, camera.width, camera.height)
        area = 0.0
        if gap is not None and corners[2:, 1].mean() < corners[:2, 1].mean():  # lid edge higher
            _, _, w, h = cv2.boundingRect(cv2.findNonZero(gap))
            area = w * h / float(camera.width * camera.height)
        return Observation(parts=parts, above=above, opening=float(state.opening),
                           scale=_scale(parts, SCALE_MARKERS), opening_area=area)


BOX_CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
"""The eight corners of a box geom in units of its half-sizes."""


def filled_hull(pixels: np.ndarray, width: int, height: int,
                min_pixels: int = MIN_BLOB_PIXELS) -> np.ndarray | None:
    """Mask of the pixels whose centres lie in the projected points' convex hull (or None if
    it covers fewer than ``min_pixels``).

    That is how the renderer covers a polygon (pixel (i, j) has its centre at j + 0.5,
    i + 0.5), so the mask has the pixels the camera would segment.
    """
    hull = cv2.convexHull(pixels.astype(np.float32)).reshape(-1, 2).astype(float)
    mask = np.zeros((height, width), dtype=np.uint8)
    x0, y0 = np.clip(np.floor(hull.min(axis=0)).astype(int), 0, [width, height])
    x1, y1 = np.clip(np.ceil(hull.max(axis=0)).astype(int) + 1, 0, [width, height])
    if x1 <= x0 or y1 <= y0 or len(hull) < 3:
        return None
    ys, xs = np.mgrid[y0:y1, x0:x1] + 0.5
    a, b = hull, np.roll(hull, -1, axis=0)
    orientation = np.sign(np.sum(a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]))
    inside = np.ones(xs.shape, dtype=bool)
    for (ax, ay), (bx, by) in zip(a, b, strict=True):
        inside &= orientation * ((bx - ax) * (ys - ay) - (by - ay) * (xs - ax)) >= 0
    mask[y0:y1, x0:x1][inside] = 255
    if cv2.countNonZero(mask) < min_pixels:
        return None
    return mask


class NoisyPerception:
    """Another perception with Gaussian sensor noise on what chapter 5 measures: σ metres on
    the opening s_o (eq. 5.14) and on each part's position (σ/α pixels on its image centre,
    α the observation's metres per pixel), so e_o and e_ψ (eqs 5.3, 5.15) are noisy as the
    NAO's were (§5.6.2: "Due to sensory noise ..."). The same for camera and ground truth."""

    def __init__(self, perception: Perception, sigma: float,
                 random_state: int | Sequence[int] | np.random.Generator | None = None):
        if not (np.isfinite(sigma) and sigma >= 0):
            raise ValueError(f"sigma must be a finite number >= 0, got {sigma!r}")
        self.perception, self.sigma = perception, float(sigma)
        self.rng = (random_state if isinstance(random_state, np.random.Generator)
                    else np.random.default_rng(random_state))

    def observe(self, world: GarbageWorld) -> Observation:
        """The wrapped perception's observation, its opening and part centres perturbed."""
        seen = self.perception.observe(world)
        pixels = self.sigma / seen.scale if seen.scale > 0 else 0.0
        parts = {}
        for name, part in seen.parts.items():
            dx, dy = self.rng.normal(0.0, 1.0, size=2) * pixels
            parts[name] = replace(part, centre=(part.centre[0] + dx, part.centre[1] + dy))
        opening = seen.opening + float(self.rng.normal(0.0, 1.0)) * self.sigma
        return replace(seen, parts=parts, opening=opening)


def make_perception(mode: str, camera: str = "head", sigma: float = 0.0,
                    random_state: int | Sequence[int] | None = None) -> Perception:
    """The perception of a mode name: "camera" (rendered frames) or "truth" (ground truth),
    through ``camera``; with ``sigma`` > 0, with that sensor noise (``NoisyPerception``,
    seeded by ``random_state``)."""
    if mode == "camera":
        seen: Perception = CameraPerception(camera)
    elif mode == "truth":
        seen = TruthPerception(camera)
    else:
        raise ValueError(f"unknown perception mode {mode!r}; use camera or truth")
    return NoisyPerception(seen, sigma, random_state) if sigma > 0 else seen


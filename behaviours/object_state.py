"""The 8-bit state of thesis eqs. 3.11-3.13 for the navigation and stacking tasks.

s = (o, s_xyz) with o = (o_height, o_color): one bit for a high object (h_o of eq. 3.11 above
``HIGH``), three for its colour, four for its discretised location. The object is the one in
front of the robot: the marker nearest its centre line within ``Encoding.half_width`` to either
side and ``Encoding.reach`` ahead, on the table. With nothing in front, o = 0000 and the
location is that of the point ``reach / 2`` ahead of the robot.

``CameraObjects`` finds markers in the rendered head-camera frame (HSV segmentation, as the
garbage cans' perception does) and places each in the world like the NAO's landmark detection
(§3.5.3): its known width (8 cm) and its width in pixels give its depth, its centre pixel
back-projected to that depth gives (x, y, z), with the camera pose known (the robot localises
itself, thesis §3.5.3; here the simulator gives the pose). ``TruthObjects`` takes the marker
positions from the simulator. Both feed the same encoding, so they agree whenever the camera
places each marker in the same cell (tested).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import cv2
import numpy as np

from behaviours.perception import MIN_BLOB_PIXELS, colour_mask
from sim.base import CameraModel
from sim.navigation import MARKER_HALF

COLOUR_BITS: dict[str, str] = {"red": "100", "green": "010", "blue": "001"}
"""3-bit colour code (o_color of eq. 3.13): one bit per RGB channel the marker colour lights."""
HIGH = 0.18
"""An object whose top is more than this (m) above the table is high (o_height = 1, eq. 3.11)."""
MARKER_WIDTH = 2 * MARKER_HALF[1]
"""Known width (m) of every marker, across the robot's view: scales pixels to depth."""
MOVED = 0.03
"""A push that displaces the object by more than this (m) moved it (effect 1, §3.5.2)."""
CAMERA = "head"


@dataclass(frozen=True)
class Encoding:
    """How a task turns marker positions into location bits and picks the object in front."""

    x0: float
    """Row 0 of the location grid starts at this x (m); rows are ``step`` deep."""
    step: float
    y_edges: tuple[float, float, float]
    """Boundaries (m) of the four lateral bins, right to left."""
    half_width: float = 0.14
    reach: float = 0.40

    def location_bits(self, x: float, y: float) -> str:
        """Two bits of row (along x) then two of lateral bin (along y)."""
        row = int(np.clip(np.floor((x - self.x0) / self.step), 0, 3))
        lane = int(np.searchsorted(self.y_edges, y))
        return f"{row:02b}{lane:02b}"


ENCODINGS: dict[str, Encoding] = {
    "navigation": Encoding(x0=0.16, step=0.15, y_edges=(-0.2, 0.0, 0.2)),
    "stacking": Encoding(x0=0.0, step=0.15, y_edges=(-0.25, -0.1, 0.1)),
}
"""Per task: grid cells centred on where the boxes stand after 0-3 pushes (navigation) and on
the spot the operator puts objects (stacking), so small drifts never change a bit."""


@dataclass(frozen=True)
class SeenMarker:
    """One marker on the table: its colour, world position (m) and object height h_o (m)."""

    colour: str
    position: tuple[float, float, float]
    height: float

    @property
    def object_bits(self) -> str:
        """o = (o_height, o_color) of eq. 3.13."""
        return ("1" if self.height > HIGH else "0") + COLOUR_BITS[self.colour]


@dataclass(frozen=True)
class ObjectState:
    """What the robot perceives: the 8-bit state, the object in front, every marker seen."""

    bits: str
    front: SeenMarker | None
    markers: tuple[SeenMarker, ...] = field(default=())

    @property
    def object_bits(self) -> str:
        """The object part o of the state (4 bits)."""
        return self.bits[:4]

    @property
    def location_bits(self) -> str:
        """The location part s_xyz of the state (4 bits)."""
        return self.bits[4:]


class TaskWorld(Protocol):
    """What object perception needs of a navigation or stacking world."""

    table_top: float
    table_x: tuple[float, float]
    table_y: tuple[float, float]
    model: object
    data: object

    @property
    def robot_pos(self) -> np.ndarray: ...
    def markers(self) -> dict[str, str]: ...
    def render(self, camera: str) -> np.ndarray: ...
    def camera_intrinsics(self, camera: str) -> CameraModel: ...


def height_above_table(marker_z: float, camera_z: float, table_top: float) -> float:
    """h_o = h_r2t - |z_r2o| (eq. 3.11): camera height over the table less its drop to the top."""
    return (camera_z - table_top) - abs(camera_z - marker_z)


def on_table(marker: SeenMarker, world: TaskWorld) -> bool:
    """True for a marker over the table surface (not on the floor, the lift or out of reach)."""
    x, y, _ = marker.position
    return (world.table_x[0] < x < world.table_x[1] and world.table_y[0] < y < world.table_y[1]
            and marker.height > 0.02)


def encode(markers: list[SeenMarker], robot: np.ndarray, encoding: Encoding) -> ObjectState:
    """The state of eq. 3.12 from the markers on the table and the robot's position."""
    ahead = [m for m in markers
             if abs(m.position[1] - robot[1]) < encoding.half_width
             and 0.0 < m.position[0] - robot[0] < encoding.reach]
    front = min(ahead, key=lambda m: abs(m.position[1] - robot[1]), default=None)
    if front is None:
        where = encoding.location_bits(robot[0] + encoding.reach / 2, robot[1])
        return ObjectState("0000" + where, None, tuple(markers))
    bits = front.object_bits + encoding.location_bits(front.position[0], front.position[1])
    return ObjectState(bits, front, tuple(markers))


def push_effect(before: ObjectState, after: ObjectState) -> int | None:
    """1 if the object in front before a push moved more than ``MOVED`` (or left the table),
    0 if it did not, None if nothing was in front (no affordance to learn)."""
    if before.front is None:
        return None
    same = [m for m in after.markers if m.colour == before.front.colour]
    if not same:
        return 1
    nearest = min(float(np.linalg.norm(np.subtract(m.position, before.front.position)))
                  for m in same)
    return int(nearest > MOVED)


class ObjectPerception(Protocol):
    """Anything that perceives a task world as an ``ObjectState``."""

    def observe(self, world: TaskWorld) -> ObjectState: ...


class TruthObjects:
    """The state from the simulator's marker positions."""

    def __init__(self, encoding: Encoding):
        """Encode with ``encoding``."""
        self.encoding = encoding

    def observe(self, world: TaskWorld) -> ObjectState:
        """Markers as they are, those on the table encoded."""
        camera_z = float(world.camera_intrinsics(CAMERA).pos[2])
        seen = []
        for name, colour in world.markers().items():
            pos = world.data.geom(f"marker_{name}").xpos  # type: ignore[attr-defined]
            marker = SeenMarker(colour, (float(pos[0]), float(pos[1]), float(pos[2])),
                                height_above_table(float(pos[2]), camera_z, world.table_top))
            if on_table(marker, world):
                seen.append(marker)
        return encode(seen, world.robot_pos, self.encoding)


class CameraObjects:
    """The state from the rendered head-camera frame."""

    def __init__(self, encoding: Encoding):
        """Encode with ``encoding``."""
        self.encoding = encoding

    def observe(self, world: TaskWorld) -> ObjectState:
        """Render, find and place the markers, encode those on the table."""
        camera = world.camera_intrinsics(CAMERA)
        seen = [m for m in locate_markers(world.render(CAMERA), camera, world.table_top)
                if on_table(m, world)]
        return encode(seen, world.robot_pos, self.encoding)


def locate_markers(image: np.ndarray, camera: CameraModel, table_top: float) -> list[SeenMarker]:
    """Every whole marker in an RGB frame, placed in the world by its known width.

    A blob touching the frame's border is cut off, so its width says nothing: it is skipped.
    """
    hsv = cv2.cvtColor(image, cv2.COLOR_RGB2HSV)
    height, width = image.shape[:2]
    found = []
    for colour in COLOUR_BITS:
        count, labels, stats, centroids = cv2.connectedComponentsWithStats(
            colour_mask(hsv, colour), connectivity=8)
        for label in range(1, count):
            x, y, w, h, area = stats[label]
            if area < MIN_BLOB_PIXELS or x == 0 or y == 0 or x + w == width or y + h == height:
                continue
            u, v = centroids[label]
            row = labels[int(round(v))] == label
            pixels = float(np.count_nonzero(row)) or float(w)
            depth = camera.fx * MARKER_WIDTH / pixels
            point = camera.back_project(float(u), float(v), depth)
            found.append(SeenMarker(colour, (float(point[0]), float(point[1]), float(point[2])),
                                    height_above_table(float(point[2]), float(camera.pos[2]),
                                                       table_top)))
    return found


def make_object_perception(mode: str, task: str) -> ObjectPerception:
    """Camera or truth perception of the 8-bit state for ``task`` (navigation or stacking)."""
    if task not in ENCODINGS:
        raise ValueError(f"unknown task {task!r}; use {' or '.join(ENCODINGS)}")
    if mode == "camera":
        return CameraObjects(ENCODINGS[task])
    if mode == "truth":
        return TruthObjects(ENCODINGS[task])
    raise ValueError(f"unknown perception mode {mode!r}; use camera or truth")

"""The 9-bit state of the head-camera search (thesis App. A, Fig. 7.2): a 3 x 3 blob grid.

The frame is cut into nine equal parts, read row by row from the top left; a bit is 1 when the
target's colour covers at least ``MIN_CELL_PIXELS`` pixels of that part (Fig. 7.2(c) reads
'100000000' with the target in the top-left corner). The fifth bit is the centre: the goal.
``CameraGrid`` segments the rendered head-camera frame (HSV, as every perception here);
``TruthGrid`` projects the target cube's corners through the camera model and fills their
hull exactly as the renderer covers pixels, so both count the same pixels (tested).
"""

from __future__ import annotations

from typing import Protocol

import cv2
import numpy as np

from behaviours.perception import BOX_CORNERS, colour_mask, filled_hull
from sim.search import TARGET_COLOUR, SearchWorld

GRID = 3
MIN_CELL_PIXELS = 4
"""A part of the image holds the blob when at least this many of its pixels are the colour."""
CAMERA = "head"


def grid_bits(mask: np.ndarray) -> str:
    """Nine bits, row by row from the top left: which ninths of ``mask`` hold a blob."""
    height, width = mask.shape[:2]
    rows = np.linspace(0, height, GRID + 1).round().astype(int)
    cols = np.linspace(0, width, GRID + 1).round().astype(int)
    return "".join(
        "1" if cv2.countNonZero(mask[rows[r]:rows[r + 1], cols[c]:cols[c + 1]])
        >= MIN_CELL_PIXELS else "0"
        for r in range(GRID) for c in range(GRID))


def centre_seen(bits: str) -> bool:
    """True when the centre ninth sees the target (the fifth bit, App. A's goal)."""
    return bits[GRID * GRID // 2] == "1"


class GridPerception(Protocol):
    """Anything that perceives the search world as a 9-bit string."""

    def observe(self, world: SearchWorld) -> str: ...


class CameraGrid:
    """The grid from the rendered head-camera frame."""

    def observe(self, world: SearchWorld) -> str:
        """Render, segment the target's colour, read the grid."""
        hsv = cv2.cvtColor(world.render(CAMERA), cv2.COLOR_RGB2HSV)
        return grid_bits(colour_mask(hsv, TARGET_COLOUR))


class TruthGrid:
    """The grid from the target cube's true pose, projected into the head camera."""

    def observe(self, world: SearchWorld) -> str:
        """Project the cube, fill its silhouette, read the grid (no rendering)."""
        camera = world.camera_intrinsics(CAMERA)
        geom = world.model.geom("target").id
        centre = world.data.geom_xpos[geom]
        axes = world.data.geom_xmat[geom].reshape(3, 3)
        corners = centre + (BOX_CORNERS * world.model.geom_size[geom]) @ axes.T
        if np.any((corners - camera.pos) @ camera.rot[:, 2] >= 0):  # behind the camera
            return "0" * GRID * GRID
        mask = filled_hull(camera.project(corners), camera.width, camera.height, min_pixels=1)
        if mask is None:
            return "0" * GRID * GRID
        return grid_bits(mask)


def make_grid_perception(mode: str) -> GridPerception:
    """Camera or truth perception of the search grid."""
    if mode == "camera":
        return CameraGrid()
    if mode == "truth":
        return TruthGrid()
    raise ValueError(f"unknown perception mode {mode!r}; use camera or truth")

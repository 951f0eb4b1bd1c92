"""What every MuJoCo world of this package shares: physics stepping, settling, headless rendering.

``RenderedWorld`` owns a model built from generated MJCF text and its data, steps and settles
the physics, renders a named camera offscreen (``MUJOCO_GL=egl`` on a machine without a
display) and gives the camera's pinhole model (``CameraModel``), which ground-truth perception
uses to project simulator geometry into the image exactly where the renderer draws it.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import ClassVar

import mujoco
import numpy as np

MAX_IMAGE = (640, 480)
"""Largest frame (width, height) the scenes' offscreen buffers hold."""


@dataclass(frozen=True)
class CameraModel:
    """Pinhole model of a rendered camera: intrinsics plus its pose in the world."""

    width: int
    height: int
    fovy: float
    fx: float
    fy: float
    cx: float
    cy: float
    pos: np.ndarray
    rot: np.ndarray
    """World-from-camera rotation; camera looks along its -z, +y is image up."""

    def project(self, points: Sequence[Sequence[float]] | np.ndarray) -> np.ndarray:
        """Pixel coordinates (u right, v down) of world points, shape (N, 2)."""
        p = np.atleast_2d(np.asarray(points, dtype=float))
        cam = (p - self.pos) @ self.rot  # rows are camera-frame coordinates
        depth = -cam[:, 2]
        u = self.cx + self.fx * cam[:, 0] / depth
        v = self.cy - self.fy * cam[:, 1] / depth
        return np.stack([u, v], axis=1)

    def back_project(self, u: float, v: float, depth: float) -> np.ndarray:
        """The world point seen at pixel (u, v) that lies ``depth`` m along the optical axis."""
        cam = np.array([(u - self.cx) * depth / self.fx, -(v - self.cy) * depth / self.fy,
                        -depth])
        return self.pos + self.rot @ cam


class RenderedWorld:
    """A MuJoCo model and its data, stepped, settled and rendered headless."""

    default_camera: ClassVar[str | None] = None
    """The camera ``render`` and ``camera_intrinsics`` use when none is named (None: name one)."""
    settle_steps: ClassVar[int] = 1500
    """How many steps ``settle`` waits at most for the world to come to rest, by default."""

    def __init__(self, mjcf: str, width: int = 320, height: int = 240):
        """Compile ``mjcf``; frames are ``width`` x ``height`` pixels."""
        if not (0 < width <= MAX_IMAGE[0] and 0 < height <= MAX_IMAGE[1]):
            raise ValueError(f"image size {width}x{height} must lie within 1x1.."
                             f"{MAX_IMAGE[0]}x{MAX_IMAGE[1]}")
        self.width, self.height = width, height
        self._renderer: mujoco.Renderer | None = None
        self.load(mjcf)
        self.steps = 0

    def load(self, mjcf: str) -> None:
        """Compile ``mjcf`` into a new model and data, replacing the current ones (a renderer
        made for the old model is freed; the next frame makes one for the new)."""
        self.model = mujoco.MjModel.from_xml_string(mjcf)
        self.data = mujoco.MjData(self.model)
        self.close()

    # ---------------------------------------------------------------- physics
    def step(self, n: int = 1) -> None:
        """Advance the physics ``n`` steps."""
        mujoco.mj_step(self.model, self.data, nstep=n)
        self.steps += n

    def settle(self, max_steps: int | None = None, calm_speed: float = 2e-3) -> None:
        """Step until every joint is (nearly) at rest for 20 steps, or ``max_steps`` passed
        (default ``settle_steps``)."""
        calm, velocity = 0, self.data.qvel  # a view: every step updates it
        for _ in range(self.settle_steps if max_steps is None else max_steps):
            self.step()
            calm = calm + 1 if float(np.abs(velocity).max()) < calm_speed else 0
            if calm >= 20:
                return

    # ----------------------------------------------------------------- camera
    def render(self, camera: str | None = None) -> np.ndarray:
        """RGB frame (H, W, 3) uint8 of ``camera`` (default ``default_camera``) as the world
        is now."""
        camera = self._camera(camera)
        if self._renderer is None:
            try:
                self._renderer = mujoco.Renderer(self.model, self.height, self.width)
            except mujoco.FatalError as exc:
                raise RuntimeError(
                    "cannot create an OpenGL context for rendering; run headless with "
                    "MUJOCO_GL=egl set before mujoco is first imported (MUJOCO_GL is "
                    f"{os.environ.get('MUJOCO_GL')!r}): {exc}") from exc
        self._renderer.update_scene(self.data, camera)
        return self._renderer.render().copy()

    def camera_intrinsics(self, camera: str | None = None) -> CameraModel:
        """Pinhole intrinsics and world pose of ``camera`` (default ``default_camera``) for the
        current image size."""
        camera = self._camera(camera)
        fovy = float(self.model.camera(camera).fovy[0])
        f = (self.height / 2) / math.tan(math.radians(fovy) / 2)
        dc = self.data.camera(camera)
        return CameraModel(self.width, self.height, fovy, f, f, self.width / 2,
                           self.height / 2, dc.xpos.copy(), dc.xmat.reshape(3, 3).copy())

    def _camera(self, camera: str | None) -> str:
        """The camera named (or the default one); unknown names are refused with the list of
        known ones."""
        names = [self.model.camera(i).name for i in range(self.model.ncam)]
        chosen = self.default_camera if camera is None else camera
        if chosen is None:
            raise ValueError(f"name a camera; this scene has {', '.join(names)}")
        if chosen not in names:
            raise ValueError(f"unknown camera {chosen!r}; this scene has {', '.join(names)}")
        return chosen

    def close(self) -> None:
        """Free the renderer's GL context."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None

"""Frames for ``render_mode="rgb_array"``: the whole scene from above, or a robot camera;
``WorldRendering`` gives an environment its ``render`` and ``close``.

``Frames`` renders the world a goalagent environment owns. ``"overview"`` is a free camera
aimed at the task's table (what a person watching the experiment sees, and what
``gymnasium.wrappers.RecordVideo`` records); any other name is one of the scene's own
cameras (``head``: what the robot's perception sees; the cans also have ``close``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import gymnasium as gym
import mujoco
import numpy as np

OVERVIEW = "overview"
FRAME_SIZE = (480, 360)
"""Width and height (pixels) of a rendered frame (within every scene's offscreen buffer)."""


@dataclass(frozen=True)
class View:
    """Where the overview camera looks from: target point (m), distance (m), angles (deg)."""

    lookat: tuple[float, float, float]
    distance: float
    azimuth: float
    elevation: float


def scene_cameras(model: mujoco.MjModel) -> tuple[str, ...]:
    """The names a ``camera`` keyword may take for this scene: the overview and its own."""
    return (OVERVIEW, *(model.camera(i).name for i in range(model.ncam)))


class Frames:
    """Renders one scene (model and data) from the overview or a named camera."""

    def __init__(self, view: View, camera: str = OVERVIEW):
        """Render through ``camera``; the overview camera looks as ``view`` says."""
        self.view, self.camera = view, camera
        self._renderer: mujoco.Renderer | None = None
        self._model: mujoco.MjModel | None = None

    def render(self, model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
        """An RGB frame (height, width, 3) of the scene as it is now."""
        if self._renderer is None or self._model is not model:
            self.close()
            width, height = FRAME_SIZE
            self._renderer, self._model = mujoco.Renderer(model, height, width), model
        if self.camera == OVERVIEW:
            camera = mujoco.MjvCamera()
            camera.type = mujoco.mjtCamera.mjCAMERA_FREE
            camera.lookat[:] = self.view.lookat
            camera.distance, camera.azimuth = self.view.distance, self.view.azimuth
            camera.elevation = self.view.elevation
            self._renderer.update_scene(data, camera)
        else:
            self._renderer.update_scene(data, self.camera)
        return self._renderer.render().copy()

    def close(self) -> None:
        """Free the renderer's GL context (a later ``render`` makes a new one)."""
        if self._renderer is not None:
            self._renderer.close()
        self._renderer = self._model = None


class WorldRendering:
    """``render`` and ``close`` of an environment that owns a ``world`` and its ``frames``."""

    render_mode: str | None
    frames: Frames
    world: Any

    def render(self) -> np.ndarray | None:
        """The scene as an RGB frame (``render_mode="rgb_array"``), else None."""
        if self.render_mode is None:
            gym.logger.warn("render() needs render_mode='rgb_array' at gymnasium.make")
            return None
        return self.frames.render(self.world.model, self.world.data)

    def close(self) -> None:
        """Free the renderers (calling it again is harmless)."""
        self.frames.close()
        self.world.close()

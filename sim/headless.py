"""Choosing MuJoCo's OpenGL backend explicitly, instead of as a side effect of an import.

MuJoCo reads ``MUJOCO_GL`` once, when ``mujoco`` is first imported; without a display it needs
``egl`` (Mesa's software renderer on CPU). Applications call ``use_headless_rendering()``
before they import ``sim.world`` (the robot application does so when the ``garbage``
environment or a robot command is first used); a backend the caller already chose is kept.
"""

from __future__ import annotations

import os

DEFAULT_BACKEND = "egl"


def use_headless_rendering(backend: str = DEFAULT_BACKEND) -> str:
    """Set ``MUJOCO_GL`` to ``backend`` unless it is already set; returns the backend in force."""
    return os.environ.setdefault("MUJOCO_GL", backend)

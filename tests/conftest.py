"""Shared pytest set-up: MuJoCo renders headless (EGL) unless the caller chose a backend."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

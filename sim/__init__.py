"""MuJoCo worlds: the garbage cans (ch. 5-6), navigation and stacking (ch. 3), head search (App. A).

Importing any of them selects headless EGL rendering unless ``MUJOCO_GL`` says otherwise, so
scenes render on machines without a display.
"""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

"""MuJoCo worlds: the garbage cans (ch. 5-6), navigation and stacking (ch. 3), head search (App. A).

Scenes as data, world wrappers, rendering; imports nothing of goalagent, behaviours or robot.
No import sets ``MUJOCO_GL``: call ``sim.headless.use_headless_rendering()`` before importing a
world (or set ``MUJOCO_GL=egl``) so scenes render on machines without a display.
"""

"""The thesis's robot tasks as Gymnasium environments (docs/gymnasium.md).

``goalagent/Navigation-v0``, ``goalagent/Stacking-v0`` and ``goalagent/HeadSearch-v0``
(``robot.gym.tasks``: chapter 3 and App. A) and ``goalagent/CanOpening-v0``
(``robot.gym.can_opening``: chapter 4), registered by ``robot.gym.registration``, whose
factories choose headless rendering (``MUJOCO_GL=egl``) unless a backend is already set, before
MuJoCo is imported. Importing the package sets nothing.
"""

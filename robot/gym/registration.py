"""The goalagent environments' Gymnasium ids, registered with ``gymnasium.register``.

``register_envs()`` is what makes ``gymnasium.make("goalagent/Navigation-v0")`` work. It runs
by itself when Gymnasium is first imported (``robot/gym_plugin.py`` sees to that, since
Gymnasium 1.x no longer reads plugin entry points); calling it again is harmless. Entry points
are strings, so registering imports nothing of the environments: MuJoCo and the worlds load at
the first ``make``.
"""

from __future__ import annotations

ENV_IDS: dict[str, str] = {
    "goalagent/Navigation-v0": "robot.gym.tasks:NavigationEnv",
    "goalagent/Stacking-v0": "robot.gym.tasks:StackingEnv",
    "goalagent/HeadSearch-v0": "robot.gym.tasks:HeadSearchEnv",
    "goalagent/CanOpening-v0": "robot.gym.can_opening:CanOpeningEnv",
}
"""Every id and the class it makes."""


def register_envs() -> None:
    """Register every id (again: an id already registered by this function is left as is)."""
    from gymnasium.envs.registration import register, registry

    for env_id, entry_point in ENV_IDS.items():
        if env_id not in registry:
            register(id=env_id, entry_point=entry_point)

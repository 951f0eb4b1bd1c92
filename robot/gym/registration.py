"""The goalagent environments' Gymnasium ids, registered with ``gymnasium.register``.

``register_envs()`` is what makes ``gymnasium.make("goalagent/Navigation-v0")`` work. It runs
by itself when Gymnasium is first imported (``robot/gym_plugin.py`` sees to that, since
Gymnasium 1.x no longer reads plugin entry points); calling it again is harmless. Entry points
are strings naming this module's factories, so registering imports nothing of the environments:
MuJoCo and the worlds load at the first ``make``, after the factory has chosen headless
rendering (``MUJOCO_GL=egl`` unless a backend is already set). No import sets the variable: a
program that imports ``robot.gym.tasks`` itself calls ``sim.headless.use_headless_rendering()``
first, as for any world.
"""

from __future__ import annotations

import functools
import importlib
from typing import Any

from sim.headless import use_headless_rendering

CLASSES: dict[str, str] = {
    "goalagent/Navigation-v0": "robot.gym.tasks:NavigationEnv",
    "goalagent/Stacking-v0": "robot.gym.tasks:StackingEnv",
    "goalagent/HeadSearch-v0": "robot.gym.tasks:HeadSearchEnv",
    "goalagent/CanOpening-v0": "robot.gym.can_opening:CanOpeningEnv",
}
"""Every id and the class it makes."""


def _make(env_id: str, **kwargs: Any) -> Any:
    """Choose headless rendering, then import and build ``env_id``'s class."""
    use_headless_rendering()
    module_name, class_name = CLASSES[env_id].split(":")
    return getattr(importlib.import_module(module_name), class_name)(**kwargs)


make_navigation = functools.partial(_make, "goalagent/Navigation-v0")
make_stacking = functools.partial(_make, "goalagent/Stacking-v0")
make_head_search = functools.partial(_make, "goalagent/HeadSearch-v0")
make_can_opening = functools.partial(_make, "goalagent/CanOpening-v0")
"""The entry points: each builds its id's class (``_make``)."""


ENV_IDS: dict[str, str] = {
    "goalagent/Navigation-v0": "robot.gym.registration:make_navigation",
    "goalagent/Stacking-v0": "robot.gym.registration:make_stacking",
    "goalagent/HeadSearch-v0": "robot.gym.registration:make_head_search",
    "goalagent/CanOpening-v0": "robot.gym.registration:make_can_opening",
}
"""Every id and the entry point Gymnasium calls for it."""


def register_envs() -> None:
    """Register every id (again: an id already registered by this function is left as is)."""
    from gymnasium.envs.registration import register, registry

    for env_id, entry_point in ENV_IDS.items():
        if env_id not in registry:
            register(id=env_id, entry_point=entry_point)

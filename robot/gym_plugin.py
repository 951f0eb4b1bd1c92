"""Registers the goalagent environments the moment Gymnasium is imported, in any program.

Gymnasium 1.x dropped its ``gymnasium.envs`` plugin entry points, so an installed package has
no hook of Gymnasium's own to register its ids. The ``goalagent-gymnasium.pth`` file that
installing goalagent puts in site-packages runs ``install()`` at interpreter start: it adds a
one-shot import hook that, right after the ``gymnasium`` package has finished loading, calls
``robot.gym.registration.register_envs()``. Nothing else is imported at start (no MuJoCo, no
Gymnasium), and a program that never imports Gymnasium pays for one finder on
``sys.meta_path`` until it does.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import importlib.util
import sys
from types import ModuleType

TARGET = "gymnasium"


class _Loader(importlib.abc.Loader):
    """Gymnasium's own loader, then the registration."""

    def __init__(self, loader: importlib.abc.Loader):
        self.loader = loader

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType | None:
        return self.loader.create_module(spec)

    def exec_module(self, module: ModuleType) -> None:
        self.loader.exec_module(module)
        from robot.gym.registration import register_envs

        register_envs()


class _GymnasiumHook(importlib.abc.MetaPathFinder):
    """Finds ``gymnasium`` as the other finders do, with the registration after its loader."""

    def find_spec(self, name: str, path: object, target: ModuleType | None = None
                  ) -> importlib.machinery.ModuleSpec | None:
        if name != TARGET:
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.loader is not None:
            spec.loader = _Loader(spec.loader)
        return spec


def install() -> None:
    """Register now if Gymnasium is already loaded, else when it is (once per process)."""
    if TARGET in sys.modules:
        from robot.gym.registration import register_envs

        register_envs()
    elif not any(isinstance(finder, _GymnasiumHook) for finder in sys.meta_path):
        sys.meta_path.insert(0, _GymnasiumHook())

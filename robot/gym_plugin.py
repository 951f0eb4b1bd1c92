"""Registers the goalagent environments the moment Gymnasium is imported, in any program.

Gymnasium 1.x dropped its ``gymnasium.envs`` plugin entry points, so an installed package has
no hook of Gymnasium's own to register its ids. The ``goalagent-gymnasium.pth`` file that
installing goalagent puts in site-packages runs ``install()`` at interpreter start: it adds a
one-shot import hook that, right after the ``gymnasium`` package has finished loading, calls
``robot.gym.registration.register_envs()``. Nothing else is imported at start (no MuJoCo, no
Gymnasium, not even ``typing``: the module costs Python's start about 2 ms), and a program
that never imports Gymnasium pays for one finder on ``sys.meta_path`` until it does.
"""

from __future__ import annotations

import importlib.util
import sys

TYPE_CHECKING = False  # not typing's: importing typing (or importlib.abc) at every start of
if TYPE_CHECKING:      # Python would cost it 20-50 ms
    from importlib.abc import Loader
    from importlib.machinery import ModuleSpec
    from types import ModuleType

TARGET = "gymnasium"


class _Loader:
    """Gymnasium's own loader, then the registration."""

    def __init__(self, loader: Loader):
        self.loader = loader

    def create_module(self, spec: ModuleSpec) -> ModuleType | None:
        return self.loader.create_module(spec)

    def exec_module(self, module: ModuleType) -> None:
        self.loader.exec_module(module)
        from robot.gym.registration import register_envs

        register_envs()


class _GymnasiumHook:
    """Finds ``gymnasium`` as the other finders do, with the registration after its loader."""

    def find_spec(self, name: str, path: object, target: ModuleType | None = None
                  ) -> ModuleSpec | None:
        if name != TARGET:
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.loader is not None:
            spec.loader = _Loader(spec.loader)  # type: ignore[assignment]
        return spec


def install() -> None:
    """Register now if Gymnasium is already loaded, else when it is (once per process)."""
    if TARGET in sys.modules:
        from robot.gym.registration import register_envs

        register_envs()
    elif not any(isinstance(finder, _GymnasiumHook) for finder in sys.meta_path):
        sys.meta_path.insert(0, _GymnasiumHook())

"""Finding environments by registered name or by ``package.module:Class`` path.

Built-in environments are registered lazily as import paths, so naming one costs nothing until
it is loaded. Applications add theirs through an extension (``goalagent.extensions``): the
robot application's ``garbage`` imports MuJoCo only when an agent asks for it.

GOAL programs name their environment by its jar file (``env = "bw4t-client-3.8.0.jar"``,
``use "ElevatorSim-1.3.2.jar" as environment``); ``_JARS`` maps the jar names of the
environments goalagent has in Python to their registered names.
"""

from __future__ import annotations

import importlib
import os
import re
import sys
from collections.abc import Callable
from types import ModuleType
from typing import TypeVar, overload

from goalagent.eis.exceptions import ManagementException, NoEnvironmentException
from goalagent.eis.interface import Environment
from goalagent.extensions import Extension, installed_extensions
from goalagent.extras import install_hint

E = TypeVar("E", bound=type[Environment])

_REGISTRY: dict[str, type[Environment] | str] = {
    "blocksworld": "goalagent.eis.envs.blocksworld:BlocksWorld",
    "towerworld": "goalagent.eis.envs.towerworld:TowerWorld",
    "printer": "goalagent.eis.envs.printer:Printer",
    "bw4t": "goalagent.eis.envs.bw4t.environment:BW4T",
    "bw4t-3.8": "goalagent.eis.envs.bw4t.environment:BW4T38",
    "bw4t-2": "goalagent.eis.envs.bw4t.environment:BW4T2",
    "elevator": "goalagent.eis.envs.elevator.environment:Elevator",
    "hanoi": "goalagent.eis.envs.hanoi:Hanoi",
}
_FROM_EXTENSION: dict[str, Extension] = {}
"""Names an extension registered, with that extension (prepared before the first import)."""
_extensions_registered = False


def _register_extensions() -> None:
    """Add the installed extensions' environment names, once; a clash is skipped, not fatal."""
    global _extensions_registered
    if _extensions_registered:
        return
    _extensions_registered = True
    for extension in installed_extensions():
        for name, path in extension.environments.items():
            try:
                register_environment(name, path)
            except (ManagementException, TypeError) as error:
                print(f"warning: goalagent extension {extension.name!r}: {error}",
                      file=sys.stderr)
                continue
            _FROM_EXTENSION[name] = extension


def _path_of(cls: type) -> str:
    return f"{cls.__module__}:{cls.__qualname__}"


@overload
def register_environment(name: str) -> Callable[[E], E]: ...


@overload
def register_environment(name: str, target: E | str) -> E | str: ...


def register_environment(name: str, target: E | str | None = None) -> object:
    """Register an environment class (or its ``module:Class`` path) under ``name``.

    Use as ``@register_environment("name")`` on a class or call it with the class or path.
    Registering a name again for a different environment is a ManagementException.
    """

    def register(value: E | str) -> E | str:
        if not isinstance(value, str) and not (
            isinstance(value, type) and issubclass(value, Environment)
        ):
            raise TypeError(f"register_environment({name!r}) needs an Environment subclass")
        old = _REGISTRY.get(name)
        if old is not None:
            old_path = old if isinstance(old, str) else _path_of(old)
            new_path = value if isinstance(value, str) else _path_of(value)
            if old_path != new_path:
                raise ManagementException(
                    f"environment name '{name}' is already registered for {old_path}"
                )
            if isinstance(old, type) and isinstance(value, str):
                return value
        _REGISTRY[name] = value
        return value

    if target is not None:
        return register(target)
    return register


# Jar file name (any folder, any case) -> registered name, first match. BW4T's vocabulary
# changed in 3.8.4 and 3.9 (see goalagent/eis/envs/README.md); BW4T 2's is that of 3.8.0.
_JARS: list[tuple[re.Pattern[str], str]] = [
    (re.compile(r"bw4t-client-3\.8\.[4-9]\b.*\.jar"), "bw4t-3.8"),
    (re.compile(r"bw4t-client-3\.[0-8](\.\d+)?\b.*\.jar|bw4tclient\.jar"), "bw4t-2"),
    (re.compile(r"bw4t-client-\d+(\.\d+)*\b.*\.jar|bw4t.*\.jar"), "bw4t"),
    (re.compile(r"(elevatorsim|elevatorenv|elevator).*\.jar"), "elevator"),
    (re.compile(r"hanoi.*\.jar"), "hanoi"),
    (re.compile(r"blocksworld.*\.jar"), "blocksworld"),
    (re.compile(r"tower.*\.jar"), "towerworld"),
    (re.compile(r"helloworldenvironment.*\.jar"), "printer"),
]


def _jar_name(spec: str) -> str | None:
    """The registered name for an environment jar file name, if goalagent has it."""
    base = re.split(r"[/\\]", spec)[-1].lower()
    for pattern, name in _JARS:
        if pattern.fullmatch(base):
            return name
    return None


def known_environments() -> list[str]:
    """The registered environment names (built in and from extensions), sorted."""
    _register_extensions()
    return sorted(_REGISTRY)


def _import_here_too(module_name: str) -> ModuleType:
    """Import a module, also from the current directory: ``goalagent`` is a console script,
    whose ``sys.path`` starts at its own folder, not where the user runs it."""
    try:
        return importlib.import_module(module_name)
    except ModuleNotFoundError as error:
        here = os.getcwd()
        top = module_name.partition(".")[0]
        if error.name != top or here in sys.path or "" in sys.path:
            raise
        sys.path.append(here)
        return importlib.import_module(module_name)


def _import_path(spec: str) -> type[Environment]:
    """Import ``package.module:Class`` and check it is an Environment subclass."""
    module_name, _, attr = spec.partition(":")
    if not module_name or not attr:
        raise NoEnvironmentException(
            f"'{spec}' is not of the form package.module:Class"
        )
    try:
        module = _import_here_too(module_name)
    except ImportError as error:
        hint = install_hint(error.name) if isinstance(error, ModuleNotFoundError) else None
        raise NoEnvironmentException(
            f"cannot load environment '{spec}': it {hint}" if hint else
            f"cannot load environment '{spec}': {error}"
        ) from error
    target: object = module
    for part in attr.split("."):
        if not hasattr(target, part):
            raise NoEnvironmentException(
                f"cannot load environment '{spec}': module '{module_name}' has no '{attr}'"
            )
        target = getattr(target, part)
    if not (isinstance(target, type) and issubclass(target, Environment)):
        raise NoEnvironmentException(
            f"'{spec}' is not an environment (not a subclass of goalagent.eis.Environment)"
        )
    return target


def load_environment(spec: str) -> type[Environment]:
    """The environment class for a registered name or a ``package.module:Class`` path."""
    _register_extensions()
    entry = _REGISTRY.get(spec)
    if entry is None and spec.lower().endswith(".jar") and _jar_name(spec) is not None:
        return load_environment(str(_jar_name(spec)))
    if entry is None:
        if ":" not in spec:
            raise NoEnvironmentException(
                f"unknown environment '{spec}' (known: {', '.join(known_environments())}; "
                "or give package.module:Class)"
            )
        return _import_path(spec)
    if isinstance(entry, str):
        if spec in _FROM_EXTENSION:
            _FROM_EXTENSION[spec].ensure_prepared()
        cls = _import_path(entry)
        _REGISTRY[spec] = cls
        return cls
    return entry

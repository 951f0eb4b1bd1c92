"""Environment registry: built-in names, package.module:Class paths and clear errors."""

from __future__ import annotations

import pytest

from goalagent.eis import (
    ManagementException,
    NoEnvironmentException,
    PythonEnvironment,
    known_environments,
    load_environment,
    register_environment,
)
from goalagent.eis.envs.blocksworld import BlocksWorld
from goalagent.eis.envs.printer import Printer
from goalagent.eis.envs.towerworld import TowerWorld


def test_builtin_names() -> None:
    assert load_environment("blocksworld") is BlocksWorld
    assert load_environment("towerworld") is TowerWorld
    assert load_environment("printer") is Printer
    assert {"blocksworld", "towerworld", "printer", "garbage"} <= set(known_environments())


def test_module_class_paths() -> None:
    assert load_environment("goalagent.eis.envs.printer:Printer") is Printer


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("blockworld", r"unknown environment 'blockworld' \(known: blocksworld, .*garbage,"),
        ("no.such.module:Env", "cannot load environment 'no.such.module:Env': No module"),
        ("goalagent.eis.envs.printer:Nope", "module 'goalagent.eis.envs.printer' has no 'Nope'"),
        ("goalagent.eis.terms:Percept", "not an environment"),
        ("goalagent.eis:", "not of the form package.module:Class"),
    ],
)
def test_unknown_environments_are_clear_errors(spec: str, message: str) -> None:
    with pytest.raises(NoEnvironmentException, match=message):
        load_environment(spec)


def test_register_by_decorator_and_clash() -> None:
    @register_environment("test-registry-env")
    class Mine(PythonEnvironment):
        name = "mine"

    assert load_environment("test-registry-env") is Mine
    register_environment("test-registry-env", Mine)  # same class again: fine

    class Other(PythonEnvironment):
        name = "other"

    with pytest.raises(ManagementException, match="already registered for .*Mine"):
        register_environment("test-registry-env", Other)
    with pytest.raises(ManagementException, match="already registered"):
        register_environment("printer", Other)
    with pytest.raises(TypeError, match="needs an Environment subclass"):
        register_environment("x", int)  # type: ignore[arg-type]

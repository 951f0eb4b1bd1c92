"""The layers, one way, on every import in the tree (README "Architecture").

``lint-imports`` (pyproject.toml) checks the same contract in ``make test``; this check reads
the sources itself with ``ast``, so imports inside functions and ``TYPE_CHECKING`` blocks count
as much as those at the top of a module, and it runs with the suite.
"""

from __future__ import annotations

import ast
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("goalagent", "sim", "behaviours", "robot", "ondisk")
ALLOWED: dict[str, frozenset[str]] = {
    "ondisk": frozenset(),  # files on disk, the lowest layer: imports nothing of ours
    "goalagent": frozenset({"ondisk"}),  # the language knows no world, behaviour or robot
    "sim": frozenset({"ondisk"}),  # the worlds import nothing of ours but ondisk
    "behaviours": frozenset({"sim", "ondisk"}),
    "robot": frozenset({"goalagent", "behaviours", "sim", "ondisk"}),  # the application, on top
}
LEARNERS = ("behaviours", "learners")
LEARNER_LIBRARIES = frozenset({"numpy", "scipy", "sklearn", "ondisk"})
"""Pure learners import only these, the standard library and other learners (ondisk: their
stores are written atomically like every other file)."""


def module_name(path: Path) -> str:
    """``goalagent/eis/registry.py`` -> ``goalagent.eis.registry`` (packages by their folder)."""
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imported_modules(source: str, module: str, is_package: bool) -> Iterator[tuple[int, str]]:
    """(line, absolute module name) of every import in ``source``, wherever it stands."""
    package = module if is_package else module.rpartition(".")[0]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node.lineno, alias.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:  # relative: resolve against this module's package
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            yield node.lineno, target


def broken_layers(source: str, module: str, is_package: bool = False) -> list[str]:
    """Every import in ``source`` (of ``module``) that runs against the layers."""
    own = module.split(".")[0]
    problems = []
    for line, target in imported_modules(source, module, is_package):
        other = target.split(".")[0]
        if other in PACKAGES and other != own and other not in ALLOWED[own]:
            problems.append(f"{module}:{line} imports {target} ({own} may not use {other})")
        if tuple(module.split(".")[:2]) == LEARNERS and not _learner_may_import(target):
            problems.append(f"{module}:{line} imports {target} (learners are pure: numpy, "
                            "scipy, scikit-learn, the standard library and other learners)")
    return problems


def _learner_may_import(target: str) -> bool:
    top = target.split(".")[0]
    return (top in LEARNER_LIBRARIES or top in sys.stdlib_module_names or top == "__future__"
            or tuple(target.split(".")[:2]) == LEARNERS)


def sources() -> Iterator[tuple[Path, str]]:
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            yield path, module_name(path)


def package_graph() -> dict[str, set[str]]:
    """Top-level package -> the other top-level packages it imports (anywhere in a file)."""
    graph: dict[str, set[str]] = {package: set() for package in PACKAGES}
    for path, module in sources():
        own = module.split(".")[0]
        for _, target in imported_modules(path.read_text(), module, path.name == "__init__.py"):
            other = target.split(".")[0]
            if other in PACKAGES and other != own:
                graph[own].add(other)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of the graph as a path (first node repeated at the end), or None."""
    state: dict[str, str] = {}

    def visit(node: str, path: list[str]) -> list[str] | None:
        state[node] = "open"
        for successor in sorted(graph.get(node, ())):
            if state.get(successor) == "open":
                return path[path.index(successor):] + [successor]
            if successor not in state:
                found = visit(successor, path + [successor])
                if found:
                    return found
        state[node] = "done"
        return None

    for start in sorted(graph):
        if start not in state:
            found = visit(start, [start])
            if found:
                return found
    return None


def test_no_import_in_the_tree_breaks_a_layer():
    problems = [problem for path, module in sources()
                for problem in broken_layers(path.read_text(), module, path.name == "__init__.py")]
    assert problems == []


def test_the_package_graph_is_the_layer_picture_and_has_no_cycle():
    graph = package_graph()
    assert find_cycle(graph) is None
    assert graph["robot"] == {"goalagent", "behaviours", "sim", "ondisk"}
    assert graph["behaviours"] == {"sim", "ondisk"}
    assert graph["goalagent"] == {"ondisk"} and graph["sim"] <= {"ondisk"}
    assert graph["ondisk"] == set()


@pytest.mark.parametrize(("module", "source", "expected"), [
    ("sim.world", "def f():\n    from behaviours import skills\n",
     "sim.world:2 imports behaviours (sim may not use behaviours)"),
    ("goalagent.cli", "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import robot.cli\n",
     "goalagent.cli:3 imports robot.cli (goalagent may not use robot)"),
    ("behaviours.learning", "from ..goalagent.kb import terms\n",
     "behaviours.learning:1 imports goalagent.kb (behaviours may not use goalagent)"),
    ("behaviours.learners.xcs", "import mujoco\n",
     "behaviours.learners.xcs:1 imports mujoco (learners are pure"),
    ("behaviours.learners.xcs", "from behaviours.skills import ACTION_TYPES\n",
     "behaviours.learners.xcs:1 imports behaviours.skills (learners are pure"),
    ("ondisk.atomic", "def f():\n    import sim\n",
     "ondisk.atomic:2 imports sim (ondisk may not use sim)"),
])
def test_the_check_sees_imports_inside_functions_type_checking_and_relative(module, source,
                                                                            expected):
    (problem,) = broken_layers(source, module)
    assert problem.startswith(expected)


def test_allowed_imports_pass_the_check():
    assert broken_layers("import numpy\nfrom sklearn.base import clone\n"
                         "from behaviours.learners.common import fit\n"
                         "from . import forward\n", "behaviours.learners.xcs") == []
    assert broken_layers("from goalagent.eis import PythonEnvironment\nimport sim.world\n"
                         "from behaviours import skills\n", "robot.envs.garbage") == []


def test_a_cycle_is_found():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None

"""The layers, one way, on every import in the tree (docs/architecture.md).

``lint-imports`` (pyproject.toml) checks the same contract in ``make test``; this check reads
the sources itself with ``ast``, so imports inside functions and ``TYPE_CHECKING`` blocks count
as much as those at the top of a module, and it runs with the suite. The same reading finds
import cycles between files: every import that runs counts, inside functions too (an import
under ``if TYPE_CHECKING:`` only names a type for annotations and never runs).
"""

from __future__ import annotations

import ast
import sys
from collections.abc import Collection, Iterable, Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("goalagent", "sim", "behaviours", "robot", "ondisk")
ALLOWED: dict[str, frozenset[str]] = {
    "ondisk": frozenset(),  # files on disk, the lowest layer: imports nothing of ours
    "goalagent": frozenset({"ondisk"}),  # the language knows no world, behaviour or robot
    "sim": frozenset({"ondisk"}),  # the worlds import nothing of ours but ondisk
    "behaviours": frozenset({"sim", "ondisk"}),
    "robot": frozenset({"goalagent", "behaviours", "sim", "ondisk"}),  # the application, on top
}
LEARNERS = ("behaviours", "learners")
LEARNER_LIBRARIES = frozenset({"numpy", "scipy", "sklearn", "ondisk", "fastjsonschema"})
"""Pure learners import only these, the standard library and other learners (ondisk: their
stores are written atomically like every other file; fastjsonschema: their stores are checked
against their JSON Schemas)."""


def module_name(path: Path) -> str:
    """``goalagent/eis/registry.py`` -> ``goalagent.eis.registry`` (packages by their folder)."""
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imported_modules(source: str, module: str, is_package: bool, *, runtime_only: bool = False,
                     submodules: Collection[str] = ()) -> Iterator[tuple[int, str]]:
    """(line, absolute module name) of every import in ``source``, wherever it stands;
    ``runtime_only``: not those in ``if TYPE_CHECKING:`` blocks (they never run); a name
    ``from``-imported that is one of ``submodules`` counts as that module."""
    package = module if is_package else module.rpartition(".")[0]
    for node in _imports(ast.parse(source), runtime_only):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node.lineno, alias.name
        else:
            if node.level:  # relative: resolve against this module's package
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            for alias in node.names:
                submodule = f"{target}.{alias.name}"
                yield node.lineno, submodule if submodule in submodules else target


def _imports(node: ast.AST, runtime_only: bool) -> Iterator[ast.Import | ast.ImportFrom]:
    """The import statements in ``node`` (at any depth: in functions, classes, branches)."""
    if isinstance(node, (ast.Import, ast.ImportFrom)):
        yield node
        return
    children: Iterable[ast.AST] = ast.iter_child_nodes(node)
    if runtime_only and isinstance(node, ast.If) and _is_type_checking(node.test):
        children = node.orelse
    for child in children:
        yield from _imports(child, runtime_only)


def _is_type_checking(test: ast.expr) -> bool:
    """``TYPE_CHECKING`` or ``typing.TYPE_CHECKING``."""
    return ((isinstance(test, ast.Name) and test.id == "TYPE_CHECKING")
            or (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"))


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


def file_graph(files: Iterable[tuple[str, str, bool]]) -> dict[str, set[str]]:
    """Module -> the modules of the tree it imports when it runs (module ``files`` as
    (name, source, is_package)), imports inside functions included; a package's
    ``__init__`` is a module of its own."""
    files = list(files)
    modules = {module for module, _, _ in files}
    graph: dict[str, set[str]] = {}
    for module, source, is_package in files:
        graph[module] = set()
        for _, target in imported_modules(source, module, is_package, runtime_only=True,
                                          submodules=modules):
            while target not in modules and "." in target:
                target = target.rpartition(".")[0]
            if target in modules and target != module:
                graph[module].add(target)
    return graph


def tree_files() -> Iterator[tuple[str, str, bool]]:
    """The tree's modules as :func:`file_graph` reads them."""
    for path, module in sources():
        yield module, path.read_text(), path.name == "__init__.py"


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


def test_no_import_cycle_between_files():
    assert find_cycle(file_graph(tree_files())) is None


def test_a_file_cycle_hidden_in_a_function_is_found_and_one_of_annotations_is_not():
    hidden = [("sim.scene", "def load():\n    from sim.canfile import load_can\n", False),
              ("sim.canfile", "from sim.scene import CanSpec\n", False)]
    assert find_cycle(file_graph(hidden)) == ["sim.canfile", "sim.scene", "sim.canfile"]
    annotations = [("a.cycle", "from a.rules import RuleApplication\n", False),
                   ("a.rules", "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
                               "    from a.cycle import Agent\n", False)]
    assert find_cycle(file_graph(annotations)) is None
    submodule = [("a", "from a import b\n", True), ("a.b", "import a\n", False)]
    assert find_cycle(file_graph(submodule)) == ["a", "a.b", "a"]

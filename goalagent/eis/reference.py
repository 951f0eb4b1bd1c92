"""The reference of an environment, read from its code: what the documentation site shows
for every shipped environment (docs/hooks/generated_pages.py), so that it cannot drift.

Read from the class: its description (docstring), init parameters (those it declares) with
their defaults (the fallbacks its code reads them with, found in the source of its module and
its bases' by ``ast``: ``params.get("seed", 0)``, ``int_param(name, params, "ticks", 4)``, a
constant or class attribute named there is looked up), actions (the ``@action`` methods:
parameters with their types, what the method's docstring says); from running it: the
entities and the percepts of an agent's first cycle with the default init parameters.
Environments are found through the registry, so the robot application's come through its
extension like any other.
"""

from __future__ import annotations

import ast
import inspect
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from goalagent.eis.interface import Environment
from goalagent.eis.pyenv import PythonEnvironment, describe_hint
from goalagent.eis.registry import known_environments, load_environment
from goalagent.kb.engine import get_engine
from goalagent.kb.terms import Atom, Struct, format_term

_READER = "reader"  # the agent registered to read the first percepts
_MISSING = object()


@dataclass(frozen=True)
class Parameter:
    """One init parameter: its name, what it does (or its type) and its default as the code
    has it (None: none found)."""

    name: str
    meaning: str
    default: str | None


@dataclass(frozen=True)
class ActionDoc:
    """One action: its name, parameters (name: what it takes; optional ones in brackets) and
    the first line of its method's docstring."""

    name: str
    parameters: tuple[str, ...]
    does: str


@dataclass(frozen=True)
class EnvironmentDoc:
    """What the reference says of one registered environment."""

    name: str
    path: str
    summary: str
    parameters: tuple[Parameter, ...]
    actions: tuple[ActionDoc, ...]
    entities: tuple[tuple[str, str], ...]
    percepts: tuple[str, ...]  # the first cycle's, as Prolog text, in the order given


def _summary(cls: type) -> str:
    """The first paragraph of the class docstring, on one line."""
    text = inspect.getdoc(cls) or ""
    return " ".join(text.split("\n\n", 1)[0].split())


def _declared(cls: type[Environment]) -> dict[str, str]:
    """Init parameter -> what it does (or its type), as the class declares them
    (``Environment.init_parameters``)."""
    return dict(cls.init_parameters() or {})


def _value(node: ast.expr, cls: type, module_globals: dict[str, object]) -> object:
    """The value of a default written as a literal, a module constant or ``self.X``/``cls.X``
    (``_MISSING`` for anything else)."""
    try:
        return ast.literal_eval(node)
    except ValueError:
        pass
    if isinstance(node, ast.Name):
        return module_globals.get(node.id, _MISSING)
    if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and \
            isinstance(node.slice, ast.Constant):  # CONSTANTS[0]
        table = module_globals.get(node.value.id)
        try:
            return table[node.slice.value] if table is not None else _MISSING  # type: ignore
        except (IndexError, KeyError, TypeError):
            return _MISSING
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) \
            and node.value.id in ("self", "cls"):
        return getattr(cls, node.attr, _MISSING)
    return _MISSING


def _defaults_in(source_of: type, cls: type) -> Iterator[tuple[str, object]]:
    """(key, default) of the init parameters read in ``source_of``'s module with a fallback:
    ``params.get("key", D)`` or ``*_param(..., params, "key", D, ...)``."""
    module = inspect.getmodule(source_of)
    if module is None or module.__file__ is None:
        return
    tree = ast.parse(Path(module.__file__).read_text())
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        func, args = node.func, node.args
        if isinstance(func, ast.Attribute) and func.attr == "get" and \
                isinstance(func.value, ast.Name) and func.value.id == "params" and len(args) == 2:
            key, default = args
        elif isinstance(func, ast.Name) and func.id.endswith("_param") and len(args) >= 4 and \
                isinstance(args[1], ast.Name) and args[1].id == "params":
            key, default = args[2], args[3]
        else:
            continue
        if isinstance(key, ast.Constant) and isinstance(key.value, str):
            value = _value(default, cls, vars(module))
            if value is not _MISSING and value != "":  # ("": none, as a text parameter's)
                yield key.value, value


def _shown(value: object) -> str:
    """A default as an agent programmer writes it (Prolog text that reads back as it)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float, list)):
        return format_term(value)
    return format_term(Atom(str(value)))


def _parameters(cls: type[Environment]) -> tuple[Parameter, ...]:
    """The declared init parameters with the defaults their code reads them with (the class's
    own module first, then its bases')."""
    defaults: dict[str, object] = {}
    for base in cls.__mro__:
        if isinstance(base, type) and issubclass(base, Environment) and base is not Environment:
            for key, value in _defaults_in(base, cls):
                defaults.setdefault(key, value)
    return tuple(Parameter(key, meaning, _shown(defaults[key]) if key in defaults else None)
                 for key, meaning in _declared(cls).items())


def _actions(cls: type[Environment]) -> tuple[ActionDoc, ...]:
    """The ``@action`` methods of a Python environment, by name."""
    if not issubclass(cls, PythonEnvironment):
        return ()
    found = []
    for name in cls.action_names():
        spec = cls._actions[name]
        shown = [f"{pname}: {describe_hint(hint)}" for pname, hint in spec.params]
        shown[spec.required:] = [f"[{item}]" for item in shown[spec.required:]]
        doc = inspect.getdoc(getattr(cls, spec.method)) or ""
        found.append(ActionDoc(name, tuple(shown), " ".join(doc.split("\n\n", 1)[0].split())))
    return tuple(found)


def describe(name: str) -> EnvironmentDoc:
    """The reference of the environment registered as ``name``: read from its class, and
    from an instance made with the default init parameters (killed afterwards)."""
    cls = load_environment(name)
    environment = cls()
    try:
        environment.init({})
        environment.start()
        entities = tuple((entity, environment.entity_type(entity))
                         for entity in environment.entities())
        percepts: tuple[str, ...] = ()
        if entities:
            environment.register_agent(_READER)
            environment.associate_entity(_READER, entities[0][0])
            first = environment.get_all_percepts(_READER)[entities[0][0]]
            percepts = tuple(str(percept) for percept in first)
    finally:
        environment.kill()
    return EnvironmentDoc(name, f"{cls.__module__}:{cls.__qualname__}", _summary(cls),
                          _parameters(cls), _actions(cls), entities, percepts)


def _cell(text: str) -> str:
    """Text for a Markdown table cell."""
    return text.replace("|", "\\|").replace("\n", " ")


def markdown(doc: EnvironmentDoc) -> str:
    """The reference of one environment as a Markdown section."""
    lines = [f"## `{doc.name}`", "", doc.summary, "",
             f"Class `{doc.path}`. Entities with the default init parameters: " +
             (", ".join(f"`{entity}` (type `{kind}`)" for entity, kind in doc.entities)
              or "none") + ".", ""]
    lines += ["### Init parameters", ""]
    if doc.parameters:
        lines += ["| parameter | default | what it does |", "| --- | --- | --- |"]
        lines += [f"| `{p.name}` | {f'`{_cell(p.default)}`' if p.default is not None else ''} "
                  f"| {_cell(p.meaning)} |" for p in doc.parameters]
    else:
        lines.append("None declared.")
    lines += ["", "### Actions", ""]
    if doc.actions:
        lines += ["| action | parameters | what it does |", "| --- | --- | --- |"]
        lines += [f"| `{a.name}` | {_cell(', '.join(a.parameters)) or 'none'} | {_cell(a.does)} |"
                  for a in doc.actions]
    else:
        lines.append("None.")
    lines += ["", f"### Percepts of an agent's first cycle (entity `{doc.entities[0][0]}`, "
              "default init parameters)" if doc.entities else "### Percepts", ""]
    groups = _grouped(doc.percepts)
    if groups:
        lines += ["| percept | how many | the first |", "| --- | --- | --- |"]
        lines += [f"| `{indicator}` | {len(texts)} | `{_cell(texts[0])}` |"
                  for indicator, texts in groups.items()]
    else:
        lines.append("None.")
    return "\n".join(lines) + "\n"


def _grouped(percepts: tuple[str, ...]) -> dict[str, list[str]]:
    """Percepts by ``name/arity``, in the order their first one came."""
    engine = get_engine()
    groups: dict[str, list[str]] = {}
    for text in percepts:
        term = engine.parse_term(text)
        indicator = (f"{term.name}/{term.arity}" if isinstance(term, Struct)
                     else f"{format_term(term)}/0")
        groups.setdefault(indicator, []).append(text)
    return groups


def reference() -> str:
    """The reference of every registered environment, as one Markdown page."""
    sections = [markdown(describe(name)) for name in known_environments()]
    return "\n".join(sections)

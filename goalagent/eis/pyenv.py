"""Writing EIS environments in plain Python: declare percepts and ``@action`` methods.

```python
class Printer(PythonEnvironment):
    name = "printer"
    def on_init(self, params: dict[str, object]) -> None: self.lines = 0
    def percepts(self, entity: str) -> list[PerceptLike]: return [("printedText", self.lines)]
    @action("printText")
    def print_text(self, entity: str, text: object) -> None: ...
```

Action parameters are converted to Python by the type hints of the method: ``str`` (an atom or
a string), ``int``, ``float`` (accepts integers too), ``bool`` (``true``/``false``), ``Path``
(``pathlib``: an atom or a string naming a file), ``list`` or ``list[X]``, ``Struct`` (a
compound term), an EIS parameter class (raw), ``object`` or no hint (``to_python``), or a union
of these, tried left to right (``bool | Path``). Wrong arity or type
is an ``ActException`` naming the action and what it expects; ``ActionRefused("why")`` refuses
(the method must then leave the world unchanged); any other exception becomes an
``ActException`` of kind failure wrapping it.

Percepts may be ``Percept`` objects, tuples ``("on", "a", "b")`` (shorthand values, see
``terms.to_parameter``), atoms/strings ``"ready"`` or kb terms (``Struct``). Init parameters go
through the same conversion when the class declares ``parameters = {"seed": int, ...}``
(unknown names are then an error), else they arrive as ``to_python`` values. An init parameter
declared ``Path`` (or a union with it) is a path: ``--env-param objects=db.json`` gives it the
file name as typed (``goalagent.mas.read_parameter``), where Prolog would read a term.
By default an environment has one entity (``entity_names`` of ``default_entity_type``, or
override ``initial_entities``); agents are associated with entities on request by the platform.
"""

from __future__ import annotations

import inspect
import types
import typing
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar, TypeVar

from goalagent.eis.exceptions import (
    ActException,
    ActExceptionKind,
    EnvironmentInterfaceException,
    ManagementException,
    PerceiveException,
)
from goalagent.eis.interface import Environment
from goalagent.eis.terms import (
    Action,
    Function,
    Identifier,
    Numeral,
    Parameter,
    ParameterList,
    Percept,
    TruthValue,
    percept_from_term,
    to_python,
)
from goalagent.kb.terms import Struct

__all__ = ["PerceptLike", "PythonEnvironment", "action"]

PerceptLike = Percept | tuple | str | Struct
F = TypeVar("F", bound=Callable[..., Any])
_ACTION_MARK = "__eis_action__"
_PARAMETER_CLASSES = (Identifier, Numeral, Function, ParameterList, TruthValue)


def action(name: str) -> Callable[[F], F]:
    """Mark a method ``(self, entity, *params)`` as the environment action ``name``."""
    if not isinstance(name, str) or not name:
        raise TypeError(f"@action needs a non-empty action name, got {name!r}")

    def mark(func: F) -> F:
        """Tag the method; ``PythonEnvironment`` collects tagged methods per class."""
        setattr(func, _ACTION_MARK, name)
        return func

    return mark


class _Mismatch(Exception):
    """A parameter that does not fit its type hint; the message says what was expected."""


def _alternatives(hint: object) -> tuple[object, ...]:
    """The members of a union hint (``bool | str``), or () for any other hint."""
    if typing.get_origin(hint) in (typing.Union, types.UnionType):
        return typing.get_args(hint)
    return ()


def describe_hint(hint: object) -> str:
    """Words for what a type hint accepts, used in error messages."""
    if _alternatives(hint):
        return " or ".join(describe_hint(alternative) for alternative in _alternatives(hint))
    if hint is str:
        return "a name or string"
    if hint is int:
        return "an integer"
    if hint is float:
        return "a number"
    if hint is bool:
        return "true or false"
    if hint is Path:
        return "a file path"
    if hint is Struct:
        return "a compound term"
    if hint is list or typing.get_origin(hint) is list:
        args = typing.get_args(hint)
        return f"a list, each element {describe_hint(args[0])}" if args else "a list"
    if isinstance(hint, type) and issubclass(hint, _PARAMETER_CLASSES):
        return f"an {hint.__name__}" if hint.__name__[0] in "AEIOU" else f"a {hint.__name__}"
    return "any term"


def _check_hint(hint: object, where: str) -> None:
    """Raise TypeError at class creation for a type hint the converter cannot honour."""
    if hint in (str, int, float, bool, Path, list, object, Any, Struct, Parameter):
        return
    if isinstance(hint, type) and issubclass(hint, _PARAMETER_CLASSES):
        return
    if _alternatives(hint):
        for alternative in _alternatives(hint):
            _check_hint(alternative, where)
        return
    if typing.get_origin(hint) is list:
        (item,) = typing.get_args(hint) or (object,)
        _check_hint(item, where)
        return
    raise TypeError(
        f"{where}: unsupported type hint {hint!r} (use str, int, float, bool, list, list[X], "
        "Struct, object or an EIS parameter class)"
    )


def _convert(param: Parameter, hint: object) -> object:
    """The Python value for ``param`` under ``hint``; raise _Mismatch when it does not fit."""
    if hint in (object, Any):
        return to_python(param)
    if hint is Parameter:
        return param
    if _alternatives(hint):
        for alternative in _alternatives(hint):
            try:
                return _convert(param, alternative)
            except _Mismatch:
                continue
    if isinstance(hint, type) and issubclass(hint, _PARAMETER_CLASSES):
        if isinstance(param, hint):
            return param
    elif hint is str:
        if isinstance(param, Identifier):
            return param.value
    elif hint is int:
        if isinstance(param, Numeral) and isinstance(param.value, int):
            return param.value
    elif hint is float:
        if isinstance(param, Numeral):
            return float(param.value)
    elif hint is Path:
        if isinstance(param, Identifier) and param.value:
            return Path(param.value)
    elif hint is bool:
        if isinstance(param, TruthValue):
            return param.value
        if isinstance(param, Identifier) and not param.string and param.value in ("true", "false"):
            return param.value == "true"
    elif hint is Struct:
        if isinstance(param, Function):
            return to_python(param)
    elif hint is list or typing.get_origin(hint) is list:
        if isinstance(param, ParameterList):
            (item,) = typing.get_args(hint) or (object,)
            try:
                return [_convert(element, item) for element in param.params]
            except _Mismatch:
                raise _Mismatch(describe_hint(hint)) from None
    raise _Mismatch(describe_hint(hint))


def _to_percept(item: object, env: str) -> Percept:
    """A Percept from the shorthand forms ``percepts()`` may return."""
    if isinstance(item, Percept):
        return item
    if isinstance(item, tuple) and item and isinstance(item[0], str):
        return Percept.of(item[0], *item[1:])
    if isinstance(item, str):
        return Percept(str(item))
    if isinstance(item, Struct):
        return percept_from_term(item)
    raise PerceiveException(
        f"environment '{env}' produced {item!r}, which is not a percept (use Percept, a tuple "
        "('name', value, ...), a name or a kb Struct)"
    )


@dataclass(frozen=True)
class _ActionSpec:
    """One ``@action`` method: its name, parameter names and hints, and required count."""

    name: str
    method: str
    params: tuple[tuple[str, object], ...]
    required: int

    def signature(self) -> str:
        """The action as users see it in messages, e.g. ``move(block: a name or string, ...)``."""
        shown = ", ".join(f"{pname}: {describe_hint(hint)}" for pname, hint in self.params)
        return f"{self.name}({shown})"


def _action_spec(cls: type, attr: str, func: Callable[..., Any], name: str) -> _ActionSpec:
    """Read an action's parameters from the method signature; TypeError for unusable ones."""
    where = f"{cls.__name__}.{attr} (@action {name!r})"
    sig = inspect.signature(func)
    params = list(sig.parameters.values())[1:]
    if not params:
        raise TypeError(f"{where}: the method needs (self, entity, *params)")
    try:
        hints = typing.get_type_hints(func)
    except Exception as error:
        raise TypeError(f"{where}: cannot read type hints: {error}") from error
    specs: list[tuple[str, object]] = []
    required = 0
    for param in params[1:]:
        if param.kind not in (param.POSITIONAL_ONLY, param.POSITIONAL_OR_KEYWORD):
            raise TypeError(f"{where}: parameter {param.name!r} must be plain positional")
        hint = hints.get(param.name, object)
        _check_hint(hint, where)
        specs.append((param.name, hint))
        if param.default is param.empty:
            required += 1
    return _ActionSpec(name, attr, tuple(specs), required)


class PythonEnvironment(Environment):
    """An environment written as Python methods; see the module docstring."""

    name: ClassVar[str] = "python"
    entity_names: ClassVar[tuple[str, ...]] = ("entity",)
    default_entity_type: ClassVar[str] = "entity"
    parameters: ClassVar[dict[str, object] | None] = None
    _actions: ClassVar[dict[str, _ActionSpec]] = {}

    def __init_subclass__(cls, **kwargs: Any) -> None:
        """Collect the ``@action`` methods of the class and its bases."""
        super().__init_subclass__(**kwargs)
        found: dict[str, _ActionSpec] = dict(cls._actions)
        for attr, value in vars(cls).items():
            name = getattr(value, _ACTION_MARK, None)
            if name is None:
                continue
            if name in found and found[name].method != attr:
                raise TypeError(
                    f"{cls.__name__}: action {name!r} is defined twice "
                    f"({found[name].method} and {attr})"
                )
            found[name] = _action_spec(cls, attr, value, name)
        cls._actions = found
        if cls.parameters is not None:
            for key, hint in cls.parameters.items():
                _check_hint(hint, f"{cls.__name__}.parameters[{key!r}]")

    # ---- what subclasses write ----------------------------------------------------------

    def on_init(self, params: dict[str, object]) -> None:
        """Build the world from init parameters given as Python values."""

    def on_reset(self, params: dict[str, object]) -> None:
        """Rebuild the world; by default the same as ``on_init``."""
        self.on_init(params)

    def on_start(self) -> None:
        """The environment starts running."""

    def on_pause(self) -> None:
        """The environment pauses."""

    def on_kill(self) -> None:
        """The environment is killed: release resources."""

    def initial_entities(self) -> dict[str, str]:
        """Entity name -> type after ``on_init``; by default ``entity_names``, one type."""
        return {entity: self.default_entity_type for entity in self.entity_names}

    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        """The percepts of ``entity`` in the current state."""
        return ()

    def push_percept(self, item: PerceptLike, *entities: str) -> None:
        """Push a percept (shorthand allowed) to the agents of ``entities``, or to all agents."""
        percept = _to_percept(item, self.name)
        if entities:
            self.notify_agents_via_entity(percept, *entities)
        else:
            self.notify_agents(percept)

    # ---- the Environment hooks ----------------------------------------------------------

    @classmethod
    def init_parameters(cls) -> Mapping[str, str] | None:
        """The declared ``parameters`` (name -> its type), if any."""
        if cls.parameters is None:
            return None
        return {key: getattr(hint, "__name__", str(hint)) for key, hint in cls.parameters.items()}

    @classmethod
    def action_names(cls) -> list[str]:
        """The actions this environment supports."""
        return sorted(cls._actions)

    def is_path_parameter(self, key: str) -> bool:
        """True when ``parameters`` declares ``key`` as ``Path`` (or a union with it)."""
        hint = (type(self).parameters or {}).get(key)
        return hint is Path or Path in _alternatives(hint)

    def _python_params(self, params: dict[str, Parameter]) -> dict[str, object]:
        """Init parameters as Python values, checked against ``parameters`` when declared."""
        spec = type(self).parameters
        if spec is None:
            return {key: to_python(value) for key, value in params.items()}
        result: dict[str, object] = {}
        for key, value in params.items():
            if key not in spec:
                known = ", ".join(spec) or "none"
                raise ManagementException(
                    f"environment '{self.name}' has no init parameter '{key}' (known: {known})"
                )
            try:
                result[key] = _convert(value, spec[key])
            except _Mismatch as mismatch:
                raise ManagementException(
                    f"environment '{self.name}': init parameter '{key}' must be {mismatch}, "
                    f"got {value}"
                ) from None
        return result

    def _run_user(self, what: str, func: Callable[..., None], *args: object) -> None:
        """Run a user hook, turning unexpected exceptions into a ManagementException."""
        try:
            func(*args)
        except EnvironmentInterfaceException:
            raise
        except Exception as error:
            raise ManagementException(
                f"environment '{self.name}' failed to {what}: {type(error).__name__}: {error}"
            ) from error

    def _sync_entities(self) -> None:
        """Add and delete entities so they match ``initial_entities``."""
        wanted = self.initial_entities()
        for entity in self.entities():
            if entity not in wanted:
                self.delete_entity(entity)
        for entity, etype in wanted.items():
            if entity not in self.entities():
                self.add_entity(entity, etype)

    def do_init(self, params: dict[str, Parameter]) -> None:
        """Run ``on_init`` with Python values, then create the entities it asks for."""
        self._run_user("initialise", self.on_init, self._python_params(params))
        self._sync_entities()

    def do_reset(self, params: dict[str, Parameter]) -> None:
        """Run ``on_reset`` with Python values, then add/delete entities to match."""
        self._run_user("reset", self.on_reset, self._python_params(params))
        self._sync_entities()

    def do_start(self) -> None:
        """Run ``on_start``, reporting its errors as ManagementException."""
        self._run_user("start", self.on_start)

    def do_pause(self) -> None:
        """Run ``on_pause``, reporting its errors as ManagementException."""
        self._run_user("pause", self.on_pause)

    def do_kill(self) -> None:
        """Run ``on_kill``, reporting its errors as ManagementException."""
        self._run_user("stop", self.on_kill)

    def percepts_for_entity(self, entity: str) -> list[Percept]:
        """``percepts(entity)`` converted to Percept objects; errors become PerceiveException."""
        try:
            items = list(self.percepts(entity))
        except EnvironmentInterfaceException:
            raise
        except Exception as error:
            raise PerceiveException(
                f"environment '{self.name}' failed to produce percepts for '{entity}': "
                f"{type(error).__name__}: {error}"
            ) from error
        return [_to_percept(item, self.name) for item in items]

    def perform_entity_action(self, entity: str, action: Action) -> Percept | None:
        """Dispatch to the ``@action`` method with converted parameters; map every failure."""
        spec = self._actions.get(action.name)
        if spec is None:
            known = ", ".join(self.action_names()) or "none"
            raise ActException(
                f"environment '{self.name}' has no action '{action.name}' (actions: {known})",
                ActExceptionKind.UNKNOWN_ACTION,
            )
        given = len(action.params)
        total = len(spec.params)
        if not spec.required <= given <= total:
            count = str(total) if spec.required == total else f"{spec.required} to {total}"
            raise ActException(
                f"action {spec.name} expects {count} parameter{'s' if total != 1 else ''} "
                f"{spec.signature()}, got {given} in {action}",
                ActExceptionKind.WRONG_PARAMETERS,
            )
        args: list[object] = []
        pairs = zip(action.params, spec.params, strict=False)
        for index, (param, (pname, hint)) in enumerate(pairs, 1):
            try:
                args.append(_convert(param, hint))
            except _Mismatch as mismatch:
                raise ActException(
                    f"action {spec.name}: parameter {index} ({pname}) must be {mismatch}, "
                    f"got {param} in {action}",
                    ActExceptionKind.WRONG_PARAMETERS,
                ) from None
        try:
            result = getattr(self, spec.method)(entity, *args)
        except EnvironmentInterfaceException:
            raise
        except Exception as error:
            raise ActException(
                f"action {action} failed in environment '{self.name}': "
                f"{type(error).__name__}: {error}",
                ActExceptionKind.FAILURE,
            ) from error
        return None if result is None else _to_percept(result, self.name)


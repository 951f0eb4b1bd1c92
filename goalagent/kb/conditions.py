"""Mental-state conditions: compiled once into a clause of the agent's belief module, then
answered in one Prolog call with the bindings passed in; single literals and unification
for the runtime's own queries.

``goal(φ)`` is evaluated against knowledge and ONE goal at a time (see mentalstate.pl).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from goalagent import ast
from goalagent.kb.engine import Engine, KBError, PrologRuntimeError
from goalagent.kb.errors import LimitError
from goalagent.kb.limits import limit_text
from goalagent.kb.prolog_modules import FALSE, TRUE, PrologModules, instantiate
from goalagent.kb.terms import Atom, Struct, Term, Var

__all__ = ["CompiledCondition", "Conditions"]

_WRAPPERS = {
    "bel": "$bel",
    "goal": "$goal",
    "a-goal": "$agoal",
    "goal-a": "$goala",
    "percept": "$percept",
}
_QUERY_POS = ast.Pos("<query>", 1, 1)

# Condition body text -> clause name, shared by all agents: equal conditions use the same
# predicate name in every agent module, so 10,000 agents do not create 10,000 functors.
_condition_names: dict[str, str] = {}


class CompiledCondition:
    """A mental state condition compiled into one clause of an agent's belief module."""

    __slots__ = ("_state", "_name", "names", "_index", "text")

    def __init__(self, state: Conditions, name: str, names: tuple[str, ...], text: str) -> None:
        self._state = state
        self._name = name  # the clause's predicate name
        self.names = names  # named variables, in order of first appearance
        self._index = {name: i for i, name in enumerate(names)}
        self.text = text  # the Prolog body the condition was compiled from

    def __repr__(self) -> str:
        return f"CompiledCondition({self.text!r}, names={self.names!r})"

    @property
    def clause(self) -> str:
        """The name of the condition's clause (the same in every agent for the same text)."""
        return self._name


class Conditions(PrologModules):
    """Compiles and answers the agent's conditions (the part of the mental state that
    queries it)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._compiled: dict[str, CompiledCondition] = {}
        super().__init__(*args, **kwargs)

    def compile(self, condition: ast.Condition, *, trusted: bool = False,
                sandboxed: bool = False) -> CompiledCondition:
        """Compiles a condition once (cached per body text) into a clause of this agent;
        an agent's condition is confined (confine.pl: checked, dynamic calls guarded), a
        ``trusted`` one (the runtime's own queries: the API, reports) is not, a
        ``sandboxed`` one (the mind inspector's) is confined in the sandbox."""
        text = _text(condition)
        if sandboxed:
            key, mode = f"sandbox\0{text}", Atom("sandbox")
        elif trusted:
            key, mode = f"trusted\0{text}", FALSE
        else:
            key, mode = text, TRUE
        compiled = self._compiled.get(key)
        if compiled is not None:
            return compiled
        name = _condition_names.get(key)
        if name is None:
            name = self._engine.unique_name("$ga_c")
            _condition_names[key] = name
        try:
            names = self._call("compile", self._b, self._g, Atom(name), text, mode, None)[5]
        except PrologRuntimeError as error:
            raise _condition_error(self._engine, condition, error) from None
        assert isinstance(names, list)
        compiled = CompiledCondition(self, name, tuple(str(item) for item in names), text)
        self._compiled[key] = compiled
        return compiled

    def copy_conditions(self, like: Conditions, conditions: Iterable[ast.Condition]) -> bool:
        """Copies the (confined) ``conditions`` ``like`` has compiled into this agent in one
        call, as :meth:`compile` would make them here: ``like`` is an agent of the same
        program loaded alike (no directives, the same limits), so only the module names
        differ (clone_conditions/6 in mentalstate_load.pl). False, and nothing copied, when
        ``like`` is closed, lacks one of them, or one names something of its own."""
        originals = [like._compiled.get(_text(condition)) for condition in conditions]
        if like.closed or None in originals:
            return False
        (from_b, from_g), (to_b, to_g) = like.modules, self.modules
        names = [Atom(original.clause) for original in originals]  # type: ignore[union-attr]
        cloned = self._call("clone_conditions", from_b, from_g, to_b, to_g, names, None)[5]
        if cloned != TRUE:
            return False
        for original in originals:
            assert original is not None
            self._compiled[original.text] = CompiledCondition(self, original.clause,
                                                              original.names, original.text)
        return True

    def solutions(self, cond: CompiledCondition, bindings: Mapping[str, Term] | None = None,
                  *, limit: int | None = None) -> list[dict[str, Term]]:
        """All (or the first ``limit``) answers of a compiled condition, in Prolog order; each
        maps every named variable of the condition and every given binding to its value."""
        if cond._state is not self:
            raise KBError("this condition was compiled for another mental state")
        if self._closed:  # checked here, not through _call: one call fewer per query
            raise KBError(f"the mental state of {self.agent_name} is closed")
        names = cond.names
        given = dict(bindings or {})
        extra = {name: value for name, value in given.items() if name not in cond._index}
        args = tuple(given.get(name, Var(name)) for name in names)
        goal = Struct(":", (self._b, Struct(cond._name, args) if args else Atom(cond._name)))
        self._watchdog.time_limit = self.limits.max_query_seconds
        self._watchdog.running = self._memory
        result = self._engine.call("solutions", goal, list(args), self.limits.max_inferences,
                                   limit if limit is not None else Atom("all"), None,
                                   module="ga_guard")
        assert result is not None
        rows = result[4]
        if not isinstance(rows, list):  # ga_limit(inferences(Max))
            raise LimitError(f"the query ran {limit_text(rows.args[0])}")  # type: ignore
        if extra:
            return [{**extra, **dict(zip(names, row, strict=True))} for row in rows]
        return [dict(zip(names, row, strict=True)) for row in rows]

    def query(self, op: str, text: str, bindings: Mapping[str, Term] | None = None, *,
              limit: int | None = None, trusted: bool = True,
              sandboxed: bool = False) -> list[dict[str, Term]]:
        """Answers of ``op(text)``, op bel/goal/a-goal/goal-a/percept/true (see compile)."""
        if op not in _WRAPPERS and op != "true":
            raise KBError(f"unknown mental literal `{op}`: use one of "
                          f"{', '.join([*_WRAPPERS, 'true'])}")
        query = ast.PrologText(text, _QUERY_POS) if op != "true" else None
        literal = ast.MentalLiteral(op, query, _QUERY_POS)  # type: ignore[arg-type]
        compiled = self.compile((literal,), trusted=trusted, sandboxed=sandboxed)
        return self.solutions(compiled, bindings, limit=limit)

    def instantiate(self, text: ast.PrologText | str, bindings: Mapping[str, Term]) -> Term:
        """The term written in ``text`` with ``bindings`` applied (unbound vars stay Var)."""
        return instantiate(text, bindings, self._engine)

    def unify(self, pattern: ast.PrologText | str, value: Term,
              bindings: Mapping[str, Term] | None = None) -> dict[str, Term] | None:
        """Unifies ``pattern`` (with ``bindings`` applied) with ``value`` as Prolog's =/2 does;
        returns ``bindings`` extended with the pattern's variables, or None."""
        term = self._term(pattern, bindings)
        result = self._engine.call("=", term, value, module="system", read=(0,))
        if result is None:
            return None
        out = dict(bindings or {})
        _match(term, result[0], out)
        return out

    def close(self) -> None:
        """Frees both Prolog modules and forgets the compiled conditions."""
        self._compiled.clear()
        super().close()


def _text(condition: ast.Condition) -> str:
    """A condition's Prolog text (the key an agent's own condition is compiled under)."""
    return ", ".join(_literal_text(literal) for literal in condition) or "true"


def _literal_text(literal: ast.Literal) -> str:
    """The Prolog text of one literal for mentalstate.pl's compile/5."""
    if isinstance(literal, ast.NotLiteral):
        inner = ", ".join(_literal_text(item) for item in literal.condition) or "true"
        return f"\\+ ({inner})"
    if literal.op == "true":
        return "true"
    if literal.op not in _WRAPPERS:
        raise KBError(f"unknown mental literal `{literal.op}` at {literal.pos}")
    if literal.query is None:
        raise KBError(f"`{literal.op}` needs a query at {literal.pos}")
    return f"'{_WRAPPERS[literal.op]}'(({literal.query.text}\n))"


def _literals(condition: ast.Condition) -> Iterable[ast.MentalLiteral]:
    """Every mental literal of a condition, also those inside not(...)."""
    for literal in condition:
        if isinstance(literal, ast.NotLiteral):
            yield from _literals(literal.condition)
        else:
            yield literal


def _match(pattern: Term, value: Term, out: dict[str, Term]) -> None:
    """Collects what each variable of ``pattern`` became in its instance ``value``."""
    if isinstance(pattern, Var):
        if pattern.name != "_":
            out[pattern.name] = value
    elif isinstance(pattern, list) and isinstance(value, list):
        for item, instance in zip(pattern, value, strict=False):
            _match(item, instance, out)
    elif isinstance(pattern, Struct):
        if pattern.name == "[|]" and len(pattern.args) == 2 and isinstance(value, list) and value:
            _match(pattern.args[0], value[0], out)
            _match(pattern.args[1], value[1:], out)
        elif isinstance(value, Struct):
            for arg, instance in zip(pattern.args, value.args, strict=False):
                _match(arg, instance, out)


def _condition_error(engine: Engine, condition: ast.Condition, error: KBError) -> KBError:
    """The error of the literal confine.pl refused or of the first literal SWI's reader
    rejects (with its position)."""
    term = getattr(error, "term", None)
    if isinstance(term, Struct) and term.name == "ga_refused_literal":
        literal = list(_literals(condition))[int(term.args[0])]  # type: ignore[arg-type]
        pos = literal.query.pos if literal.query is not None else literal.pos
        text = literal.query.text if literal.query is not None else ""
        return KBError(f"{literal.op}({text}): refused: {term.args[1]}", pos)
    for literal in _literals(condition):
        if literal.query is None:
            continue
        try:
            engine.check_query(literal.query.text)
        except KBError as syntax:
            return KBError(f"{literal.op}({literal.query.text}) at {literal.query.pos}: "
                           f"{syntax}", literal.query.pos)
    return error

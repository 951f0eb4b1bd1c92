"""The mental state of one agent on SWI-Prolog: knowledge, beliefs, goals, percepts, mailbox.

Each agent owns two fresh Prolog modules (based on ``system`` only, so nothing from ``user``
or another agent leaks in): a belief module (knowledge + beliefs + percepts + messages) and a
goal module (knowledge again + the goal bases). ``goal(φ)`` is evaluated against knowledge and
ONE goal at a time (see mentalstate.pl). A rule's whole condition is compiled once into a
clause of the belief module and evaluated in one Prolog call with the bindings passed in.

A rule can also be compiled with its leading actions (:meth:`MentalState.compile_rule`:
insert/delete/adopt/drop and user actions' pre/postconditions, blind commitment after each)
into one clause shared by every agent, and consecutive such rules into one pass
(:meth:`MentalState.compile_pass`); :meth:`MentalState.fire` / ``fire_pass`` apply them in
one call and return :class:`Firings` (the action count at once, the bindings when read).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from goalagent import ast
from goalagent.kb.engine import Engine, KBError, PrologRuntimeError, Record, get_engine
from goalagent.kb.terms import Atom, Struct, Term, Var, format_term

__all__ = ["RULE_ACTIONS", "AgentDirectory", "CompiledCondition", "CompiledPass",
           "CompiledRule", "Firings", "LazyBindings", "MentalState", "Problem", "instantiate"]

_WRAPPERS = {
    "bel": "$bel",
    "goal": "$goal",
    "a-goal": "$agoal",
    "goal-a": "$goala",
    "percept": "$percept",
}
_MOODS = {":": None, "!": "imp", "?": "int"}
_QUERY_POS = ast.Pos("<query>", 1, 1)
_TRUE, _FALSE = Atom("true"), Atom("false")

# Condition body text -> clause name, shared by all agents: equal conditions use the same
# predicate name in every agent module, so 10,000 agents do not create 10,000 functors.
_condition_names: dict[str, str] = {}

# Rule and pass clauses live in one module for all agents (they take the agent's belief
# module as their first argument): key -> (clause name, the rule's variable names).
_RULES = "ga_rules"
_shared_rules: dict[str, tuple[str, tuple[str, ...]]] = {}


class CompiledCondition:
    """A mental state condition compiled into one clause of an agent's belief module."""

    __slots__ = ("_state", "_pred", "_name", "names", "_index", "text")

    def __init__(self, state: MentalState, pred: int, name: str, names: tuple[str, ...],
                 text: str) -> None:
        self._state = state
        self._pred = pred
        self._name = name  # the clause's predicate name
        self.names = names  # named variables, in order of first appearance
        self._index = {name: i for i, name in enumerate(names)}
        self.text = text  # the Prolog body the condition was compiled from

    def __repr__(self) -> str:
        return f"CompiledCondition({self.text!r}, names={self.names!r})"


class CompiledRule:
    """A rule (its condition and the leading actions Prolog can do) compiled into one clause
    (shared by every agent that reads the rule alike, see ``compile_rule/7``): one Prolog
    call evaluates the condition and performs those actions."""

    __slots__ = ("_state", "_pred", "_name", "names", "condition_names", "_index", "kind",
                 "actions", "pending")

    def __init__(self, state: MentalState, pred: int, name: str, names: tuple[str, ...],
                 condition_names: tuple[str, ...], kind: str, actions: int,
                 pending: bool = False) -> None:
        self._state = state
        self._pred = pred
        self._name = name  # the clause's predicate name
        self.condition_names = condition_names
        self.names = names  # named variables: the condition's, then the actions' own
        self._index = {name: i for i, name in enumerate(names)}
        self.kind = kind  # if or forall
        self.actions = actions  # how many leading actions the clause performs
        self.pending = pending  # the last of them is left to Python (an environment action)

    def __repr__(self) -> str:
        return (f"CompiledRule({self.kind}, names={self.names!r}, actions={self.actions}, "
                f"pending={self.pending})")


class CompiledPass:
    """Consecutive compiled rules (all their actions done in Prolog, no given bindings)
    applied in order by one Prolog call: a module pass without a return to Python per
    rule."""

    __slots__ = ("_state", "_pred", "rules", "stop")

    def __init__(self, state: MentalState, pred: int, rules: tuple[CompiledRule, ...],
                 stop: bool) -> None:
        self._state = state
        self._pred = pred
        self.rules = rules
        self.stop = stop  # stop after the first rule that fires (linear order)

    def __repr__(self) -> str:
        return f"CompiledPass({len(self.rules)} rules, stop={self.stop})"


class Firings:
    """What one call of a compiled rule or pass did: how many actions it performed, which
    rules fired with which bindings (kept in Prolog, a :class:`Record`, until someone asks:
    most cycles nobody does), and the problems it met. Rules are numbered by their place
    in the order tried."""

    __slots__ = ("_record", "_names", "_given", "_nested", "actions", "problems")

    def __init__(self, actions: int, record: Record, names: Sequence[tuple[str, ...]],
                 given: Mapping[str, Term], nested: bool, problems: list[tuple[int, Problem]]
                 ) -> None:
        # record: k(Dones, Values[, Pending]); Dones has per firing its number of actions
        # (for a pass, 0 ends a rule's firings), Values the values per rule (nested) or of
        # the one rule, Pending the action left for Python (see pending).
        self._record = record
        self._names = names  # per rule: its condition's variables (the first values)
        self._given = given
        self._nested = nested
        self.actions = actions
        self.problems = problems

    def __bool__(self) -> bool:
        """True when a rule fired."""
        return self.actions > 0

    def pending(self) -> tuple[Term, Term, int] | None:
        """The environment action a compiled rule left for Python, enabled and closed: (the
        action, its postcondition instantiated by the precondition, the actionspec's index
        in the program), or None."""
        kept = self._record.value()
        assert isinstance(kept, Struct)
        found = kept.args[2]
        if not isinstance(found, Struct):
            return None
        action, post, spec = found.args
        return action, post, int(spec)  # type: ignore[arg-type]

    def items(self) -> list[tuple[int, LazyBindings, int]]:
        """Per firing, in order: the rule's place, its bindings, its number of actions."""
        result = []
        place = index = 0
        kept = self._record.value()
        assert isinstance(kept, Struct)
        for done in kept.args[0]:  # type: ignore[union-attr]
            if done == 0:
                place, index = place + 1, 0
            else:
                result.append((place, LazyBindings(self, place, index), done))
                index += 1
        return result

    def bindings(self, place: int, index: int) -> dict[str, Term]:
        """The bindings of firing ``index`` of the rule at ``place``: the given bindings and
        the condition's variables (as a condition's answers have them)."""
        values = self._record.value().args[1]  # type: ignore[union-attr]
        if self._nested:
            values = values[place]  # type: ignore[index]
        found = dict(zip(self._names[place], values[index], strict=False))  # type: ignore
        if not self._given:
            return found
        # As a condition's answers: the given bindings it does not name, then its variables.
        result = {name: value for name, value in self._given.items() if name not in found}
        result.update(found)
        return result


class LazyBindings:
    """The bindings of one firing of a compiled rule, read from Prolog on first use."""

    __slots__ = ("_firings", "_place", "_index", "_value")

    def __init__(self, firings: Firings, place: int, index: int) -> None:
        self._firings = firings
        self._place = place
        self._index = index
        self._value: dict[str, Term] | None = None

    def resolve(self) -> dict[str, Term]:
        """The bindings as Python values (converted once)."""
        if self._value is None:
            self._value = self._firings.bindings(self._place, self._index)
        return self._value


# What a rule clause performs itself: the built-in updates, ``do`` (a user action:
# precondition, then postcondition; see declare_actions) and, last, ``env`` (a user action
# for the environment: the clause checks its precondition, Python performs it and applies
# its postcondition; see Firings.pending).
RULE_ACTIONS = frozenset({"insert", "delete", "adopt", "drop", "do", "env"})

# A problem met while applying a compiled rule: (kind, index, detail). Kinds: "action" (an
# action raised an error: index of the action, message), "open" (a user action not closed
# after its precondition: index of the action, the action term), "pre" (a precondition
# raised an error: index of the actionspec, message), "condition" (None, message).
Problem = tuple[str, int | None, Term]
_PROBLEM_KINDS = {"w": "action", "o": "open", "p": "pre"}


def _problem(warning: Struct) -> Problem:
    """A warning term of mentalstate.pl (see warning/2) as a :data:`Problem`."""
    if warning.name == "c":
        return ("condition", None, warning.args[0])
    index, detail = warning.args
    return (_PROBLEM_KINDS[warning.name], int(index), detail)  # type: ignore[arg-type]


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


def _substitute(term: Term, bindings: Mapping[str, Term]) -> Term:
    """``term`` with every bound ``Var`` replaced by its value (lists are rebuilt)."""
    if isinstance(term, Var):
        return bindings.get(term.name, term) if term.name != "_" else term
    if isinstance(term, Struct):
        return Struct(term.name, tuple(_substitute(arg, bindings) for arg in term.args))
    if isinstance(term, list):
        return [_substitute(item, bindings) for item in term]
    return term


def instantiate(text: ast.PrologText | str, bindings: Mapping[str, Term],
                engine: Engine | None = None) -> Term:
    """The term written in ``text`` with ``bindings`` applied (unbound vars stay Var)."""
    return _substitute((engine or get_engine()).parsed(_text_of(text)), bindings)


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


def _split_update(term: Term, mode: str) -> tuple[list[Term], list[Term]]:
    """The facts an insert/delete (``mode``) of ``term`` deletes and adds, in the order
    mentalstate.pl's update/7 handles them (conjunction order, `true` skipped)."""
    removals: list[Term] = []
    additions: list[Term] = []
    pending = [term]
    while pending:
        literal = pending.pop()
        if isinstance(literal, Struct) and literal.name == "," and len(literal.args) == 2:
            pending.extend(reversed(literal.args))
        elif type(literal) is Atom and literal == "true":
            continue
        elif isinstance(literal, Struct) and literal.name in ("not", "\\+") and literal.arity == 1:
            (additions if mode == "delete" else removals).append(literal.args[0])
        else:
            (additions if mode == "insert" else removals).append(literal)
    return removals, additions


def _text_of(formula: ast.PrologText | str) -> str:
    """The Prolog text of a program fragment or plain string (anything else is a KBError)."""
    if isinstance(formula, ast.PrologText):
        return formula.text
    if isinstance(formula, str):
        return formula
    raise KBError(f"Prolog text expected, got {formula!r}")


class AgentDirectory:
    """The names of the agents of one system, kept once in a Prolog module that every
    member's ``agent/1`` reads (see :meth:`MentalState.join`): adding an agent is one fact."""

    def __init__(self, engine: Engine | None = None) -> None:
        self._engine = engine or get_engine()
        self.module = Atom(f"ga_dir{self._engine.unique_name('')}")
        self.closed = False
        self._engine.call("new_directory", self.module)

    def add(self, name: str) -> None:
        """Adds ``agent(name)`` for every member."""
        if self.closed:
            raise KBError("the agent directory is closed")
        self._engine.call("directory_add", self.module, Atom(name))

    def close(self) -> None:
        """Frees the module (close the members first: their ``agent/1`` reads it)."""
        if not self.closed:
            self._engine.call("destroy_directory", self.module)
            self._engine.forget_atom(self.module)
            self.closed = True


class MentalState:
    """Knowledge, beliefs, goal bases, percepts and mailbox of one agent (two Prolog modules)."""

    def __init__(self, agent_name: str, *, knowledge: Sequence[ast.PrologText] = (),
                 beliefs: Sequence[ast.PrologText] = (), engine: Engine | None = None) -> None:
        self._engine = engine or get_engine()
        self.agent_name = agent_name
        number = self._engine.unique_name("")
        self._b = Atom(f"ga_b{number}")
        self._g = Atom(f"ga_g{number}")
        self._closed = False
        self._compiled: dict[str, CompiledCondition | CompiledRule | CompiledPass] = {}
        self._achieved: list[list[Term]] = []  # goals removed by updates, not yet reported
        self._recheck = True  # beliefs or goals changed in a way updates did not check
        self._has_percepts = False  # the percept base is not empty
        clauses = [("knowledge", text) for text in knowledge]
        clauses += [("beliefs", text) for text in beliefs]
        # Directives (op/3, use_module/1, ...) change how this agent reads text.
        self._directives = "\n".join(_text_of(text) for _, text in clauses
                                     if _text_of(text).lstrip().startswith(":-"))
        items = [Struct(kind[0], (_text_of(text),)) for kind, text in clauses]
        self._engine.call("new_agent", self._b, self._g)
        result = self._call("load", self._b, self._g, items, None)[3]
        if isinstance(result, Struct) and result.name == "error":
            index, message = result.args
            kind, text = clauses[int(index)]
            self.close()
            pos = text.pos if isinstance(text, ast.PrologText) else None
            where = f" at {pos}" if pos else ""
            raise KBError(f"{kind} clause `{_text_of(text)}`{where}: {message}", pos)

    # ------------------------------------------------------------------ plumbing

    def _call(self, name: str, *args: Term | None) -> list[Any]:
        """Runs ga_kb:name(args) once (it must succeed); raises KBError when closed."""
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        result = self._engine.call(name, *args)
        if result is None:
            raise KBError(f"internal: ga_kb:{name}/{len(args)} failed")
        return result

    def _term(self, formula: ast.PrologText | str, bindings: Mapping[str, Term] | None) -> Term:
        """The formula as a term with the bindings applied (parsed once per text); without
        bindings it is the engine's shared cached term, so it is only handed to Prolog."""
        term = self._engine.parsed(_text_of(formula))
        return _substitute(term, bindings) if bindings else term

    def __enter__(self) -> MentalState:
        """``with MentalState(...) as state:`` closes the state at the end of the block."""
        return self

    def __exit__(self, *exc: Any) -> None:
        """Closes the state (frees its Prolog modules)."""
        self.close()

    # ------------------------------------------------------------------ conditions

    def declare_updates(self, formulas: Iterable[ast.PrologText | str]) -> None:
        """Declares dynamic every predicate in these conjunctions (also under not/1), so that
        querying them before the first insert/adopt fails instead of raising an error."""
        terms = [self._engine.parsed(_text_of(formula)) for formula in formulas]
        self._call("declare", self._b, self._g, terms)

    def compile(self, condition: ast.Condition) -> CompiledCondition:
        """Compiles a condition once (cached per body text) into a clause of this agent."""
        text = ", ".join(_literal_text(literal) for literal in condition) or "true"
        compiled = self._compiled.get(text)
        if compiled is not None:
            assert isinstance(compiled, CompiledCondition)
            return compiled
        name = _condition_names.get(text)
        if name is None:
            name = self._engine.unique_name("$ga_c")
            _condition_names[text] = name
        try:
            names = self._call("compile", self._b, self._g, Atom(name), text, None)[4]
        except PrologRuntimeError as error:
            raise self._condition_error(condition, error) from None
        assert isinstance(names, list)
        names_tuple = tuple(str(item) for item in names)
        pred = self._engine.predicate(name, len(names_tuple), str(self._b), cache=False)
        compiled = CompiledCondition(self, pred, name, names_tuple, text)
        self._compiled[text] = compiled
        return compiled

    def compile_rule(self, kind: str, condition: CompiledCondition,
                     actions: Sequence[tuple[str, ast.PrologText | str]]) -> CompiledRule:
        """Compiles a rule (``kind`` if or forall) whose condition is ``condition`` and whose
        actions start with ``actions`` (name in RULE_ACTIONS, formula) into one clause."""
        if kind not in ("if", "forall"):
            raise KBError(f"only if and forall rules compile into one clause, not {kind}")
        if condition._state is not self:
            raise KBError("this condition was compiled for another mental state")
        for index, (name, _) in enumerate(actions):
            if name not in RULE_ACTIONS:
                raise KBError(f"{name} is not an action a rule clause performs")
            if name == "env" and (index < len(actions) - 1 or kind != "if"):
                raise KBError("an environment action can only end the actions of an if rule")
        texts = ", ".join(f"{name}(({_text_of(formula)}\n))" for name, formula in actions)
        text = f"'$rule'(({condition.text}\n), [{texts}])"
        key = f"{kind}:{text}"
        compiled = self._compiled.get(key)
        if compiled is not None:
            assert isinstance(compiled, CompiledRule)
            return compiled
        # One clause for every agent that reads the text alike (same directives: operators).
        shared_key = f"{key}\0{self._directives}"
        shared = _shared_rules.get(shared_key)
        if shared is None:
            name = self._engine.unique_name("$ga_r")
            names = self._call("compile_rule", self._b, Atom(kind), Atom(name),
                               Atom(condition._name), len(condition.names), text, None)[6]
            assert isinstance(names, list)
            shared = (name, tuple(str(item) for item in names))
            _shared_rules[shared_key] = shared
        name, names_tuple = shared
        pred = self._engine.predicate(name, len(names_tuple) + 5, _RULES)
        pending = bool(actions) and actions[-1][0] == "env"
        rule = CompiledRule(self, pred, name, names_tuple, condition.names, kind, len(actions),
                            pending)
        self._compiled[key] = rule
        return rule

    def fire(self, rule: CompiledRule, bindings: Mapping[str, Term] | None = None) -> Firings:
        """Applies a compiled rule in one Prolog call (see fire/9 in mentalstate.pl); what
        it did (actions that raised an error are not enabled). A Prolog error in the
        condition raises PrologRuntimeError before any action."""
        if rule._state is not self:
            raise KBError("this rule was compiled for another mental state")
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        index = rule._index
        arity = len(rule.names) + 1  # the belief module, then the rule's variables
        inputs: list[tuple[int, Term | None]] = [(0, self._b),
                                                 (arity, _TRUE if self._recheck else _FALSE)]
        if bindings:
            inputs.extend((index[name] + 1, value) for name, value in bindings.items()
                          if name in index)
        total, kept, warnings = self._engine.solve(
            rule._pred, arity + 4, inputs, 1, outputs=(arity + 1, arity + 2, arity + 3),
            keep=arity + 2)[0]
        if total:
            self._recheck = False
        problems = [(0, _problem(w)) for w in warnings]  # type: ignore[union-attr, arg-type]
        return Firings(total, kept, (rule.condition_names,), dict(bindings or {}),  # type: ignore
                       False, problems)

    def declare_actions(self, specs: Sequence[ast.ActionSpec]) -> None:
        """Makes the actionspecs known to rule clauses (their ``do`` actions): each spec's
        precondition and postcondition, in program order (the first that applies wins)."""
        items = []
        for index, spec in enumerate(specs):
            head = format_term(Atom(spec.name))
            if spec.params:
                head += "(" + ", ".join(param.text for param in spec.params) + ")"
            text = f"'$spec'({head}, ({spec.pre.text}\n), ({spec.post.text}\n))"
            items.append(Struct("spec", (index, text)))
        self._call("declare_actions", self._b, items)

    def compile_pass(self, rules: Sequence[CompiledRule], *, stop: bool) -> CompiledPass:
        """Compiles consecutive rules into one pass (``stop``: after the first that fires)."""
        for rule in rules:
            if rule._state is not self:
                raise KBError("this rule was compiled for another mental state")
        key = f"pass:{stop}:{[rule._name for rule in rules]}"
        compiled = self._compiled.get(key)
        if compiled is not None:
            assert isinstance(compiled, CompiledPass)
            return compiled
        name = _shared_rules.get(key, ("", ()))[0]
        if not name:  # one clause for every agent (its rules are shared too)
            name = self._engine.unique_name("$ga_p")
            specs = [Struct("/", (Atom(rule._name), len(rule.names) + 5)) for rule in rules]
            self._call("compile_pass", Atom(name), _TRUE if stop else _FALSE, specs)
            _shared_rules[key] = (name, ())
        pred = self._engine.predicate(name, 6, _RULES)
        compiled = CompiledPass(self, pred, tuple(rules), stop)
        self._compiled[key] = compiled
        return compiled

    def fire_pass(self, compiled: CompiledPass, order: Sequence[int] = ()) -> Firings:
        """Applies a compiled pass in one Prolog call (see pass/7 in mentalstate.pl), its
        rules in their order or in ``order`` (their indices); what it did (a rule whose
        condition raised an error is not applicable)."""
        if compiled._state is not self:
            raise KBError("this pass was compiled for another mental state")
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        total, kept, warnings = self._engine.solve(
            compiled._pred, 6,
            [(0, self._b), (1, list(order)), (2, _TRUE if self._recheck else _FALSE)],
            1, outputs=(3, 4, 5), keep=4)[0]
        rules = [compiled.rules[index] for index in order] if order else compiled.rules
        problems = [(int(w.args[0]), _problem(w.args[1]))  # type: ignore[union-attr]
                    for w in warnings]  # type: ignore[union-attr]
        firings = Firings(total, kept, [rule.condition_names for rule in rules],  # type: ignore
                          {}, True, problems)
        if firings:
            self._recheck = False
        return firings

    def _condition_error(self, condition: ast.Condition, error: KBError) -> KBError:
        """The error of the first literal SWI's reader rejects (with its position)."""
        for literal in _literals(condition):
            if literal.query is None:
                continue
            try:
                self._engine.check_query(literal.query.text)
            except KBError as syntax:
                return KBError(f"{literal.op}({literal.query.text}) at {literal.query.pos}: "
                               f"{syntax}", literal.query.pos)
        return error

    def solutions(self, cond: CompiledCondition, bindings: Mapping[str, Term] | None = None,
                  *, limit: int | None = None) -> list[dict[str, Term]]:
        """All (or the first ``limit``) answers of a compiled condition, in Prolog order; each
        maps every named variable of the condition and every given binding to its value."""
        if cond._state is not self:
            raise KBError("this condition was compiled for another mental state")
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        index = cond._index
        if bindings:
            inputs = [(index[name], value) for name, value in bindings.items() if name in index]
            extra = {name: value for name, value in bindings.items() if name not in index}
        else:
            inputs, extra = [], {}
        rows = self._engine.solve(cond._pred, len(cond.names), inputs, limit)
        names = cond.names
        if extra:
            return [{**extra, **dict(zip(names, row, strict=True))} for row in rows]
        return [dict(zip(names, row, strict=True)) for row in rows]

    def query(self, op: str, text: str, bindings: Mapping[str, Term] | None = None, *,
              limit: int | None = None) -> list[dict[str, Term]]:
        """Answers of one literal ``op(text)``, op in bel/goal/a-goal/goal-a/percept/true."""
        if op not in _WRAPPERS and op != "true":
            raise KBError(f"unknown mental literal `{op}`: use one of "
                          f"{', '.join([*_WRAPPERS, 'true'])}")
        query = ast.PrologText(text, _QUERY_POS) if op != "true" else None
        literal = ast.MentalLiteral(op, query, _QUERY_POS)  # type: ignore[arg-type]
        return self.solutions(self.compile((literal,)), bindings, limit=limit)

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

    # ------------------------------------------------------------------ beliefs

    def insert(self, formula: ast.PrologText | str,
               bindings: Mapping[str, Term] | None = None) -> list[tuple[str, Term]]:
        """Adds the positive literals, deletes those under not(..); returns the changes.
        Goals the change achieves are removed at once (blind commitment: the agent calls
        :meth:`blind_commitment` after every action, which then reports them)."""
        return self._update("insert", instantiate(formula, bindings or {}, self._engine))

    def delete(self, formula: ast.PrologText | str,
               bindings: Mapping[str, Term] | None = None) -> list[tuple[str, Term]]:
        """Deletes the positive literals, adds those under not(..); returns the changes
        (achieved goals are removed at once, as for :meth:`insert`)."""
        return self._update("delete", instantiate(formula, bindings or {}, self._engine))

    def _update(self, mode: str, term: Term) -> list[tuple[str, Term]]:
        """Runs insert or delete (``mode``) of ``term`` in Prolog, with blind commitment in
        the same call when beliefs changed (its result waits for :meth:`blind_commitment`)."""
        result = self._call("update", self._b, self._g, Atom(mode), term, None, None, None)
        deleted, added, achieved = result[4], result[5], result[6]
        self._achieved.extend(achieved)
        removals, additions = _split_update(term, mode)
        changes: list[tuple[str, Term]] = []
        for fact, outcome in zip(removals, deleted, strict=True):
            if isinstance(outcome, int):
                changes.extend([("-", fact)] * outcome)
            else:
                changes.extend(("-", instance) for instance in outcome)
        changes.extend(("+", fact) for fact, flag in zip(additions, added, strict=True) if flag)
        return changes

    def insert_term(self, term: Term) -> list[tuple[str, Term]]:
        """As :meth:`insert` for a formula already a term (a postcondition from Prolog)."""
        return self._update("insert", term)

    def beliefs(self) -> list[Term]:
        """The belief facts (not knowledge, not percepts), in Prolog clause order."""
        facts = self._call("beliefs", self._b, None)[1]
        assert isinstance(facts, list)
        return facts

    # ------------------------------------------------------------------ goals

    def adopt(self, formula: ast.PrologText | str,
              bindings: Mapping[str, Term] | None = None) -> bool:
        """Adds the conjunction as one goal; False when already believed or already a goal."""
        term = self._term(formula, bindings)
        result = self._call("adopt", self._b, self._g, term, None)[3]
        return result == "adopted"

    def drop(self, formula: ast.PrologText | str,
             bindings: Mapping[str, Term] | None = None) -> list[list[Term]]:
        """Removes every goal (of the top goal base) from which the formula follows."""
        term = self._term(formula, bindings)
        removed = self._call("drop", self._b, self._g, term, None)[3]
        assert isinstance(removed, list)
        return removed

    def blind_commitment(self) -> list[list[Term]]:
        """Removes every goal whose facts are all believed (all goal bases); returns them,
        with those already removed by insert/delete since the last call. Prolog is asked
        only when percepts, messages or goal bases changed since (updates check themselves)."""
        removed, self._achieved = self._achieved, []
        if self._recheck:
            removed += self._call("blind_commitment", self._b, self._g, None)[2]
            self._recheck = False
        unique: list[list[Term]] = []
        for goal in removed:
            if goal not in unique:
                unique.append(goal)
        return unique

    def goals(self) -> list[list[Term]]:
        """The top goal base; each goal is the list of its facts."""
        goals = self._call("goals", self._g, None)[1]
        assert isinstance(goals, list)
        return goals

    def push_goal_base(self, goals: Iterable[Iterable[Term]] = ()) -> None:
        """Starts a new top goal base (module focus) holding ``goals`` (lists of facts)."""
        self._call("push", self._b, self._g, [list(goal) for goal in goals])
        self._recheck = True

    def pop_goal_base(self) -> list[list[Term]]:
        """Removes the top goal base and returns its goals."""
        goals = self._call("pop", self._g, None)[1]
        assert isinstance(goals, list)
        return goals

    # ------------------------------------------------------------------ percepts, mail

    def set_percepts(self, percepts: Iterable[Term]) -> None:
        """Replaces the percept base (``percept(φ)`` and ``bel(percept(φ))`` see it); an
        empty base replaced by an empty one costs no Prolog call."""
        percepts = list(percepts)
        if not percepts and not self._has_percepts:
            return
        self._call("set_percepts", self._b, percepts)
        self._has_percepts = bool(percepts)
        self._recheck = True

    def percepts(self) -> list[Term]:
        """The current percepts."""
        percepts = self._call("percepts", self._b, None)[1]
        assert isinstance(percepts, list)
        return percepts

    def _message(self, peer: str, mood: str, content: Term) -> list[Term]:
        """The (peer, content) arguments of received/2 or sent/2 for a message in ``mood``."""
        if mood not in _MOODS:
            raise KBError(f"unknown message mood {mood!r}: use ':', '!' or '?'")
        wrapper = _MOODS[mood]
        body = Struct(wrapper, (content,)) if wrapper else content
        return [peer if isinstance(peer, Atom) else Atom(peer), body]

    def add_received(self, sender: str, mood: str, content: Term) -> None:
        """Believes ``received(Sender, φ)`` (``imp(φ)`` for '!', ``int(φ)`` for '?')."""
        fact = Struct("received", tuple(self._message(sender, mood, content)))
        self._call("add_once", self._b, fact, None)
        self._recheck = True

    def add_sent(self, receiver: str, mood: str, content: Term) -> bool:
        """Believes ``sent(Receiver, φ)`` (moods as for received); False if already there."""
        fact = Struct("sent", tuple(self._message(receiver, mood, content)))
        self._recheck = True
        return self._call("add_once", self._b, fact, None)[2] == "true"

    def set_identity(self, me: str, agents: Iterable[str]) -> None:
        """Believes ``me(Me)`` and ``agent(A)`` for every agent of the system (a private copy
        of the list; agents of one system share theirs through :meth:`join`)."""
        names = [name if isinstance(name, Atom) else Atom(name) for name in agents]
        self._call("set_identity", self._b, self._g, Atom(me), names)
        self._recheck = True

    def join(self, me: str, directory: AgentDirectory) -> None:
        """Believes ``me(Me)``, and ``agent(A)`` for every agent in ``directory``, also for
        agents added to it later (the list is shared, not copied)."""
        if directory.closed:
            raise KBError("the agent directory is closed")
        self._call("join_directory", self._b, Atom(me), directory.module)
        self._recheck = True

    # ------------------------------------------------------------------ lifetime

    def close(self) -> None:
        """Frees both Prolog modules; the object is unusable afterwards."""
        if self._closed:
            return
        self._call("destroy", self._b, self._g)
        self._engine.forget_atom(self._b)
        self._engine.forget_atom(self._g)
        self._compiled.clear()
        self._closed = True

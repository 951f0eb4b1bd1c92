"""The mental state of one agent on SWI-Prolog: knowledge, beliefs, goals, percepts, mailbox.

Each agent owns two fresh Prolog modules (based on ``system`` only, so nothing from ``user``
or another agent leaks in): a belief module (knowledge + beliefs + percepts + messages) and a
goal module (knowledge again + the goal bases). ``goal(φ)`` is evaluated against knowledge and
ONE goal at a time (see mentalstate.pl). A rule's whole condition is compiled once into a
clause of the belief module and evaluated in one Prolog call with the bindings passed in.
The rules themselves run in the interpreter (``goalagent.kb.interpreter``, rules.pl).
"""

from __future__ import annotations

import secrets
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from goalagent import ast
from goalagent.kb.engine import Engine, KBError, PrologRuntimeError, Record, get_engine
from goalagent.kb.errors import LimitError
from goalagent.kb.facts import FactFile, FactFileError, FactWatch
from goalagent.kb.limits import Limits, limit_text, refused_precondition, stopping_error
from goalagent.kb.terms import Atom, Struct, Term, Var, format_term
from goalagent.kb.watchdog import watchdog

__all__ = ["AgentDirectory", "CompiledCondition", "MentalState", "instantiate"]

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

    @property
    def clause(self) -> str:
        """The name of the condition's clause (the same in every agent for the same text)."""
        return self._name


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
        self.module = Atom(f"ga_dir_{secrets.token_hex(8)}")
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
                 beliefs: Sequence[ast.PrologText] = (), engine: Engine | None = None,
                 limits: Limits | None = None) -> None:
        self._engine = engine or get_engine()
        self.agent_name = agent_name
        self.limits = limits or Limits()
        self._watchdog = watchdog()
        # Module names no agent can guess (another agent's are never named to it).
        secret = secrets.token_hex(8)
        self._b = Atom(f"ga_b_{secret}")
        self._g = Atom(f"ga_g_{secret}")
        self._closed = False
        self._compiled: dict[str, CompiledCondition] = {}
        self._achieved: list[list[Term]] = []  # goals removed by updates, not yet reported
        # Prolog's recheck flag as last seen (recheck/1): goals achieved unchecked (percepts, ...)
        self._recheck = True
        self._run_pred: int | None = None
        self._has_percepts = self._has_mail = False  # the percept base, received/2 not empty
        # Goals adopted or kept because checking them passed a limit or raised an error
        # (facts, why), for the agent to warn about (take_unchecked()).
        self._unchecked: list[tuple[list[Term], str]] = []
        clauses = [("knowledge", text) for text in knowledge]
        clauses += [("beliefs", text) for text in beliefs]
        # Directives (op/3, use_module/1, ...) change how this agent reads text.
        self._directives = "\n".join(_text_of(text) for _, text in clauses
                                     if _text_of(text).lstrip().startswith(":-"))
        items = [Struct(kind[0], (_text_of(text),)) for kind, text in clauses]
        self._engine.call("new_agent", self._b, self._g)
        self._engine.call("set_limits", self._b, self.limits.max_inferences,
                          self.limits.max_beliefs, module="ga_guard")
        self._watchdog.time_limit = self.limits.max_query_seconds  # its directives run
        result = self._call("load", self._b, self._g, items,
                            _TRUE if self.limits.sandbox else _FALSE, None)[4]
        if isinstance(result, Struct) and result.name == "error":
            index, message = result.args
            kind, text = clauses[int(index)]
            self.close()
            pos = text.pos if isinstance(text, ast.PrologText) else None
            where = f"{pos}: " if pos else ""
            raise KBError(f"{where}{kind} clause `{_text_of(text)}`: {message}", pos)

    # ------------------------------------------------------------------ plumbing

    @property
    def engine(self) -> Engine:
        """The Prolog engine the state lives in."""
        return self._engine

    @property
    def belief_module(self) -> Atom:
        """The name of the belief module (rule clauses read texts with its operators)."""
        return self._b

    @property
    def modules(self) -> tuple[Atom, Atom]:
        """The names of the belief and the goal module."""
        return self._b, self._g

    @property
    def directives(self) -> str:
        """The ``:-`` directives of knowledge and beliefs (they change how texts read)."""
        return self._directives

    def call(self, name: str, *args: Term | None) -> list[Any]:
        """Runs ga_kb:name(args) once (it must succeed): for goalagent.kb's own modules."""
        return self._call(name, *args)

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
        querying them before the first insert/adopt fails instead of raising an error; they
        are the agent's own even where SWI-Prolog has a predicate of that name. A KBError
        (at the formula) when one is an ISO built-in."""
        formulas = list(formulas)
        terms = [self._engine.parsed(_text_of(formula)) for formula in formulas]
        result = self._call("declare", self._b, self._g, terms, None)[3]
        if isinstance(result, Struct) and result.name == "error":
            index, message = result.args
            formula = formulas[int(index)]  # type: ignore[arg-type]
            pos = formula.pos if isinstance(formula, ast.PrologText) else None
            where = f"{pos}: " if pos else ""
            raise KBError(f"{where}`{_text_of(formula)}`: {message}", pos)

    def compile(self, condition: ast.Condition, *, trusted: bool = False) -> CompiledCondition:
        """Compiles a condition once (cached per body text) into a clause of this agent;
        an agent's condition is confined (confine.pl: checked, dynamic calls guarded), a
        ``trusted`` one (the runtime's own queries: the API, reports) is not."""
        text = ", ".join(_literal_text(literal) for literal in condition) or "true"
        key = f"trusted\0{text}" if trusted else text
        compiled = self._compiled.get(key)
        if compiled is not None:
            assert isinstance(compiled, CompiledCondition)
            return compiled
        name = _condition_names.get(key)
        if name is None:
            name = self._engine.unique_name("$ga_c")
            _condition_names[key] = name
        try:
            names = self._call("compile", self._b, self._g, Atom(name), text,
                               _FALSE if trusted else _TRUE, None)[5]
        except PrologRuntimeError as error:
            raise _condition_error(self._engine, condition, error) from None
        assert isinstance(names, list)
        names_tuple = tuple(str(item) for item in names)
        pred = self._engine.predicate(name, len(names_tuple), str(self._b), cache=False)
        compiled = CompiledCondition(self, pred, name, names_tuple, text)
        self._compiled[key] = compiled
        return compiled

    def declare_actions(self, specs: Sequence[ast.ActionSpec]) -> None:
        """Makes the actionspecs known to the rule interpreter: each spec's precondition and
        postcondition, in program order (the first that applies wins; see rules.pl)."""
        items = []
        for index, spec in enumerate(specs):
            head = format_term(Atom(spec.name))
            if spec.params:
                head += "(" + ", ".join(param.text for param in spec.params) + ")"
            text = f"'$spec'({head}, ({spec.pre.text}\n), ({spec.post.text}\n))"
            items.append(Struct("spec", (index, _TRUE if spec.internal else _FALSE, text)))
        try:
            self._call("declare_actions", self._b, items)
        except PrologRuntimeError as error:
            raise refused_precondition(error, specs) from None

    def run(self, plan: Term) -> tuple[int, Record]:
        """Runs a plan of module passes in one call of the rule interpreter (run/3 in
        rules.pl; see goalagent.kb.interpreter): its outcome (one integer) and journal,
        kept in Prolog."""
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        if self._run_pred is None:
            self._run_pred = self._engine.predicate("run", 3, "ga_kb")
        self._watchdog.time_limit = self.limits.max_query_seconds
        try:
            outcome, journal = self._engine.call_once(self._run_pred, 3, ((0, plan),), 1, 2)
        except PrologRuntimeError as error:
            raise stopping_error(error) from None
        self._recheck = bool(outcome & 1)
        return outcome, journal

    def solutions(self, cond: CompiledCondition, bindings: Mapping[str, Term] | None = None,
                  *, limit: int | None = None) -> list[dict[str, Term]]:
        """All (or the first ``limit``) answers of a compiled condition, in Prolog order; each
        maps every named variable of the condition and every given binding to its value."""
        if cond._state is not self:
            raise KBError("this condition was compiled for another mental state")
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        names = cond.names
        given = dict(bindings or {})
        extra = {name: value for name, value in given.items() if name not in cond._index}
        args = tuple(given.get(name, Var(name)) for name in names)
        goal = Struct(":", (self._b, Struct(cond._name, args) if args else Atom(cond._name)))
        self._watchdog.time_limit = self.limits.max_query_seconds
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
              limit: int | None = None) -> list[dict[str, Term]]:
        """Answers of one literal ``op(text)``, op in bel/goal/a-goal/goal-a/percept/true."""
        if op not in _WRAPPERS and op != "true":
            raise KBError(f"unknown mental literal `{op}`: use one of "
                          f"{', '.join([*_WRAPPERS, 'true'])}")
        query = ast.PrologText(text, _QUERY_POS) if op != "true" else None
        literal = ast.MentalLiteral(op, query, _QUERY_POS)  # type: ignore[arg-type]
        return self.solutions(self.compile((literal,), trusted=True), bindings, limit=limit)

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

    def add_facts(self, facts: FactFile) -> int:
        """Adds a checked file of facts (:func:`goalagent.kb.facts.read_facts`) to the
        beliefs, as insert would, each fact once and in file order; returns how many were
        new. One Prolog call, however many facts."""
        if facts.closed:
            raise KBError(f"the facts of {facts.file} were freed")
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        result = self._engine.call("load_facts", self._b, self._g, facts.key, None,
                                   module="ga_guard")
        assert result is not None
        outcome = result[3]
        if outcome.name == "error":
            offset, message = outcome.args
            raise FactFileError(facts.pos(int(offset)), str(message))
        self._recheck = True
        return int(outcome.args[0])

    def watch(self, name: str, arity: int) -> FactWatch:
        """Follows this agent's facts of ``name/arity`` (see :class:`FactWatch`)."""
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        return FactWatch(self._engine, self._b, name, arity)

    def beliefs(self) -> list[Term]:
        """The belief facts (not knowledge, not percepts), in Prolog clause order."""
        facts = self._call("beliefs", self._b, None)[1]
        assert isinstance(facts, list)
        return facts

    # ------------------------------------------------------------------ goals

    def adopt(self, formula: ast.PrologText | str,
              bindings: Mapping[str, Term] | None = None) -> bool:
        """Adds the conjunction as one goal; False when already believed or already a goal.
        Checking whether it is believed is bounded by --max-inferences; one that passes a
        limit or raises an error adopts the goal (see :meth:`take_unchecked`)."""
        term = self._term(formula, bindings)
        result = self._call("adopt_checked", self._b, self._g, term, None)[3]
        if isinstance(result, Struct):  # unchecked(Message)
            self._unchecked.append((list(_split_update(term, "insert")[1]), str(result.args[0])))
            return True
        return result == "adopted"

    def take_unchecked(self) -> list[tuple[list[Term], str]]:
        """The goals adopted or kept since the last call because checking whether they are
        believed passed a limit or raised an error: (their facts, what the check met)."""
        unchecked, self._unchecked = self._unchecked, []
        return unchecked

    def drop(self, formula: ast.PrologText | str,
             bindings: Mapping[str, Term] | None = None) -> list[list[Term]]:
        """Removes every goal (of the top goal base) from which the formula follows."""
        term = self._term(formula, bindings)
        removed = self._call("drop", self._b, self._g, term, None)[3]
        assert isinstance(removed, list)
        return removed

    @property
    def goals_unchecked(self) -> bool:
        """Goals may have been achieved since the last :meth:`blind_commitment`."""
        return self._recheck or bool(self._achieved)

    def blind_commitment(self) -> list[list[Term]]:
        """Removes every goal whose facts are all believed (all goal bases); returns them,
        with those already removed by insert/delete since the last call. Prolog is asked
        only when percepts, messages or goal bases changed since (updates check themselves)."""
        if not self._recheck and not self._achieved:
            return []
        removed, self._achieved = self._achieved, []
        if self._recheck:
            result = self._call("check_goals_bounded", self._b, self._g, None, None)
            removed += result[2]
            self._unchecked += [(facts, str(why)) for facts, why in
                                (pair.args for pair in result[3])]  # type: ignore[union-attr]
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

    def receive(self, messages: Sequence[tuple[str, str, Term]], replace: bool = False) -> None:
        """Believes received(S, φ), imp(φ) for '!', int(φ) for '?'; ``replace``: GOAL 6+'s mail."""
        facts = [Struct("received", tuple(self._message(*message))) for message in messages]
        if facts or (replace and self._has_mail):  # no Prolog call for no change
            self._call("receive", self._b, facts, Atom("true" if replace else "false"))
            self._has_mail, self._recheck = bool(facts) or (self._has_mail and not replace), True

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


def goal_count(state: MentalState) -> int:
    """How many goals the top goal base holds, none converted (a summary needs no more)."""
    return int(state._call("goal_count", state._g, None)[1])

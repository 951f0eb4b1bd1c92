"""Mental state conditions and macros (``#define`` in `.goal` files, ``define m(X) as MSC.``
in `.mod2g` files): the literals of a rule's condition, with each macro call expanded into
the macro's condition (arguments substituted, its other variables renamed apart). GOAL 6's
``(Sender).sent!(φ)`` reads the mailbox; ``done(Action)`` (tests only) is kept as a literal
of its own; the newest dialect's bare literals (``p(X)`` for ``bel(p(X))``) are read as
belief queries when the builder's ``plain_beliefs`` is set.

Expansion is bounded, so a small file cannot make the parser work without end (20 macros
each using the previous twice expand to a million literals): a macro may use macros at
most ``MAX_MACRO_DEPTH`` deep, a condition holds at most ``MAX_CONDITION_LITERALS``
literals and ``MAX_CONDITION_TEXT`` characters once expanded, and one file expands at most
``MAX_FILE_EXPANSION`` literals in all. Each limit is checked before the work it bounds and
reported where it is passed, with the chain of macros that led there.
"""

from __future__ import annotations

import itertools
import re

from lark import v_args

from goalagent import ast
from goalagent.parser.builder_base import BuilderBase
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.variables import rename_variables, variable_occurrences

MAX_MACRO_DEPTH = 64
"""How deep macros may be defined in terms of other macros."""
MAX_CONDITION_LITERALS = 1_000
"""The most literals of one condition (a rule's or a macro's), macros expanded."""
MAX_CONDITION_TEXT = 100_000
"""The most characters of Prolog text in one condition, macros expanded."""
MAX_FILE_EXPANSION = 20_000
"""The most literals all macro expansions of one file may produce (each is read by SWI)."""


def condition_texts(condition: ast.Condition):
    """The Prolog texts of a condition's literals, negated ones included."""
    for literal in condition:
        if isinstance(literal, ast.NotLiteral):
            yield from condition_texts(literal.condition)
        elif literal.query is not None:
            yield literal.query


@v_args(meta=True)
class ConditionParts(BuilderBase):
    """The builder's part for conditions and macros (a macro is known from its definition on;
    a call before it is an error, as in GOAL)."""

    def __init__(self, source) -> None:
        super().__init__(source)
        self.macros: dict[tuple[str, int], ast.Macro] = {}
        self.macro_list: list[ast.Macro] = []
        self._fresh_suffixes = itertools.count(1)
        self.plain_beliefs = False  # the newest dialect: p(X) in a condition is bel(p(X))
        # per macro: (its literals, its text size, the chain of macros it expands through)
        self._expansion: dict[tuple[str, int], tuple[int, int, tuple[str, ...]]] = {}
        self._calls: list[tuple[int, tuple[str, int]]] = []  # (offset, macro) of each call
        self._expanded = 0  # literals produced by expansions in this file

    def macro(self, meta, children):
        return self._define_macro(meta, children)

    def macro_def(self, meta, children):
        return self._define_macro(meta, children)

    def _define_macro(self, meta, children) -> ast.Macro:
        """``#define name(Params) MSC.`` or ``define name(Params) as MSC.``."""
        name = children[1]
        params = next((c for c in children[2:] if isinstance(c, tuple) and c and
                       isinstance(c[0], ast.PrologText)), ())
        condition = children[-2]
        param_names = []
        for param in params:
            if not re.fullmatch(r"[A-Z_][A-Za-z0-9_]*", param.text):
                raise GoalSyntaxError.at(param.pos, "a macro parameter must be a variable")
            param_names.append(param.text)
        macro = ast.Macro(str(name), tuple(param_names), condition, self._token_pos(name))
        key = (macro.name, len(param_names))
        used = [called for offset, called in self._calls
                if meta.start_pos <= offset < meta.end_pos]
        self._calls = [call for call in self._calls if call[0] >= meta.end_pos]
        chain = (f"{macro.name}/{len(param_names)}",)
        if used:
            chain += max((self._expansion[called][2] for called in used), key=len)
        if len(chain) > MAX_MACRO_DEPTH:
            raise GoalSyntaxError.at(macro.pos, f"macros nested more than {MAX_MACRO_DEPTH} "
                                     f"deep: {_chain(chain)}")
        self._expansion[key] = (_count(condition), _text_size(condition), chain)
        self.macros[key] = macro
        self.macro_list.append(macro)
        return macro

    def msc(self, meta, children):
        literals: list[ast.Literal] = []
        for child in children:
            if isinstance(child, tuple):
                literals.extend(child)  # an expanded macro
            else:
                literals.append(child)
        if _count(literals) > MAX_CONDITION_LITERALS:
            used = [self._expansion[called][2] for offset, called in self._calls
                    if meta.start_pos <= offset < meta.end_pos]
            where = f" ({_chain(max(used, key=len))})" if used else ""
            raise self.source.error(meta.start_pos, "this condition expands to more than "
                                    f"{MAX_CONDITION_LITERALS} literals{where}")
        return tuple(literals)

    def _mental(self, op: str, meta, children) -> ast.MentalLiteral:
        return ast.MentalLiteral(op, self.check(children[1]), self._pos(meta))

    def bel(self, meta, children):
        return self._mental("bel", meta, children)

    def goal(self, meta, children):
        return self._mental("goal", meta, children)

    def agoal(self, meta, children):
        return self._mental("a-goal", meta, children)

    def goala(self, meta, children):
        return self._mental("goal-a", meta, children)

    def percept(self, meta, children):
        return self._mental("percept", meta, children)

    def not_(self, meta, children):
        return ast.NotLiteral(children[1], self._pos(meta))

    def true_(self, meta, children):
        return ast.MentalLiteral("true", None, self._pos(meta))

    def done_(self, meta, children):
        """``done(Action)``: the action was just performed (a test condition)."""
        return ast.MentalLiteral("done", self.check(children[1]), self._pos(meta))

    def sender(self, meta, children):
        token = children[0]
        text = str(token)
        if token.type == "SENT_FROM":
            text = text.strip()[1:].split(")")[0].strip()
        return text

    def sent(self, meta, children):
        """``(S).sent!(φ)``: a message in the mailbox, as ``bel(received(S, imp(φ)))``."""
        sender, content = children[0], children[-1]
        mood = next((str(c) for c in children[2:-1] if getattr(c, "type", "") == "MOOD"), ":")
        wrapped = {"!": f"imp(({content.text}\n))", "?": f"int(({content.text}\n))"}.get(
            mood, f"({content.text}\n)")
        query = ast.PrologText(f"received({sender}, {wrapped})", content.pos)
        return ast.MentalLiteral("bel", self.check(query), self._pos(meta))

    def selector_literal(self, meta, children):
        """GOAL's selectors on mental literals: ``self.bel(φ)`` / ``this.bel(φ)`` is the
        agent's own ``bel(φ)``; ``(S).bel(φ)`` with S this agent (``me(S)``) is its own
        literal, with another agent what that agent told it (``received(S, φ)``; for goal
        literals the goals it asked it to adopt, ``received(S, imp(φ))``): goalagent keeps no
        other model of other agents' minds. ``all``/``allother``/``some``/``someother``
        (quantified models) are not supported."""
        raw = str(children[0]).strip()[:-1].strip()
        op = {"a-goal": "a-goal", "goal-a": "goal-a"}.get(str(children[1]), str(children[1]))
        content = children[2]
        if raw in ("self", "this"):
            return self._mental(op, meta, [None, content])
        if raw in ("all", "allother", "some", "someother"):
            raise GoalSyntaxError.at(self._pos(meta), f"the selector {raw}.{op}(..) (a "
                                     "quantified mental model) is not supported by goalagent; "
                                     "query received/2 for what other agents told")
        selector = raw[1:-1].strip() if raw.startswith("(") else raw
        told = "imp(" + content.text + "\n)" if op != "bel" else "(" + content.text + "\n)"
        own = "true" if op != "bel" else "(" + content.text + "\n)"
        text = f"(me({selector}) -> {own} ; received({selector}, {told}))"
        literal = ast.MentalLiteral("bel", self.check(ast.PrologText(text, content.pos)),
                                    self._pos(meta))
        if op == "bel":
            return literal
        # own goals when the selector is this agent, else the told goal (the bel above)
        own_goal = ast.MentalLiteral(op, self.check(content), self._pos(meta))  # type: ignore
        me = self.check(ast.PrologText(f"me({selector})", content.pos))
        return (literal, ast.NotLiteral((ast.MentalLiteral("bel", me, self._pos(meta)),
                                         ast.NotLiteral((own_goal,), self._pos(meta))),
                                        self._pos(meta)))

    def macro_call(self, meta, children):
        name = str(children[0])
        args: tuple[ast.PrologText, ...] = children[1] if len(children) > 1 else ()
        macro = self.macros.get((name, len(args)))
        if macro is None and self.plain_beliefs:
            return ast.MentalLiteral("bel", self.check(self._text(meta)), self._pos(meta))
        if macro is None:
            raise GoalSyntaxError.at(
                self._pos(meta),
                f"unknown mental literal {name}/{len(args)}: expected bel, goal, a-goal, "
                "goal-a, percept, not, true or a macro defined earlier with #define",
            )
        literals, size, chain = self._expansion[(name, len(args))]
        # Each occurrence of a parameter becomes its argument's text (in parentheses).
        for param, arg in zip(macro.params, args, strict=True):
            occurrences = sum(1 for text in condition_texts(macro.condition)
                              for var in variable_occurrences(text.text) if var == param)
            size += occurrences * (len(arg.text) + 2 - len(param))
        self._expanded += literals
        where = f" ({_chain(chain)})" if len(chain) > 1 else ""
        if literals > MAX_CONDITION_LITERALS or size > MAX_CONDITION_TEXT:
            raise GoalSyntaxError.at(self._pos(meta), f"macro {name}/{len(args)} expands to "
                                     f"more than {MAX_CONDITION_LITERALS} literals or "
                                     f"{MAX_CONDITION_TEXT} characters{where}")
        if self._expanded > MAX_FILE_EXPANSION:
            raise GoalSyntaxError.at(self._pos(meta), "macros expand to more than "
                                     f"{MAX_FILE_EXPANSION} literals in this file{where}")
        self._calls.append((meta.start_pos, (name, len(args))))
        return self._expand_macro(macro, args)

    def bare_expression(self, meta, children):
        """``PlaceID \\= 'DropZone'``, ``N is M + 1``: a bare Prolog literal, a belief query in
        the newest dialect (as its bare ``p(X)``); elsewhere it must be inside ``bel(..)``."""
        text = self._text(meta)
        if not self.plain_beliefs:
            raise GoalSyntaxError.at(
                self._pos(meta), f"`{text.text}` outside bel(..): only the newest dialect "
                "(use m for decisions) reads bare Prolog literals as belief queries")
        return ast.MentalLiteral("bel", self.check(text), self._pos(meta))

    def bare_operand(self, meta, _children):
        return None  # read as part of bare_expression's text

    def _expand_macro(self, macro: ast.Macro,
                      args: tuple[ast.PrologText, ...]) -> ast.Condition:
        """Substitute the arguments for the parameters; other variables become fresh."""
        mapping = {
            param: arg.text if re.fullmatch(r"[A-Za-z0-9_]+", arg.text) else f"({arg.text})"
            for param, arg in zip(macro.params, args, strict=True)
        }
        expansion = next(self._fresh_suffixes)
        for literal_text in condition_texts(macro.condition):
            for var in variable_occurrences(literal_text.text):
                if var not in mapping and var != "_":
                    mapping[var] = ast.macro_local(var, expansion)
        return self._renamed_condition(macro.condition, mapping)

    def _renamed_condition(self, condition: ast.Condition,
                           mapping: dict[str, str]) -> ast.Condition:
        """``condition`` with its variables renamed by ``mapping`` (texts checked again)."""
        renamed: list[ast.Literal] = []
        for literal in condition:
            if isinstance(literal, ast.NotLiteral):
                renamed.append(ast.NotLiteral(self._renamed_condition(literal.condition,
                                                                      mapping), literal.pos))
            elif literal.query is None:
                renamed.append(literal)
            else:
                text = rename_variables(literal.query.text, mapping)
                query = self.check(ast.PrologText(text, literal.query.pos))
                renamed.append(ast.MentalLiteral(literal.op, query, literal.pos))
        return tuple(renamed)


def _count(condition) -> int:
    """The literals of a condition, those inside not(...) included."""
    return sum(_count(literal.condition) + 1 if isinstance(literal, ast.NotLiteral) else 1
               for literal in condition)


def _text_size(condition) -> int:
    """The characters of Prolog text in a condition."""
    return sum(len(text.text) for text in condition_texts(condition))


def _chain(chain: tuple[str, ...]) -> str:
    """A macro chain as ``m3/0 -> m2/0 -> m1/0`` (shortened when long)."""
    shown = chain if len(chain) <= 8 else (*chain[:4], "...", *chain[-3:])
    return " -> ".join(shown)

"""Mental state conditions and macros (``#define`` in `.goal` files, ``define m(X) as MSC.``
in `.mod2g` files): the literals of a rule's condition, with each macro call expanded into
the macro's condition (arguments substituted, its other variables renamed apart). GOAL 6's
``(Sender).sent!(φ)`` reads the mailbox; ``done(Action)`` (tests only) is kept as a literal
of its own; the newest dialect's bare literals (``p(X)`` for ``bel(p(X))``) are read as
belief queries when the builder's ``plain_beliefs`` is set."""

from __future__ import annotations

import itertools
import re

from lark import v_args

from goalagent import ast
from goalagent.parser.builder_base import BuilderBase
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.variables import rename_variables, variable_occurrences


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

    def macro(self, meta, children):
        return self._define_macro(children)

    def macro_def(self, meta, children):
        return self._define_macro(children)

    def _define_macro(self, children) -> ast.Macro:
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
        self.macros[(macro.name, len(param_names))] = macro
        self.macro_list.append(macro)
        return macro

    def msc(self, meta, children):
        literals: list[ast.Literal] = []
        for child in children:
            if isinstance(child, tuple):
                literals.extend(child)  # an expanded macro
            else:
                literals.append(child)
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
        """GOAL's selectors (``(A).bel(φ)``, ``allother.goal(φ)``): not supported."""
        raise GoalSyntaxError.at(self._pos(meta), f"selectors on mental literals "
                                 f"({str(children[0]).strip()}{children[1]}(..)) are not "
                                 "supported by goalagent; write the literal without it")

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

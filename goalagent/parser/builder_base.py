"""What every part of the AST builder shares: positions, Prolog text checked by SWI-Prolog's
own reader, option lists, and the tree nodes of Prolog "token soup"."""

from __future__ import annotations

from collections.abc import Iterable

from lark import Token, Transformer, v_args

from goalagent import ast
from goalagent.kb.engine import PrologSyntaxError, get_engine
from goalagent.kb.terms import Struct, format_term
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.source import Source


class ParsedSection:
    """A parsed section (knowledge, beliefs, goals, program, actionspecs) before it is
    attached to its module."""

    def __init__(self, kind: str, items: tuple, pos: ast.Pos, options: dict | None = None):
        self.kind = kind
        self.items = items
        self.pos = pos
        self.options = options or {}


@v_args(meta=True)
class BuilderBase(Transformer):
    """Turns lark tree nodes into ``goalagent.ast`` objects; the parts for `.goal` sections,
    conditions and `.mas2g` files are mixed into :class:`~goalagent.parser.ast_builder.
    AstBuilder`."""

    def __init__(self, source: Source) -> None:
        super().__init__()
        self.source = source
        self.engine = get_engine()
        self.split_facts = True  # `a, b.` in a Prolog file is two facts (not for goal files)

    # --- helpers ------------------------------------------------------------------------
    def _pos(self, meta) -> ast.Pos:
        """The position where a tree node starts."""
        return self.source.pos(meta.start_pos)

    def _token_pos(self, token: Token) -> ast.Pos:
        """The position where a token starts."""
        return self.source.pos(token.start_pos)

    def _text(self, meta) -> ast.PrologText:
        """The (unchecked) Prolog text a tree node spans."""
        text, start = self.source.fragment(meta.start_pos, meta.end_pos)
        return ast.PrologText(text, self.source.pos(start))

    def check(self, fragment: ast.PrologText, clause: bool = False) -> ast.PrologText:
        """Read ``fragment`` with SWI-Prolog; a syntax error is reported at its position."""
        try:
            if clause:
                variables = self.engine.check_clause(fragment.text)
            else:
                variables = self.engine.check_query(fragment.text)
        except PrologSyntaxError as err:
            offset = fragment.pos.offset + min(max(err.offset, 0), len(fragment.text))
            raise self.source.error(offset, f"Prolog syntax error: {err.message}") from None
        return ast.PrologText(fragment.text, fragment.pos, tuple(variables))

    def _options(self, options, allowed: dict[str, tuple[str, ...]]) -> dict[str, str]:
        """``[key = value, ...]`` checked against the allowed keys and values."""
        result: dict[str, str] = {}
        for key_token, value_token in options or ():
            key, value = str(key_token), str(value_token)
            if key not in allowed:
                raise GoalSyntaxError.at(
                    self._token_pos(key_token),
                    f"unknown option {key!r} here; allowed: {', '.join(sorted(allowed))}",
                )
            if value not in allowed[key]:
                raise GoalSyntaxError.at(
                    self._token_pos(value_token),
                    f"{key}={value} is not allowed; {key} is one of {', '.join(allowed[key])}",
                )
            result[key] = value
        return result

    def _facts(self, clauses: Iterable[ast.PrologText]) -> tuple[ast.PrologText, ...]:
        """Clauses, with GOAL 3's ``block(a), block(b).`` split into one fact each."""
        result: list[ast.PrologText] = []
        for clause in clauses:
            term = self.engine.parse_term(clause.text) if "," in clause.text else None
            if isinstance(term, Struct) and term.name == "," and term.arity == 2:
                while isinstance(term, Struct) and term.name == "," and term.arity == 2:
                    result.append(self.check(ast.PrologText(format_term(term.args[0]),
                                                            clause.pos), clause=True))
                    term = term.args[1]
                result.append(self.check(ast.PrologText(format_term(term), clause.pos),
                                         clause=True))
            else:
                result.append(clause)
        return tuple(result)

    # --- Prolog soup ----------------------------------------------------------------------
    def ptext(self, meta, _children):
        return self._text(meta)

    def ptext_top(self, meta, _children):
        return self._text(meta)

    def parg(self, meta, _children):
        return self.check(self._text(meta))

    def pitem(self, meta, _children):
        return None

    def args(self, meta, children):
        return tuple(children)

    def clause(self, meta, children):
        return self.check(children[0], clause=True)

    def prolog_file(self, meta, children):
        return self._facts(children) if self.split_facts else tuple(children)

    # --- options --------------------------------------------------------------------------
    def option(self, meta, children):
        return (children[0], children[1])

    def options(self, meta, children):
        return list(children)

"""What every part of the AST builder shares: positions, Prolog text checked by SWI-Prolog's
own reader, option lists, and the tree nodes of Prolog "token soup"."""

from __future__ import annotations

import re
from collections.abc import Iterable

from lark import Token, Transformer_NonRecursive, v_args

from goalagent import ast
from goalagent.kb.engine import PrologSyntaxError, get_engine
from goalagent.kb.terms import Struct, format_term
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.source import Source

# A lower-case name, blanks, an opening parenthesis (quoted text matched first and kept).
_GLUED_ARGUMENTS = re.compile(r"'(?:\\.|''|[^'\\])*'|\"(?:\\.|\"\"|[^\"\\])*\"|"
                              r"(?<![A-Za-z0-9_])([a-z][A-Za-z0-9_]*)[ \t]+\(")
# Prefix operators a blank may separate from "(" (SWI-Prolog's and GOAL's common ones).
_PREFIX_WORDS = frozenset({"dynamic", "discontiguous", "initialization", "meta_predicate",
                           "module_transparent", "multifile", "public", "thread_local",
                           "table", "not", "is", "mod", "rem", "xor", "rdiv", "div", "as"})
# A message's mood: indicative, imperative (achieve goal), interrogative.
MOODS = (":", "!", "?")


class ParsedSection:
    """A parsed section (knowledge, beliefs, goals, program, actionspecs) before it is
    attached to its module."""

    def __init__(self, kind: str, items: tuple, pos: ast.Pos, options: dict | None = None):
        self.kind = kind
        self.items = items
        self.pos = pos
        self.options = options or {}


@v_args(meta=True)
class BuilderBase(Transformer_NonRecursive):
    """Turns lark tree nodes into ``goalagent.ast`` objects; the parts for `.goal` sections,
    conditions and `.mas2g` files are mixed into :class:`~goalagent.parser.ast_builder.
    AstBuilder`."""

    def __init__(self, source: Source) -> None:
        super().__init__()
        self.source = source
        self.engine = get_engine()
        self.split_facts = True  # `a, b.` in a Prolog file is two facts (not for goal files)
        self.warnings: list[str] = []  # what GOAL warns about but accepts, as located lines

    # --- helpers ------------------------------------------------------------------------
    def warn(self, pos: ast.Pos, message: str) -> None:
        """A located warning (the file is still accepted)."""
        self.warnings.append(f"{pos}: warning: {message}")

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
        """Read ``fragment`` with SWI-Prolog; a syntax error is reported at its position.
        Text that SWI-Prolog 7+ rejects only for a blank between a name and its arguments
        (``in ('DropZone')``, which the SWI-Prolog of GOAL 4/5 read as ``in('DropZone')``)
        or for an infix bar in an argument is read as those read it."""
        try:
            variables = self._read(fragment.text, clause)
        except PrologSyntaxError as err:
            for lenient in self._lenient_readings(fragment.text, clause):
                try:
                    variables = self._read(lenient, clause)
                    return ast.PrologText(lenient, fragment.pos, tuple(variables))
                except PrologSyntaxError:
                    pass
            offset = fragment.pos.offset + min(max(err.offset, 0), len(fragment.text))
            raise self.source.error(offset, f"Prolog syntax error: {err.message}") from None
        return ast.PrologText(fragment.text, fragment.pos, tuple(variables))

    def _lenient_readings(self, text: str, clause: bool) -> list[str]:
        """Readings of a text SWI-Prolog 9 refuses that the SWI-Prolog of GOAL 4/5 took:
        without a blank between a name and its arguments, and an argument holding SWI-7's
        infix bar (``print("a:"|X)``) in parentheses, where the bar may stand."""
        readings = []
        glued = _GLUED_ARGUMENTS.sub(self._glue, text)
        if glued != text:
            readings.append(glued)
        if "|" in text and not clause:
            readings.append(f"({text}\n)")
        return readings

    def _read(self, text: str, clause: bool) -> tuple[str, ...]:
        return tuple(self.engine.check_clause(text) if clause else self.engine.check_query(text))

    def _glue(self, match) -> str:
        """``name (`` as ``name(`` unless the name is a prefix operator (``dynamic (p/1)``)."""
        name = match.group(1)
        if name is None or name in _PREFIX_WORDS:
            return match.group(0)
        return name + "("

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
        text = self._text(meta)
        if text.text[:1] in MOODS and not text.text.startswith(":-"):
            # GOAL 3's send(Receiver, :φ): a mood before the content; call() checks the rest
            rest = self.check(ast.PrologText(text.text[1:], text.pos))
            return ast.PrologText(text.text, text.pos, rest.variables)
        return self.check(text)

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

"""The concrete syntax (``grammar.lark``, one LALR parser for `.goal`, `.mas2g` and Prolog
files) and the translation of lark's errors into located, readable messages."""

from __future__ import annotations

from collections.abc import Iterable
from functools import cache
from pathlib import Path

from lark import Lark, Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken

from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.source import Source


@cache
def _grammar() -> Lark:
    """The parser, built once per process from grammar.lark."""
    grammar = (Path(__file__).with_name("grammar.lark")).read_text(encoding="utf-8")
    return Lark(
        grammar,
        parser="lalr",
        lexer="contextual",
        start=["agent", "mas", "prolog_file", "module_file", "action_file", "test_file"],
        propagate_positions=True,
        maybe_placeholders=False,
    )


def parse_tree(source: Source, start: str) -> Tree:
    """The syntax tree of ``source`` from rule ``start`` (agent, mas or prolog_file)."""
    try:
        return _grammar().parse(source.text, start=start)
    except UnexpectedInput as err:
        raise _located_error(err, source) from None


_TOKEN_NAMES = {
    "END_DOT": "'.' (end of clause or rule)",
    "LBRACE": "'{'",
    "RBRACE": "'}'",
    "LPAR": "'('",
    "RPAR": "')'",
    "LSQB": "'['",
    "RSQB": "']'",
    "COMMA": "','",
    "PLUS": "'+'",
    "COLON": "':'",
    "EQUAL": "'='",
    "NAME": "a name",
    "VAR": "a variable",
    "DQSTRING": "a string",
    "AT_INT": "'@int'",
    "LARROW": "'<-'",
    "DOT": "'.send(...)' after a receiver",
    "EXIT_MODULE": "'exit-module'",
}


_PROLOG_TOKENS = frozenset({"NAME", "VAR", "NUMBER", "QATOM", "DQSTRING", "BQSTRING",
                            "CHARCODE", "SYMBOL", "SOLO", "LPAR", "LSQB", "LBRACE", "COMMA",
                            "VBAR"})


def _describe_expected(expected: Iterable[str]) -> str:
    """A readable list of what the grammar expected; Prolog tokens are summed up as such."""
    expected = set(expected)
    prolog = expected & _PROLOG_TOKENS
    names = {_TOKEN_NAMES.get(t, t.lower().replace("_kw", "")) for t in expected - prolog}
    if len(prolog) >= 4:
        names.add("more Prolog text")
    else:
        names |= {_TOKEN_NAMES.get(t, t.lower()) for t in prolog}
    names = sorted(names)
    if len(names) > 8:
        names = names[:8] + ["..."]
    return ", ".join(names)


def _shortened(text: str, keep: int = 40) -> str:
    """``text`` quoted, cut to its first ``keep`` characters (a token may be a whole line)."""
    return repr(text) if len(text) <= keep else f"{text[:keep]!r}... ({len(text)} characters)"


def _located_error(err: UnexpectedInput, source: Source) -> GoalSyntaxError:
    """Lark's error as a GoalSyntaxError at the offending character."""
    if isinstance(err, UnexpectedEOF):
        return source.error(
            len(source.text), f"unexpected end of file, expected {_describe_expected(err.expected)}"
        )
    if isinstance(err, UnexpectedToken):
        token = err.token
        if token.type == "$END":
            return source.error(
                len(source.text.rstrip()),
                f"unexpected end of file, expected {_describe_expected(err.expected)}",
            )
        return source.error(
            token.start_pos,
            f"unexpected {_shortened(token.value)}, expected {_describe_expected(err.expected)}",
        )
    if isinstance(err, UnexpectedCharacters):
        char = source.text[err.pos_in_stream] if err.pos_in_stream < len(source.text) else ""
        expected = _describe_expected(err.allowed) if err.allowed else "something else"
        return source.error(err.pos_in_stream,
                            f"unexpected character {char!r}, expected {expected}")
    return source.error(0, str(err))

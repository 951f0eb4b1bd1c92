"""The concrete syntax (``grammar.lark``, one LALR parser for `.goal`, `.mas2g` and Prolog
files) and the translation of lark's errors into located, readable messages.

The built parser is kept beside the bytecode and loaded by the next process (0.02 s instead
of the 0.2 s its tables take to build). Lark's own ``cache=`` option is not used: it pickles
to the shared temporary folder, where another user could leave a file for this one to
unpickle, and writes it in place, where a second process can read it half written."""

from __future__ import annotations

import contextlib
import hashlib
import io
import sys
from collections.abc import Iterable
from functools import cache
from pathlib import Path

import lark
from lark import Lark, Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken

from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.source import Source
from ondisk import write_atomically

GRAMMAR = Path(__file__).with_name("grammar.lark")
OPTIONS = {"parser": "lalr", "lexer": "contextual",
           "start": ["agent", "mas", "prolog_file", "module_file", "action_file", "test_file"],
           "propagate_positions": True, "maybe_placeholders": False}
"""How grammar.lark is made a parser (the cached parser's key includes them)."""


@cache
def _grammar() -> Lark:
    """The parser, built once per process from grammar.lark, or loaded from the one built
    before (see :func:`cached_parser_path`): building the LALR tables took 0.2 s of every
    ``goalagent`` process's start, loading them takes 0.02 s."""
    grammar = GRAMMAR.read_text(encoding="utf-8")
    return load_or_build(grammar, cached_parser_path(grammar), keep=not sys.dont_write_bytecode)


def load_or_build(grammar: str, cached: Path, keep: bool) -> Lark:
    """The parser kept at ``cached``, or, when there is none that loads, the one built from
    ``grammar`` (and kept there if ``keep``)."""
    with contextlib.suppress(Exception), cached.open("rb") as stream:  # else build it
        return Lark.load(stream)
    parser = Lark(grammar, **OPTIONS)
    if keep:
        save_parser(parser, cached)
    return parser


def cached_parser_path(grammar: str) -> Path:
    """Where the parser built from ``grammar`` is kept: beside this module's bytecode, as
    Python keeps that, named by a digest of the grammar, lark's and Python's versions and
    OPTIONS (a changed grammar, lark or Python gets a new file). It is trusted as the
    bytecode is: only the one who installed goalagent can write there."""
    key = hashlib.sha256(repr((grammar, lark.__version__, sys.version_info[:2],
                               sorted(OPTIONS.items()))).encode("utf-8")).hexdigest()[:20]
    return GRAMMAR.with_name("__pycache__") / f"grammar.{key}.lark"


def save_parser(parser: Lark, path: Path) -> None:
    """Keep ``parser`` at ``path`` for the next processes, written atomically; where it cannot
    be written (a read-only install) each process builds its own, as before."""
    stream = io.BytesIO()
    parser.save(stream)
    with contextlib.suppress(OSError):
        path.parent.mkdir(exist_ok=True)
        write_atomically(path, stream.getvalue())


def keep_parser() -> Path:
    """Build the parser and keep it whatever PYTHONDONTWRITEBYTECODE says, as
    ``python -m compileall`` keeps bytecode (``scripts/setup.sh`` calls this once)."""
    grammar = GRAMMAR.read_text(encoding="utf-8")
    path = cached_parser_path(grammar)
    save_parser(Lark(grammar, **OPTIONS), path)
    return path


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

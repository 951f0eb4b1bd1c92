"""Parse `.goal` and `.mas2g` files into immutable program objects (``goalagent.ast``).

The program structure is parsed by lark with ``grammar.lark``; every Prolog fragment is then
read by SWI-Prolog itself (``goalagent.kb.engine``), so Prolog text means exactly what it
means to SWI-Prolog. Every error is a ``GoalSyntaxError`` carrying ``file:line:col``.
"""

from __future__ import annotations

import bisect
import itertools
import re
from collections import Counter
from collections.abc import Iterable, Iterator
from dataclasses import replace
from functools import cache
from pathlib import Path

from lark import Lark, Token, Transformer, v_args
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken

from goalagent import ast
from goalagent.kb.engine import PrologSyntaxError, get_engine
from goalagent.kb.terms import Struct, format_term


class GoalSyntaxError(Exception):
    """A user error in a program file, located at ``file:line:col``."""

    def __init__(self, file: str, line: int, col: int, message: str) -> None:
        super().__init__(f"{file}:{line}:{col}: {message}")
        self.file = file
        self.line = line
        self.col = col
        self.message = message

    @classmethod
    def at(cls, pos: ast.Pos, message: str) -> GoalSyntaxError:
        return cls(pos.file, pos.line, pos.col, message)


# ----------------------------------------------------------------------------- source text


class Source:
    """A program text with comments blanked out and offset -> line/column mapping."""

    def __init__(self, text: str, file: str) -> None:
        self.file = file
        self.original = text
        self._line_starts = [0] + [m.end() for m in re.finditer(r"\n", text)]
        self.text = self._blank_comments(text)

    def pos(self, offset: int) -> ast.Pos:
        line = bisect.bisect_right(self._line_starts, offset)
        col = offset - self._line_starts[line - 1] + 1
        return ast.Pos(self.file, line, col, offset)

    def error(self, offset: int, message: str) -> GoalSyntaxError:
        return GoalSyntaxError.at(self.pos(offset), message)

    def fragment(self, start: int, end: int) -> tuple[str, int]:
        """The stripped text between two offsets and the offset where it starts."""
        raw = self.text[start:end]
        stripped = raw.lstrip()
        return stripped.rstrip(), start + len(raw) - len(stripped)

    def _blank_comments(self, text: str) -> str:
        """Replace comments by spaces (newlines kept) so that offsets stay valid.

        ``%`` and ``/* */`` comments are Prolog's own; ``//`` starts a comment only outside
        Prolog text, i.e. where it begins a line or follows ``{ } ] .``.
        """
        out = list(text)
        i, n = 0, len(text)
        while i < n:
            ch = text[i]
            if ch in "'\"`":
                if ch == "'" and i > 0 and text[i - 1] == "0" and (
                    i < 2 or not (text[i - 2].isalnum() or text[i - 2] == "_")
                ):
                    i += 3 if text[i + 1 : i + 2] == "\\" else 2  # 0'c character code
                    continue
                i = self._skip_quoted(text, i)
            elif ch == "%":
                i = self._blank_until(out, text, i, "\n")
            elif text.startswith("/*", i):
                end = text.find("*/", i + 2)
                if end < 0:
                    raise self.error(i, "unterminated /* comment")
                for k in range(i, end + 2):
                    if out[k] != "\n":
                        out[k] = " "
                i = end + 2
            elif text.startswith("//", i) and self._slash_comment_allowed(text, i):
                i = self._blank_until(out, text, i, "\n")
            else:
                i += 1
        return "".join(out)

    def _skip_quoted(self, text: str, start: int) -> int:
        quote = text[start]
        i = start + 1
        while i < len(text):
            ch = text[i]
            if ch == "\\":
                i += 2
            elif ch == quote:
                if text[i + 1 : i + 2] == quote:
                    i += 2
                else:
                    return i + 1
            else:
                i += 1
        raise self.error(start, f"unterminated quoted text starting with {quote}")

    @staticmethod
    def _blank_until(out: list[str], text: str, start: int, stop: str) -> int:
        end = text.find(stop, start)
        end = len(text) if end < 0 else end
        for k in range(start, end):
            out[k] = " "
        return end

    @staticmethod
    def _slash_comment_allowed(text: str, i: int) -> bool:
        k = i - 1
        while k >= 0 and text[k] in " \t\r":
            k -= 1
        return k < 0 or text[k] in "\n{}]."


LIBRARY = Path(__file__).parent / "kb"  # Prolog libraries an agent can #import by name

# ----------------------------------------------------------------------------- lark


@cache
def _lark() -> Lark:
    grammar = (Path(__file__).with_name("grammar.lark")).read_text(encoding="utf-8")
    return Lark(
        grammar,
        parser="lalr",
        lexer="contextual",
        start=["agent", "mas", "prolog_file"],
        propagate_positions=True,
        maybe_placeholders=False,
    )


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


def _lark_error(err: UnexpectedInput, source: Source) -> GoalSyntaxError:
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
            f"unexpected {token.value!r}, expected {_describe_expected(err.expected)}",
        )
    if isinstance(err, UnexpectedCharacters):
        char = source.text[err.pos_in_stream] if err.pos_in_stream < len(source.text) else ""
        expected = _describe_expected(err.allowed) if err.allowed else "something else"
        return source.error(err.pos_in_stream,
                            f"unexpected character {char!r}, expected {expected}")
    return source.error(0, str(err))


# ----------------------------------------------------------------------------- variables

_VAR_OR_QUOTED = re.compile(
    r"'(?:\\.|''|[^'\\])*'|\"(?:\\.|\"\"|[^\"\\])*\"|`(?:\\.|``|[^`\\])*`|0'(?:\\.|''|.)"
    r"|(?<![A-Za-z0-9_])([A-Z_][A-Za-z0-9_]*)"
)


def variable_occurrences(text: str) -> Iterator[str]:
    """Variable names in Prolog text, once per occurrence (quoted text skipped)."""
    for match in _VAR_OR_QUOTED.finditer(text):
        if match.group(1):
            yield match.group(1)


def rename_variables(text: str, mapping: dict[str, str]) -> str:
    """Replace variables by the texts in ``mapping`` (quoted text untouched)."""

    def substitute(match: re.Match[str]) -> str:
        name = match.group(1)
        return mapping.get(name, match.group(0)) if name else match.group(0)

    return _VAR_OR_QUOTED.sub(substitute, text)


# ----------------------------------------------------------------------------- transformer

_MODULE_OPTIONS = {
    "exit": ("always", "never", "nogoals", "noaction"),
    "focus": ("none", "new", "select", "filter"),
}
_PROGRAM_OPTIONS = {"order": ("linear", "linearall", "random", "randomall", "adaptive")}
_MOODS = {"!": "!", "?": "?", ":": ":"}
_CONJUNCTION_ACTIONS = frozenset({"insert", "delete", "adopt", "drop"})


class _Section:
    """A parsed section before it is attached to its module."""

    def __init__(self, kind: str, items: tuple, pos: ast.Pos, options: dict | None = None):
        self.kind = kind
        self.items = items
        self.pos = pos
        self.options = options or {}


@v_args(meta=True)
class _Builder(Transformer):
    """Turns the lark tree into ``goalagent.ast`` objects, checking Prolog text with SWI."""

    def __init__(self, source: Source) -> None:
        super().__init__()
        self.source = source
        self.engine = get_engine()
        self.macros: dict[tuple[str, int], ast.Macro] = {}
        self.macro_list: list[ast.Macro] = []
        self._fresh = itertools.count(1)

    # --- helpers ------------------------------------------------------------------------
    def _pos(self, meta) -> ast.Pos:
        return self.source.pos(meta.start_pos)

    def _tpos(self, token: Token) -> ast.Pos:
        return self.source.pos(token.start_pos)

    def _text(self, meta) -> ast.PrologText:
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
        result: dict[str, str] = {}
        for key_token, value_token in options or ():
            key, value = str(key_token), str(value_token)
            if key not in allowed:
                raise GoalSyntaxError.at(
                    self._tpos(key_token),
                    f"unknown option {key!r} here; allowed: {', '.join(sorted(allowed))}",
                )
            if value not in allowed[key]:
                raise GoalSyntaxError.at(
                    self._tpos(value_token),
                    f"{key}={value} is not allowed; {key} is one of {', '.join(allowed[key])}",
                )
            result[key] = value
        return result

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

    # --- options --------------------------------------------------------------------------
    def option(self, meta, children):
        return (children[0], children[1])

    def options(self, meta, children):
        return list(children)

    # --- sections -------------------------------------------------------------------------
    def knowledge(self, meta, children):
        return _Section("knowledge", self._facts(children[1:]), self._pos(meta))

    def beliefs(self, meta, children):
        return _Section("beliefs", self._facts(children[1:]), self._pos(meta))

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

    def goals(self, meta, children):
        return _Section("goals", tuple(children[1:]), self._pos(meta))

    def program(self, meta, children):
        options = next((c for c in children if isinstance(c, list)), None)
        rules = tuple(c for c in children if isinstance(c, ast.Rule))
        return _Section(
            "program", rules, self._pos(meta), self._options(options, _PROGRAM_OPTIONS)
        )

    def actionspecs(self, meta, children):
        return _Section("actionspecs", tuple(children[1:]), self._pos(meta))

    def pre(self, meta, children):
        return self._condition_text(children)

    def post(self, meta, children):
        return self._condition_text(children)

    def _condition_text(self, children) -> ast.PrologText:
        if len(children) > 1:
            return self.check(children[1])
        return ast.PrologText("true", self._tpos(children[0]), ())

    def actionspec(self, meta, children):
        name = children[0]
        params = next((c for c in children if isinstance(c, tuple)), ())
        internal = any(isinstance(c, Token) and c.type == "AT_INT" for c in children)
        environment = any(isinstance(c, Token) and c.type == "AT_ENV" for c in children)
        if str(name) in ast.BUILTIN_ACTIONS and not environment:
            raise GoalSyntaxError.at(
                self._tpos(name), f"{name} is a built-in action; write {name}(...)@env {{ ... }}"
                " to declare an environment action with that name")
        pre, post = children[-2], children[-1]
        return ast.ActionSpec(str(name), params, pre, post, self._tpos(name), internal,
                              environment)

    def import_(self, meta, children):
        """``#import "file.pl".``: the file's clauses become knowledge (GOAL 5)."""
        name = str(self.engine.parse_term(str(children[1])))
        pos = self._tpos(children[1])
        if not name.endswith(".pl"):
            raise GoalSyntaxError.at(pos, f"cannot #import {name!r}: only Prolog (.pl) files "
                                     "can be imported; put modules in this file")
        path = Path(self.source.file).parent / name
        if not path.exists() and (LIBRARY / name).exists():
            path = LIBRARY / name  # a library shipped with goalagent, e.g. affordance.pl
        if not path.exists():
            raise GoalSyntaxError.at(pos, f"cannot #import {name!r}: no such file next to "
                                     "this program nor in goalagent's Prolog libraries")
        clauses = parse_prolog_file(path)
        return _Section("knowledge", clauses, pos)

    def prolog_file(self, meta, children):
        return self._facts(children)

    # --- macros and mental state conditions ---------------------------------------------
    def macro(self, meta, children):
        name = children[1]
        params = next((c for c in children[2:] if isinstance(c, tuple) and c and
                       isinstance(c[0], ast.PrologText)), ())
        condition = children[-2]
        param_names = []
        for param in params:
            if not re.fullmatch(r"[A-Z_][A-Za-z0-9_]*", param.text):
                raise GoalSyntaxError.at(param.pos, "a macro parameter must be a variable")
            param_names.append(param.text)
        macro = ast.Macro(str(name), tuple(param_names), condition, self._tpos(name))
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

    def macro_call(self, meta, children):
        name = str(children[0])
        args: tuple[ast.PrologText, ...] = children[1] if len(children) > 1 else ()
        macro = self.macros.get((name, len(args)))
        if macro is None:
            raise GoalSyntaxError.at(
                self._pos(meta),
                f"unknown mental literal {name}/{len(args)}: expected bel, goal, a-goal, "
                "goal-a, percept, not, true or a macro defined earlier with #define",
            )
        return self._expand(macro, args)

    def _expand(self, macro: ast.Macro, args: tuple[ast.PrologText, ...]) -> ast.Condition:
        """Substitute the arguments for the parameters; other variables become fresh."""
        mapping = {
            param: arg.text if re.fullmatch(r"[A-Za-z0-9_]+", arg.text) else f"({arg.text})"
            for param, arg in zip(macro.params, args, strict=True)
        }
        suffix = f"_M{next(self._fresh)}"
        for literal_text in _condition_texts(macro.condition):
            for var in variable_occurrences(literal_text.text):
                if var not in mapping and var != "_":
                    mapping[var] = var + suffix
        return self._rename(macro.condition, mapping)

    def _rename(self, condition: ast.Condition, mapping: dict[str, str]) -> ast.Condition:
        renamed: list[ast.Literal] = []
        for literal in condition:
            if isinstance(literal, ast.NotLiteral):
                renamed.append(ast.NotLiteral(self._rename(literal.condition, mapping),
                                              literal.pos))
            elif literal.query is None:
                renamed.append(literal)
            else:
                text = rename_variables(literal.query.text, mapping)
                query = self.check(ast.PrologText(text, literal.query.pos))
                renamed.append(ast.MentalLiteral(literal.op, query, literal.pos))
        return tuple(renamed)

    # --- actions ---------------------------------------------------------------------------
    def combo(self, meta, children):
        return tuple(children)

    def call(self, meta, children):
        name = str(children[0])
        args = children[1] if len(children) > 1 else ()
        pos = self._pos(meta)
        if name in ("send", "sendonce"):
            if len(args) != 2:
                raise GoalSyntaxError.at(
                    pos, f"{name} needs an addressee: write Receiver.{name}(Message), "
                    f"with Receiver an agent, allother or all"
                )
            mood, content = self._mood(args[1])
            return ast.SendAction(name == "sendonce", args[0], mood, content, pos)
        if name in _CONJUNCTION_ACTIONS and len(args) > 1:
            # insert(a, not(b)) is insert((a, not(b))): one conjunction, as GOAL reads it
            joined = ", ".join(arg.text for arg in args)
            args = (self.check(ast.PrologText(joined, args[0].pos)),)
        return ast.ActionCall(name, args, pos)

    def exit_module(self, meta, children):
        return ast.ActionCall("exit-module", (), self._pos(meta))

    def receiver(self, meta, children):
        token = children[0]
        return ast.PrologText(str(token), self._tpos(token), (str(token),)
                              if token.type == "VAR" else ())

    def send(self, meta, children):
        receiver, keyword, content = children[0], children[1], children[2]
        mood, message = self._mood(content)
        return ast.SendAction(str(keyword) == "sendonce", receiver, mood, message,
                              self._pos(meta))

    def _mood(self, content: ast.PrologText) -> tuple[str, ast.PrologText]:
        text = content.text
        mood = ":"
        if text[:1] in _MOODS and not text.startswith(":-") and len(text) > 1:
            mood = text[0]
            stripped = text[1:].lstrip()
            skipped = len(text) - len(stripped)
            pos = self.source.pos(content.pos.offset + skipped)
            content = ast.PrologText(stripped, pos)
        return mood, self.check(content)

    # --- rules ---------------------------------------------------------------------------
    def combo_body(self, meta, children):
        return ("actions", children[0])

    def block_body(self, meta, children):
        rules = tuple(c for c in children if isinstance(c, ast.Rule))
        return ("rules", rules)

    def _rule(self, kind: str, meta, condition, body, list_var=None) -> ast.Rule:
        body_kind, content = body
        if body_kind == "actions":
            return ast.Rule(kind, condition, self._pos(meta), actions=content, list_var=list_var)
        return ast.Rule(kind, condition, self._pos(meta), rules=content, list_var=list_var)

    def if_rule(self, meta, children):
        return self._rule("if", meta, children[1], children[3])

    def forall_rule(self, meta, children):
        return self._rule("forall", meta, children[1], children[3])

    def listall_rule(self, meta, children):
        return self._rule("listall", meta, children[3], children[5], list_var=str(children[1]))

    def listall_rule_rtl(self, meta, children):
        return self._rule("listall", meta, children[1], children[5], list_var=str(children[3]))

    # --- modules ---------------------------------------------------------------------------
    def init_head(self, meta, children):
        return ("init", "init", (), children[2] if len(children) > 2 else None, meta)

    def main_head(self, meta, children):
        return ("main", "main", (), children[2] if len(children) > 2 else None, meta)

    def event_head(self, meta, children):
        return ("event", "event", (), children[2] if len(children) > 2 else None, meta)

    def user_head(self, meta, children):
        name = str(children[1])
        params = next((c for c in children[2:] if isinstance(c, tuple)), ())
        options = next((c for c in children[2:] if isinstance(c, list)), None)
        return ("user", name, params, options, meta)

    def module(self, meta, children):
        kind, name, params, options, head_meta = children[0]
        opts = self._options(options, _MODULE_OPTIONS)
        fields: dict[str, list] = {"knowledge": [], "beliefs": [], "goals": [], "actionspecs": []}
        rules: tuple[ast.Rule, ...] = ()
        order = None
        seen_program = False
        for item in children[1:]:
            if isinstance(item, ast.Macro):
                continue
            if item.kind == "program":
                if seen_program:
                    raise GoalSyntaxError.at(item.pos, f"module {name} has two program sections")
                seen_program = True
                rules, order = item.items, item.options.get("order")
            else:
                fields[item.kind].extend(item.items)
        return ast.Module(
            name, kind, self.source.pos(head_meta.start_pos), params,
            exit=opts.get("exit"), focus=opts.get("focus"), order=order, rules=rules,
            knowledge=tuple(fields["knowledge"]), beliefs=tuple(fields["beliefs"]),
            goals=tuple(fields["goals"]), actionspecs=tuple(fields["actionspecs"]),
        )

    def wrapper(self, meta, children):
        return ("wrapper", str(children[1]), children[2:])

    def agent(self, meta, children):
        if len(children) == 1 and isinstance(children[0], tuple) and children[0][0] == "wrapper":
            return children[0][1], list(children[0][2])
        return None, list(children)

    # --- .mas2g ---------------------------------------------------------------------------
    def env_item(self, meta, children):
        return (str(children[0]), self.check(children[1]), self._tpos(children[0]))

    def environment(self, meta, children):
        return ("environment", children[1:], self._pos(meta))

    def agentfile(self, meta, children):
        path = self.engine.parse_term(str(children[0]))
        options = next((c for c in children[1:] if isinstance(c, list)), [])
        values = {str(k): (str(v), k) for k, v in options}
        unknown = [key for key in values if key not in ("name", "number")]
        if unknown:
            raise GoalSyntaxError.at(self._tpos(values[unknown[0]][1]),
                                     f"unknown agent file option {unknown[0]!r}")
        name = values.get("name", (Path(str(path)).stem, None))[0]
        number = self._int_option(values, "number")
        return ast.AgentFile(str(path), name, self._pos(meta), number or 1)

    def _int_option(self, values: dict, key: str) -> int | None:
        if key not in values:
            return None
        text, token = values[key]
        if not text.isdigit():
            raise GoalSyntaxError.at(self._tpos(token), f"{key} must be a whole number")
        return int(text)

    def agentfiles(self, meta, children):
        return ("agentfiles", children[1:], self._pos(meta))

    def launch_target(self, meta, children):
        return (str(children[0]), str(children[1]))

    def entity_condition(self, meta, children):
        return children

    def launch(self, meta, children):
        name, file = children[1]
        return ast.LaunchRule(name, file, self._pos(meta))

    def when_launch(self, meta, children):
        condition = children[1]
        name, file = children[-2] if isinstance(children[-2], tuple) else children[-1]
        entity_type = None
        limit = None
        for item in condition:
            if isinstance(item, tuple):
                key, value = str(item[0]), str(item[1])
                if key == "type":
                    entity_type = value
                elif key == "max":
                    limit = self._int_option({key: (value, item[1])}, key)
                else:
                    raise GoalSyntaxError.at(self._tpos(item[0]),
                                             f"unknown entity condition {key!r} (type, max)")
        return ast.LaunchRule(name, file, self._pos(meta), on_entity=True,
                              entity_type=entity_type, max=limit)

    def launchpolicy(self, meta, children):
        return ("launchpolicy", children[1:], self._pos(meta))

    def mas(self, meta, children):
        return children


# ----------------------------------------------------------------------------- assembly


def _assemble(name: str | None, items: list, file: str, builder: _Builder) -> ast.AgentProgram:
    modules: list[ast.Module] = []
    top: dict[str, list] = {"knowledge": [], "beliefs": [], "goals": [], "actionspecs": []}
    top_program: _Section | None = None
    for item in items:
        if isinstance(item, ast.Module):
            if item.kind != "user" and any(m.name == item.name for m in modules):
                raise GoalSyntaxError.at(item.pos, f"there is already a {item.name} module")
            modules.append(item)
        elif isinstance(item, _Section):
            if item.kind == "program":
                top_program = item
            else:
                top[item.kind].extend(item.items)
    if top_program is not None:
        if any(m.kind == "main" for m in modules):
            raise GoalSyntaxError.at(top_program.pos,
                                     "a program section outside modules and a main module")
        modules.append(ast.Module("main", "main", top_program.pos, rules=top_program.items,
                                  order=top_program.options.get("order")))
    everything = [top, *({"knowledge": list(m.knowledge), "beliefs": list(m.beliefs),
                          "goals": list(m.goals), "actionspecs": list(m.actionspecs)}
                         for m in modules)]
    gathered = {key: tuple(x for part in everything for x in part[key]) for key in top}
    overriding = {(spec.name, spec.arity) for spec in gathered["actionspecs"]
                  if spec.name in ast.BUILTIN_ACTIONS}
    if overriding:
        modules = [replace(m, rules=_mark_overrides(m.rules, overriding)) for m in modules]
    return ast.AgentProgram(
        name=name or Path(file).stem,
        file=file,
        modules=tuple(modules),
        macros=tuple(builder.macro_list),
        knowledge=gathered["knowledge"],
        beliefs=gathered["beliefs"],
        goals=gathered["goals"],
        actionspecs=gathered["actionspecs"],
    )


def _mark_overrides(rules: tuple[ast.Rule, ...],
                    overriding: set[tuple[str, int]]) -> tuple[ast.Rule, ...]:
    """Calls of built-in names that an ``@env`` actionspec declares go to that actionspec."""
    marked = []
    for rule in rules:
        actions = tuple(
            replace(a, overrides_builtin=True)
            if isinstance(a, ast.ActionCall) and (a.name, a.arity) in overriding else a
            for a in rule.actions
        )
        inner = _mark_overrides(rule.rules, overriding) if rule.rules else rule.rules
        marked.append(replace(rule, actions=actions, rules=inner))
    return tuple(marked)


def _parse(text: str, file: str, start: str):
    source = Source(text, file)
    try:
        tree = _lark().parse(source.text, start=start)
    except UnexpectedInput as err:
        raise _lark_error(err, source) from None
    builder = _Builder(source)
    try:
        return builder.transform(tree), builder
    except Exception as err:  # lark wraps errors raised inside callbacks
        inner = getattr(err, "orig_exc", None)
        if isinstance(inner, GoalSyntaxError):
            raise inner from None
        raise


def parse_agent(text: str, file: str = "<string>") -> ast.AgentProgram:
    """Parse the text of a `.goal` agent program."""
    (name, items), builder = _parse(text, file, "agent")
    program = _assemble(name, items, file, builder)
    return _with_warnings(program)


def parse_agent_file(path: str | Path) -> ast.AgentProgram:
    """Parse a `.goal` file (any extension but `.mas2g`)."""
    return parse_agent(_read(path), str(path))


def parse_mas(text: str, file: str = "<string>") -> ast.MasProgram:
    """Parse the text of a `.mas2g` multi-agent system file."""
    sections, _ = _parse(text, file, "mas")
    environment = None
    env_init: tuple[tuple[str, ast.PrologText], ...] = ()
    agentfiles: list[ast.AgentFile] = []
    launches: list[ast.LaunchRule] = []
    for kind, items, _ in sections:
        if kind == "environment":
            for key, value, key_pos in items:
                if key == "env":
                    environment = str(get_engine().parse_term(value.text))
                elif key == "init":
                    env_init = _init_pairs(value, key_pos)
                else:
                    raise GoalSyntaxError.at(key_pos, f"unknown environment key {key!r} "
                                             "(env, init)")
        elif kind == "agentfiles":
            agentfiles.extend(items)
        else:
            launches.extend(items)
    known = {a.name for a in agentfiles}
    for rule in launches:
        if rule.agentfile not in known:
            raise GoalSyntaxError.at(rule.pos, f"launch refers to unknown agent file "
                                     f"{rule.agentfile!r}; known: {', '.join(sorted(known))}")
    first = sections[0][2] if sections else ast.Pos(file, 1, 1)
    return ast.MasProgram(file, environment, env_init, tuple(agentfiles), tuple(launches), first)


def _init_pairs(value: ast.PrologText, pos: ast.Pos) -> tuple[tuple[str, ast.PrologText], ...]:
    """``[key = value, ...]`` as (key, value text) pairs, each value kept as Prolog text."""
    term = get_engine().parse_term(value.text)
    if not isinstance(term, list):
        raise GoalSyntaxError.at(value.pos, "init must be a list [key = value, ...]")
    pairs = []
    for item in term:
        if not (isinstance(item, Struct) and item.name == "=" and item.arity == 2):
            raise GoalSyntaxError.at(value.pos,
                                     f"init entry {format_term(item)} is not key = value")
        key = item.args[0]
        pairs.append((str(key), ast.PrologText(format_term(item.args[1]), value.pos)))
    return tuple(pairs)


def parse_prolog_file(path: str | Path) -> tuple[ast.PrologText, ...]:
    """The clauses of a Prolog file, each read by SWI-Prolog (for ``#import``)."""
    clauses, _ = _parse(_read(path), str(path), "prolog_file")
    return clauses


def parse_mas_file(path: str | Path) -> ast.MasProgram:
    """Parse a `.mas2g` file."""
    return parse_mas(_read(path), str(path))


def _read(path: str | Path) -> str:
    try:
        return Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise GoalSyntaxError(str(path), 1, 1, "no such file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise GoalSyntaxError(str(path), 1, 1, f"cannot read file: {err}") from None


# ----------------------------------------------------------------------------- warnings


def _condition_texts(condition: ast.Condition) -> Iterator[ast.PrologText]:
    """The Prolog texts of a condition's literals, negated ones included."""
    for literal in condition:
        if isinstance(literal, ast.NotLiteral):
            yield from _condition_texts(literal.condition)
        elif literal.query is not None:
            yield literal.query


def _rule_texts(rule: ast.Rule) -> Iterator[ast.PrologText]:
    yield from _condition_texts(rule.condition)
    for action in rule.actions:
        if isinstance(action, ast.SendAction):
            yield action.receiver
            yield action.content
        else:
            yield from action.args
    for inner in rule.rules or ():
        yield from _rule_texts(inner)


def _with_warnings(program: ast.AgentProgram) -> ast.AgentProgram:
    """Singleton variables in rules, as GOAL reports them (warnings, not errors)."""
    warnings = []
    for module in program.modules:
        for rule in module.rules:
            counts: Counter[str] = Counter()
            for text in _rule_texts(rule):
                counts.update(variable_occurrences(text.text))
            if rule.list_var:  # listall uses its list variable and what it collects
                counts[rule.list_var] += 1
                for text in _condition_texts(rule.condition):
                    counts.update(variable_occurrences(text.text))
            for param in module.params:  # module parameters are bound by the caller
                for var in variable_occurrences(param.text):
                    if counts[var]:
                        counts[var] += 1
            for var, count in counts.items():
                if count == 1 and not var.startswith("_") and "_M" not in var:
                    warnings.append(f"{rule.pos}: warning: singleton variable {var} in rule")
    if not warnings:
        return program
    return replace(program, warnings=tuple(warnings))


def iter_rules(rules: Iterable[ast.Rule]) -> Iterator[ast.Rule]:
    """Every rule, nested ones included, in source order."""
    for rule in rules:
        yield rule
        if rule.rules:
            yield from iter_rules(rule.rules)

"""The builder's part for `.mas2g` files of every GOAL version: GOAL 4/5's ``environment``,
``agentfiles`` and ``launchpolicy`` sections (also the older ``environment{"x.jar".
init[..].}``), GOAL 6+'s ``use "x.jar" as environment with k = v.``, ``define a as agent
{ use m as main module. }`` and launch instructions with ``with name/number/max``, and the
newest dialect's ``define a { use m for decisions. replace p/1. }``."""

from __future__ import annotations

import itertools
import re
from pathlib import Path

from lark import Token, v_args

from goalagent import ast
from goalagent.parser.builder_base import BuilderBase
from goalagent.parser.errors import GoalSyntaxError

LIMIT_OPTIONS = ("sandbox", "max_inferences", "max_query_seconds", "max_beliefs",
                 "max_memory")
"""Agent file options that bound an agent (goalagent.kb.limits), overriding the run's."""
MAX_NUMBER = 100_000
"""The largest ``number`` (agents launched from one file) or ``max`` a .mas2g may ask for."""

_LANGUAGES = ("swiprolog", "swi-prolog", "prolog")
_AGENT_ROLES = ("init", "main", "event", "shutdown")
_PURPOSES = {"decisions": "main", "updates": "event"}
_PERCEPT_RULES = ("add", "replace", "update")


_QUOTED = re.compile(r'"((?:\\.|""|[^"\\])*)"')


def verbatim_strings(text: str) -> str:
    """Init values as GOAL reads them: a backslash in a double-quoted string is itself
    (``"C:\\Starcraft"`` is a Windows path, not an escape), but before a quote."""

    def double(match: re.Match[str]) -> str:
        body = re.sub(r'\\(?!")', r"\\\\", match.group(1))
        return f'"{body}"'

    return _QUOTED.sub(double, text)


def reference_path(text: str) -> str:
    """A file reference as written in a program, with Windows separators made portable."""
    return text.replace("\\", "/")


@v_args(meta=True)
class MasParts(BuilderBase):
    """Tree nodes of `.mas2g` files (and the use clauses GOAL 6+ files share)."""

    def __init__(self, source) -> None:
        super().__init__(source)
        self._launch_groups = itertools.count(1)

    # --- GOAL 4/5 ----------------------------------------------------------------------
    def env_item(self, meta, children):
        value = children[1]
        value = ast.PrologText(verbatim_strings(value.text), value.pos)
        return (str(children[0]), self.check(value), self._token_pos(children[0]))

    def env_string(self, meta, children):
        """``env = "x.jar".`` (the file as written: GOAL reads no escapes in it, so
        ``"environments\\BW4T2\\BW4TClient.jar"`` is a Windows path) or another key's
        string value."""
        key, value = children[0], children[1]
        if str(key) == "env":
            return self.env_file(meta, [value])
        return (str(key), self.check(ast.PrologText(verbatim_strings(str(value)),
                                                    self._token_pos(value))),
                self._token_pos(key))

    def env_file(self, meta, children):
        """``"x.jar".`` in GOAL 4's environment section: the environment's file."""
        raw = reference_path(str(children[0])[1:-1])
        return ("env", ast.PrologText(repr(raw), self._token_pos(children[0])),
                self._token_pos(children[0]))

    def env_init_list(self, meta, children):
        """``init[k = v, ...].`` (GOAL 4's form, without ``=``)."""
        key = children[0]
        if str(key) != "init":
            raise GoalSyntaxError.at(self._token_pos(key),
                                     f"unknown environment entry {key}[...]; expected init[...]")
        start, end = children[1].start_pos, children[-2].end_pos
        text, offset = self.source.fragment(start, end)
        return ("init", self.check(ast.PrologText(verbatim_strings(text),
                                                  self.source.pos(offset))),
                self._token_pos(key))

    def environment(self, meta, children):
        return ("environment", children[1:], self._pos(meta))

    def agentfile(self, meta, children):
        path = reference_path(str(children[0])[1:-1])
        options = next((c for c in children[1:] if isinstance(c, list)), [])
        values: dict[str, tuple[str, Token]] = {}
        for key, value in options:
            if str(key) in values:
                self.warn(self._token_pos(key), f"agent file option {key} is given twice; "
                          "the first is used")
                continue
            values[str(key)] = (str(value), key)
        language = values.pop("language", None)
        if language is not None and language[0].lower() not in _LANGUAGES:
            raise GoalSyntaxError.at(self._token_pos(language[1]), f"language = {language[0]}:"
                                     " goalagent's knowledge representation is SWI-Prolog "
                                     "(language = swiprolog)")
        unknown = [key for key in values if key not in ("name", "number", *LIMIT_OPTIONS)]
        if unknown:
            raise GoalSyntaxError.at(self._token_pos(values[unknown[0]][1]),
                                     f"unknown agent file option {unknown[0]!r} (name, "
                                     f"number, {', '.join(LIMIT_OPTIONS)})")
        name = values.get("name", (Path(path).stem, None))[0]
        number = self._whole_number_option(values, "number")
        limits = tuple((key, self._limit_option(key, *values[key])) for key in LIMIT_OPTIONS
                       if key in values)
        return ast.AgentFile(path, name, self._pos(meta), number or 1, limits)

    def _limit_option(self, key: str, text: str, token: Token) -> object:
        """The value of a bound (goalagent.kb.limits) set for an agent file."""
        if key == "sandbox":
            if text not in ("true", "false"):
                raise GoalSyntaxError.at(self._token_pos(token), "sandbox is true or false")
            return text == "true"
        try:
            value = float(text) if key == "max_query_seconds" else int(text)
            if not 0 < value <= 2**62:
                raise ValueError
        except ValueError:
            raise GoalSyntaxError.at(self._token_pos(token), f"{key} must be a positive "
                                     "number") from None
        return value

    def _whole_number_option(self, values: dict, key: str) -> int | None:
        """The option ``key`` as a whole number (None when absent)."""
        if key not in values:
            return None
        text, token = values[key]
        if not text.isdigit() or len(text) > len(str(MAX_NUMBER)) or int(text) > MAX_NUMBER:
            raise GoalSyntaxError.at(self._token_pos(token), f"{key} must be a whole number "
                                     f"up to {MAX_NUMBER}")
        return int(text)

    def agentfiles(self, meta, children):
        return ("agentfiles", children[1:], self._pos(meta))

    # --- use clauses (.mas2g, .mod2g, .act2g, .test2g) ------------------------------------
    def ref(self, meta, children):
        token = children[0]
        text = str(token)
        if token.type in ("DQSTRING", "QATOM"):
            return reference_path(text[1:-1]), True
        return text, False

    def use_case(self, meta, children):
        first = children[0]
        return "module" if first.type == "MODULE" else str(first)

    def use_as(self, meta, children):
        (ref, quoted), case = children[1], None
        if len(children) > 3:
            case = children[3]
        return ast.UseClause(ref, case, self._pos(meta), quoted)

    def use_for(self, meta, children):
        (ref, quoted), purpose = children[1], children[3]
        if str(purpose) not in _PURPOSES:
            raise GoalSyntaxError.at(self._token_pos(purpose), f"use ... for {purpose}: "
                                     "expected for decisions or for updates")
        return ast.UseClause(ref, str(purpose), self._pos(meta), quoted)

    # --- GOAL 6+ .mas2g --------------------------------------------------------------------
    def env_value(self, meta, _children):
        """A parameter's value after ``with k =``: its strings read as GOAL reads them
        (``map = "sscai\\(2)Destination.scx"`` holds a backslash, not an escape)."""
        text = self._text(meta)
        return self.check(ast.PrologText(verbatim_strings(text.text), text.pos))

    def env_pair(self, meta, children):
        key, value = children[0], children[1]
        return (str(key), value, self._token_pos(key))

    def mas_use(self, meta, children):
        (ref, quoted) = children[1]
        case = None
        pairs = [c for c in children if isinstance(c, tuple) and len(c) == 3]
        for index, child in enumerate(children):
            if isinstance(child, Token) and child.type == "AS":
                case = children[index + 1]
        if case is not None and str(case) != "environment":
            raise GoalSyntaxError.at(self._token_pos(case), f"a .mas2g uses a file as "
                                     f"environment only, not as {case}")
        use = ast.UseClause(ref, "environment", self._pos(meta), quoted)
        return ("use", use, pairs, self._pos(meta))

    def agent_use(self, meta, children):
        (ref, quoted), case = children[1], children[3]
        if case not in _AGENT_ROLES:
            raise GoalSyntaxError.at(self._pos(meta), f"use {ref} as {case}: an agent "
                                     f"definition uses modules as {', '.join(_AGENT_ROLES)}")
        return ast.UseClause(ref, case, self._pos(meta), quoted)

    def agent_use_for(self, meta, children):
        return self.use_for(meta, children)

    def percept_rule(self, meta, children):
        how, name, arity = children[0], children[1], children[2]
        if str(how) not in _PERCEPT_RULES:
            raise GoalSyntaxError.at(self._token_pos(how), f"unknown percept rule {how}: "
                                     f"expected {', '.join(_PERCEPT_RULES)} name/arity")
        if not str(arity).isdigit() or len(str(arity)) > 4:
            raise GoalSyntaxError.at(self._token_pos(arity), f"{arity} is not an arity: "
                                     "expected a whole number up to 9999")
        return ast.PerceptRule(str(how), str(name), int(str(arity)),  # type: ignore[arg-type]
                               self._pos(meta))

    def agent_def(self, meta, children):
        name = children[1]
        items = [c for c in children[2:] if not isinstance(c, Token)]
        kinds = [c for c in children[2:] if isinstance(c, Token) and c.type == "NAME"]
        if kinds and str(kinds[0]) != "agent":
            raise GoalSyntaxError.at(self._token_pos(kinds[0]),
                                     f"define {name} as {kinds[0]}: expected 'as agent'")
        uses = tuple(i for i in items if isinstance(i, ast.UseClause))
        rules = tuple(i for i in items if isinstance(i, ast.PerceptRule))
        return ast.AgentDefinition(str(name), self._token_pos(name), uses, rules)

    # --- launch policy -------------------------------------------------------------------
    def instruction(self, meta, children):
        name = children[0]
        file = None
        options: list = []
        for child in children[1:]:
            if isinstance(child, Token) and child.type in ("NAME", "VAR"):
                file = child
            elif isinstance(child, Token) and child.type == "NUMBER":  # GOAL 4: launch a[3]:f.
                options.append((Token("NAME", "number"), child))
            elif isinstance(child, tuple):
                options.append(child)
        return (name, file, options, self._pos(meta))

    def instructions(self, meta, children):
        return list(children)

    def entity_condition(self, meta, children):
        return children

    def entity_spec(self, meta, children):
        if children[0].type == "STAR":
            return []
        return [(children[0], children[1])]

    def launch(self, meta, children):
        return self._launch_rules(children[1], [], False, self._pos(meta))

    def when_launch(self, meta, children):
        condition = children[1]
        if isinstance(condition, list) and condition and isinstance(condition[0], Token):
            condition = []  # GOAL 4/5's `when entity@env`
        return self._launch_rules(children[-2], condition, True, self._pos(meta))

    def _launch_rules(self, instructions, condition, on_entity: bool,
                      pos: ast.Pos) -> list[ast.LaunchRule]:
        """One launch rule per instruction; those of one ``when`` share a group."""
        entity: dict[str, str] = {}
        limit = None
        seen: set[str] = set()
        for key_token, value_token in condition:
            key = str(key_token)
            if key in seen:
                self.warn(self._token_pos(key_token), f"entity condition {key} is given "
                          "twice; the first is used")
                continue
            seen.add(key)
            if key in ("type", "name"):
                entity[key] = self._plain(value_token)
            elif key == "max":
                limit = self._whole_number_option({key: (str(value_token), value_token)}, key)
            else:
                raise GoalSyntaxError.at(self._token_pos(key_token),
                                         f"unknown entity condition {key!r} (type, name, max)")
        group = next(self._launch_groups)
        rules = []
        for name_token, file_token, options, _ in instructions:
            values = {str(k): (str(v), k) for k, v in options}
            unknown = [key for key in values if key not in ("name", "number", "max")]
            if unknown:
                raise GoalSyntaxError.at(self._token_pos(values[unknown[0]][1]),
                                         f"unknown launch option {unknown[0]!r} "
                                         "(name, number, max)")
            if str(name_token) == "*" and not on_entity:
                self.warn(pos, "launch * takes the name of an entity: it belongs in a "
                          "conditional rule (when ... do launch *); this one launches nothing")
                continue
            agentfile = str(file_token) if file_token is not None else str(name_token)
            agent_name = values.get("name", (str(name_token), None))[0]
            number = self._whole_number_option(values, "number") or 1
            rule_max = self._whole_number_option(values, "max")
            rules.append(ast.LaunchRule(
                agent_name, agentfile, pos, on_entity=on_entity,
                entity_type=entity.get("type"), max=rule_max if rule_max is not None else limit,
                number=number, entity_name=entity.get("name"), group=group))
        return rules

    def _plain(self, token: Token) -> str:
        """A name, number or quoted text as plain text."""
        text = str(token)
        if token.type in ("DQSTRING", "QATOM"):
            return text[1:-1]
        return text

    def launchpolicy(self, meta, children):
        rules = [rule for group in children[1:] for rule in group]
        return ("launchpolicy", rules, self._pos(meta))

    def mas(self, meta, children):
        return children

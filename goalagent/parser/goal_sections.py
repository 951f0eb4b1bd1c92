"""The builder's part for `.goal` programs: sections, actionspecs, ``#import``, actions,
rules and modules (conditions and macros are in ``conditions.py``)."""

from __future__ import annotations

from dataclasses import replace
from functools import partial
from pathlib import Path

from lark import Token, v_args

from goalagent import ast
from goalagent.extensions import prolog_library
from goalagent.parser.builder_base import MOODS, BuilderBase, ParsedSection
from goalagent.parser.conditions import condition_texts
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.mas_sections import reference_path
from goalagent.parser.reparse import observe
from goalagent.parser.variables import variable_occurrences

_MODULE_OPTIONS = {
    "exit": ("always", "never", "nogoals", "noaction"),
    "focus": ("none", "new", "select", "filter"),
}
_PROGRAM_OPTIONS = {"order": ("linear", "linearall", "random", "randomall", "adaptive",
                              "linearrandom", "linearallrandom")}
_CONTEXT_OPTIONS = {"focusmethod": ("none", "new", "select", "filter", "filtergoals")}
_FOCUS_METHODS = {"none": None, "new": "new", "select": "select", "filter": "filter",
                  "filtergoals": "filter"}
_ORDER_NAMES = {"linearrandom": "random", "linearallrandom": "randomall"}  # GOAL 6's names
_CONJUNCTION_ACTIONS = frozenset({"insert", "delete", "adopt", "drop"})


def program_options(options: dict[str, str]) -> dict[str, str]:
    """Program options with GOAL 6's order names (linearrandom, ...) as the runtime knows
    them (random, ...)."""
    if "order" in options:
        options = {**options, "order": _ORDER_NAMES.get(options["order"], options["order"])}
    return options


@v_args(meta=True)
class GoalParts(BuilderBase):
    """Tree nodes of a `.goal` program. ``#import`` parses another file through
    ``self._import_prolog_file``, which the composed ``AstBuilder`` provides."""

    def __init__(self, source) -> None:
        super().__init__(source)
        self.nested_modules: list[ast.Module] = []  # GOAL 3's modules inside programs
        self.percept_rules: list[ast.Rule] = []  # GOAL 3's percept rules, wherever written

    # --- sections -------------------------------------------------------------------------
    def knowledge(self, meta, children):
        return ParsedSection("knowledge", self._clauses(children[1:]), self._pos(meta))

    def beliefs(self, meta, children):
        return ParsedSection("beliefs", self._clauses(children[1:]), self._pos(meta))

    def _clauses(self, items) -> tuple[ast.PrologText, ...]:
        """A section's clauses, those of ``#import``ed Prolog files in their place."""
        clauses: list[ast.PrologText] = []
        for item in items:
            if isinstance(item, ParsedSection):
                if item.kind != "knowledge":
                    raise GoalSyntaxError.at(item.pos, "only Prolog files can be #imported "
                                             "inside knowledge or beliefs")
                clauses.extend(item.items)
            else:
                clauses.extend(self._facts([item]))
        return tuple(clauses)

    def goals(self, meta, children):
        return ParsedSection("goals", tuple(children[1:]), self._pos(meta))

    def program(self, meta, children):
        options = next((c for c in children if isinstance(c, list)), None)
        rules = tuple(c for c in children if isinstance(c, ast.Rule))
        return ParsedSection("program", rules, self._pos(meta), program_options(
            self._options(options, _PROGRAM_OPTIONS)))

    def actionspecs(self, meta, children):
        return ParsedSection("actionspecs", tuple(children[1:]), self._pos(meta))

    def pre(self, meta, children):
        return self._pre_or_post_text(children)

    def post(self, meta, children):
        return self._pre_or_post_text(children)

    def _pre_or_post_text(self, children) -> ast.PrologText:
        """The checked text of ``pre { .. }`` / ``post { .. }``; ``true`` when empty (GOAL
        warns: an empty precondition or postcondition is more likely forgotten than meant)."""
        if len(children) > 1:
            return self.check(children[1])
        pos = self._token_pos(children[0])
        self.warn(pos, f"empty {children[0]} {{ }}: read as true")
        return ast.PrologText("true", pos, ())

    def actionspec(self, meta, children):
        name = children[0]
        params = next((c for c in children if isinstance(c, tuple)), ())
        internal = any(isinstance(c, Token) and c.type == "AT_INT" for c in children)
        environment = any(isinstance(c, Token) and c.type == "AT_ENV" for c in children)
        if str(name) in ast.BUILTIN_ACTIONS and not environment:
            raise GoalSyntaxError.at(
                self._token_pos(name), f"{name} is a built-in action; write "
                f"{name}(...)@env {{ ... }} to declare an environment action with that name")
        pre, post = children[-2], children[-1]
        return ast.ActionSpec(str(name), params, pre, post, self._token_pos(name), internal,
                              environment)

    def import_(self, meta, children):
        """``#import "file.pl".``: the file's clauses become knowledge; ``#import
        "file.mod2g".``: the modules of a GOAL 5 module file join the program. A name
        without an extension is a Prolog file, as GOAL 5 reads it."""
        name = reference_path(str(children[1])[1:-1])
        pos = self._token_pos(children[1])
        suffix = Path(name).suffix
        if suffix not in (".pl", ".mod2g", ".goal"):
            name += ".pl"
        path = Path(self.source.file).parent / name
        if not observe(path.exists):  # a library an application brings: robot's affordance.pl
            path = observe(partial(prolog_library, name)) or path
        if not observe(path.exists):
            raise GoalSyntaxError.at(pos, f"cannot #import {name!r}: no such file next to "
                                     "this program nor among the installed extensions' "
                                     "Prolog libraries")
        if path.suffix == ".pl":
            clauses = self._import_prolog_file(path)  # type: ignore[attr-defined]
            return ParsedSection("knowledge", clauses, pos)
        modules = self._import_module_file(path, pos)  # type: ignore[attr-defined]
        return ParsedSection("modules", modules, pos)

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
        for arg in args:  # a mood prefix (parg accepts it) belongs to messages only
            if arg.text[:1] in MOODS and not arg.text.startswith(":-"):
                self.check(arg)
        if name in _CONJUNCTION_ACTIONS and len(args) > 1:
            # insert(a, not(b)) is insert((a, not(b))): one conjunction, as GOAL reads it
            joined = ", ".join(arg.text for arg in args)
            args = (self.check(ast.PrologText(joined, args[0].pos)),)
        return ast.ActionCall(name, args, pos)

    def exit_module(self, meta, children):
        return ast.ActionCall("exit-module", (), self._pos(meta))

    def receiver(self, meta, children):
        """An addressee: a name, a variable or, in parentheses, a quoted name; GOAL's
        selector takes ``("bob")`` for the agent ``bob``, so a string becomes that atom."""
        token = children[0]
        text = str(token)
        if token.type == "DQSTRING":
            # the same escapes mean the same in a quoted atom; only the quotes change
            name = text[1:-1].replace('\\"', '"').replace('""', '"')
            text = "'" + name.replace("'", "''") + "'"
        return ast.PrologText(text, self._token_pos(token), (text,)
                              if token.type == "VAR" else ())

    def send(self, meta, children):
        """``R.send(:φ)`` (GOAL 4/5: the mood starts the content) or ``R.send:(φ)`` (GOAL
        6: the mood follows the keyword)."""
        receiver, keyword, content = children[0], children[1], children[-1]
        mood, message = self._mood(content)
        if len(children) == 4:
            mood = str(children[2])
        return ast.SendAction(str(keyword) == "sendonce", receiver, mood, message,
                              self._pos(meta))

    def _mood(self, content: ast.PrologText) -> tuple[str, ast.PrologText]:
        """A message's mood prefix (``:`` when none) and its content without it."""
        text = content.text
        mood = ":"
        if text[:1] in MOODS and not text.startswith(":-") and len(text) > 1:
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
        """A rule whose body is an action combo or a nested block of rules."""
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
            if item.kind == "modules":
                raise GoalSyntaxError.at(item.pos, "#import of a module file belongs outside "
                                         "modules, next to them")
            if item.kind == "perceptrules":
                self.percept_rules.extend(item.items)
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
            has_program=seen_program,
        )

    # --- GOAL 3 -------------------------------------------------------------------------
    def perceptrules(self, meta, children):
        """GOAL 3's percept rules: applied every cycle before the program, each for every
        instantiation of its condition (GOAL 4 made them the event module's forall rules)."""
        rules = tuple(replace(rule, kind="forall") if rule.kind == "if" else rule
                      for rule in children[1:] if isinstance(rule, ast.Rule))
        return ParsedSection("perceptrules", rules, self._pos(meta))

    def context(self, meta, children):
        options = next((c for c in children if isinstance(c, list)), None)
        condition = next((c for c in children if isinstance(c, tuple)), None)
        return ("context", self._options(options, _CONTEXT_OPTIONS), condition)

    def nested_module(self, meta, children):
        """GOAL 3's ``module name { context[focusmethod=F] { MSC } goals{..} program{..} }``
        inside a program: a rule ``if MSC then name(Vars)`` entering a module whose
        parameters are the context's variables (they instantiate its goals), focused as F
        says, staying in it until its goals are achieved (when it has a goal focus)."""
        name = str(children[1])
        _, options, condition = children[2]
        pos = self._pos(meta)
        condition = condition or (ast.MentalLiteral("true", None, pos),)
        names = list(dict.fromkeys(var for text in condition_texts(condition)
                                   for var in variable_occurrences(text.text)
                                   if var != "_" and not var.startswith("_")))
        params = tuple(self.check(ast.PrologText(var, pos)) for var in names)
        focus = _FOCUS_METHODS.get(options.get("focusmethod", "none"))
        module = self.module(meta, [("user", name, params, None, meta), *children[3:]])
        exit_option = "nogoals" if focus in ("filter", "select", "new") or module.goals else None
        self.nested_modules.append(replace(module, focus=focus, exit=exit_option))
        args = tuple(self.check(ast.PrologText(var, pos)) for var in names)
        return ast.Rule("if", condition, pos, actions=(ast.ActionCall(name, args, pos),))

    def wrapper(self, meta, children):
        return ("wrapper", str(children[1]), children[2:])

    def agent(self, meta, children):
        if len(children) == 1 and isinstance(children[0], tuple) and children[0][0] == "wrapper":
            return children[0][1], list(children[0][2])
        return None, list(children)

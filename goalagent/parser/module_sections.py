"""The builder's part for GOAL 6+ files: `.mod2g` module files (use clauses, ``exit=`` /
``focus=`` / ``order=`` options, ``define`` macros, one ``module name(Params) { rules }``)
and `.act2g` action specification files (``define a(X) [as internal] with pre{..}
post{..}``). What the use clauses name is loaded by ``goalagent.parser.agents``."""

from __future__ import annotations

from dataclasses import dataclass

from lark import Token, v_args

from goalagent import ast
from goalagent.parser.builder_base import BuilderBase
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.goal_sections import program_options

_FILE_OPTIONS = {
    "exit": ("always", "never", "nogoals", "noaction"),
    "focus": ("none", "new", "select", "filter"),
    "order": ("linear", "linearall", "random", "randomall", "adaptive", "linearrandom",
              "linearallrandom"),
}
_ACTION_KINDS = ("internal", "external")


@dataclass(frozen=True)
class ModuleFile:
    """A parsed `.mod2g` file: its use clauses and its module (options applied)."""

    file: str
    uses: tuple[ast.UseClause, ...]
    module: ast.Module
    macros: tuple[ast.Macro, ...]


@dataclass(frozen=True)
class ActionFile:
    """A parsed `.act2g` file: its use clauses and action specifications."""

    file: str
    uses: tuple[ast.UseClause, ...]
    specs: tuple[ast.ActionSpec, ...]


@v_args(meta=True)
class ModuleParts(BuilderBase):
    """Tree nodes of `.mod2g` and `.act2g` files."""

    def file_option(self, meta, children):
        key, value = children[0], children[1]
        return ("option", key, value)

    def module_def(self, meta, children):
        name = children[1]
        params = next((c for c in children[2:] if isinstance(c, tuple)), ())
        rules = tuple(c for c in children[2:] if isinstance(c, ast.Rule))
        return (str(name), params, rules, self._token_pos(name))

    def module_file(self, meta, children):
        uses = tuple(c for c in children if isinstance(c, ast.UseClause))
        macros = tuple(c for c in children if isinstance(c, ast.Macro))
        pairs = [(c[1], c[2]) for c in children if isinstance(c, tuple) and c[0] == "option"]
        seen: set[str] = set()
        for key, _ in pairs:
            if str(key) in seen:
                raise GoalSyntaxError.at(self._token_pos(key), f"option {key} is set twice")
            seen.add(str(key))
        options = program_options(self._options(pairs, _FILE_OPTIONS))
        name, params, rules, pos = children[-1]
        module = ast.Module(name, "user", pos, params, exit=options.get("exit"),  # type: ignore
                            focus=options.get("focus"), order=options.get("order"),  # type: ignore
                            rules=rules, declared=name)
        return ModuleFile(self.source.file, uses, module, macros)

    def action_def(self, meta, children):
        name = children[1]
        params = next((c for c in children[2:] if isinstance(c, tuple)), ())
        tokens = [c for c in children[2:] if isinstance(c, Token)]
        internal = any(t.type == "AT_INT" for t in tokens)
        environment = any(t.type == "AT_ENV" for t in tokens)
        for index, token in enumerate(tokens):
            if token.type == "AS":
                kind = tokens[index + 1]
                if str(kind) not in _ACTION_KINDS:
                    raise GoalSyntaxError.at(self._token_pos(kind), f"define {name} as {kind}: "
                                             "expected as internal or as external")
                internal = internal or str(kind) == "internal"
        if str(name) in ast.BUILTIN_ACTIONS and not environment:
            raise GoalSyntaxError.at(
                self._token_pos(name), f"{name} is a built-in action; write "
                f"define {name}(...)@env with ... to declare an environment action with that "
                "name")
        pre, post = children[-2], children[-1]
        return ast.ActionSpec(str(name), params, pre, post, self._token_pos(name), internal,
                              environment)

    def action_file(self, meta, children):
        uses = tuple(c for c in children if isinstance(c, ast.UseClause))
        specs = tuple(c for c in children if isinstance(c, ast.ActionSpec))
        return ActionFile(self.source.file, uses, specs)

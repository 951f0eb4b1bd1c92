"""The builder's part for `.mas2g` files: the environment, agent files and launch rules."""

from __future__ import annotations

from pathlib import Path

from lark import v_args

from goalagent import ast
from goalagent.parser.builder_base import BuilderBase
from goalagent.parser.errors import GoalSyntaxError


@v_args(meta=True)
class MasParts(BuilderBase):
    """Tree nodes of ``environment``, ``agentfiles`` and ``launchpolicy`` sections."""

    def env_item(self, meta, children):
        return (str(children[0]), self.check(children[1]), self._token_pos(children[0]))

    def environment(self, meta, children):
        return ("environment", children[1:], self._pos(meta))

    def agentfile(self, meta, children):
        path = self.engine.parse_term(str(children[0]))
        options = next((c for c in children[1:] if isinstance(c, list)), [])
        values = {str(k): (str(v), k) for k, v in options}
        unknown = [key for key in values if key not in ("name", "number")]
        if unknown:
            raise GoalSyntaxError.at(self._token_pos(values[unknown[0]][1]),
                                     f"unknown agent file option {unknown[0]!r}")
        name = values.get("name", (Path(str(path)).stem, None))[0]
        number = self._whole_number_option(values, "number")
        return ast.AgentFile(str(path), name, self._pos(meta), number or 1)

    def _whole_number_option(self, values: dict, key: str) -> int | None:
        """The option ``key`` as a whole number (None when absent)."""
        if key not in values:
            return None
        text, token = values[key]
        if not text.isdigit():
            raise GoalSyntaxError.at(self._token_pos(token), f"{key} must be a whole number")
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
                    limit = self._whole_number_option({key: (value, item[1])}, key)
                else:
                    raise GoalSyntaxError.at(self._token_pos(item[0]),
                                             f"unknown entity condition {key!r} (type, max)")
        return ast.LaunchRule(name, file, self._pos(meta), on_entity=True,
                              entity_type=entity_type, max=limit)

    def launchpolicy(self, meta, children):
        return ("launchpolicy", children[1:], self._pos(meta))

    def mas(self, meta, children):
        return children

"""The rules agents run, by id: one entry per module, rule and binding names, shared by every
agent that runs the same program text. Prolog names rules by these ids (in requests, the
journal, problems); this registry turns them back into the rules of the program.
"""

from __future__ import annotations

from dataclasses import dataclass

from goalagent import ast
from goalagent.kb.engine import Engine

__all__ = ["RULES", "RuleInfo", "aborted_rule", "register_rule"]


@dataclass(frozen=True, eq=False)
class RuleInfo:
    """A compiled rule: where it is and the names of the bindings its body sees (the
    values of a firing, in this order): given ones its condition does not name, then the
    condition's variables (a listall rule: the given ones, then its list)."""

    id: int
    module: str
    rule: ast.Rule
    names: tuple[str, ...]
    recorded: frozenset[int] = frozenset()  # actions whose closed form the journal keeps
    shown: str = ""  # the module's name as its file gives it (traces and warnings say it)


RULES: list[RuleInfo] = []
"""Every registered rule, at its id (read by index where Prolog names a rule)."""
_rule_ids: dict[tuple[str, ast.Rule, tuple[str, ...]], int] = {}


def register_rule(module: ast.Module, rule: ast.Rule, names: tuple[str, ...],
                  recorded: frozenset[int]) -> RuleInfo:
    """The rule's entry in the registry of rules (one id per module, rule and names)."""
    key = (module.name, rule, names)
    rule_id = _rule_ids.get(key)
    if rule_id is None:
        rule_id = len(RULES)
        RULES.append(RuleInfo(rule_id, module.name, rule, names, recorded,
                              module.declared or module.name))
        _rule_ids[key] = rule_id
    return RULES[rule_id]


def aborted_rule(engine: Engine) -> RuleInfo | None:
    """The rule a query the watchdog aborted was in (the innermost), if any; read once."""
    result = engine.call("aborted_rule", None, module="ga_guard")
    found = result[0] if result else None
    return RULES[found] if isinstance(found, int) and 0 <= found < len(RULES) else None

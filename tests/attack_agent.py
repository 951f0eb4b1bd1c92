"""A one-rule-base agent made from knowledge and rules text, for the confinement and attack
tests (tests/goalagent/kb/test_confinement.py, tests/attacks/test_attacks.py): RUNTIME_MODULES
are the modules no agent may change."""

from __future__ import annotations

import io

from goalagent.agent import Agent
from goalagent.kb.limits import Limits
from goalagent.parser import parse_agent

RUNTIME_MODULES = ("ga_kb", "ga_rules", "ga_read", "ga_guard", "ga_confine", "user", "system")


def load_agent(knowledge: str = "", rules: str = "if true then print(ok).", *,
               sandbox: bool = False, warnings: list[str] | None = None) -> Agent:
    """An agent whose init module knows ``knowledge`` and whose main module (exit=always)
    has ``rules``; its warnings go to ``warnings`` (or nowhere), its output nowhere."""
    text = (f"init module {{ knowledge {{ {knowledge} }} }}\n"
            f"main module [exit=always] {{ program {{\n{rules}\n}} }}\n")
    return Agent(parse_agent(text, "attack.goal"), limits=Limits(sandbox=sandbox),
                 output=io.StringIO(), warn=(warnings if warnings is not None else []).append)

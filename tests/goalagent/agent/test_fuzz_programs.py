"""Mutated programs give a located error or run cleanly, never an uncaught exception."""

from __future__ import annotations

import io
import re
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from goalagent.agent import Agent, AgentError
from goalagent.parser import GoalSyntaxError

EXAMPLES = Path(__file__).resolve().parents[3] / "agents" / "examples"
SEEDS = [
    (EXAMPLES / name).read_text()
    for name in ("hello_world.goal", "stack_builder.goal", "nested_rules.goal",
                 "listall_macros.goal", "table_agent.goal", "user_modules.goal")
]
PIECES = ["(", ")", "{", "}", "[", "]", ".", ",", "'", '"', "%", "/*", "*/", "//", "+", "\\+",
          "not(", "bel(", "goal(", "a-goal(", "if", "then", "forall", "do", "X", "_", "0'",
          "#define m(X) bel(X).", "module", "[exit=never]", ":-", "->", ";", "!", "@int",
          "insert(", "adopt(p(X))", "print(", "1.5e3", "\n", " "]


@st.composite
def mutated(draw: st.DrawFn) -> str:
    """A shipped example with a few characters deleted, pieces inserted or tokens swapped."""
    text = draw(st.sampled_from(SEEDS))
    for _ in range(draw(st.integers(1, 4))):
        where = draw(st.integers(0, len(text)))
        kind = draw(st.sampled_from(["delete", "insert", "replace"]))
        if kind == "delete":
            text = text[:where] + text[where + draw(st.integers(1, 6)):]
        elif kind == "insert":
            text = text[:where] + draw(st.sampled_from(PIECES)) + text[where:]
        else:
            tokens = re.findall(r"\w+|\S", text)
            old, new = draw(st.sampled_from(tokens)), draw(st.sampled_from(PIECES))
            text = text.replace(old, new, 1)
    return text


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated())
def test_mutated_program_fails_cleanly_or_runs(text: str) -> None:
    try:
        agent = Agent.from_string(text, "mutant.goal", output=io.StringIO(),
                                  warn=lambda message: None)
    except GoalSyntaxError as err:
        assert re.match(r"mutant\.goal:\d+:\d+: \S", str(err)), str(err)
        return
    except AgentError as err:
        assert str(err)
        return
    try:
        agent.run(max_cycles=5)
    finally:
        agent.close()

"""Module focus options: which goals a called module sees (GOAL's focus=none|new|select|filter)."""

from __future__ import annotations

import io

import pytest

from goalagent.agent import Agent
from goalagent.kb.terms import Atom, Struct

PROGRAM = """
init module { goals { clean(kitchen), clean(hall). clean(attic). tidy(desk). } }
module work(Room) [focus=FOCUS, exit=always] { program {
    if true then report.
} }
module report { program [order=linearall] {
    forall goal(clean(X)) do print(clean(X)).
    forall goal(tidy(X)) do print(tidy(X)).
} }
main module { program { if a-goal(clean(R)), bel(R == attic) then work(R). } }
"""


def goals_seen(focus: str) -> list[str]:
    agent = Agent.from_string(PROGRAM.replace("FOCUS", focus), "focus.goal",
                              output=io.StringIO())
    agent.step()
    return sorted(agent.output.getvalue().split())


def test_focus_none_sees_every_goal():
    assert goals_seen("none") == ["clean(attic)", "clean(hall)", "clean(kitchen)", "tidy(desk)"]


def test_focus_new_sees_no_goal():
    assert goals_seen("new") == []


def test_focus_filter_sees_the_goal_the_rule_named():
    assert goals_seen("filter") == ["clean(attic)"]


def test_focus_select_sees_the_goal_that_contains_it():
    agent = Agent.from_string(PROGRAM.replace("FOCUS", "select").replace(
        "R == attic", "R == hall"), "focus.goal", output=io.StringIO())
    agent.step()
    assert sorted(agent.output.getvalue().split()) == ["clean(hall)", "clean(kitchen)"]


@pytest.mark.parametrize("focus", ["new", "filter", "select"])
def test_the_callers_goals_are_back_after_the_module(focus):
    agent = Agent.from_string(PROGRAM.replace("FOCUS", focus), "focus.goal",
                              output=io.StringIO())
    agent.step()
    assert [Struct("clean", (Atom("attic"),))] in agent.goals()
    assert len(agent.goals()) == 3

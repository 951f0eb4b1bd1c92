"""Built-in action names (insert, delete, adopt, drop, print, log) and @env actionspecs."""

from __future__ import annotations

import io

import pytest

from goalagent.agent import Agent
from goalagent.kb.terms import Atom, Struct
from goalagent.parser import GoalSyntaxError, parse_agent


class Recorder:
    """An environment seam that records the actions sent to it."""

    def __init__(self) -> None:
        self.sent: list[object] = []

    def percepts(self) -> list[object]:
        return []

    def act(self, action: object) -> None:
        self.sent.append(action)


def test_an_env_actionspec_named_drop_is_sent_to_the_environment():
    io_ = Recorder()
    agent = Agent.from_string("""
        init module { goals { g. } actionspec { drop(X)@env { pre { true } post { true } } } }
        main module { program { if true then drop(ball). } }
    """, "t.goal", io=io_, output=io.StringIO())
    agent.step()
    assert io_.sent == [Struct("drop", (Atom("ball"),))]
    assert agent.goals() == [[Atom("g")]]  # the built-in drop/1 did not run


def test_without_an_env_actionspec_drop_is_the_goal_built_in():
    agent = Agent.from_string("""
        init module { goals { g. } }
        main module { program { if true then drop(g). } }
    """, "t.goal", output=io.StringIO())
    agent.step()
    assert agent.goals() == []


def test_an_actionspec_with_a_built_in_name_needs_env():
    with pytest.raises(GoalSyntaxError) as err:
        parse_agent("init module { actionspec {\n  insert(X) { pre { true } post { X } } } }",
                    "t.goal")
    assert str(err.value).startswith("t.goal:2:3: insert is a built-in action")

"""Rules 6.2, 6.12 and 6.4 of agents/garbage_disposal.goal on hand-made belief states.

The robot holds the ball in front of a closed can; what it does next depends only on its
afford/6 beliefs. The percepts come from a fixed script and the actions are recorded, so each
test shows which rule fired for which reliabilities.
"""

from __future__ import annotations

import io
from pathlib import Path

import pytest

from goalagent.agent import Agent
from goalagent.kb.terms import Atom, Struct, Term, format_term

AGENT = Path(__file__).resolve().parents[1] / "agents" / "garbage_disposal.goal"
ACTIONS = ("extend_arm", "contract_arm", "sweep_left", "sweep_right", "lift_up", "sweep_down")
TAU, R1 = 0.6, 0.3


class HoldingTheBall:
    """Percepts of a robot holding the ball in front of a closed can; records its actions."""

    def __init__(self, parts: tuple[str, ...] = ("body", "lid")) -> None:
        self.sent: list[str] = []
        self._percepts: list[Term] = [Struct("trials", (1,)), Struct("disposed", (0,)),
                                      Struct("holding", (Atom("ball"),))]
        self._percepts += [Struct("obs", (Atom(part),)) for part in parts]

    def percepts(self) -> list[Term]:
        return list(self._percepts)

    def act(self, action: Struct | Atom) -> None:
        self.sent.append(format_term(action))


def robot(beliefs: dict[str, float], *facts: str,
          parts: tuple[str, ...] = ("body", "lid")) -> tuple[Agent, HoldingTheBall]:
    """The agent with lid affordances at the given reliabilities (others at r0 = 0.1)."""
    io_ = HoldingTheBall(parts)
    agent = Agent.from_file(AGENT, io=io_, output=io.StringIO(), warn=lambda message: None)
    for act in ACTIONS:
        rel = beliefs.get(act, 0.1)
        tot = 5 if rel >= TAU else 0
        agent.ms.insert(f"afford(lid, {act}, opened, {tot}, {tot}, {rel})")
    for fact in facts:
        agent.ms.insert(fact)
    return agent, io_


def test_rule_6_2_uses_the_most_reliable_action_at_or_above_tau():
    agent, io_ = robot({"extend_arm": 0.7, "lift_up": 0.9, "sweep_left": 0.6})
    agent.step()
    assert io_.sent == ["apply(lid,lift_up)"]


def test_just_below_tau_nothing_is_used_and_learning_starts():
    agent, io_ = robot({"extend_arm": 0.59})
    agent.step()
    assert len(io_.sent) == 1 and io_.sent[0].startswith("learn(lid,")
    assert io_.sent[0].endswith(",opened,random)")


@pytest.mark.parametrize("rel", [R1, 0.45, 0.599])
def test_rule_6_12_verifies_a_promising_affordance_in_its_band(rel: float):
    agent, io_ = robot({"extend_arm": rel}, "promising(lid, extend_arm)")
    agent.step()
    assert io_.sent == ["apply(lid,extend_arm)"]


@pytest.mark.parametrize("rel", [0.299, 0.6])
def test_rule_6_12_does_not_fire_outside_its_band(rel: float):
    agent, io_ = robot({"extend_arm": rel}, "promising(lid, extend_arm)")
    agent.step()
    expected = "apply(lid,extend_arm)" if rel >= TAU else None  # rule 6.2 at tau
    if expected:
        assert io_.sent == [expected]
    else:
        assert io_.sent[0].startswith("learn(lid,")


def test_rule_6_4_draws_only_actions_not_explored_in_this_episode():
    explored = [f"explored(lid, {act})" for act in ACTIONS if act != "sweep_down"]
    drawn = set()
    for seed in range(6):
        agent, io_ = robot({}, *explored)
        agent.random.seed(seed)
        agent.step()
        drawn.add(io_.sent[0])
        agent.close()
    assert drawn == {"learn(lid,sweep_down,opened,random)"}


def test_when_learning_on_the_lid_is_exhausted_the_agent_turns_to_the_handle():
    explored = [f"explored(lid, {act})" for act in ACTIONS]
    agent, io_ = robot({act: 0.05 for act in ACTIONS}, *explored,
                       parts=("body", "lid", "handle"))
    agent.step()
    assert io_.sent == []
    assert agent.query("bel", "focus(P)") == [{"P": "handle"}]
    agent.step()  # the event module creates the handle's affordances (6.5), learning starts
    assert len(agent.query("bel", "afford(handle, A, opened, 0, 0, 0.1)")) == len(ACTIONS)
    assert io_.sent[0].startswith("learn(handle,")

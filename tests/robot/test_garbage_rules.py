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

AGENT = Path(__file__).resolve().parents[2] / "agents" / "garbage_disposal.goal"
ACTIONS = ("extend_arm", "contract_arm", "sweep_left", "sweep_right", "lift_up", "sweep_down")
TAU, R1 = 0.6, 0.3


class HoldingTheBall:
    """Percepts of a robot holding the ball in front of a closed can; records its actions.
    ``next`` holds percepts for the next cycle only (what an action reported)."""

    def __init__(self, parts: tuple[str, ...] = ("body", "lid")) -> None:
        self.sent: list[str] = []
        self._percepts: list[Term] = [Struct("trials", (1,)), Struct("disposed", (0,)),
                                      Struct("holding", (Atom("ball"),))]
        self._percepts += [Struct("obs", (Atom(part),)) for part in parts]
        self.next: list[Term] = []

    def percepts(self) -> list[Term]:
        once, self.next = self.next, []
        return list(self._percepts) + once

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


def afford(obj: str, act: str, tot: int, suc: int, rel: float) -> Struct:
    return Struct("afford", (Atom(obj), Atom(act), Atom("opened"), tot, suc, rel))


def beliefs(agent: Agent, query: str) -> list[dict]:
    return agent.query("bel", query)


def test_a_percept_about_a_part_not_in_focus_merges_into_its_initial_affordance():
    """Transfer reports on parts the agent is not working on: eq. 6.3 from r0 = 0.1."""
    agent, io_ = robot({}, parts=("body", "lid", "handle"))
    io_.next = [afford("handle", "lift_up", 0, 0, 0.05), afford("handle", "extend_arm", 0, 0, 0.3)]
    agent.step()
    assert beliefs(agent, "afford(handle, A, opened, T, S, R)") == [
        {"A": "lift_up", "T": 0, "S": 0, "R": pytest.approx(0.05)},
        {"A": "extend_arm", "T": 0, "S": 0, "R": pytest.approx(0.3)}]
    assert beliefs(agent, "focus(P)") == [{"P": "lid"}]  # nothing reliable there


def test_a_reliable_affordance_on_another_part_moves_the_focus_and_rule_6_2_uses_it():
    agent, io_ = robot({}, parts=("body", "lid", "handle"))
    io_.next = [afford("lid", "extend_arm", 0, 0, 0.05), afford("handle", "lift_up", 0, 0, 0.05),
                afford("handle", "contract_arm", 1, 1, 1)]
    agent.step()
    assert beliefs(agent, "focus(P)") == [{"P": "handle"}]
    assert beliefs(agent, "afford(handle, contract_arm, opened, T, S, R)") == [
        {"T": 1, "S": 1, "R": 1.0}]
    assert io_.sent == ["apply(handle,contract_arm)"]  # in the same cycle


def test_a_part_out_of_view_does_not_take_the_focus():
    agent, io_ = robot({}, parts=("body", "lid"))
    io_.next = [afford("handle", "lift_up", 1, 1, 1)]
    agent.step()
    assert beliefs(agent, "focus(P)") == [{"P": "lid"}]
    assert io_.sent[0].startswith("learn(lid,")


def test_learning_never_asks_the_same_question_twice_in_an_episode():
    """No answer comes back (as when transfer answers about other pairs): each learn is
    about another action, and after six the lid is exhausted and the body is next."""
    agent, io_ = robot({}, "learning_mode(transfer)")
    agent.ms.delete("learning_mode(random)")
    for _ in range(6):
        agent.step()
    asked = [text for text in io_.sent if text.startswith("learn(lid,")]
    assert len(asked) == len(set(asked)) == len(ACTIONS)
    assert all(text.endswith(",opened,transfer)") for text in asked)
    agent.step()
    agent.step()
    assert beliefs(agent, "focus(P)") == [{"P": "body"}]
    assert io_.sent[-1].startswith("learn(body,")


def test_the_environment_s_repeat_answer_marks_the_question_asked():
    agent, io_ = robot({})
    io_.next = [Struct("learn_repeated", tuple(Atom(a) for a in
                                               ("lid", "extend_arm", "opened", "random")))]
    agent.step()
    assert beliefs(agent, "asked(pair(lid, extend_arm, opened, random))") == [{}]
    assert "learn_repeated(lid,extend_arm,opened,random)" in agent.output.getvalue()
    assert io_.sent[0] != "learn(lid,extend_arm,opened,random)"


def test_a_transfer_that_found_nothing_leaves_the_parts_it_did_not_try_to_learning():
    """Transfer tried every action on the lid (the look-alike of the known can's functional
    part) and found nothing: the lid stays explored, and the body is learned pair by pair."""
    explored = [f"explored(lid, {act})" for act in ACTIONS]
    agent, io_ = robot({act: 0.05 for act in ACTIONS}, *explored,
                       "asked(pair(lid, lift_up, opened, transfer))")
    io_.next = [Struct("transferred", (Atom("opened"), Atom("o1")))]
    agent.step()
    assert len(beliefs(agent, "explored(lid, _)")) == len(ACTIONS)
    assert beliefs(agent, "transfer_verdicts(opened)") == [{}]
    agent.step()
    assert beliefs(agent, "focus(P)") == [{"P": "body"}]
    assert io_.sent[-1].startswith("learn(body,")


def test_exhausted_everywhere_after_a_transfer_learning_starts_over_once_then_gives_up():
    """Transfer's verdicts rest on single tries: before giving up, one new episode."""
    explored = [f"explored({part}, {act})" for act in ACTIONS for part in ("lid", "body")]
    agent, io_ = robot({act: 0.05 for act in ACTIONS}, *explored,
                       "asked(pair(lid, lift_up, opened, transfer))")
    io_.next = [Struct("transferred", (Atom("opened"), Atom("o1")))]
    agent.step()
    assert beliefs(agent, "explored(_, _)") == []
    assert beliefs(agent, "transfer_verdicts(_)") == []
    (learn,) = io_.sent  # learning starts over on the lid: one pair asked so far
    assert learn.startswith("learn(lid,") and not agent.terminated
    assert len(beliefs(agent, "asked(_)")) == 1
    for fact in explored:
        agent.ms.insert(fact)
    agent.step()
    assert agent.terminated and "cannot_open(lid)" in agent.output.getvalue()


def test_the_pedal_comes_after_the_lid_and_before_the_body():
    explored = [f"explored(lid, {act})" for act in ACTIONS]
    agent, io_ = robot({act: 0.05 for act in ACTIONS}, *explored,
                       parts=("body", "lid", "pedal"))
    agent.step()
    assert beliefs(agent, "focus(P)") == [{"P": "pedal"}]


def test_with_learning_exhausted_on_every_part_the_agent_says_so_and_stops():
    explored = [f"explored({part}, {act})" for act in ACTIONS for part in ("lid", "body")]
    agent, io_ = robot({act: 0.05 for act in ACTIONS}, *explored)
    agent.step()
    assert io_.sent == [] and agent.terminated
    assert agent.output.getvalue() == "cannot_open(lid)\n"
    assert beliefs(agent, "disposed(0)") == [{}]  # nothing disposed of: it gave up


def test_the_count_of_balls_disposed_of_is_the_environment_s():
    agent, io_ = robot({})
    io_.next = [Struct("disposed", (1,))]
    agent.step()
    assert beliefs(agent, "disposed(K)") == [{"K": 1}]
    assert agent.terminated  # trials(1): finished


def test_a_lid_that_will_not_close_is_tried_three_times_then_the_task_ends():
    agent, io_ = robot({})
    io_._percepts = [p for p in io_._percepts if p != Struct("holding", (Atom("ball"),))]
    io_._percepts.append(Struct("in_can", (Atom("ball"),)))
    agent.step()  # the ball is in: close the can
    for _ in range(2):
        io_.next = [Struct("lid_stuck", (0.05,))]  # what the last close_lid reported
        agent.step()
    assert io_.sent == ["close_lid"] * 3
    io_.next = [Struct("lid_stuck", (0.05,))]
    agent.step()
    assert agent.terminated and io_.sent == ["close_lid"] * 3
    assert agent.output.getvalue().split() == ["lid_stuck(0.05)"] * 3 + ["cannot_close"]

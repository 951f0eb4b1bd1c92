"""The affordance library inside a running GOAL agent: the eq. 6.3 merge as event-module rules."""

from __future__ import annotations

import io

import pytest

from goalagent.agent import Agent
from goalagent.kb.terms import Atom, Struct

PROGRAM = """
init module {
    #import "affordance.pl".
    beliefs {
        afford(lid, extend_arm, opened, 0, 0, 0.1).
        afford(lid, sweep_left, opened, 0, 0, 0.1).
        afford(handle, lift_up, opened, 5, 5, 1).
    }
}
event module {
    program {
        % eq. 6.3: merge each afford/6 percept into the matching belief
        forall bel(percept(afford(O, A, E, T1, S1, R1)), afford(O, A, E, T, S, R),
                   afford_merge(afford(O, A, E, T, S, R), afford(O, A, E, T1, S1, R1),
                                afford(O, A, E, T2, S2, R2)))
            do delete(afford(O, A, E, T, S, R)) + insert(afford(O, A, E, T2, S2, R2)).
        % a percept about an affordance not believed yet is adopted as it is
        forall bel(percept(afford(O, A, E, T, S, R)), not(afford(O, A, E, _, _, _)))
            do insert(afford(O, A, E, T, S, R)).
    }
}
main module {
    program {
        if bel(afford_best(handle, Act, opened)) then print(Act).
    }
}
"""


def afford(obj: str, act: str, tot: int, suc: int, rel: float) -> Struct:
    return Struct("afford", (Atom(obj), Atom(act), Atom("opened"), tot, suc, rel))


class Percepts:
    """An environment stand-in that hands the agent one scripted percept list per cycle."""

    def __init__(self, script: list[list[Struct]]) -> None:
        self.script = list(script)

    def percepts(self) -> list[Struct]:
        return self.script.pop(0) if self.script else []

    def act(self, action: object) -> None:
        raise AssertionError(f"the test agent has no external actions, got {action}")


def table(agent: Agent, obj: str) -> dict[str, tuple]:
    rows = agent.query("bel", f"afford({obj}, A, opened, T, S, R)")
    return {str(r["A"]): (r["T"], r["S"], r["R"]) for r in rows}


def test_learning_and_verification_percepts_merge_as_in_experiment_1() -> None:
    script = [
        [afford("lid", "sweep_left", 0, 0, 0.05), afford("lid", "extend_arm", 0, 0, 0.3)],
        [afford("lid", "extend_arm", 1, 1, 1)],
        [afford("lid", "extend_arm", 1, 1, 1), afford("body", "lift_up", 0, 0, 0.05)],
    ]
    agent = Agent.from_string(PROGRAM, io=Percepts(script), output=io.StringIO())
    try:
        agent.step()
        assert table(agent, "lid") == {
            "sweep_left": (0, 0, pytest.approx(0.05)),
            "extend_arm": (0, 0, pytest.approx(0.3)),
        }
        agent.step()
        assert table(agent, "lid")["extend_arm"] == (1, 1, pytest.approx(1.0))
        agent.step()
        assert table(agent, "lid")["extend_arm"] == (2, 2, pytest.approx(1.0))
        assert table(agent, "body") == {"lift_up": (0, 0, 0.05)}  # new: adopted as perceived
    finally:
        agent.close()


def test_failures_decay_a_reliable_affordance_as_in_experiment_2() -> None:
    failure = [afford("handle", "lift_up", 1, 0, 0)]
    agent = Agent.from_string(PROGRAM, io=Percepts([failure] * 4), output=io.StringIO())
    try:
        trail = []
        for _ in range(4):
            agent.step()
            trail.append(table(agent, "handle")["lift_up"])
        assert [(t, s) for t, s, _ in trail] == [(6, 5), (7, 5), (8, 5), (9, 5)]
        assert [round(r, 3) for _, _, r in trail] == [0.833, 0.714, 0.625, 0.556]
        # rule 6.2 used lift_up while Rel >= tau = 0.6, then stopped
        assert agent.output.getvalue().split() == ["lift_up"] * 3
    finally:
        agent.close()

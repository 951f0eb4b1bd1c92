"""goalagent/kb/affordance.pl through real SWI-Prolog: eq. 6.3, parameters, bands, roulette."""

from __future__ import annotations

import itertools
from collections import Counter
from pathlib import Path

import pytest
from pyswip import Prolog
from scipy.stats import chisquare

from goalagent.kb.terms import Atom, format_term

LIBRARY = Path(__file__).resolve().parents[1] / "goalagent" / "kb" / "affordance.pl"
ACTIONS = ["sweep_left", "sweep_right", "extend_arm", "contract_arm", "lift_up", "sweep_down"]
_modules = itertools.count()


class AgentModule:
    """A fresh isolated Prolog module holding the library, like one agent's knowledge base."""

    def __init__(self, prolog: Prolog, knowledge: list[str] = ()) -> None:
        self.prolog = prolog
        self.name = f"afford_test_{next(_modules)}"
        path = format_term(Atom(str(LIBRARY)))
        self.once(
            f"set_module({self.name}:base(system)),"
            f"setup_call_cleanup(open({path}, read, S),"
            " findall(T, (repeat, read_term(S, T, []), (T == end_of_file -> !, fail ; true)), Ts),"
            " close(S)),"
            f" forall(member(T, Ts), assertz({self.name}:T))"
        )
        for clause in knowledge:
            self.once(f"assertz({self.name}:({clause}))")

    def believe(self, obj: str, act: str, eff: str, tot: int, suc: int, rel: float) -> None:
        """Add the belief afford(obj, act, eff, tot, suc, rel)."""
        args = ",".join(format_term(x) for x in (Atom(obj), Atom(act), Atom(eff), tot, suc, rel))
        self.once(f"assertz({self.name}:afford({args}))")

    def all(self, goal: str) -> list[dict]:
        """Every solution of goal, run inside the agent module."""
        return list(self.prolog.query(f"{self.name}:({goal})", catcherrors=True))

    def once(self, goal: str) -> dict | None:
        """The first solution of goal (None when it fails)."""
        answers = self.all(f"once(({goal}))")
        return answers[0] if answers else None

    def holds(self, goal: str) -> bool:
        """Whether goal succeeds in the agent module."""
        return self.once(goal) is not None


@pytest.fixture(scope="module")
def prolog() -> Prolog:
    engine = Prolog()
    list(engine.query("set_prolog_flag(debug_on_error, false)"))
    return engine


@pytest.fixture
def agent(prolog: Prolog) -> AgentModule:
    return AgentModule(prolog)


def merge(agent: AgentModule, old: tuple, new: tuple) -> tuple[int, int, float]:
    """afford_merge of afford(lid, a, opened, *old) with afford(lid, a, opened, *new)."""
    old_t = ",".join(format_term(x) for x in old)
    new_t = ",".join(format_term(x) for x in new)
    answer = agent.once(
        f"afford_merge(afford(lid,a,opened,{old_t}), afford(lid,a,opened,{new_t}),"
        " afford(lid,a,opened,T,S,R))"
    )
    assert answer is not None
    return answer["T"], answer["S"], answer["R"]


def test_merge_reproduces_the_thesis_numbers(agent: AgentModule) -> None:
    # unverified r0 merged with the learner's r2 / r1 percepts (§6.4.2, Experiment 1)
    assert merge(agent, (0, 0, 0.1), (0, 0, 0.05)) == (0, 0, pytest.approx(0.05))
    assert merge(agent, (0, 0, 0.1), (0, 0, 0.3)) == (0, 0, pytest.approx(0.3))
    # the verified success with theta_max
    assert merge(agent, (0, 0, 0.3), (1, 1, 1)) == (1, 1, pytest.approx(1.0))
    # Experiment 2: (5,5,1) failing three times; eq. 6.3 gives 0.625 where the text says 0.57
    state = (5, 5, 1)
    trail = []
    for _ in range(3):
        state = merge(agent, state, (1, 0, 0))
        trail.append(state)
    assert trail == [
        (6, 5, pytest.approx(5 / 6)),
        (7, 5, pytest.approx(5 / 7)),
        (8, 5, pytest.approx(5 / 8)),
    ]
    assert [round(r, 3) for _, _, r in trail] == [0.833, 0.714, 0.625]


def test_merge_keeps_the_affordance_identity(agent: AgentModule) -> None:
    assert not agent.holds(
        "afford_merge(afford(lid,a,opened,0,0,0.1), afford(handle,a,opened,1,1,1), _)"
    )
    assert not agent.holds(
        "afford_merge(afford(lid,a,opened,0,0,0.1), afford(lid,b,opened,1,1,1), _)"
    )


def test_merge_is_one_event_rule_over_beliefs(agent: AgentModule) -> None:
    """The forall rule from the library's header, run as a forall over a percept belief."""
    agent.believe("lid", "extend_arm", "opened", 0, 0, 0.1)
    agent.believe("lid", "sweep_left", "opened", 0, 0, 0.1)
    agent.once("assertz(percept(afford(lid, extend_arm, opened, 0, 0, 0.3)))")
    agent.once(
        "forall((percept(afford(O,A,E,T1,S1,R1)), afford(O,A,E,T,S,R),"
        "        afford_merge(afford(O,A,E,T,S,R), afford(O,A,E,T1,S1,R1), New)),"
        "       (retract(afford(O,A,E,T,S,R)), assertz(New)))"
    )
    rows = agent.all("afford(lid, A, opened, T, S, R)")
    table = {str(r["A"]): (r["T"], r["S"], r["R"]) for r in rows}
    assert table == {
        "sweep_left": (0, 0, pytest.approx(0.1)),
        "extend_arm": (0, 0, pytest.approx(0.3)),
    }


def test_parameters_default_to_the_thesis_values(agent: AgentModule) -> None:
    values = {str(a["N"]): a["V"] for a in agent.all("afford_param(N, V)")}
    assert values == {"r0": 0.1, "r1": 0.3, "r2": 0.05, "tau": 0.6}


def test_a_knowledge_setting_overrides_one_default(prolog: Prolog) -> None:
    agent = AgentModule(prolog, knowledge=["afford_setting(tau, 0.7)"])
    values = {str(a["N"]): a["V"] for a in agent.all("afford_param(N, V)")}
    assert values == {"r0": 0.1, "r1": 0.3, "r2": 0.05, "tau": 0.7}
    assert agent.all("afford_param(tau, V)") == [{"V": 0.7}]
    agent.believe("lid", "extend_arm", "opened", 3, 2, 0.65)
    assert not agent.holds("afford_reliable(lid, extend_arm, opened)")
    assert agent.holds("afford_to_verify(lid, extend_arm, opened)")


@pytest.mark.parametrize(
    ("setting", "message"),
    [
        ("afford_setting(r1, 0.8)", "0 < r2 < r0 < r1 < tau < 1"),
        ("afford_setting(tau, high)", "tau=high"),
        ("afford_setting(r3, 0.2)", "unknown affordance parameter r3"),
    ],
)
def test_bad_settings_raise_a_clear_error(prolog: Prolog, setting: str, message: str) -> None:
    agent = AgentModule(prolog, knowledge=[setting])
    answer = agent.once("catch(afford_param(tau, _), error(_, context(_, M)), true)")
    assert answer is not None
    assert message in str(answer["M"])


def test_reliable_and_best_follow_rule_6_2(agent: AgentModule) -> None:
    agent.believe("handle", "pull", "opened", 5, 4, 0.8)
    agent.believe("handle", "lift_up", "opened", 2, 2, 1.0)
    agent.believe("handle", "push", "opened", 4, 2, 0.59)
    agent.believe("handle", "sweep_left", "opened", 5, 3, 0.6)
    reliable = {str(a["A"]) for a in agent.all("afford_reliable(handle, A, opened)")}
    assert reliable == {"pull", "lift_up", "sweep_left"}  # tau itself counts as reliable
    assert agent.all("afford_best(handle, A, opened)") == [{"A": "lift_up"}]
    assert agent.all("afford_best(lid, A, opened)") == []


def test_best_takes_the_first_belief_on_ties(agent: AgentModule) -> None:
    agent.believe("lid", "extend_arm", "opened", 5, 5, 1.0)
    agent.believe("lid", "lift_up", "opened", 2, 2, 1.0)
    assert agent.all("afford_best(lid, A, opened)") == [{"A": "extend_arm"}]


def test_bands_of_rules_6_4_and_6_12(agent: AgentModule) -> None:
    for act, rel in zip(ACTIONS, [0.1, 0.05, 0.3, 0.59, 0.6, 0.0], strict=True):
        agent.believe("lid", act, "opened", 0, 0, rel)
    to_verify = {str(a["A"]) for a in agent.all("afford_to_verify(lid, A, opened)")}
    assert to_verify == {"extend_arm", "contract_arm"}  # r1 <= Rel < tau
    # lift_up is reliable (0.6 = tau), so learning is not needed
    assert not agent.holds("afford_learning_needed(lid, opened)")
    agent.once("retract(afford(lid, lift_up, opened, _, _, _))")
    assert agent.all("afford_learning_needed(O, E)") == [{"O": "lid", "E": "opened"}]


def test_learning_exhaustion_needs_every_reliability_below_r2(agent: AgentModule) -> None:
    assert not agent.holds("afford_learning_exhausted(lid, opened)")  # nothing believed
    assert not agent.holds("afford_learning_needed(lid, opened)")
    agent.believe("lid", "extend_arm", "opened", 9, 5, 0.04)
    agent.believe("lid", "sweep_left", "opened", 1, 0, 0.0)
    agent.believe("lid", "lift_up", "opened", 0, 0, 0.05)  # exactly r2: not below it
    assert not agent.holds("afford_learning_exhausted(lid, opened)")
    assert agent.holds("afford_learning_needed(lid, opened)")
    agent.once("retract(afford(lid, lift_up, opened, _, _, _))")
    assert agent.holds("afford_learning_exhausted(lid, opened)")
    assert not agent.holds("afford_learning_needed(lid, opened)")
    agent.believe("handle", "lift_up", "opened", 0, 0, 0.1)
    assert agent.all("afford_learning_needed(O, opened)") == [{"O": "handle"}]


def test_predicates_fail_quietly_without_any_afford_belief(agent: AgentModule) -> None:
    for goal in (
        "afford_reliable(_, _, _)",
        "afford_best(_, _, _)",
        "afford_roulette(lid, _, opened)",
        "afford_learning_needed(_, _)",
        "afford_to_verify(_, _, _)",
        "afford_learning_exhausted(_, _)",
    ):
        assert agent.all(goal) == [], goal


def spin(agent: AgentModule, seed: int, draws: int) -> list[str]:
    """Draws of afford_roulette(lid, A, opened) after set_random(seed(seed))."""
    answer = agent.once(
        f"set_random(seed({seed})),"
        f" findall(A, (between(1, {draws}, _), afford_roulette(lid, A, opened)), As)"
    )
    assert answer is not None
    return [str(a) for a in answer["As"]]


def test_roulette_frequencies_match_reliabilities(agent: AgentModule) -> None:
    rels = dict(zip(ACTIONS, [0.05, 0.1, 0.3, 0.05, 0.5, 0.0], strict=True))
    for act, rel in rels.items():
        agent.believe("lid", act, "opened", 0, 0, rel)
    draws = 6000
    counts = Counter(spin(agent, 7, draws))
    assert "sweep_down" not in counts  # Rel = 0 is never drawn
    live = [a for a in ACTIONS if rels[a] > 0]
    observed = [counts[a] for a in live]
    total = sum(rels.values())
    expected = [draws * rels[a] / total for a in live]
    assert sum(observed) == draws
    assert chisquare(observed, expected).pvalue > 0.001
    # the same draws clearly reject a uniform choice: the test has power
    assert chisquare(observed, [draws / len(live)] * len(live)).pvalue < 1e-9


def test_roulette_is_seeded_by_prolog_random(agent: AgentModule) -> None:
    for act, rel in zip(ACTIONS, [0.1, 0.1, 0.3, 0.05, 0.1, 0.1], strict=True):
        agent.believe("lid", act, "opened", 0, 0, rel)
    assert spin(agent, 3, 50) == spin(agent, 3, 50)
    assert spin(agent, 3, 50) != spin(agent, 4, 50)


def test_roulette_fails_when_every_reliability_is_zero(agent: AgentModule) -> None:
    agent.believe("lid", "extend_arm", "opened", 3, 0, 0.0)
    assert agent.all("afford_roulette(lid, A, opened)") == []


def test_roulette_needs_object_and_effect(agent: AgentModule) -> None:
    agent.believe("lid", "extend_arm", "opened", 0, 0, 0.1)
    answer = agent.once("catch(afford_roulette(_, _, opened), error(E, context(_, M)), true)")
    assert answer is not None
    assert str(answer["E"]) == "instantiation_error" and "needs Obj and Eff bound" in str(
        answer["M"]
    )

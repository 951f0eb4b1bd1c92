"""robot/affordance.pl in a real mental state: eq. 6.3, parameters, bands, roulette.

The library is read the way ``#import "affordance.pl".`` reads it (parse_prolog_file) and
loaded as knowledge into a MentalState, i.e. into the agent's own SWI-Prolog module.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.stats import chisquare

from goalagent.ast import Pos, PrologText
from goalagent.extensions import prolog_library
from goalagent.kb.engine import PrologRuntimeError
from goalagent.kb.mentalstate import MentalState
from goalagent.kb.terms import Atom, format_term
from goalagent.parser import parse_prolog_file

ACTIONS = ["sweep_left", "sweep_right", "extend_arm", "contract_arm", "lift_up", "sweep_down"]


class AgentBeliefs:
    """One agent's mental state with the library (plus extra knowledge clauses) loaded."""

    def __init__(self, knowledge: tuple[str, ...] = ()) -> None:
        extra = tuple(PrologText(c, Pos("<test>", i + 1, 1)) for i, c in enumerate(knowledge))
        self.ms = MentalState(
            "afford_test", knowledge=parse_prolog_file(prolog_library("affordance.pl")) + extra
        )

    def believe(self, obj: str, act: str, eff: str, tot: int, suc: int, rel: float) -> None:
        """Insert the belief afford(obj, act, eff, tot, suc, rel)."""
        self.ms.insert(self.fact(obj, act, eff, tot, suc, rel))

    def forget(self, obj: str, act: str, eff: str, tot: int, suc: int, rel: float) -> None:
        """Delete that belief again."""
        self.ms.delete(self.fact(obj, act, eff, tot, suc, rel))

    @staticmethod
    def fact(*args: object) -> str:
        names = [Atom(a) if isinstance(a, str) else a for a in args]
        return "afford(" + ",".join(format_term(x) for x in names) + ")"

    def all(self, goal: str) -> list[dict]:
        """Every answer of bel(goal)."""
        return self.ms.query("bel", goal)

    def holds(self, goal: str) -> bool:
        """Whether bel(goal) holds."""
        return bool(self.ms.query("bel", goal, limit=1))


@pytest.fixture
def agent() -> Iterator[AgentBeliefs]:
    beliefs = AgentBeliefs()
    yield beliefs
    beliefs.ms.close()


@pytest.fixture
def make_agent() -> Iterator:
    made: list[AgentBeliefs] = []

    def make(*knowledge: str) -> AgentBeliefs:
        made.append(AgentBeliefs(knowledge))
        return made[-1]

    yield make
    for beliefs in made:
        beliefs.ms.close()


def merge(agent: AgentBeliefs, old: tuple, new: tuple) -> tuple[int, int, float]:
    """afford_merge of afford(lid, a, opened, *old) with afford(lid, a, opened, *new)."""
    old_t = ",".join(format_term(x) for x in old)
    new_t = ",".join(format_term(x) for x in new)
    (answer,) = agent.all(
        f"afford_merge(afford(lid,a,opened,{old_t}), afford(lid,a,opened,{new_t}),"
        " afford(lid,a,opened,T,S,R))"
    )
    return answer["T"], answer["S"], answer["R"]


def test_merge_reproduces_the_thesis_numbers(agent: AgentBeliefs) -> None:
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


def test_merge_keeps_the_affordance_identity(agent: AgentBeliefs) -> None:
    assert not agent.holds(
        "afford_merge(afford(lid,a,opened,0,0,0.1), afford(handle,a,opened,1,1,1), _)"
    )
    assert not agent.holds(
        "afford_merge(afford(lid,a,opened,0,0,0.1), afford(lid,b,opened,1,1,1), _)"
    )


def test_parameters_default_to_the_thesis_values(agent: AgentBeliefs) -> None:
    values = {str(a["N"]): a["V"] for a in agent.all("afford_param(N, V)")}
    assert values == {"r0": 0.1, "r1": 0.3, "r2": 0.05, "tau": 0.6}


def test_a_knowledge_setting_overrides_one_default(make_agent) -> None:
    agent = make_agent("afford_setting(tau, 0.7)")
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
        ("afford_setting(tau, high)", r"tau=high\]' \(affordance parameters must be numbers"),
        ("afford_setting(r3, 0.2)", "r0, r1, r2 or tau' expected, found `r3'"),
    ],
)
def test_bad_settings_raise_a_clear_error(make_agent, setting: str, message: str) -> None:
    agent = make_agent(setting)
    agent.believe("lid", "extend_arm", "opened", 0, 0, 0.1)
    with pytest.raises(PrologRuntimeError, match=message):
        agent.holds("afford_reliable(lid, A, opened)")


def test_reliable_and_best_follow_rule_6_2(agent: AgentBeliefs) -> None:
    agent.believe("handle", "pull", "opened", 5, 4, 0.8)
    agent.believe("handle", "lift_up", "opened", 2, 2, 1.0)
    agent.believe("handle", "push", "opened", 4, 2, 0.59)
    agent.believe("handle", "sweep_left", "opened", 5, 3, 0.6)
    reliable = {str(a["A"]) for a in agent.all("afford_reliable(handle, A, opened)")}
    assert reliable == {"pull", "lift_up", "sweep_left"}  # tau itself counts as reliable
    assert agent.all("afford_best(handle, A, opened)") == [{"A": "lift_up"}]
    assert agent.all("afford_best(lid, A, opened)") == []


def test_best_takes_the_first_belief_on_ties(agent: AgentBeliefs) -> None:
    agent.believe("lid", "extend_arm", "opened", 5, 5, 1.0)
    agent.believe("lid", "lift_up", "opened", 2, 2, 1.0)
    assert agent.all("afford_best(lid, A, opened)") == [{"A": "extend_arm"}]


def test_bands_of_rules_6_4_and_6_12(agent: AgentBeliefs) -> None:
    for act, rel in zip(ACTIONS, [0.1, 0.05, 0.3, 0.59, 0.6, 0.0], strict=True):
        agent.believe("lid", act, "opened", 0, 0, rel)
    to_verify = {str(a["A"]) for a in agent.all("afford_to_verify(lid, A, opened)")}
    assert to_verify == {"extend_arm", "contract_arm"}  # r1 <= Rel < tau
    # lift_up is reliable (0.6 = tau), so learning is not needed
    assert not agent.holds("afford_learning_needed(lid, opened)")
    agent.forget("lid", "lift_up", "opened", 0, 0, 0.6)
    assert agent.all("afford_learning_needed(O, E)") == [{"O": "lid", "E": "opened"}]


def test_learning_exhaustion_needs_every_reliability_below_r2(agent: AgentBeliefs) -> None:
    assert not agent.holds("afford_learning_exhausted(lid, opened)")  # nothing believed
    assert not agent.holds("afford_learning_needed(lid, opened)")
    agent.believe("lid", "extend_arm", "opened", 9, 5, 0.04)
    agent.believe("lid", "sweep_left", "opened", 1, 0, 0.0)
    agent.believe("lid", "lift_up", "opened", 0, 0, 0.05)  # exactly r2: not below it
    assert not agent.holds("afford_learning_exhausted(lid, opened)")
    assert agent.holds("afford_learning_needed(lid, opened)")
    agent.forget("lid", "lift_up", "opened", 0, 0, 0.05)
    assert agent.holds("afford_learning_exhausted(lid, opened)")
    assert not agent.holds("afford_learning_needed(lid, opened)")
    agent.believe("handle", "lift_up", "opened", 0, 0, 0.1)
    assert agent.all("afford_learning_needed(O, opened)") == [{"O": "handle"}]


def test_predicates_fail_quietly_without_any_afford_belief(agent: AgentBeliefs) -> None:
    for goal in (
        "afford_reliable(_, _, _)",
        "afford_best(_, _, _)",
        "afford_roulette(lid, _, opened)",
        "afford_learning_needed(_, _)",
        "afford_to_verify(_, _, _)",
        "afford_learning_exhausted(_, _)",
    ):
        assert agent.all(goal) == [], goal


def spin(agent: AgentBeliefs, seed: int, draws: int) -> list[str]:
    """Draws of afford_roulette(lid, A, opened) after set_random(seed(seed))."""
    (answer,) = agent.all(
        f"set_random(seed({seed})),"
        f" findall(A, (between(1, {draws}, _), afford_roulette(lid, A, opened)), As)"
    )
    return [str(a) for a in answer["As"]]


def test_roulette_frequencies_match_reliabilities(agent: AgentBeliefs) -> None:
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


def test_roulette_is_seeded_by_prolog_random(agent: AgentBeliefs) -> None:
    for act, rel in zip(ACTIONS, [0.1, 0.1, 0.3, 0.05, 0.1, 0.1], strict=True):
        agent.believe("lid", act, "opened", 0, 0, rel)
    assert spin(agent, 3, 50) == spin(agent, 3, 50)
    assert spin(agent, 3, 50) != spin(agent, 4, 50)


def test_roulette_fails_when_every_reliability_is_zero(agent: AgentBeliefs) -> None:
    agent.believe("lid", "extend_arm", "opened", 3, 0, 0.0)
    assert agent.all("afford_roulette(lid, A, opened)") == []


def test_roulette_needs_object_and_effect(agent: AgentBeliefs) -> None:
    agent.believe("lid", "extend_arm", "opened", 0, 0, 0.1)
    with pytest.raises(PrologRuntimeError, match="needs Obj and Eff bound"):
        agent.holds("afford_roulette(_, _, opened)")


def test_spin_draws_from_an_agents_own_wheel(agent: AgentBeliefs) -> None:
    (answer,) = agent.all(
        "set_random(seed(11)),"
        " findall(A, (between(1, 3000, _), afford_spin([0.1-a, 0.0-b, 0.3-c, -1-d], A)), As)"
    )
    counts = Counter(str(a) for a in answer["As"])
    assert set(counts) == {"a", "c"}
    assert chisquare([counts["a"], counts["c"]], [750, 2250]).pvalue > 0.001
    assert not agent.holds("afford_spin([0.0-a, 0-b], _)")
    assert not agent.holds("afford_spin([], _)")


@settings(max_examples=60, deadline=None)
@given(
    start=st.floats(min_value=0.01, max_value=0.99),
    outcomes=st.lists(st.booleans(), min_size=1, max_size=25),
)
def test_verifications_make_reliability_the_success_rate(
    start: float, outcomes: list[bool]
) -> None:
    """Eq. 6.3 from (0, 0, r): after n >= 1 verified uses, Rel = Suc / Tot whatever r was."""
    beliefs = AgentBeliefs()
    try:
        percepts = ",".join(
            "afford(lid,a,opened,1,1,1)" if ok else "afford(lid,a,opened,1,0,0)" for ok in outcomes
        )
        (answer,) = beliefs.all(
            f"foldl([P, Old, New]>>afford_merge(Old, P, New), [{percepts}],"
            f" afford(lid,a,opened,0,0,{format_term(start)}), afford(lid,a,opened,T,S,R))"
        )
    finally:
        beliefs.ms.close()
    assert (answer["T"], answer["S"]) == (len(outcomes), sum(outcomes))
    assert answer["R"] == pytest.approx(sum(outcomes) / len(outcomes), abs=1e-9)

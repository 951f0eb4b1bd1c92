"""What launching many agents of one program shares or puts off (issue 29): agents copy
the conditions an earlier one compiled (clone_conditions/6) and do to their modules what
loading the first one's knowledge and beliefs did (load_imaged/7) instead of reading and
confining each text again, and a copy behaves exactly as the agent's own compile or load
would (it reads the agent's own beliefs and keys); Prolog's generator is seeded before
anything draws, as if each agent had seeded it when launched."""

from __future__ import annotations

import io
from collections.abc import Iterator
from dataclasses import replace

import pytest

from goalagent.agent import Agent
from goalagent.agent.checks import update_formulas
from goalagent.kb.conditions import Conditions
from goalagent.kb.engine import get_engine
from goalagent.kb.terms import Atom, Struct, Term
from goalagent.mas import MultiAgentSystem
from goalagent.parser import parse_agent

COUNTER = """
init module { beliefs { n(0). } }
main module { program [order=linearall] {
    if bel(n(N), N < 2, M is N + 1) then delete(n(N)) + insert(n(M)).
    if bel(me(Me), n(1), atom_length(Me, L)) then insert(len(L)).
} }
"""

KEYS = """
main module { program [order=linearall] {
    if bel(me(Me), not(nb_current(k, _)), nb_setval(k, Me)) then insert(set).
    if bel(set, nb_getval(k, V)) then insert(got(V)).
} }
"""


@pytest.fixture
def system() -> Iterator[MultiAgentSystem]:
    """A system without an environment whose agents print and warn nowhere, closed after."""
    made = MultiAgentSystem(output=io.StringIO(), warn=lambda message: None)
    yield made
    made.close()


@pytest.fixture
def copies(monkeypatch: pytest.MonkeyPatch) -> list[bool]:
    """What each copy_conditions call answered (True: copied)."""
    answers: list[bool] = []
    copy = Conditions.copy_conditions

    def spy(self: Conditions, like: Conditions, conditions: object) -> bool:
        answers.append(copy(self, like, conditions))  # type: ignore[arg-type]
        return answers[-1]

    monkeypatch.setattr(Conditions, "copy_conditions", spy)
    return answers


def test_copied_conditions_read_each_agent_s_own_beliefs(copies: list[bool],
                                                         system: MultiAgentSystem) -> None:
    program = parse_agent(COUNTER, "counter.goal")
    for name in ("a", "bb", "ccc"):
        system.launch(name, program)
    assert copies == [True, True]
    first = system.agents[0]
    first.ms.delete("n(0)")
    first.ms.insert("n(2)")  # the first agent's beliefs are not the others'
    system.run(max_cycles=3)
    assert [agent.query("bel", "n(N)") for agent in system.agents] == [
        [{"N": 2}], [{"N": 2}], [{"N": 2}]]
    assert [agent.query("bel", "len(L)") for agent in system.agents] == [
        [], [{"L": 2}], [{"L": 3}]]


def test_a_condition_naming_an_own_key_is_compiled_by_each_agent(
        copies: list[bool], system: MultiAgentSystem) -> None:
    program = parse_agent(KEYS, "keys.goal")
    for name in ("a", "b", "c"):
        system.launch(name, program)
    assert copies == [False, False]  # the first agent's key is in its clause
    system.run(max_cycles=2)
    assert [agent.query("bel", "got(V)") for agent in system.agents] == [
        [{"V": Atom(name)}] for name in ("a", "b", "c")]


def test_once_the_agent_copied_from_is_closed_the_next_compiles_and_is_copied(
        copies: list[bool], system: MultiAgentSystem) -> None:
    program = parse_agent(COUNTER, "counter.goal")
    system.launch("a", program).close()
    system.agents.clear()
    later = [system.launch(name, program) for name in ("bb", "ccc")]
    assert copies == [True]  # bb compiled its own (a was closed); ccc copied bb's
    for agent in later:
        agent.step()
        agent.step()
    assert [agent.query("bel", "len(L)") for agent in later] == [[{"L": 2}], [{"L": 3}]]


def test_agents_with_directives_compile_their_own(copies: list[bool],
                                                  system: MultiAgentSystem) -> None:
    program = parse_agent(COUNTER.replace(
        "beliefs { n(0). }", "knowledge { :- dynamic(seen/1). } beliefs { n(0). }"), "d.goal")
    system.launch("a", program)
    system.launch("bb", program)
    assert copies == []
    system.run(max_cycles=3)
    assert system.agents[1].query("bel", "len(L)") == [{"L": 2}]


DRAWS = """
init module { knowledge { KNOWLEDGE } beliefs { n(0). first(0). } goals { GOAL } }
main module { program {
    if bel(n(0), random_between(1, 1000000, X)) then insert(drew(X)) + delete(n(0)).
} }
"""

LUCKY = "lucky(X) :- random_between(1, 1000000, Y), Y =:= X."
DRAWING_DIRECTIVE = ":- dynamic(first/1). :- random_between(1, 1000000, Y), assertz(first(Y))."


def _draws(knowledge: str, goal: str, agents: int, *, eager: bool,
           monkeypatch: pytest.MonkeyPatch) -> list[list[dict[str, object]]]:
    """What each of ``agents`` agents of the DRAWS program drew (first/1 and drew/1) in
    its first two cycles, seeds 5, 6, ...; ``eager``: Prolog seeded at each launch, as
    before seeds were held back."""
    engine = get_engine()
    if eager:
        monkeypatch.setattr(engine, "seed_random", lambda seed: engine.call(
            "set_random", Struct("seed", (seed,)), module="system"))
    program = parse_agent(DRAWS.replace("KNOWLEDGE", knowledge).replace("GOAL", goal),
                          "draws.goal")
    system = MultiAgentSystem(output=io.StringIO(), seed=5)
    try:
        for index in range(agents):
            system.launch(f"a{index}", program)
        system.run(max_cycles=2)
        return [agent.query("bel", "drew(X) ; first(X), X > 0") for agent in system.agents]
    finally:
        system.close()
        monkeypatch.undo()


@pytest.mark.parametrize(("knowledge", "goal"), [
    ("", "g(1)."),  # nothing draws before the first cycle: it draws from the last seed
    (LUCKY, "lucky(3)."),  # checking the goal runs a knowledge rule that draws
    (DRAWING_DIRECTIVE, ""),  # a directive draws while the agent loads
], ids=["cycles", "goal-check", "directive"])
def test_prolog_draws_the_numbers_it_drew_when_each_launch_seeded_it(
        knowledge: str, goal: str, monkeypatch: pytest.MonkeyPatch) -> None:
    held_back = _draws(knowledge, goal, 3, eager=False, monkeypatch=monkeypatch)
    assert all(drawn for drawn in held_back)
    assert held_back == _draws(knowledge, goal, 3, eager=True, monkeypatch=monkeypatch)


LOADED = """
init module {
    knowledge {
        double(X, Y) :- Y is 2 * X.
        last(L, X) :- reverse(L, [X|_]).
        greeting --> [hello], name.
        name --> [world].
        told :- true.
    }
    beliefs { n(1). n(2). n(3). pair(a, 1). pair(b, 2). told. }
    goals { sum(6). }
}
main module { program {
    if a-goal(sum(S)), bel(findall(D, (n(N), double(N, D)), Ds), sum_list(Ds, T), S is T / 2)
        then insert(summed(S)).
} }
"""

OWN_KEY = """
init module { knowledge { mine(V) :- nb_getval(k, V). } beliefs { n(0). } }
main module { program [order=linearall] {
    if bel(me(Me), not(nb_current(k, _)), nb_setval(k, Me)) then insert(set).
    if bel(set, mine(V)) then insert(got(V)).
} }
"""


@pytest.fixture
def loads(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The loading calls each launch makes (load/6 reads the texts, load_imaged/7 reads
    them only for the first agent of a program)."""
    engine = get_engine()
    names: list[str] = []
    call = engine.call

    def spy(name: str, *args: object, **options: object) -> object:
        if name.startswith("load"):
            names.append(name)
        return call(name, *args, **options)  # type: ignore[arg-type]

    monkeypatch.setattr(engine, "call", spy)
    return names


def _imaged(condition: str) -> bool:
    """Whether some image of a load (ga_kb:'$ga_image'(Id, B, G, Loaded)) meets
    ``condition`` on ``Loaded``."""
    engine = get_engine()
    goal = engine.parse_term(f"ga_kb:'$ga_image'(_, _, _, Loaded), {condition}")
    return engine.call("once", goal, module="system") is not None


def _held(agent: Agent) -> list[Term]:
    """The agent's beliefs but me/1."""
    return [belief for belief in agent.beliefs()
            if not (isinstance(belief, Struct) and belief.name == "me")]


def test_agents_loaded_from_the_image_hold_what_loading_the_texts_gives(
        loads: list[str], system: MultiAgentSystem) -> None:
    program = parse_agent(LOADED, "loaded.goal")
    reference = parse_agent(LOADED.replace("n(1).", "n(1). "), "reference.goal")
    agents = [system.launch(name, program) for name in ("a", "b", "c")]
    texts_only = system.launch("r", reference, limits=replace(system.limits,
                                                             sandbox=True))
    assert loads == ["load_imaged"] * 4
    assert _imaged("memberchk(assert(b, told), Loaded), memberchk(redefine(g, told), Loaded)"
                   ", memberchk(dynamic(g, pair/2), Loaded)")
    queries = ["n(N)", "pair(P, V)", "double(4, Y)", "last([1, 2, 3], X)",
               "phrase(greeting, [hello, world])", "told"]
    assert len(_held(agents[0])) == 5  # (told/0 is knowledge too)
    for agent in [*agents[1:], texts_only]:
        assert _held(agent) == _held(agents[0])
        for query in queries:
            assert agent.query("bel", query) == agents[0].query("bel", query), query
    assert _imaged("memberchk(dynamic(b, summed/1), Loaded)")  # declared: updated
    assert agents[1].query("bel", "summed(S)") == []  # (no existence error)
    assert agents[0].query("bel", "double(4, Y)") == [{"Y": 8}]
    assert agents[0].query("bel", "last([1, 2, 3], X)") == [{"X": 3}]
    system.run(max_cycles=1)
    assert [agent.query("bel", "summed(S)") for agent in system.agents] == [
        [{"S": 6}]] * 4
    second = agents[1]
    second.ms.delete("n(3)")
    assert agents[2].query("bel", "n(3)") == [{}]  # each agent's beliefs its own


def test_a_knowledge_clause_naming_an_own_key_is_loaded_by_each_agent(
        loads: list[str], system: MultiAgentSystem) -> None:
    program = parse_agent(OWN_KEY, "own_key.goal")
    for name in ("a", "b", "c"):
        system.launch(name, program)
    assert loads == ["load_imaged"] * 3
    assert not _imaged("memberchk(assert(_, (mine(_) :- _)), Loaded)")
    system.run(max_cycles=2)
    assert [agent.query("bel", "got(V)") for agent in system.agents] == [
        [{"V": Atom(name)}] for name in ("a", "b", "c")]


SYSTEM_NAMED = """
main module { program { if true then insert(append(x)). } }
"""


def test_declaring_again_from_the_image_keeps_what_the_agent_believes(
        system: MultiAgentSystem) -> None:
    program = parse_agent(SYSTEM_NAMED, "system_named.goal")  # append/1: SWI's, not ISO
    first, second = (system.launch(name, program) for name in ("a", "b"))
    assert _imaged("memberchk(redefine(b, append(_)), Loaded)")
    second.step()
    assert second.query("bel", "append(X)") == [{"X": Atom("x")}]
    second.ms.declare_updates(update_formulas(program))  # as the launch did: replayed
    assert second.query("bel", "append(X)") == [{"X": Atom("x")}]
    assert first.query("bel", "append(X)") == []

"""GOAL's semantics where they are easy to get wrong: the list a listall rule binds (one
entry per answer over the condition's free variables), the random choice among an if
rule's instantiations (the agent's seeded stream, shown by the trace), and belief
predicates named like SWI-Prolog's built-ins (the agent's own, or a located error)."""

from __future__ import annotations

import io

import pytest

from goalagent.agent import Agent, AgentError, EventKind
from goalagent.kb.terms import Atom


def agent(text: str, **kwargs) -> Agent:
    kwargs.setdefault("output", io.StringIO())
    kwargs.setdefault("warn", lambda message: None)
    return Agent.from_string(text, "semantics.goal", **kwargs)


def printed(text: str, cycles: int = 1, **kwargs) -> list[str]:
    """The lines an agent prints in its first cycles."""
    a = agent(text, **kwargs)
    try:
        a.run(max_cycles=cycles)
        return a.output.getvalue().splitlines()
    finally:
        a.close()


LISTALL = """
init module {{
    knowledge {{ :- dynamic p/2, q/1, r/1. }}
    beliefs {{ p(a, 1). p(b, 2). p(b, 2). q(a). r(x). }}
}}
main module [exit=always] {{ program [order=linearall] {{
    #define pair(X, Y) bel(p(X, Y), atom(X), Local = X, Local \\== none).
    {rule}
}} }}
"""


@pytest.mark.parametrize("rule, expected", [
    # two free variables: one [X, Y] entry per (distinct) answer
    ("listall L <- bel(p(X, Y)) do print(L).", "[[a,1],[b,2]]"),
    # one free variable: its values
    ("listall L <- bel(p(X, _)) do print(L).", "[a,b]"),
    # a macro contributes its arguments, not its own variables (Local)
    ("listall L <- pair(A, B) do print(L).", "[[a,1],[b,2]]"),
    # variables of negated literals are not collected; _Anonymous ones neither
    ("listall L <- bel(q(X)), not(bel(p(X, Z))), bel(r(_W)) do print(L).", "[]"),
    ("listall L <- bel(p(X, _N)), not(bel(q(X))) do print(L).", "[b]"),
    # no free variable: nothing to list, even when the condition holds
    ("listall L <- bel(q(a)) do print(L).", "[]"),
    # variables an enclosing rule binds are not collected
    ("if bel(q(X)) then { listall L <- bel(p(X, Y)) do print(L). }", "[1]"),
    # the left-to-right form binds the same list
    ("listall bel(p(X, Y)) -> L do print(L).", "[[a,1],[b,2]]"),
])
def test_listall_binds_one_entry_per_answer(rule: str, expected: str) -> None:
    assert printed(LISTALL.format(rule=rule)) == [expected]


def test_a_real_agents_pattern_matches_listall_entries() -> None:
    """[[_, Colour] | _] only matches a list of pairs (a BW4T agent's next-colour rule)."""
    lines = printed("""
        init module { beliefs { seq(1, red). seq(2, blue). } }
        main module [exit=always] { program {
            listall Seq <- bel(seq(I, Colour)) do {
                if bel(Seq = [[_, First] | _]) then print(First).
            }
        } }""")
    assert lines == ["red"]


CHOICE = """
init module { beliefs { n(1). n(2). n(3). n(4). n(5). } }
main module [exit=always] { program { if bel(n(X)) then print(X). } }
"""


def test_an_if_rule_fires_with_an_instantiation_drawn_by_the_agents_seed() -> None:
    chosen = {seed: printed(CHOICE, seed=seed)[0] for seed in range(12)}
    assert len(set(chosen.values())) >= 3  # not always Prolog's first answer
    assert all(printed(CHOICE, seed=seed)[0] == chosen[seed] for seed in (0, 5))


def test_the_trace_shows_the_order_in_which_instantiations_are_tried() -> None:
    events = []
    a = agent(CHOICE, seed=3)
    a.listen(events.append)
    a.step()
    tried = next(e for e in events if e.kind is EventKind.RULE_TRIED)
    order = [bindings["X"] for bindings in tried.instantiations]
    assert sorted(order) == [1, 2, 3, 4, 5]
    assert a.output.getvalue() == f"{order[0]}\n"  # the first of the drawn order fires
    assert " ".join(f"[X={x}]" for x in order) in tried.text


def test_the_first_enabled_instantiation_in_the_drawn_order_fires() -> None:
    text = """
        init module {
            beliefs { n(1). n(2). n(3). n(4). }
            actionspec { take(X) { pre { X > 3 } post { taken(X) } } }
        }
        main module [exit=always] { program { if bel(n(X)) then take(X) + print(X). } }"""
    assert {printed(text, seed=seed)[0] for seed in range(6)} == {"4"}


def test_forall_and_listall_do_not_draw() -> None:
    a = agent("""
        init module { beliefs { n(1). n(2). n(3). } }
        main module [exit=always] { program [order=linearall] {
            forall bel(n(X)) do print(X).
            listall L <- bel(n(X)) do print(L).
        } }""", seed=4)
    draws = []
    original = a.random.shuffle
    a.random.shuffle = lambda order: (draws.append(len(order)), original(order))  # type: ignore
    a.step()
    assert a.output.getvalue().split() == ["1", "2", "3", "[1,2,3]"]
    assert draws == []


@pytest.mark.parametrize("name", ["told", "index(3)", "flush", "append(x)"])
def test_beliefs_named_like_swi_builtins_are_the_agents_own(name: str) -> None:
    """told/0 and append/1 are system predicates (Edinburgh I/O), index/1 and flush/0
    deprecated library ones: believed, inserted, deleted and queried as the agent's own."""
    base = name.split("(")[0]
    args = name[len(base):]
    lines = printed(f"""
        main module {{ program [order=linearall] {{
            if not(bel({name})) then print(absent).
            if bel(not(seen)) then insert({name}) + insert(seen).
            if bel({name}) then print(present) + delete({name}) + insert(gone).
            if bel(gone), not(bel({base}{args})) then print(deleted) + exit-module.
        }} }}""", cycles=3)
    assert lines[:3] == ["absent", "present", "deleted"]
    assert not any("found" in line for line in lines)


def test_a_belief_file_may_define_what_swi_has_as_a_builtin() -> None:
    a = agent("""
        init module { beliefs { told. index(1). index(2). } }
        main module [exit=always] { program {
            if bel(told, findall(I, index(I), Is)) then print(Is).
        } }""")
    a.step()
    assert a.output.getvalue() == "[1,2]\n"
    assert a.query("bel", "index(X)") == [{"X": 1}, {"X": 2}]


@pytest.mark.parametrize("program, where", [
    ("init module { beliefs { atom(x). } }", (1, 25)),
    ("main module { program { if true then insert(ok, atom(x)). } }", (1, 45)),
])
def test_an_iso_builtin_cannot_be_a_belief(program: str, where: tuple[int, int]) -> None:
    with pytest.raises(AgentError, match="atom/1 is a built-in predicate of ISO Prolog") as err:
        agent(program)
    assert str(err.value).startswith(f"semantics.goal:{where[0]}:{where[1]}")


def test_calling_a_deprecated_builtin_gives_a_located_warning_not_a_bare_one(
        capfd: pytest.CaptureFixture[str]) -> None:
    warnings: list[str] = []
    a = agent("""main module [exit=always] { program {
        if bel(index(X)) then print(called).
    } }""", warn=warnings.append)
    a.step()
    assert len(warnings) == 1 and "semantics.goal:2:9" in warnings[0]
    assert "SWI-Prolog warning: Deprecated declaration" in warnings[0]
    assert "Deprecated" not in capfd.readouterr().err


def test_a_warning_after_a_module_call_belongs_to_the_calling_rule() -> None:
    """The called module's rules run in a query of their own; when it returns, the rule that
    called it is again the one a warning names (rules.pl: the call's frame restores it)."""
    warnings: list[str] = []
    a = agent("""init module { actionspec { act { pre { index(_) ; true } post { true } } } }
    main module [exit=always] { program {
        if true then sub + act.
    } }
    module sub { program {
        if true then print(inner).
    } }""", warn=warnings.append)
    a.step()
    assert len(warnings) == 1 and "semantics.goal:3:9" in warnings[0], warnings


def test_an_agent_without_the_belief_still_sees_its_absence() -> None:
    a = agent("""
        init module { knowledge { :- dynamic told/0. } }
        main module [exit=always] { program { if not(bel(told)) then print(untold). } }""")
    a.step()
    assert a.output.getvalue() == "untold\n"
    assert Atom("told") not in a.beliefs()

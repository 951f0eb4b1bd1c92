"""Agents' minds are private and the runtime is not theirs to change, sandbox or not; under
--sandbox their Prolog may call only safe built-ins (issue 14 items 2 and 3, issue 19 item 6).
Each attack is refused where the program is loaded (a located error) or, for goals built
while it runs, where it runs (a warning; the rule is not applicable) -- or is harmless."""

from __future__ import annotations

import io
import re
import subprocess
import sys
from pathlib import Path

import pytest

from goalagent.agent import Agent, AgentError
from goalagent.kb.engine import get_engine
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Atom, Struct
from goalagent.mas import MultiAgentSystem
from goalagent.parser import parse_agent
from tests.attack_agent import RUNTIME_MODULES, load_agent


def _untouched() -> None:
    """Nothing the attacks tried exists in the runtime's modules."""
    engine = get_engine()
    for module in RUNTIME_MODULES:
        for name in ("foo", "owned", "evil"):
            for arity in (0, 1):
                head = Atom(name) if arity == 0 else Struct(name, (Atom("x"),))
                found = engine.call("current_predicate", Atom(name),
                                    Struct(":", (Atom(module), head)), module="system")
                assert found is None, f"{module}:{name}/{arity} was created"


# Written in the program: refused when it is loaded, sandbox or not.
STATIC = [
    ("", "if bel(current_module(M)) then print(M).", "current_module/1 would reveal"),
    ("", "if bel(module_property(ga_kb, P)) then print(P).", "module_property/2 would reveal"),
    ("", "if bel(current_atom(A)) then print(A).", "current_atom/1 would reveal"),
    ("", "if bel(ga_kb:assertz(foo)) then print(x).", "qualified with a module"),
    ("", "if bel(assertz(ga_rules:foo)) then print(x).", "qualified with a module"),
    ("", "if bel(retract(ga_kb:error_message(_, _))) then print(x).", "qualified with a module"),
    ("", "if bel(@(foo, user)) then print(x).", "@/2 would reveal"),
    ("", "if bel(user:foo) then print(x).", "qualified with a module"),
    ("", "if bel(findall(X, user:p(X), L)) then print(L).", "qualified with a module"),
    ("", "if bel(maplist(ga_kb:assertz, [foo])) then print(x).", "qualified with a module"),
    ("", "if bel('$destroy_module'(ga_kb)) then print(x).", "reserved for SWI-Prolog"),
    ("", "if bel(nb_current(K, V)) then print(K).", "key only known at run time"),
    ("", "if bel(nb_getval('$ga_listen', V)) then print(V).", "reserved for the runtime"),
    ("", "if bel(format(\"~@\", [assertz(ga_kb:foo)])) then print(x).", "~@ calls a goal"),
    ("evil :- ga_kb:assertz(foo).", "", "qualified with a module"),
    (":- dynamic(ga_kb:foo/1).", "", "qualified with a module"),
    (":- initialization(assertz(user:foo)).", "", "qualified with a module"),
    ("'$ga_gm'(evil).", "", "reserved for the runtime"),
    # module-sensitive built-ins without a meta declaration, code loading, the process
    ("", "if bel(abolish(ga_kb:run/3)) then print(x).", "names the module ga_kb"),
    ("", "if bel(clause(ga_kb:run(_, _, _), B)) then print(B).", "qualified with a module"),
    ("", "if bel(apply(assertz, [ga_kb:foo])) then print(x).", "qualified with a module"),
    ("", "if bel(foldl([X, A, A]>>ga_kb:assertz(X), [foo], 0, _)) then print(x).",
     "qualified with a module"),
    ("", "if bel(consult('/etc/passwd')) then print(x).", "whole process"),
    ("", "if bel(use_module('/tmp/evil.pl')) then print(x).", "loads code"),
    ("", "if bel(set_prolog_flag(unknown, fail)) then print(x).", "whole process"),
    ("", "if bel(halt) then print(x).", "whole process"),
    ("", "if bel(thread_create(true, _, [])) then print(x).", "whole process"),
]


@pytest.mark.parametrize("sandbox", [False, True])
@pytest.mark.parametrize("knowledge, rules, says", STATIC)
def test_reaching_other_modules_is_refused_when_loading(knowledge: str, rules: str, says: str,
                                                         sandbox: bool):
    with pytest.raises(AgentError) as caught:
        load_agent(knowledge, rules or "if true then print(ok).", sandbox=sandbox).close()
    message = str(caught.value)
    assert re.match(r"attack\.goal:\d+:\d+: ", message), message
    assert says in message or (sandbox and "not allowed in the sandbox" in message), message
    _untouched()


# Built while the program runs: refused when it runs (the rule is not applicable).
DYNAMIC = [
    "G =.. [assertz, ga_kb:foo(x)], call(G)",
    "atom_to_term('ga_rules:assertz(foo)', T, _), call(T)",
    "T = user:foo, findall(x, T, _)",
    "C = (ga_kb:owned :- true), assertz(C)",
    "M = ga_kb, G = M:assertz(evil), once(G)",
    "P = assertz, call(P, user:foo)",
    "atom_to_term('current_module(M)', T, _), call(T)",
    "atom_to_term('nb_current(K, _)', T, _), call(T)",
    "atom_concat('$destroy_', 'module', N), G =.. [N, ga_kb], call(G)",
    "G = format(\"~@\", [assertz(user:foo)]), call(G)",
    "forall(member(G, [assertz(ga_kb:foo)]), G)",
    "foldl([X, A, A]>>assertz(X), [ga_kb:foo], 0, _)",
    "maplist([C]>>assertz(C), [ga_kb:foo])",
    "forall(member(C, [ga_kb:foo]), assertz(C))",
    "X = ga_kb:run(_, _, _), abolish(X)",
    "G = apply(assertz, [ga_kb:foo]), call(G)",
    "G = halt, call(G)",
    # issue 24: grammar bodies, and goals bound by a goal before them in what is checked
    "B = {ga_kb:assertz(owned)}, phrase(B, [])",
    "phrase(({X = ga_kb:owned}, {assertz(X)}), [])",
    "G = assertz(ga_kb:owned), phrase({G}, [])",
    "B = ({G = halt}, {G}), phrase(B, [])",
    "G = (X = ga_kb:owned, assertz(X)), call(G)",
    "findall(y, (X = ga_kb:owned, assertz(X)), _)",
]


@pytest.mark.parametrize("sandbox", [False, True])
@pytest.mark.parametrize("query", DYNAMIC)
def test_goals_built_at_run_time_are_checked_when_they_run(query: str, sandbox: bool):
    warnings: list[str] = []
    agent = load_agent(rules=f"if bel({query}) then print(never).\nif true then print(after).",
                  sandbox=sandbox, warnings=warnings)
    try:
        report = agent.step()
    finally:
        agent.close()
    assert [fired.pos.line for fired in report.fired] == [4]
    assert len(warnings) == 1 and "refused: " in warnings[0], warnings
    assert "attack.goal:3:1" in warnings[0]
    _untouched()


def test_another_agents_beliefs_cannot_be_read_or_written():
    secret = "init module { beliefs { secret(42). } }\nmain module { program { " \
             "if true then print(x). } }"
    spy = """
    main module [exit=always] { program {
        if bel(atom_concat('$ga_', dir, P), Q =.. [P, D], call(Q), G =.. [:, D, agent(A)],
               call(G)) then insert(saw(A)).
        if bel(atom_concat(ga_b_, _, M), G =.. [:, M, secret(S)], call(G)) then insert(saw(S)).
        if bel(agent(A), A \\= spy, G = secret(S), call(G)) then insert(saw(S)).
        if bel(me(Me), atom(Me)) then insert(me_is(Me)).
    } }
    """
    warnings: list[str] = []
    mas = MultiAgentSystem(output=io.StringIO(), warn=warnings.append)
    victim = mas.launch("victim", parse_agent(secret, "victim.goal"))
    spy_agent = mas.launch("spy", parse_agent(spy, "spy.goal"))
    try:
        mas.run(max_cycles=1)
        assert not spy_agent.query("bel", "saw(X)")
        assert spy_agent.query("bel", "me_is(X)") == [{"X": "spy"}]  # its own name, only
        assert victim.query("bel", "secret(X)") == [{"X": 42}]
        names = [victim.ms.belief_module, spy_agent.ms.belief_module]
    finally:
        mas.close()
    assert sum("refused: " in warning for warning in warnings) >= 1
    assert all(re.fullmatch(r"ga_b_[0-9a-f]{16}", str(name)) for name in names)
    assert names[0] != names[1]


# ------------------------------------------------------------------ the sandbox

SANDBOX_STATIC = [
    ("evil :- shell('touch PWNED').", "", "shell"),
    ("evil :- open('out.txt', write, S), close(S).", "", "open"),
    ("evil :- halt.", "", "halt"),
    ("evil :- consult('other.pl').", "", "whole process"),
    ("evil :- set_prolog_flag(stack_limit, 1000).", "", "set_prolog_flag/2 would end"),
    ("evil :- thread_create(true, _, []).", "", "thread_create"),
    (":- initialization(shell(ls)).", "", "not allowed in the sandbox"),
    (":- use_module('/tmp/other.pl').", "", "not allowed in the sandbox"),
    ("", "if bel(shell('touch PWNED')) then print(x).", "shell"),
    ("", "if bel(tmp_file(x, F), open(F, write, S)) then print(S).", "not allowed"),
    ("", "if bel(maplist(shell, ['touch PWNED'])) then print(x).", "shell"),
]


@pytest.mark.parametrize("knowledge, rules, says", SANDBOX_STATIC)
def test_the_sandbox_refuses_unsafe_calls_when_loading(knowledge: str, rules: str, says: str,
                                                        tmp_path: Path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(AgentError) as caught:
        load_agent(knowledge, rules or "if true then print(ok).", sandbox=True).close()
    assert re.match(r"attack\.goal:\d+:\d+: ", str(caught.value))
    assert says in str(caught.value) and "refused" in str(caught.value)
    assert not (tmp_path / "PWNED").exists()


@pytest.mark.parametrize("query", [
    "G = shell('touch PWNED'), call(G)",
    "atom_to_term('halt', T, _), call(T)",
    "X = open('out.txt', write, _), call(X)",
    "C = (q :- shell('touch PWNED')), assertz(C), q",
    "S = shell, maplist(S, ['touch PWNED'])",
])
def test_the_sandbox_refuses_unsafe_goals_built_at_run_time(query: str, tmp_path: Path,
                                                             monkeypatch):
    monkeypatch.chdir(tmp_path)
    warnings: list[str] = []
    agent = load_agent(rules=f"if bel({query}) then print(never).\nif true then print(after).",
                  sandbox=True, warnings=warnings)
    try:
        agent.step()
    finally:
        agent.close()
    assert len(warnings) == 1 and "refused: " in warnings[0], warnings
    assert not (tmp_path / "PWNED").exists() and not (tmp_path / "out.txt").exists()


def test_the_sandbox_leaves_ordinary_prolog_alone():
    knowledge = """
        tower([X]) :- on(X, table).
        tower([X, Y | T]) :- on(X, Y), tower([Y | T]).
        clear(X) :- \\+ on(_, X).
        total(L, S) :- foldl([X, A0, A]>>(A is A0 + X), L, 0, S).
        :- dynamic(on/2).
        :- use_module(library(lists)).
    """
    rules = ("if bel(findall(N, between(1, 4, N), L), total(L, S), sum_list(L, S2),"
             " format(atom(A), '~w-~w', [S, S2]), msort([b, a], M), "
             "aggregate_all(count, member(_, M), C), C > 1) then print(A).")
    output = io.StringIO()
    agent = Agent(parse_agent(f"init module {{ knowledge {{ {knowledge} }} }}\n"
                              f"main module [exit=always] {{ program {{ {rules} }} }}", "ok.goal"),
                  limits=Limits(sandbox=True), output=output, warn=lambda message: None)
    try:
        agent.step()
    finally:
        agent.close()
    assert output.getvalue() == "10-10\n"


def test_goals_that_name_built_ins_are_data_never_run(tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    agent = load_agent(rules="if true then adopt(shell('touch PWNED')).\nif true then print(x).")
    try:
        agent.step()
        goals = agent.goals()
    finally:
        agent.close()
    assert goals == [[Struct("shell", (Atom("touch PWNED"),))]]  # the agent's own predicate
    assert not (tmp_path / "PWNED").exists()


def test_check_sandbox_reports_without_running(tmp_path: Path):
    program = tmp_path / "evil.goal"
    program.write_text("init module { knowledge { evil :- shell('touch PWNED'). } }\n"
                       "main module { program { if bel(evil) then print(x). } }\n")
    fine = Path(__file__).resolve().parents[3] / "agents" / "examples" / "hello_world.goal"
    result = subprocess.run([sys.executable, "-m", "goalagent", "check", "--sandbox",
                             str(program), str(fine)], capture_output=True, text=True,
                            timeout=120, cwd=tmp_path)
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert lines[0].startswith(f"{program}:1:27: ") and "not allowed in the sandbox" in lines[0]
    assert lines[1] == f"{fine}: ok"
    assert not (tmp_path / "PWNED").exists()


def test_only_a_sandboxed_agent_loads_library_sandbox() -> None:
    """library(sandbox) loads library(apply_macros), whose goal expansion changes how every
    file compiled afterwards runs (bench/cycles.py's floor among them): a process running
    agents without the sandbox must not load it; the first sandboxed agent does."""
    code = """
from goalagent.agent import Agent
from goalagent.kb.engine import get_engine
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Atom
def loaded(module):
    return get_engine().call("current_module", Atom(module), module="system") is not None
Agent.from_string("main module { program { if true then print(ok). } }", "plain.goal").step()
print("macros", loaded("apply_macros"))
Agent.from_string("main module { program { if true then print(ok). } }", "boxed.goal",
                  limits=Limits(sandbox=True)).step()
print("macros", loaded("apply_macros"))
"""
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            timeout=120, check=False)
    assert result.returncode == 0, result.stderr
    answers = [line.split()[1] for line in result.stdout.splitlines() if line.startswith("macros")]
    assert answers == ["False", "True"], result.stdout

"""Attack programs from the red team of 2026-11-23 evening (issue 14): each hole they found,
as the smallest program that showed it. Runaway programs run in a child process with a
timeout (one regression would otherwise hang the suite: SWI-Prolog cannot interrupt a
cleanup handler while an exception unwinds): the module's runs one after the other in one
child, each measured alone (``runs``).

Issue 24's failures (its "Why", items 1-9) and where each is tested (tests/attacks/ unless
said):
1. the inspector: tests/goalagent/inspector/test_inspector_gate.py (Host, Origin, token;
   binary, deep, long and malformed messages; 20,000 breakpoints; many pages flooding;
   queries confined and always sandboxed) and test_inspector.py there (a page of another
   origin in Chromium, DNS rebinding);
2. phrase/2,3, call_dcg/3 and {}: here (grammar bodies) and
   tests/goalagent/kb/test_confinement.py;
3. check and test running agent code: tests/goalagent/test_check_and_test_confined.py;
4. memory outside Prolog's stacks: test_attacks_limits.py (memory);
5. limits that ran over (~d of 100,000,000 digits, sig_atomic, prolog_alert_signal, tab,
   runaway initial goals and goal checks, a sleeping test condition): test_attacks_limits.py,
   here (process-wide built-ins) and test_check_and_test_confined.py;
6. process-wide built-ins without the sandbox, shared global variables and flags: here;
7. one agent's deep fact stopping every save: test_attacks_limits.py (saves);
8. can files and the object database: test_attacks_io.py;
9. the smaller items (2 MB one-line program, agentfiles with ..\\.., --port 70000, --trace-file
   /dev/full, SIGHUP, SIGTERM while starting, a save path that is a link):
   test_attacks_cli.py.
"""

from __future__ import annotations

import io
import subprocess
import sys
from pathlib import Path

import pytest

from goalagent.agent import Agent, AgentError
from goalagent.kb.engine import KBError, get_engine
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Atom, Struct, Var
from goalagent.mas import MultiAgentSystem
from goalagent.parser import parse_agent
from goalagent.parser.errors import GoalSyntaxError
from tests.attack_agent import RUNTIME_MODULES, load_agent
from tests.attacks.beside_counter import beside_counter, counter_finished
from tests.measured import Measured, goalagent_measured_each

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)


def _attacker(knowledge: str, rule: str, after: str = "after") -> str:
    """An agent knowing spin/1 and ``knowledge`` that tries ``rule``, then prints ``after``."""
    return (f"init module {{ knowledge {{ spin(N) :- N1 is N + 1, spin(N1). {knowledge} }} }}\n"
            f"main module [exit=always] {{ program {{\n{rule}\n"
            f"if true then print({after}). }} }}\n")


RUNAWAY_LIMITS = ("--max-inferences", "200000", "--max-query-seconds", "0.5")
"""Small limits, so that each runaway meets one soon."""


RUNAWAYS = [
    # a catch-all whose recovery runs the runaway again: each limit (and abort) was caught
    ("st :- catch(spin(0), _, st).", "if bel(st) then print(never)."),
    ("st :- catch_with_backtrace(sleep(100), _, st).", "if bel(st) then print(never)."),
    # a runaway cleanup: SWI runs it with signals held back while the limit's exception
    # unwinds the goal -- not even SIGTERM ended the process
    ("", "if bel(setup_call_cleanup(true, spin(0), spin(0))) then print(never)."),
    ("", "if bel(call_cleanup(spin(0), spin(0))) then print(never)."),
    ("", "if bel(setup_call_catcher_cleanup(true, throw(x), _, spin(0))) then print(never)."),
    # SWI runs every cleanup handler with signals held back, after an exit or failure too
    ("", "if bel(setup_call_cleanup(true, true, (repeat, sleep(0.1), fail))) then print(never)."),
    ("st :- catch(sleep(100), _, true), st.",
     "if bel(setup_call_cleanup(true, fail, st)) then print(never)."),
    ("", "if bel(call_cleanup(spin(0), _, spin(0))) then print(never)."),  # call_cleanup/3
]


THROWN = [
    "if bel(throw('$aborted')) then print(x).",         # was Ctrl-C for the whole run
    "if bel(B = '$aborted', throw(B)) then print(x).",
    "if bel(X = ga_limit(time(1)), throw(X)) then print(x).",
]
"""Rules throwing the runtime's own exceptions."""


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Measured]:
    """The module's runs, one after the other in one child with a timeout (a regression of
    any of them fails these, never the suite), each measured alone, by name: ``runaways``,
    one run of agent atkI for each case I of RUNAWAYS (printing afterI when its rule has
    ended) and of agent cyclic, which sends a cyclic list, beside the counter; ``thrownI``,
    a run of agent atk trying rule I of THROWN beside the counter (a run each: one refused
    when loading refuses its whole run)."""
    programs = {f"atk{index}": _attacker(knowledge, rule, f"after{index}")
                for index, (knowledge, rule) in enumerate(RUNAWAYS)}
    programs["cyclic"] = _attacker("", "if bel(X = [a|X]) then counter.send(X).")
    commands = {"runaways": beside_counter(tmp_path_factory.mktemp("runaways"), programs,
                                           *RUNAWAY_LIMITS)}
    for index, rule in enumerate(THROWN):
        commands[f"thrown{index}"] = beside_counter(tmp_path_factory.mktemp("thrown"),
                                                    {"atk": _attacker("", rule)},
                                                    *RUNAWAY_LIMITS)
    results = goalagent_measured_each(*commands.values(), timeout=120)
    return dict(zip(commands, results, strict=True))


@pytest.fixture(scope="module")
def runaways(runs: dict[str, Measured]) -> Measured:
    return runs["runaways"]


def _ended_with_its_rule(result: Measured, index: int) -> None:
    """Agent atkI's rule (line 3) was ended as not applicable, and the agent went on; the
    counter finished."""
    counter_finished(result)
    assert any(f"atk{index}.goal:3:1:" in line and "the rule is not applicable" in line
               for line in result.stderr.splitlines()), result.stderr


@pytest.mark.parametrize("knowledge, rule", RUNAWAYS[:-1])
def test_runaway_recovery_or_cleanup_ends_with_its_rule(runaways: Measured,
                                                       knowledge: str, rule: str):
    index = RUNAWAYS.index((knowledge, rule))
    _ended_with_its_rule(runaways, index)
    assert f"after{index}" in runaways.stdout.split()


def test_cleanup_still_runs_when_its_goal_ends_without_an_exception():
    agent = load_agent("", "if bel(setup_call_cleanup(true, X = 1, assertz(done(X))), "
                      "call_cleanup(true, assertz(done(c)))) then print(X).")
    try:
        agent.step()
        assert agent.query("bel", "done(X)") == [{"X": 1}, {"X": Atom("c")}]
    finally:
        agent.close()


def _untouched() -> None:
    engine = get_engine()
    for module in RUNTIME_MODULES:
        found = engine.call("current_predicate", Atom("owned"),
                            Struct(":", (Atom(module), Atom("owned"))), module="system")
        assert found is None, f"{module}:owned/0 was created"


HIDDEN = "ga_kb:assertz(owned)"
# Each ran a goal that confine.pl never saw (a module-qualified one, here) -- the sandbox
# included for the first two.
WRITTEN = [
    f"if bel(put_attr(X, freeze, {HIDDEN}), X = 1) then print(x).",
    f"if bel(print_message(error, format(\"~@\", [{HIDDEN}]))) then print(x).",
    f"if bel(put_attrs(X, att(freeze, {HIDDEN}, [])), X = 1) then print(x).",
    f"if bel(print_message_lines(user_error, '', ['~@'-[{HIDDEN}]])) then print(x).",
    "if bel(write_term(call(x), [portray_goal(call_cleanup)])) then print(x).",
    "if bel(format(\"~W\", [x, [portray_goal(call_cleanup)]])) then print(x).",
    ":- use_module(library('../../../../../../tmp/evil')).",
    ":- [library(lists), '/tmp/evil'].",
    "if bel(prolog_listen(erase, spy)) then print(x).",
    "if bel(on_signal(int, _, ignore)) then print(x).",
    "if bel(format_predicate(w, spy(_, _))) then print(x).",
    ":- at_halt(spy).",
    ":- expects_dialect(sicstus).",  # the process's dialect flag, global operators (#, mode)
    "if bel(abolish('$ga_limits'/2)) then print(x).",  # the agent's limits, the runtime's
    f"if bel(open_string(\":- initialization({HIDDEN}).\", S), load_files(library(x), "
    "[stream(S)])) then print(x).",
]
# Only known when they run: refused there (the rule is not applicable).
BUILT = [
    f"if bel(F = [0'~, 0'@], print_message_lines(user_error, '', [F-[{HIDDEN}]])) then print(x).",
    "if bel(O = portray_goal(call_cleanup), write_term(x, [O])) then print(x).",
]


@pytest.mark.parametrize("sandbox", [False, True])
@pytest.mark.parametrize("text", WRITTEN)
def test_goals_hidden_from_the_check_are_refused_when_loading(text: str, sandbox: bool):
    knowledge, rules = (text, "if true then print(x).") if text.startswith(":-") else ("", text)
    with pytest.raises(AgentError, match="refused"):
        load_agent("spy(_) :- true. spy(_, _) :- true. " + knowledge, rules,
              sandbox=sandbox).close()
    _untouched()


@pytest.mark.parametrize("sandbox", [False, True])
@pytest.mark.parametrize("rules", BUILT)
def test_goals_hidden_from_the_check_are_refused_when_they_run(rules: str, sandbox: bool):
    warnings: list[str] = []
    try:
        agent = load_agent("", rules, sandbox=sandbox, warnings=warnings)
    except AgentError as error:  # the sandbox refuses some of them outright
        assert sandbox and "refused" in str(error)
    else:
        try:
            agent.step()
        finally:
            agent.close()
        assert len(warnings) == 1 and "the rule is not applicable" in warnings[0], warnings
    _untouched()


def test_the_sandbox_loads_only_libraries_that_change_nothing_else():
    # library(clpfd) loads library(apply_macros), whose goal expansion changes how every
    # later file of the process compiles
    with pytest.raises(AgentError, match="agents load only these libraries"):
        load_agent(":- use_module(library(clpfd)).", sandbox=True).close()
    load_agent(":- use_module(library(assoc)).", sandbox=True).close()


@pytest.mark.parametrize("directive", [":- spin(0).", ":- initialization(spin(0))."])
def test_a_runaway_directive_is_a_located_error_when_loading(directive: str):
    text = (f"init module {{ knowledge {{ spin(N) :- N1 is N + 1, spin(N1). {directive} }} }}\n"
            "main module { program { if true then print(x). } }\n")
    with pytest.raises(AgentError, match=r"runaway.goal:1:\d+: knowledge clause .*more than "
                                         r"200,000 inferences"):
        Agent(parse_agent(text, "runaway.goal"), limits=Limits(max_inferences=200_000),
              output=io.StringIO(), warn=lambda message: None)


@pytest.mark.parametrize("thrown, says", [
    ("length(L, 1000000), maplist(=(0'a), L), atom_codes(A, L), throw(A)",
     "... (1,000,0"),  # not 1 MB of a
    ("X = [a|X], throw(X)", "an error whose term is cyclic"),  # walked for ever before
])
def test_an_error_carrying_a_huge_or_cyclic_term_is_a_short_warning(thrown: str, says: str):
    warnings: list[str] = []
    agent = load_agent("", f"if bel({thrown}) then print(x).", warnings=warnings)
    try:
        agent.step()
    finally:
        agent.close()
    assert len(warnings) == 1 and says in warnings[0] and len(warnings[0]) < 1300, warnings


def test_sending_a_cyclic_list_stops_that_agent_not_the_process(
        runaways: Measured):
    # converting it for Python never ended (a cyclic list has no end), past every limit
    counter_finished(runaways)
    assert "error: agent cyclic failed: cannot pass a cyclic term" in runaways.stderr


def test_files_that_import_each_other_are_a_located_error(tmp_path: Path):
    # read until Python's recursion limit before: lark's 'maximum recursion depth exceeded'
    (tmp_path / "b.mod2g").write_text('#import "c.mod2g".\nmodule m { program { if true then '
                                      'print(x). } }\n')
    (tmp_path / "c.mod2g").write_text('#import "b.mod2g".\nmodule n { program { if true then '
                                      'print(x). } }\n')
    text = '#import "b.mod2g".\nmain module { program { if true then print(x). } }\n'
    with pytest.raises(GoalSyntaxError, match=r"c.mod2g:1:9: #import b.mod2g: the files import "
                                              r"each other \(b.mod2g -> c.mod2g -> b.mod2g\)"):
        parse_agent(text, str(tmp_path / "a.goal"))


@pytest.mark.parametrize("rule", THROWN)
def test_an_agent_cannot_throw_the_runtime_s_exceptions(runs: dict[str, Measured], rule: str):
    result = runs[f"thrown{THROWN.index(rule)}"]
    assert result.returncode in (0, 2), result.stderr  # 2: refused when loading
    assert "this exception is the runtime's" in result.stderr
    assert "interrupted" not in result.stderr


def test_a_query_whose_answer_is_a_cyclic_list_is_an_error():
    # the API's and the inspector's queries: Python read the list for ever
    agent = load_agent()
    try:
        with pytest.raises(KBError, match="an answer is a cyclic term"):
            agent.query("bel", "X = [a|X]")
        assert agent.query("bel", "X = [a]") == [{"X": [Atom("a")]}]
    finally:
        agent.close()


@pytest.mark.parametrize("sandbox", [False, True])
def test_format_counts_too_large_to_interrupt_are_refused(sandbox: bool):
    # format('~*c', [1000000000, 0'x]) wrote 1 GB to stdout, 30 s past a 3 s time limit:
    # SWI-Prolog's writer does not look at signals
    with pytest.raises(AgentError, match="repeats or pads 1,000,000,000 characters"):
        load_agent("", "if bel(format('~*c', [1000000000, 0'x])) then print(x).",
              sandbox=sandbox).close()
    warnings: list[str] = []
    agent = load_agent("", "if bel(N is 10 ** 9, format(atom(_), '~*c', [N, 0'x])) then print(x).\n"
                      "if bel(format(atom(A), '~*c~w~t~8|~2f', [2, 0'x, y, 3.14159])) then "
                      "print(A).", sandbox=sandbox, warnings=warnings)
    try:
        agent.step()
    finally:
        agent.close()
    assert len(warnings) == 1 and "repeats or pads 1,000,000,000" in warnings[0], warnings


# Issue 24: grammar bodies ran unchecked -- phrase({shell(..)}, []) passed check --sandbox and
# ran under run --sandbox; phrase({halt}, []) ended the run; phrase({ga_kb:assertz(..)}, [])
# wrote into the runtime. Now a body is checked as the goal SWI-Prolog translates it to (those
# built while the agent runs are in tests/goalagent/kb/test_confinement.py's DYNAMIC).
GRAMMAR_WRITTEN = [
    f"if bel(phrase({{{HIDDEN}}}, [])) then print(x).",
    f"if bel(phrase(([a], {{{HIDDEN}}}), [a])) then print(x).",
    f"if bel(call_dcg({{{HIDDEN}}}, [], _)) then print(x).",
    f"if bel(phrase(({{true}} ; {{{HIDDEN}}}), [], _)) then print(x).",
    "if bel(phrase({halt}, [])) then print(x).",
    "if bel(phrase({set_prolog_flag(unknown, fail)}, [])) then print(x).",
]


@pytest.mark.parametrize("sandbox", [False, True])
@pytest.mark.parametrize("rules", GRAMMAR_WRITTEN)
def test_grammar_bodies_are_checked_when_loading(rules: str, sandbox: bool):
    with pytest.raises(AgentError, match=r"attack\.goal:3:\d+: .*refused: "):
        load_agent("", rules, sandbox=sandbox).close()
    _untouched()


def test_grammars_still_parse(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    knowledge = ("greeting --> [hello], name. name --> [world]. name --> [prolog]. "
                 "digits([D|T]) --> [D], { code_type(D, digit) }, !, digits(T). digits([]) --> [].")
    rules = ("if bel(phrase(greeting, [hello, prolog]), phrase(digits(Ds), `12a`, Rest), "
             "atom_codes(A, Ds), atom_codes(R, Rest), B = ([x], {true}), phrase(B, [x]), "
             "phrase({shell('touch made')}, [])) then print(A-R).")
    output = io.StringIO()
    agent = Agent(parse_agent(f"init module {{ knowledge {{ {knowledge} }} }}\n"
                              f"main module [exit=always] {{ program {{ {rules} }} }}", "g.goal"),
                  output=output, warn=lambda message: None)
    try:
        agent.step()
    finally:
        agent.close()
    assert output.getvalue() == "'12'-a\n"
    assert (tmp_path / "made").exists()  # without the sandbox an agent may use the shell


# Issue 24: process-wide built-ins that were open without the sandbox.
@pytest.mark.parametrize("sandbox", [False, True])
@pytest.mark.parametrize("rules, says", [
    ("if bel(working_directory(_, '/tmp')) then print(x).", "whole process"),
    ("if bel(unload_file(library(lists))) then print(x).", "whole process"),
    ("if bel(prolog_alert_signal(_, 0)) then print(x).", "whole process"),
    ("if bel(sig_atomic(sleep(40))) then print(x).", "whole process"),
    ("if bel(sig_block(_)) then print(x).", "whole process"),
    ("if bel(dynamic([foo/1, user:owned/0])) then print(x).", "qualified with a module"),
    ("if bel(dynamic((foo/1, ga_kb:owned/0))) then print(x).", "qualified with a module"),
    ("if bel(dynamic(['$ga_limits'/2])) then print(x).", "reserved"),
    ("if bel(op(700, xfx, [user:(===)])) then print(x).", "qualified with a module"),
    ("if bel(set_output(user_error)) then print(x).", "whole process"),
    ("if bel(setenv('MUJOCO_GL', glx)) then print(x).", "whole process"),
    ("if bel(set_random(seed(1))) then print(x).", "whole process"),
    ("if bel(engine_create(x, true, _)) then print(x).", "whole process"),
    ("if bel(thread_send_message(main, x)) then print(x).", "whole process"),
    ("if bel(import_module(M, _)) then print(M).", "would reveal"),
    ("if bel(abolish_all_tables) then print(x).", "whole process"),
    ("if bel(require([append/3])) then print(x).", "whole process"),
    ("if bel(trace) then print(x).", "whole process"),
])
def test_process_wide_built_ins_are_refused(rules: str, says: str, sandbox: bool):
    with pytest.raises(AgentError) as caught:
        load_agent("", rules, sandbox=sandbox).close()
    assert says in str(caught.value) or (sandbox and "not allowed in the sandbox"
                                         in str(caught.value)), str(caught.value)
    _untouched()


def test_a_runaway_call_cleanup_3_handler_ends_with_its_rule(
        runaways: Measured):
    _ended_with_its_rule(runaways, len(RUNAWAYS) - 1)


def test_global_variables_flags_and_records_are_each_agent_s_own():
    # agents read each other's global variables and flags (nb_getval, flag/3): a channel;
    # library(gensym) counts in the process's flags, so one agent's gensym/2 and
    # reset_gensym/0 changed the names another made (attack round of 2026-11-26)
    writer = ("main module [exit=always] { program { if bel(nb_setval(k, secret), "
              "flag(f, _, 42), recordz(r(1), secret), set_flag(g, 7), gensym(n, _), "
              "gensym(n, _), gensym(m, _)) then print(x). } }")
    reader = """main module [exit=always] { program [order=linearall] {
        if bel(catch(nb_getval(k, V), _, V = none)) then insert(k(V)).
        if bel(flag(f, F, F), get_flag(g, G)) then insert(f(F, G)).
        if bel(findall(R, recorded(r(2), R), Rs)) then insert(r(Rs)).
        if bel(nb_setval(k, mine), nb_getval(k, M)) then insert(own(M)).
        if bel(gensym(n, N1), gensym(n, N2), reset_gensym(n), gensym(n, N3), gensym(m, M1),
               reset_gensym, gensym(m, M2)) then insert(names([N1, N2, N3, M1, M2])).
    } }"""
    mas = MultiAgentSystem(output=io.StringIO(), warn=lambda message: None)
    try:
        mas.launch("writer", parse_agent(writer, "w.goal"))
        reading = mas.launch("reader", parse_agent(reader, "r.goal"))
        mas.run(max_cycles=1)
        assert reading.query("bel", "k(V), f(F, G), r(R), own(M)") == [
            {"V": Atom("none"), "F": 0, "G": 0, "R": [], "M": Atom("mine")}]
        assert reading.query("bel", "names(Ns)") == [
            {"Ns": [Atom("n1"), Atom("n2"), Atom("n1"), Atom("m1"), Atom("m1")]}]
        writer_again = mas.launch("writer2", parse_agent(
            "main module [exit=always] { program { if bel(gensym(n, N)) then insert(n(N)). "
            "} }", "w2.goal"))
        mas.run(max_cycles=1)
        assert writer_again.query("bel", "n(N)") == [{"N": Atom("n1")}]
    finally:
        mas.close()
    engine = get_engine()  # and freed with their agents
    assert engine.call("nb_current", Atom("k"), None, module="system") is None
    keys = engine.call("findall", Struct("-", (Var("K"), Var("V"))),
                       Struct(",", (Struct("nb_current", (Var("K"), Var("V"))),
                                    Struct("sub_atom", (Var("K"), 0, Var("_"), Var("_"),
                                                        Atom("ga_b_"))))),
                       None, module="system")
    assert keys is not None and [str(k) for k in keys[2] if ":k" in str(k)] == []


def test_an_answer_with_many_variables_converts_in_linear_time():
    # an answer of 10,000 fresh variables took 178 s to convert for Python (each compared
    # with every one seen before): an inspector query or a test condition held the whole
    # run; a child process so that a regression cannot hang the suite
    code = ("from tests.attack_agent import load_agent\n"
            "agent = load_agent()\n"
            "print(len(agent.query('bel', 'length(L, 40000)')[0]['L']))\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            timeout=120, cwd=Path(__file__).resolve().parents[2])
    assert result.stdout.strip() == "40000", result.stderr


@pytest.mark.parametrize("sandbox", [False, True])
def test_a_sandboxed_agent_s_print_cannot_drive_the_terminal(sandbox: bool):
    # attack round of 2026-11-26: print('\e]0;owned\a\e[2J') set the terminal's title and
    # cleared it from a sandboxed agent; without the sandbox print/1 is the program's output
    text = ("main module [exit=always] { program { if true then "
            "print('\\e]0;owned\\a\\e[2Jdone'). } }")
    output = io.StringIO()
    agent = Agent(parse_agent(text, "p.goal"), limits=Limits(sandbox=sandbox), output=output)
    try:
        agent.run(max_cycles=1)
    finally:
        agent.close()
    if sandbox:
        assert output.getvalue() == "\\x1b]0;owned\\x07\\x1b[2Jdone\n"
    else:
        assert output.getvalue() == "\x1b]0;owned\x07\x1b[2Jdone\n"

"""Terms too deep for SWI-Prolog's C recursion (its writer and reader) never take the process
down (issue 14): SWI runs with its C-stack guard (goalagent/kb/clib.py starts it with signal
handling on), so a condition that writes or reads such a term is not applicable, with a
located warning, and the agent and the others go on; the signal handlers Python relies on
stay as they were. Everything runs in a child process: a crash there fails the tests of that
child, naming the command (exit -11), instead of ending the test run. The ``goalagent``
commands run one after the other in one child, each measured alone (``commands``)."""

from __future__ import annotations

import re
import signal
import textwrap
from pathlib import Path

import pytest

from tests.conftest import python
from tests.measured import Measured, goalagent_measured_each

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

KNOWLEDGE = """
init module {
    knowledge {
        nest(0, z).
        nest(N, f(T)) :- N > 0, M is N - 1, nest(M, T).
        text(N, A) :- length(O, N), maplist(=('f('), O), length(C, N), maplist(=(')'), C),
            append([O, [z], C], P), atomic_list_concat(P, A).
    }
}
"""
# (condition, what the rule prints when it fires, or None: SWI's writer/reader runs out of
# C stack and the rule is not applicable). One rule per line, from line 12 of the program.
RULES = [
    ("nest(1000000, T), term_to_atom(T, A)", None),
    ("nest(100000, T), format(atom(A), '~w', [T])", None),
    ("nest(100000, T), with_output_to(string(S), print(T))", None),
    ("text(100000, A), term_to_atom(T, A)", None),
    ("text(100000, A), atom_to_term(A, T, B)", None),
    ("nest(100000, T), copy_term(T, U), T == U, compare(O, T, U), msort([U, T], M)", "same"),
    ("nest(100000, T), T =.. L, ground(T), term_variables(T, V), numbervars(T, 0, E)", "walk"),
    ("nest(100000, T), assertz(held(T)), held(U), U == T", "held"),
    ("X = f(X), term_to_atom(X, A), copy_term(X, Y), X == Y, ground(X), msort([Y, X], M)",
     "cyclic"),
]
FIRST_RULE_LINE = 12
COUNTER = """
init module { beliefs { n(0). } goals { n(5). } }
main module [exit=nogoals] { program {
    if bel(n(N), N < 5, M is N + 1) then delete(n(N)) + insert(n(M)).
} }
"""


def _deep_program() -> str:
    rules = "".join(f"        if bel({condition}) then print({said or 'never'}).\n"
                    for condition, said in RULES)
    program = (KNOWLEDGE + "main module [exit=always] {\n    program [order=linearall] {\n"
               + rules + "        if true then print(after).\n    }\n}\n")
    assert program.splitlines()[FIRST_RULE_LINE - 1].lstrip().startswith(
        f"if bel({RULES[0][0]})")
    return program


def _expected_warnings(path: str) -> list[str]:
    return [f"warning: agent deep: module main, rule at {path}:{FIRST_RULE_LINE + i}:9: "
            for i, (_, said) in enumerate(RULES) if said is None]


def _check_deep_run(stdout: str, stderr: str, path: str) -> None:
    assert stdout.splitlines() == [said for _, said in RULES if said] + ["after"], stderr
    warnings = [line for line in stderr.splitlines() if line.startswith("warning: ")]
    assert len(warnings) == len(_expected_warnings(path)), stderr
    for warning, start in zip(warnings, _expected_warnings(path), strict=True):
        assert warning.startswith(start), warning
        assert re.search(r"(term_to_atom/2|format/3|print/1|atom_to_term/3): C-stack limit "
                         r"\([\d,]+ bytes\) exceeded.*; the rule is not applicable$", warning)


@pytest.fixture(scope="module")
def commands(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Measured]:
    """The module's ``goalagent`` commands, run in one folder one after the other in one
    child, each measured alone, by name: what each did."""
    folder = tmp_path_factory.mktemp("deep")
    (folder / "deep.goal").write_text(_deep_program())
    (folder / "counter.goal").write_text(COUNTER)
    (folder / "two.mas2g").write_text('agentfiles { "deep.goal". "counter.goal". }\n')
    (folder / "text.goal").write_text("init module { beliefs { t(" + "f(" * 100_000 + "z"
                                      + ")" * 100_000 + "). } }\n")
    (folder / "facts.pl").write_text("depth(1000000).\nwidth(100000).\n")
    (folder / "loads.goal").write_text(
        KNOWLEDGE + "main module [exit=always] { program [order=linearall] {\n"
        "    if bel(depth(N), nest(N, T), term_to_atom(T, A)) then print(never).\n"
        "    if bel(width(N), text(N, A), term_to_atom(T, A)) then print(never).\n"
        "    if bel(width(N), nest(N, T), ground(T)) then print(ground).\n"
        "    if true then print(after). } }\n")
    named = {"run two": ["run", "two.mas2g"], "check deep": ["check", "deep.goal"],
             "check text": ["check", "text.goal"], "run text": ["run", "text.goal"],
             "run loads": ["run", "loads.goal", "--load-beliefs", "facts.pl"]}
    results = goalagent_measured_each(*named.values(), cwd=folder)
    return dict(zip(named, results, strict=True))


def test_a_deep_term_in_a_condition_is_a_located_warning_and_the_others_go_on(
        commands: dict[str, Measured]):
    result = commands["run two"]
    assert result.returncode == 0, result.stderr  # it was a segmentation fault (-11)
    _check_deep_run(result.stdout, result.stderr, "deep.goal")
    assert "counter: terminated after 5 cycles" in result.stderr
    assert "Traceback" not in result.stderr


def test_check_takes_the_program_and_refuses_deep_text_located(commands: dict[str, Measured]):
    result, refused = commands["check deep"], [commands["check text"], commands["run text"]]
    assert result.returncode == 0 and "error" not in result.stdout + result.stderr, result
    for result in refused:
        assert result.returncode == 2, result.stderr
        assert result.stderr.strip().removeprefix("error: ") == (
            "text.goal:1:422: brackets nested more than 200 deep")  # the 201st: 26 + 2 * 198


def test_load_beliefs_gives_the_depth_and_the_text_the_run_goes_on(
        commands: dict[str, Measured]):
    result = commands["run loads"]
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["ground", "after"]
    assert [line.split(": Prolog error")[0] for line in result.stderr.splitlines()
            if line.startswith("warning")] == [
        "warning: agent loads: module main, rule at loads.goal:11:5",
        "warning: agent loads: module main, rule at loads.goal:12:5"]


def test_the_guard_holds_for_an_agent_run_in_another_thread(tmp_path: Path):
    (tmp_path / "deep.goal").write_text(_deep_program())
    code = textwrap.dedent("""
        import io, threading
        from goalagent.agent import Agent
        from goalagent.parser import parse_agent
        def run():
            out, warnings = io.StringIO(), []
            agent = Agent(parse_agent(open("deep.goal").read(), "deep.goal"), output=out,
                          warn=warnings.append)
            agent.step()
            agent.close()
            print(out.getvalue(), end="")
            print("\\n".join(warnings))
        thread = threading.Thread(target=run)
        thread.start()
        thread.join()
    """)
    result = python(code, cwd=tmp_path)
    assert result.returncode == 0, result.stderr  # made in a thread: it was a segfault
    said = [said for _, said in RULES if said] + ["after"]
    lines = result.stdout.splitlines()
    assert lines[:len(said)] == said
    _check_deep_run("\n".join(said), "\n".join(lines[len(said):]), "deep.goal")


def test_swi_keeps_only_its_stack_guard_and_thread_alert_of_the_signal_handlers():
    """Every other handler (Python's SIGINT, SIG_IGN for SIGPIPE, the defaults for SIGTERM,
    SIGHUP, SIGALRM, SIGCHLD, ...) is what it was before SWI started: Ctrl-C and SIGTERM
    work as tests/goalagent/kb/test_limits.py and test_saving.py check."""
    code = textwrap.dedent("""
        import ctypes, signal
        libc = ctypes.CDLL(None)
        def handlers():
            found = {}
            for signum in range(1, signal.NSIG):
                action = ctypes.create_string_buffer(512)
                if libc.sigaction(signum, None, action) == 0:
                    found[signum] = action.raw[:ctypes.sizeof(ctypes.c_void_p)]
            return found
        before = handlers()
        from goalagent.kb.engine import get_engine
        from goalagent.kb.terms import Atom
        engine = get_engine()
        after = handlers()
        print(sorted(signum for signum in before if after[signum] != before[signum]))
        for flag in ("signals", "gc_thread"):
            print(engine.call("current_prolog_flag", Atom(flag), None, module="system")[1])
    """)
    result = python(code, timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == [
        str(sorted([signal.SIGSEGV.value, signal.SIGUSR2.value])), "true", "false"]


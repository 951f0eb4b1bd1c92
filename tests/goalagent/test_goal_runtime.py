"""Runtime and test semantics matched to GOAL's own runtime tests (issue 26): module calls
nest as deep as the C stack safely allows (a limit with a flag), two launches of one name
get unique names, a rule entering a ``focus=select`` module needs its goal literals in one
goal, test conditions are judged in the state ``do main`` starts from, a test block with no
tests passes, GOAL 5 masTest steps doing modules and several actions. Programs are our
own; each comment names the GOAL test it re-states."""

from __future__ import annotations

import io
import subprocess
import sys
import textwrap
from pathlib import Path

from goalagent.kb.limits import default_module_depth
from goalagent.mas import MultiAgentSystem
from goalagent.testing import run_test_file

RECURSIVE = """
main module [exit=always] { program { if true then down(0). } }
module down(N) {
    program {
        if bel(N >= {depth}) then print(N).
        if bel(N < {depth}, M is N + 1) then down(M).
    }
}
"""


def goalagent(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "goalagent", *args], capture_output=True,
                          text=True, timeout=300)


def test_module_calls_nest_far_deeper_than_24_by_default(tmp_path: Path) -> None:
    # GOAL's runtime test split.goal recurses into split/1 24 calls deep and more
    assert default_module_depth() >= 500
    path = tmp_path / "deep.goal"
    path.write_text(RECURSIVE.replace("{depth}", "300"))
    result = goalagent("run", str(path))
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "300"


def test_module_depth_is_a_limit_with_a_flag(tmp_path: Path) -> None:
    path = tmp_path / "deep.goal"
    path.write_text(RECURSIVE.replace("{depth}", "300"))
    result = goalagent("run", str(path), "--max-module-depth", "50")
    assert result.returncode == 1
    assert "error: agent deep failed: module calls nested more than 50 deep" in result.stderr
    assert "--max-module-depth" in result.stderr
    assert "Traceback" not in result.stderr


def test_two_launches_of_one_name_get_unique_names(tmp_path: Path) -> None:
    (tmp_path / "a.goal").write_text("main module [exit=always] { program { if bel(me(X)) "
                                     "then print(X). } }\n")
    (tmp_path / "s.mas2g").write_text('agentfiles { "a.goal" [name = a]. }\n'
                                      "launchpolicy { launch bot : a. launch bot : a. "
                                      "launch bot : a. }\n")
    output = io.StringIO()
    system = MultiAgentSystem.from_mas_file(tmp_path / "s.mas2g", output=output,
                                            warn=lambda message: None)
    try:
        assert [agent.name for agent in system.agents] == ["bot", "bot2", "bot3"]
        system.run(max_cycles=1)
        assert output.getvalue().split() == ["bot", "bot2", "bot3"]
    finally:
        system.close()


def test_focus_select_needs_the_goal_literals_in_one_goal(tmp_path: Path) -> None:
    # GOAL's runtime test testselect.goal
    path = tmp_path / "select.goal"
    path.write_text(textwrap.dedent("""
        init module { goals { aap, kat. beer, koe. } }
        main module [exit=always] {
            program {
                if goal(aap), goal(beer) then aapbeer.
                if goal(aap), goal(kat) then aapkat.
            }
        }
        module aapbeer [focus=select] { program { if true then print(failure). } }
        module aapkat [focus=select] {
            program { if goal(aap), goal(kat), not(goal(beer)) then print(ok). }
        }
    """))
    result = goalagent("run", str(path))
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["ok"]


def _system(tmp_path: Path, agent: str, test: str) -> Path:
    (tmp_path / "a.goal").write_text(textwrap.dedent(agent))
    (tmp_path / "a.mas2g").write_text('agentfiles { "a.goal". }\nlaunchpolicy { launch a. }\n')
    (tmp_path / "a.test2g").write_text(textwrap.dedent(test))
    return tmp_path / "a.test2g"


def test_eventually_is_judged_in_the_state_do_main_starts_from(tmp_path: Path) -> None:
    # the goal g is achieved in main's first cycle: it held only before it
    path = _system(tmp_path, """
        init module { goals { g. } }
        main module [exit=always] { program { if a-goal(g) then insert(g). } }
    """, """
        masTest {
            mas = "a.mas2g".
            a { test { evaluate { eventually goal(g). } in do main. } }
        }
    """)
    report = run_test_file(path, output=io.StringIO())
    assert report.passed, report.text()
    assert "eventually goal(g)" in report.text()


def test_a_test_block_with_no_tests_passes(tmp_path: Path) -> None:
    path = _system(tmp_path, "main module [exit=always] { program { if true then print(x). } }",
                   'masTest { mas = "a.mas2g". a { test { } } }')
    report = run_test_file(path, output=io.StringIO())
    assert report.verdicts == [] and report.passed
    result = goalagent("test", str(path))
    assert result.returncode == 0, result.stderr
    assert "0 passed, 0 failed" in result.stdout


def test_goal5_mastest_does_modules_and_several_actions_and_watches(tmp_path: Path) -> None:
    # GOAL 5's correctExhaustive.test2g: before/test/after blocks doing modules with
    # arguments; a knowledge predicate as a condition; watch in an evaluate block
    path = _system(tmp_path, """
        init module { knowledge { ready :- started. } }
        main module [exit=nogoals] { program { if true then insert(tick). } }
        module start { program { if true then insert(started). } }
        module mark(X, Y) { program { if true then insert(marked(X, Y)). } }
    """, """
        masTest {
            mas = "a.mas2g".
            timeout = 10.
            a {
                before { assert not(bel(started)). do start. assert ready. }
                testMarks {
                    do mark(a, 1) + mark(b, 2).
                    assert bel(marked(a, 1), marked(b, 2)).
                    evaluate { watch bel(tick). atstart bel(started). } in do main.
                }
            }
        }
    """)
    report = run_test_file(path, output=io.StringIO())
    assert report.passed, report.text()
    text = report.text()
    assert "do start" in text and "do mark" in text and "held in" in text


def test_goal7_timers_raise_goals_timer_percepts(tmp_path: Path) -> None:
    # GOAL 7's RunState.startTimer: timer(Name, Elapsed) every interval for the duration,
    # the last with Elapsed = Duration; canceltimer of a finished timer is a warning
    path = tmp_path / "timer.goal"
    path.write_text(textwrap.dedent("""
        init module { goals { finished. } }
        main module [exit=nogoals] {
            program [order=linearall] {
                if bel(not(started)) then insert(started) + starttimer(tick, 20, 50).
                forall bel(percept(timer(N, E))) do print(fired(N, E)).
                if bel(percept(timer(tick, 50))) then canceltimer(tick) + insert(finished).
            }
        }
    """))
    result = goalagent("run", str(path), "--max-cycles", "200000")
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["fired(tick,20)", "fired(tick,40)", "fired(tick,50)"]
    assert "timer 'tick' was not running or already cancelled." in result.stderr


def test_goal7_channels_reach_their_subscribers(tmp_path: Path) -> None:
    (tmp_path / "listener.goal").write_text(textwrap.dedent("""
        main module [exit=never] {
            program [order=linearall] {
                if bel(not(joined)) then insert(joined) + subscribe(news).
                forall bel(received(S, M)) do print(heard(S, M)) + delete(received(S, M)).
            }
        }
    """))
    (tmp_path / "speaker.goal").write_text(textwrap.dedent("""
        main module [exit=never] {
            program { if bel(not(said)) then insert(said) + news.send(hello). }
        }
    """))
    (tmp_path / "s.mas2g").write_text(
        'agentfiles { "listener.goal". "speaker.goal". }\n'
        "launchpolicy { launch ann : listener. launch bob : listener. "
        "launch sam : speaker. }\n")
    result = goalagent("run", str(tmp_path / "s.mas2g"), "--max-cycles", "3")
    assert result.returncode == 0, result.stderr
    assert sorted(result.stdout.split()) == ["heard(sam,hello)", "heard(sam,hello)"]


def test_traces_and_warnings_name_the_users_own_modules(tmp_path: Path) -> None:
    (tmp_path / "moverMain.mod2g").write_text(
        "module moverMain { if bel(atom_length(X, _)) then print(x). "
        "if true then print(moved). }\n")
    (tmp_path / "s.mas2g").write_text(
        "define mover as agent { use moverMain as main module. }\n"
        "launchpolicy { launch mover. }\n")
    result = goalagent("run", str(tmp_path / "s.mas2g"), "--max-cycles", "1", "--trace=rules")
    assert result.returncode == 0, result.stderr
    assert "fired moverMain " in result.stdout and "fired main " not in result.stdout
    assert "warning: agent mover: module moverMain, rule at" in result.stderr

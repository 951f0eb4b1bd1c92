"""GOAL's agent tests (.test2g), GOAL 6's and GOAL 5's forms, run by ``goalagent test`` and
from Python: steps (do .. until, do init, assert, evaluate .. in), temporal conditions
(eventually, always, never, atend, leadsto) with done(..), module tests with pre and post;
a report per item, exit code 1 when one failed, 2 for a test that cannot run."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from goalagent.parser import GoalSyntaxError, parse_test
from goalagent.testing import run_test_file

ROOT = Path(__file__).resolve().parents[2]
COFFEE_TEST = ROOT / "agents" / "examples" / "goal6" / "coffee" / "coffee.test2g"

COUNTER_MAS = """
define counter as agent {
    use count as main module.
    use start as init module.
}
launchpolicy { launch counter. }
"""
COUNT_MOD = """
exit = nogoals.
module count {
    if bel(n(N), N < 5, M is N + 1) then delete(n(N)) + insert(n(M)) + tick(M).
    if bel(n(5)) then insert(done).
}
"""
START_MOD = """
use tick as actionspec.
module start { if true then insert(n(0)) + adopt(done). }
"""
TICK_ACT = "define tick(N) as internal with pre { true } post { ticked(N) }\n"


def counter(tmp_path: Path, test: str, name: str = "t.test2g") -> Path:
    files = {"sys.mas2g": COUNTER_MAS, "count.mod2g": COUNT_MOD.replace(
        "exit = nogoals.", "use tick as actionspec.\nexit = nogoals."),
        "start.mod2g": START_MOD, "tick.act2g": TICK_ACT, name: test}
    for file, text in files.items():
        (tmp_path / file).write_text(textwrap.dedent(text))
    return tmp_path / name


def verdicts(report) -> list[tuple[str, bool]]:
    return [(v.what, v.passed) for v in report.verdicts]


def test_the_coffee_test_passes_from_python() -> None:
    report = run_test_file(COFFEE_TEST)
    assert report.passed, report.text()
    assert len(report.verdicts) == 10
    assert ("eventually bel(have(coffee))", True) in verdicts(report)


def test_every_kind_of_condition_is_judged_and_failures_say_why(tmp_path: Path) -> None:
    path = counter(tmp_path, """
        use sys.
        test count with
            pre { bel(n(0)) }
            in {
                eventually bel(n(3)).
                eventually bel(n(9)).
                always bel(n(N), N =< 5).
                always bel(n(N), N < 3).
                never bel(n(7)).
                never done(tick(4)).
                done(tick(N)) leadsto bel(ticked(N)).
                bel(n(2)) leadsto bel(n(8)).
                atend bel(done).
                atend bel(n(0)).
            }
            post { bel(ticked(5)) }
        counter { do count until bel(done). }
    """)
    report = run_test_file(path)
    assert not report.passed
    found = {v.what: (v.passed, v.detail) for v in report.verdicts}
    assert found["do count until ..."] == (True, "reached after 6 cycle(s)")
    assert found["pre"][0] and found["post"][0]
    assert found["eventually bel(n(3))"] == (True, "held at cycle 3")
    assert found["eventually bel(n(9))"] == (False, "never held in 6 state(s)")
    assert found["always bel(n(N), N =< 5)"][0]
    assert found["always bel(n(N), N < 3)"] == (False, "did not hold at cycle 3")
    assert found["never bel(n(7))"][0]
    assert found["never done(tick(4))"] == (False, "held at cycle 4")
    assert found["done(tick(N)) leadsto bel(ticked(N))"][0]
    assert found["bel(n(2)) leadsto bel(n(8))"] == (
        False, "its left side held at cycle 2, its right side never after")
    assert found["atend bel(done)"][0] and not found["atend bel(n(0))"][0]
    text = report.text()
    assert "FAILED  eventually bel(n(9))" in text and "5 failed" in text


def test_a_prolog_error_in_a_condition_fails_that_item_only(tmp_path: Path) -> None:
    """JoshCode-uni/BW4T's robot.test2g queries nextBlockInSeq/1, which its agent has
    commented out: that item fails with the error (and where), the others are judged."""
    path = counter(tmp_path, """
        use sys.
        test count with
            in {
                never bel(n(N)), bel(next(N)).
                atend bel(missing(x)).
                eventually bel(n(4)).
            }
        counter { do count until bel(done). }
    """)
    report = run_test_file(path)
    found = {v.what: (v.passed, v.detail) for v in report.verdicts}
    assert found["never bel(n(N)), bel(next(N))"] == (
        False, "a Prolog error at cycle 1: Unknown procedure: next/1")
    assert found["atend bel(missing(x))"] == (
        False, "a Prolog error at the end: Unknown procedure: missing/1")
    assert found["eventually bel(n(4))"] == (True, "held at cycle 4")
    assert "t.test2g:5:9) -- a Prolog error at cycle 1" in report.text()


def test_until_not_reached_fails_and_agents_run_to_their_end(tmp_path: Path) -> None:
    path = counter(tmp_path, """
        use sys.
        counter { do main until bel(n(9)). }
    """)
    report = run_test_file(path)
    assert verdicts(report) == [("do main until ...", False)]
    assert "the agent stopped after 6 cycle(s) before its condition held" in report.text()


def test_the_test_file_timeout_and_max_cycles_stop_a_run(tmp_path: Path) -> None:
    (tmp_path / "forever.mod2g").write_text("module forever { if true then insert(x). }\n")
    (tmp_path / "f.mas2g").write_text("define f as agent { use forever as main. }\n"
                                      "launchpolicy { launch f. }\n")
    (tmp_path / "f.test2g").write_text("use f.\ntimeout = 30.\nf { do main. }\n")
    report = run_test_file(tmp_path / "f.test2g", max_cycles=7)
    assert report.passed and report.cycles == 7
    assert "time ran out after 7 cycle(s)" in report.text()


def test_goal5_mas_tests_with_init_assert_and_evaluate(tmp_path: Path) -> None:
    (tmp_path / "c.goal").write_text(textwrap.dedent("""
        init module { program { if true then insert(n(0)). } }
        main module [exit=nogoals] {
            goals { n(3). }
            program { if bel(n(N), M is N + 1) then delete(n(N)) + insert(n(M)). }
        }
    """))
    (tmp_path / "c.mas2g").write_text('agentfiles { "c.goal". }\nlaunchpolicy { launch c. }\n')
    (tmp_path / "c.test2g").write_text(textwrap.dedent("""
        masTest {
            mas = "c.mas2g".
            timeout = 10.
            c {
                test {
                    assert not(bel(n(_))) : "nothing before init".
                    do init.
                    assert bel(n(0)).
                    evaluate {
                        eventually bel(n(2)).
                        never bel(n(4)).
                        atend bel(n(3)).
                    } in do main until bel(n(3)).
                    assert bel(n(1)) : "went past one".
                }
            }
        }
    """))
    report = run_test_file(tmp_path / "c.test2g")
    assert verdicts(report) == [
        ("assert: nothing before init", True), ("assert", True),
        ("do main until ...", True), ("eventually bel(n(2))", True),
        ("never bel(n(4))", True), ("atend bel(n(3))", True),
        ("assert: went past one", False)]


def test_cli_reports_and_exits_with_the_outcome(tmp_path: Path) -> None:
    good = subprocess.run([sys.executable, "-m", "goalagent", "test", str(COFFEE_TEST)],
                          capture_output=True, text=True, timeout=120)
    assert good.returncode == 0, good.stderr
    assert "10 passed, 0 failed" in good.stdout
    failing = counter(tmp_path, "use sys.\ncounter { do main until bel(n(9)). }\n")
    bad = subprocess.run([sys.executable, "-m", "goalagent", "test", str(failing)],
                         capture_output=True, text=True, timeout=120)
    assert bad.returncode == 1 and "FAILED  do main until" in bad.stdout
    broken = counter(tmp_path, "use sys.\nnobody { do main. }\n", "b.test2g")
    error = subprocess.run([sys.executable, "-m", "goalagent", "test", str(broken)],
                           capture_output=True, text=True, timeout=120)
    assert error.returncode == 2 and "Traceback" not in error.stderr
    assert "b.test2g:2:1: no agent called nobody in sys.mas2g" in error.stderr


@pytest.mark.parametrize("text, message", [
    ("timeout = 3.\n", "names no system"),
    ("use nowhere.\n", "use nowhere as mas: no such file"),
    ("use sys.\nlength = 3.\n", "unknown test option 'length'"),
    ("use sys.\ntest nothing with in { eventually true. }\ncounter { do main. }\n",
     "test nothing: no agent of the test has a module"),
])
def test_mistakes_in_test_files_are_located(tmp_path: Path, text: str, message: str) -> None:
    path = counter(tmp_path, text)
    with pytest.raises(GoalSyntaxError, match=message):
        run_test_file(path)


def test_a_test_step_may_do_several_actions(tmp_path: Path) -> None:
    path = counter(tmp_path, "use sys.\ncounter { do insert(x) + insert(y). }\n")
    step = parse_test(path.read_text(), str(path)).agent_tests[0]
    assert [action.name for action in step.steps[0].actions] == ["insert", "insert"]

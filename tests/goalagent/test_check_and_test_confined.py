"""``goalagent check`` runs no agent code, and ``goalagent test`` runs agents and conditions
under the confinement and limits of ``run`` (issue 24 item 3): a test condition that runs
away, sleeps or is refused fails its own item, with its position, and the file goes on.
``check`` runs in this process (in the test's folder, where what a regression ran would
write), ``test`` in a child: a regression there could run ``halt``."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from goalagent.kb.limits import Limits
from goalagent.testing import run_test_file
from tests.conftest import cli, goalagent

# goalagent check ran agent code: the undefined-call check loaded the agent unconfined and
# adopting the initial goals ran knowledge rules, even under check --sandbox.
CHECKED = """
init module {
    knowledge {
        :- dynamic(seen/1).
        :- shell('touch PWNED1').
        :- initialization(shell('touch PWNED2')).
        foo :- shell('touch PWNED3').
        :- use_module(library(lists)).
    }
    beliefs { :- shell('touch PWNED4'). }
    goals { foo. }
}
main module { program {
    if bel(foo, sum_list([1], _), seen(_)) then print(x).
    if bel(undefined_here(1)) then print(y).
} }
"""


@pytest.mark.parametrize("sandbox", [False, True])
def test_check_runs_no_agent_code(tmp_path: Path, sandbox: bool,
                                  monkeypatch: pytest.MonkeyPatch):
    (tmp_path / "evil.goal").write_text(CHECKED)
    monkeypatch.chdir(tmp_path)
    result = cli("check", "evil.goal", *["--sandbox"] * sandbox)
    assert not list(tmp_path.glob("PWNED*")), result.stderr
    if sandbox:  # refused, located; and still not run
        assert result.exit_code == 2
        assert result.stderr.startswith("evil.goal:5:9: knowledge clause `:- shell(")
        assert "not allowed in the sandbox" in result.stderr
    else:  # declarations and library loads took effect: only the real undefined call
        assert result.exit_code == 0, result.stderr
        assert result.stderr.splitlines() == [
            "evil.goal:15:12: warning: undefined_here/1 is called but defined nowhere (not "
            "built in, not in knowledge or beliefs, never inserted)", "evil.goal: ok"]


def test_check_still_reports_what_run_refuses_in_a_directive(tmp_path: Path,
                                                             monkeypatch: pytest.MonkeyPatch):
    (tmp_path / "a.goal").write_text("init module { knowledge { :- ga_kb:assertz(x). } }\n"
                                     "main module { program { if true then print(x). } }\n")
    monkeypatch.chdir(tmp_path)
    result = cli("check", "a.goal")
    assert result.exit_code == 2
    assert "a.goal:1:27: knowledge clause" in result.stderr
    assert "qualified with a module" in result.stderr


AGENT = """
init module {
    knowledge { spin(N) :- N1 is N + 1, spin(N1). }
    beliefs { n(0). }
}
main module { program {
    if bel(n(N), N < 5, M is N + 1) then delete(n(N)) + insert(n(M)).
} }
"""


def _system(tmp_path: Path, test: str) -> Path:
    (tmp_path / "a.goal").write_text(AGENT)
    (tmp_path / "s.mas2g").write_text('agentfiles { "a.goal". }\nlaunchpolicy { launch a : a. }\n')
    (tmp_path / "t.test2g").write_text(textwrap.dedent(test))
    return tmp_path / "t.test2g"


def test_runaway_and_sleeping_conditions_fail_their_own_items(tmp_path: Path):
    # a runaway `until` ended the whole file with one unlocated error line
    path = _system(tmp_path, """\
        use s as mas.
        timeout = 60.
        test a with
            pre { bel(spin(0)) }
            in { eventually bel(n(2), sleep(30)). eventually bel(n(3)). }
            post { bel(n(5), spin(0)) }
        a {
            do main until bel(n(3), spin(0)).
            do main until bel(n(5)).
        }
    """)
    report = run_test_file(path, limits=Limits(max_inferences=200_000, max_query_seconds=0.5))
    found = [(v.what, v.pos.line, v.passed, v.detail) for v in report.verdicts]
    inferences = "more than 200,000 inferences (--max-inferences)"
    slept = "longer than 0.5 s (--max-query-seconds)"
    assert ("do main until ...", 8, False) == found[0][:3] and inferences in found[0][3]
    assert found[1] == ("do main until ...", 9, True, "reached after 2 cycle(s)")
    judged = {(what, passed, inferences in detail or slept in detail)
              for what, _, passed, detail in found[2:]}
    for item in [("pre", False, True), ("eventually bel(n(2), sleep(30))", False, True),
                 ("eventually bel(n(3))", True, False), ("post", False, True)]:
        assert item in judged, found


def test_goalagent_test_takes_the_sandbox_and_the_limits(tmp_path: Path):
    _system(tmp_path, """\
        masTest {
            mas = "s.mas2g".
            timeout = 20.
            a {
                test {
                    assert bel(halt).
                    evaluate { eventually bel(shell('touch PWNED')). }
                    in do main until bel(n(5)).
                    assert bel(n(5), spin(0)).
                }
            }
        }
    """)
    result = goalagent("test", "t.test2g", "--sandbox", "--max-query-seconds", "5",
                        "--max-inferences", "1000000", cwd=tmp_path)
    assert result.returncode == 1, result.stderr
    assert not (tmp_path / "PWNED").exists()
    lines = result.stdout.splitlines()
    assert "FAILED  assert  (t.test2g:6:13)" in lines[2]
    assert "halt/0 would end or change the whole process" in lines[2]
    assert "passed  do main until ...  (t.test2g:7:13)" in lines[3]
    assert "(t.test2g:7:24) -- a Prolog error at cycle 0" in lines[4]
    assert "not allowed in the sandbox" in lines[4]
    assert "FAILED  assert  (t.test2g:9:13)" in lines[5]
    assert "more than 1,000,000 inferences" in lines[5]
    bad = cli("test", str(tmp_path / "t.test2g"), "--max-query-seconds", "0")
    assert bad.exit_code == 2 and "--max-query-seconds" in bad.stderr

"""Attacks on memory, limits and saves (issue 24, items 4-6): each hole the red team found,
as the smallest program that showed it, run the way a user reaches it -- ``goalagent run``
in a child process with a timeout, beside a counter agent that must finish (a regression
would otherwise take the test process down with it or hang the suite)."""

from __future__ import annotations

from pathlib import Path

from measured import Measured, goalagent_measured

COUNTER = """
init module { beliefs { n(0). } goals { n(5). } }
main module [exit=nogoals] { program {
    if bel(n(N), N < 5, M is N + 1) then delete(n(N)) + insert(n(M)).
} }
"""


def _run_beside_counter(tmp_path: Path, program: str, *options: str,
                        timeout: float = 120) -> Measured:
    """``goalagent run`` of the agent ``program`` (atk.goal) and the counter."""
    (tmp_path / "atk.goal").write_text(program)
    (tmp_path / "counter.goal").write_text(COUNTER)
    (tmp_path / "s.mas2g").write_text('agentfiles { "atk.goal". "counter.goal". }\n')
    return goalagent_measured("run", str(tmp_path / "s.mas2g"), *options, timeout=timeout)


def _counter_finished(result: Measured) -> None:
    assert "Traceback" not in result.stderr, result.stderr
    assert "counter: terminated after 5 cycles" in result.stderr, result.stderr


# ----------------------------------------------------------------------------- saves

DEEP_FACT = """
init module { knowledge { nest(0, z). nest(N, f(T)) :- N > 0, M is N - 1, nest(M, T). }
              beliefs { keep(a). } }
main module [exit=always] { program {
    if bel(nest(100000, T)) then insert(keep(T)) + insert(other(b)).
} }
"""


def test_a_fact_too_deep_to_write_costs_only_its_agent_s_save(tmp_path: Path):
    # 'too deeply nested term' in the saver stopped every agent's save: nothing was written
    saved = tmp_path / "saved.pl"
    result = _run_beside_counter(tmp_path, DEEP_FACT, "--save-beliefs", str(saved),
                                 "--save-predicate", "n/1", "--save-predicate", "keep/1",
                                 "--save-predicate", "other/1")
    _counter_finished(result)
    assert ("warning: beliefs of agent atk not saved to " in result.stderr
            and "keep/1: an answer is a cyclic or too deeply nested term" in result.stderr)
    text = saved.read_text()
    assert "% agent counter\nn(5).\n" in text  # every other agent's facts
    assert "% agent atk\n% not saved: keep/1: " in text and "other(b)." in text
    assert "saved 2 " in result.stderr

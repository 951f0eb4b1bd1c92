"""Bounded Prolog work per agent (issue 14 item 1, issue 19 items 2 and 3): runaway rules end
with a located warning and the others go on; a module calling itself, an agent flooding its
beliefs or one whose environment raises is stopped alone; Ctrl-C and SIGTERM stop a run
even inside a runaway query, saying where, saving what was asked."""

from __future__ import annotations

import io
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from goalagent.agent import Agent
from goalagent.beliefs import read_belief_file
from goalagent.kb.errors import LimitError
from goalagent.kb.limits import Limits
from goalagent.mas import MultiAgentSystem
from goalagent.parser import parse_agent
from tests.conftest import cli

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

RUNAWAYS = """
init module { knowledge {
    p :- p.
    spin(N) :- N1 is N + 1, spin(N1).
    deep(N) :- N1 is N + 1, deep(N1), true.
    nap :- sleep(60).
    stubborn :- catch(sleep(60), _, true), stubborn.
} }
"""
COUNTER = """
init module { beliefs { n(0). } goals { n(5). } }
main module [exit=nogoals] { program {
    if bel(n(N), N < 5, M is N + 1) then delete(n(N)) + insert(n(M)).
} }
"""


def _agent(program: str, limits: Limits, warnings: list[str]) -> Agent:
    return Agent(parse_agent(program, "runaway.goal"), limits=limits, output=io.StringIO(),
                 warn=warnings.append)


@pytest.mark.parametrize("query", ["p", "spin(0)", "deep(0)"])
def test_a_runaway_condition_is_not_applicable_with_a_located_warning(query: str):
    warnings: list[str] = []
    program = RUNAWAYS + ("main module [exit=always] { program {\n"
                          f"    if bel({query}) then print(never).\n"
                          "    if true then print(after). } }")
    agent = _agent(program, Limits(max_inferences=200_000), warnings)
    try:
        report = agent.step()
    finally:
        agent.close()
    assert [fired.pos.line for fired in report.fired] == [11]  # the next one fired
    assert warnings == ["warning: agent runaway: module main, rule at runaway.goal:10:5: ran "
                        "more than 200,000 inferences (--max-inferences); the rule is not "
                        "applicable"]


def test_a_rule_that_stalls_without_inferences_meets_the_time_limit():
    warnings: list[str] = []
    program = RUNAWAYS + ("main module [exit=always] { program {\n"
                          "    if bel(nap) then print(never).\n"
                          "    if true then print(after). } }")
    agent = _agent(program, Limits(max_query_seconds=0.5), warnings)
    start = time.monotonic()
    try:
        agent.step()
    finally:
        agent.close()
    assert time.monotonic() - start < 30  # not the 60 s the rule asked for
    assert warnings == ["warning: agent runaway: module main, rule at runaway.goal:10:5: ran "
                        "longer than 0.5 s (--max-query-seconds); the rule is not applicable"]


def test_a_catch_all_cannot_swallow_the_time_limit():
    # catch(sleep(60), _, true) in a loop: the agent's catch/3 lets the limit pass, so
    # the rule is not applicable (each cycle, within the limit) and the others go on
    stubborn = RUNAWAYS + "main module { program { if bel(stubborn) then print(never). } }"
    warnings: list[str] = []
    mas = MultiAgentSystem(output=io.StringIO(), warn=warnings.append,
                           limits=Limits(max_query_seconds=0.3))
    mas.launch("stubborn", parse_agent(stubborn, "stubborn.goal"))
    mas.launch("counter", parse_agent(COUNTER, "counter.goal"))
    start = time.monotonic()
    try:
        summaries = {summary.name: summary for summary in mas.run(max_cycles=6)}
    finally:
        mas.close()
    assert time.monotonic() - start < 15
    assert summaries["stubborn"].status != "failed" and summaries["stubborn"].cycles == 6
    assert "stubborn.goal:9:25: ran longer than 0.3 s (--max-query-seconds)" in warnings[0]
    assert summaries["counter"].status == "terminated" and summaries["counter"].cycles == 5


def test_the_other_agents_keep_running_past_a_runaway_one():
    runaway = RUNAWAYS + "main module { program { if bel(spin(0)) then print(never). } }"
    warnings: list[str] = []
    mas = MultiAgentSystem(output=io.StringIO(), warn=warnings.append,
                           limits=Limits(max_inferences=100_000))
    mas.launch("runaway", parse_agent(runaway, "runaway.goal"))
    mas.launch("counter", parse_agent(COUNTER, "counter.goal"))
    try:
        summaries = {summary.name: summary for summary in mas.run(max_cycles=6)}
    finally:
        mas.close()
    assert summaries["counter"].status == "terminated"
    assert summaries["runaway"].cycles == 6 and summaries["runaway"].status != "failed"
    # met in every cycle; a repeated warning is shown twice (the second says "again")
    assert sum("runaway.goal:9:" in warning for warning in warnings) == 2
    assert summaries["runaway"].cycles == 6


def test_an_api_query_is_bounded_too():
    agent = _agent(RUNAWAYS + "main module { program { if true then print(x). } }",
                   Limits(max_inferences=100_000), [])
    try:
        with pytest.raises(LimitError, match="more than 100,000 inferences"):
            agent.query("bel", "spin(0)")
        assert agent.query("bel", "X is 1 + 1") == [{"X": 2}]
    finally:
        agent.close()


def test_a_module_calling_itself_stops_that_agent_alone_without_a_traceback(tmp_path: Path):
    (tmp_path / "selfcall.goal").write_text(
        "main module [exit=always] { program { if true then loop. } }\n"
        "module loop { program { if true then loop. } }\n")
    (tmp_path / "counter.goal").write_text(COUNTER)
    (tmp_path / "system.mas2g").write_text('agentfiles { "selfcall.goal". "counter.goal". }\n')
    result = cli("run", str(tmp_path / "system.mas2g"))
    assert result.exit_code == 1
    assert "Traceback" not in result.stderr
    assert re.search(r"error: agent selfcall failed: module calls nested more than \d+ deep "
                     r"\(.*loop -> loop\)", result.stderr)
    assert "counter: terminated after 5 cycles" in result.stderr


def test_an_agent_flooding_its_beliefs_is_stopped_and_the_other_finishes(tmp_path: Path):
    (tmp_path / "flood.goal").write_text(
        "init module { knowledge { flood :- forall(between(1, inf, X), assertz(junk(X))). } }\n"
        "main module { program { if bel(flood) then print(never). } }\n")
    (tmp_path / "counter.goal").write_text(COUNTER)
    (tmp_path / "system.mas2g").write_text('agentfiles { "flood.goal". "counter.goal". }\n')
    result = cli("run", str(tmp_path / "system.mas2g"), "--max-inferences", "1000000",
                 "--max-beliefs", "100000")
    assert result.exit_code == 1  # one agent failed; the run ended normally
    assert re.search(r"error: agent flood failed: holds [\d,]+ beliefs, more than 100,000 "
                     r"\(--max-beliefs\); stopped", result.stderr), result.stderr
    assert "counter: terminated after 5 cycles" in result.stderr


def test_inserting_without_end_meets_the_belief_bound():
    program = ("init module { beliefs { n(0). } }\n"
               "main module { program {\n"
               "    if bel(aggregate_all(max(N), n(N), Max), M is Max + 1) then insert(n(M)). } }")
    agent = _agent(program, Limits(max_beliefs=50), [])
    try:
        with pytest.raises(LimitError, match=r"holds 5\d beliefs, more than 50"):
            agent.run(max_cycles=1000)
        assert 35 < agent.cycle <= 50  # the runtime keeps a few clauses of its own there
    finally:
        agent.close()


def test_an_environment_that_raises_fails_its_agent_only():
    class Broken:
        def percepts(self):
            raise RuntimeError("the camera fell off")

        def act(self, action):
            raise RuntimeError("never")

    mas = MultiAgentSystem(output=io.StringIO(), warn=lambda message: None)
    broken = mas.launch("broken", parse_agent(COUNTER, "broken.goal"))
    broken.io = Broken()
    mas.launch("counter", parse_agent(COUNTER, "counter.goal"))
    try:
        summaries = {summary.name: summary for summary in mas.run(max_cycles=10)}
    finally:
        mas.close()
    assert mas.failures["broken"] == "RuntimeError: the camera fell off"
    assert summaries["counter"].status == "terminated"


def test_limits_per_agent_file_in_a_mas2g(tmp_path: Path):
    (tmp_path / "runaway.goal").write_text(
        RUNAWAYS + "main module [exit=always] { program { if bel(spin(0)) then print(x). } }")
    (tmp_path / "system.mas2g").write_text(
        'agentfiles { "runaway.goal" [name = tight, max_inferences = 50000]. '
        '"runaway.goal" [name = loose, sandbox = true, max_query_seconds = 2.5]. }\n')
    mas = MultiAgentSystem.from_mas_file(tmp_path / "system.mas2g", output=io.StringIO(),
                                         warn=lambda message: None)
    try:
        limits = {agent.name: agent.ms.limits for agent in mas.agents}
    finally:
        mas.close()
    assert limits["tight"] == Limits(max_inferences=50_000)
    assert limits["loose"] == Limits(max_query_seconds=2.5, sandbox=True)


# ------------------------------------------------------------------ signals

SPIN = """
init module { knowledge { spin(N) :- N1 is N + 1, spin(N1). } beliefs { learned(1). }
              program { if true then print(started). } }
main module { program { if bel(spin(0)) then print(never). } }
"""


def _cpu_seconds(pid: int) -> float:
    """The CPU time process ``pid`` has used (/proc/PID/stat: user and system ticks)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


@pytest.mark.parametrize("signum, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_stops_a_runaway_query_says_where_and_saves(tmp_path: Path, signum: int,
                                                             code: int):
    program = tmp_path / "spin.goal"
    program.write_text(SPIN)
    saved = tmp_path / "saved.pl"
    child = subprocess.Popen(
        [sys.executable, "-m", "goalagent", "run", str(program), "--save-beliefs", str(saved),
         "--save-predicate", "learned/1", "--max-inferences", str(10**15),
         "--max-query-seconds", "100000"], cwd=tmp_path, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True, env={**os.environ, "PYTHONUNBUFFERED": "1"})
    assert child.stdout is not None and child.stdout.readline() == "started\n"
    started = _cpu_seconds(child.pid)
    deadline = time.monotonic() + 60
    while _cpu_seconds(child.pid) < started + 0.2:  # well inside spin/1: working on and on
        assert child.poll() is None and time.monotonic() < deadline, child.returncode
        time.sleep(0.02)
    sent = time.monotonic()
    child.send_signal(signum)
    _, stderr = child.communicate(timeout=60)
    took = time.monotonic() - sent
    assert child.returncode == code, stderr
    name = signal.Signals(signum).name
    assert re.search(rf"interrupted \({name}\) in agent spin, cycle 1, module main, rule at "
                     rf"{re.escape(str(program))}:4:\d+: stopping", stderr), stderr
    assert "Traceback" not in stderr
    with read_belief_file(saved, []) as facts:
        assert facts.count == 1
    assert "learned(1)." in saved.read_text()
    assert took < 30, took  # on an idle machine well under a second (see bench notes)

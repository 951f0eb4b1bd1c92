"""Stepping and breakpoints (``goalagent.debugger``) and ``goalagent run --step``: the run
stops before the first cycle, after each cycle, inside a cycle at a rule breakpoint, after a
condition becomes true; queries answer from the stopped agent."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from goalagent.debugger import Breakpoint, Debugger, DebuggerError, Stop, answer_text
from goalagent.extensions import RunContext
from goalagent.kb.terms import Atom, Struct, Var
from goalagent.mas import MultiAgentSystem

ROOT = Path(__file__).resolve().parents[2]
BLOCKS = ROOT / "agents" / "examples" / "blocks_builder.goal"
STATE = "state=[on(c,a), on(a,table), on(b,table)]"


class Script:
    """A front end that records each stop (and the answers of queries made there) and
    goes on as its script says: ``step``, ``continue`` or a callable."""

    def __init__(self, *moves) -> None:
        self.moves = list(moves)
        self.stops: list[tuple[str | None, int, str, bool]] = []

    def wait(self, debugger: Debugger, stop: Stop) -> None:
        agent = stop.agent
        self.stops.append((agent.name if agent else None, agent.cycle if agent else 0,
                           stop.reason, stop.inside))
        move = self.moves.pop(0) if self.moves else "continue"
        while callable(move):
            move(debugger, stop)
            move = self.moves.pop(0) if self.moves else "continue"
        debugger.resume(step=move == "step")


def run_blocks(front: Script, breakpoints=(), stepping=True) -> MultiAgentSystem:
    from goalagent.eis.registry import load_environment  # noqa: F401 - registry warm-up

    system = MultiAgentSystem.for_agent_file(BLOCKS, environment="blocksworld",
                                             env_params={"state": _state()})
    debugger = Debugger(front, stepping=stepping)
    debugger.system = system
    for text in breakpoints:
        debugger.add_breakpoint(text)
    context = RunContext(system, {}, None)  # type: ignore[arg-type]
    debugger.start(context)
    system.run(20, after_cycle=lambda agent: debugger.after_cycle(context, agent))
    return system


def _state():
    from goalagent.mas import parse_parameter

    return parse_parameter(STATE.split("=", 1)[1])


def test_steps_stop_before_the_first_cycle_and_after_each() -> None:
    front = Script("step", "step", "step", "step")
    system = run_blocks(front)
    try:
        assert [(name, cycle) for name, cycle, _, _ in front.stops] == [
            (None, 0), ("blocks_builder", 1), ("blocks_builder", 2), ("blocks_builder", 3)]
        assert system.agents[0].terminated
    finally:
        system.close()


def test_rule_breakpoint_holds_the_agent_inside_its_cycle_where_queries_see_the_state() -> None:
    answers: list[list[str]] = []

    def ask(debugger: Debugger, stop: Stop) -> None:
        answers.append(debugger.query(stop.agent, "bel(on(b, X))"))

    front = Script("continue", ask, "continue", ask, "continue")
    system = run_blocks(front, breakpoints=[f"{BLOCKS.name}:30"])
    try:
        inside = [stop for stop in front.stops if stop[3]]
        assert [(name, cycle) for name, cycle, _, _ in inside] == [
            ("blocks_builder", 2), ("blocks_builder", 3)]
        assert "X=b, Y=c" in inside[0][2]
        # at cycle 2 the rule has not moved b yet; at cycle 3 it has (b is on c)
        assert answers == [["X=table"], ["X=c"]]
    finally:
        system.close()


def test_condition_breakpoint_stops_once_when_it_becomes_true() -> None:
    front = Script("continue", "continue", "continue")
    system = run_blocks(front, breakpoints=["bel(on(b, c))"])
    try:
        assert front.stops[1:] == [("blocks_builder", 2, "breakpoint bel(on(b, c)) became true",
                                    False)]
    finally:
        system.close()


@pytest.mark.parametrize("text", ["nowhere.goal:3", f"{BLOCKS.name}:2", "bel(on(X,)"])
def test_unusable_breakpoints_are_refused(text: str) -> None:
    system = MultiAgentSystem.for_agent_file(BLOCKS, environment="blocksworld",
                                             env_params={"state": _state()})
    try:
        debugger = Debugger(Script())
        debugger.system = system
        with pytest.raises(DebuggerError):
            debugger.add_breakpoint(text)
    finally:
        system.close()


def test_breakpoint_files_match_by_path_end() -> None:
    from goalagent.ast import Pos

    pos = Pos("/x/agents/examples/blocks_builder.goal", 30, 9)
    assert Breakpoint.parse("blocks_builder.goal:30").at(pos)
    assert Breakpoint.parse("examples/blocks_builder.goal:30").at(pos)
    assert not Breakpoint.parse("builder.goal:30").at(pos)
    assert not Breakpoint.parse("blocks_builder.goal:31").at(pos)


def test_step_prompt_on_the_terminal() -> None:
    commands = "\n".join(["?", "n", "q bel(on(X, table))", "b bel(on(a, b))",
                          "b blocks_builder.goal:31", "b", "zz", "c", "m", "c"]) + "\n"
    result = subprocess.run(
        [sys.executable, "-m", "goalagent", "run", str(BLOCKS), "--env", "blocksworld",
         "--env-param", STATE, "--step"], input=commands, capture_output=True, text=True,
        timeout=120, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    err = result.stderr
    assert "-- before the first cycle" in err and "q bel(...)" in err  # the help
    assert "-- blocks_builder #1: after cycle 1" in err
    assert "fired main" in err and "-> move(c,table)" in err
    assert "X=a\nX=b\nX=c" in err
    assert "unknown command 'zz'" in err
    assert "-- blocks_builder #3: breakpoint bel(on(a, b)) became true" in err
    assert "goals:\npercepts:" in err  # m: all goals achieved
    assert "blocks_builder: terminated after 3 cycles" in err
    assert result.stdout == ""


def test_answers_show_fresh_variables_as_underscores() -> None:
    """A mailbox query (``received(S, M)``) answered with Prolog's own variables: ``_``,
    never ``_G44``, in the prompt and in the inspector alike."""
    question = Struct("int", (Struct("canMake", (Var("_G44"), Var("_G45"))),))
    assert answer_text([{"S": Atom("grinder"), "M": question}, {}]) == [
        "S=grinder, M=int(canMake(_,_))", "true"]
    result = subprocess.run(
        [sys.executable, "-m", "goalagent", "run", "agents/examples/coffee.mas2g", "--step"],
        input="n\nn\nn\nq bel(received(grinder, M))\nc\n", capture_output=True, text=True,
        timeout=120, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert "M=int(canMake(_,_))" in result.stderr and "_G" not in result.stderr

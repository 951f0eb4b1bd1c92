"""Conformance of the two formats: each example of agents/examples/goal6 is an agent of
agents/examples written in GOAL 6's multi-file format, and must do exactly what the
single-file agent does -- the same lines printed, the same rules fired with the same
bindings in the same order, the same end state (but for the mailbox: GOAL 6 keeps a received
message one cycle, GOAL 4/5 until the agent deletes it)."""

from __future__ import annotations

import io
import re
import subprocess
import sys
from pathlib import Path

import pytest

from goalagent.mas import MultiAgentSystem, parse_parameter

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "agents" / "examples"
GOAL6 = EXAMPLES / "goal6"
SUSSMAN = "[on(c,a), on(a,table), on(b,table)]"

# (multi-file system, single-file counterpart, environment and its parameters)
PAIRS = [
    ("coffee/coffee.mas2g", "coffee.mas2g", None, {}),
    ("blocks/blocks.mas2g", "blocks_builder.goal", "blocksworld", {"state": SUSSMAN}),
    ("chores/chores.mas2g", "user_modules.goal", None, {}),
    ("tower/tower.mas2g", "tower_agent.goal", "towerworld",
     {"state": "[on(a,b), on(b,c), on(c,d), on(d,e), on(e,f), on(f,table)]"}),
]


def unnamed(text: str) -> str:
    """``text`` without the numbers Prolog gives fresh variables (_G123) and macro
    expansions give a macro's own variables (Rest_M2)."""
    return re.sub(r"_M\d+", "_M", re.sub(r"_G\d+", "_G", text))


def run(path: Path, environment: str | None, params: dict[str, str]) -> dict[str, object]:
    """What a system did: printed lines, each agent's firings (module and bindings, in
    order), beliefs and goals at the end, and its summary."""
    output = io.StringIO()
    if path.suffix == ".mas2g":
        system = MultiAgentSystem.from_mas_file(path, output=output, warn=lambda m: None)
    else:
        system = MultiAgentSystem.for_agent_file(
            path, environment=environment, output=output, warn=lambda m: None,
            env_params={key: parse_parameter(value) for key, value in params.items()})
    firings: list[tuple[str, str, list[str]]] = []
    try:
        def record(agent) -> None:
            for fired in agent.last_report.fired:
                firings.append((fired.module, unnamed(str(sorted(fired.bindings.items()))),
                                list(fired.actions)))

        system.run(max_cycles=30, after_cycle=record)
        return {
            "printed": output.getvalue(),
            "firings": firings,
            "beliefs": [sorted(unnamed(str(b)) for b in agent.beliefs()
                               if not str(b).startswith(("me(", "received(")))
                        for agent in system.agents],
            "goals": [agent.goals() for agent in system.agents],
            "cycles": [(s.cycles, s.actions, s.status) for s in system.summaries()],
        }
    finally:
        system.close()


@pytest.mark.parametrize("multi, single, environment, params", PAIRS,
                         ids=[pair[1] for pair in PAIRS])
def test_the_same_agent_in_both_formats_does_the_same(
        multi: str, single: str, environment: str | None, params: dict[str, str]) -> None:
    in_goal6 = run(GOAL6 / multi, environment, params)
    in_goal5 = run(EXAMPLES / single, environment, params)
    assert in_goal6["firings"], "the example did nothing"
    assert in_goal6 == in_goal5


def test_the_multi_file_blocks_builder_reaches_its_goal() -> None:
    result = run(GOAL6 / "blocks/blocks.mas2g", None, {})
    assert result["goals"] == [[]]
    assert {"on(a,b)", "on(b,c)", "on(c,table)"} <= set(result["beliefs"][0])  # type: ignore
    assert [status for _, _, status in result["cycles"]] == ["terminated"]  # type: ignore


def test_a_stacker_on_goals_blocks_world_vocabulary_reaches_its_goal() -> None:
    """start = [2, 3, 0, 5, 0, 7, 0], blocks b1..b7, the gripper entity, GOAL's jar name."""
    system = MultiAgentSystem.from_mas_file(GOAL6 / "stack/stack.mas2g", output=io.StringIO())
    try:
        assert system.environment.entities() == ["gripper"]  # type: ignore[union-attr]
        system.run(max_cycles=20)
        world = system.environment.on  # type: ignore[union-attr]
        assert world == {"b1": "table", "b2": "b1", "b3": "b2", "b4": "table", "b5": "b4",
                         "b6": "b5", "b7": "b6"}
        assert [(s.status, s.goals_left) for s in system.summaries()] == [("terminated", 0)]
    finally:
        system.close()


def test_the_multi_file_coffee_pair_uses_goal6_message_syntax() -> None:
    text = (GOAL6 / "coffee" / "makerEvents.mod2g").read_text()
    assert "(Asker).sent?(" in text and "allother.sendonce?(" in text
    result = run(GOAL6 / "coffee/coffee.mas2g", None, {})
    assert result["printed"] == "made(coffee)\n"


def test_cli_checks_and_runs_every_multi_file_example() -> None:
    systems = sorted(GOAL6.glob("*/*.mas2g"))
    assert len(systems) == 8  # blocks, chores, coffee, stack, tower; bw4t, elevator, hanoi
    files = [str(p) for p in systems] + [str(p) for p in GOAL6.glob("*/*.mod2g")]
    checked = subprocess.run([sys.executable, "-m", "goalagent", "check", *files],
                             capture_output=True, text=True, timeout=120)
    assert checked.returncode == 0, checked.stderr
    assert checked.stderr.count(": ok") == len(files)
    coffee = str(GOAL6 / "coffee/coffee.mas2g")
    ran = subprocess.run([sys.executable, "-m", "goalagent", "run", coffee],
                         capture_output=True, text=True, timeout=120)
    assert ran.returncode == 0 and ran.stdout == "made(coffee)\n", ran.stderr
    assert re.findall(r"(\w+): terminated", ran.stderr) == ["maker", "grinder"]


def test_a_multi_file_agent_knows_the_others() -> None:
    system = MultiAgentSystem.from_mas_file(GOAL6 / "coffee/coffee.mas2g",
                                            output=io.StringIO())
    try:
        assert {str(a["A"]) for a in system.agents[0].query("bel", "agent(A)")} == {
            "maker", "grinder"}
        assert system.agents[0].query("bel", "canMake(M, P)") == [{"M": "maker",
                                                                   "P": ["coffee"]}]
        assert [[str(fact) for fact in goal] for goal in system.agents[1].goals()] == [
            ["served"]]
    finally:
        system.close()

"""Every example agent runs the same with and without the trace: alone, on its environment,
as a multi-agent system, and the garbage disposal robot in MuJoCo. The trace observes the
one rule interpreter; it must never change what the agents do."""

from __future__ import annotations

import io
import re
from pathlib import Path

import pytest

from goalagent.agent import Event, EventKind
from goalagent.kb.terms import Atom
from goalagent.mas import MultiAgentSystem

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "agents" / "examples"
ALONE = sorted(path.name for path in EXAMPLES.glob("*.goal"))
ON_ENVIRONMENTS = [
    ("tower_builder.goal", "towerworld", {"seed": 2}),
    ("tower_agent.goal", "towerworld", {"blocks": 6, "seed": 6}),
    ("blocks_builder.goal", "blocksworld", {"seed": 3}),
    ("stack_builder.goal", "blocksworld", {"seed": 4}),
    ("table_agent.goal", "blocksworld", {"seed": 5}),
    ("script_printer.goal", "printer", {}),
]
SYSTEMS = sorted(path.name for path in EXAMPLES.glob("*.mas2g"))


def outcome(make_system, cycles: int, traced: bool) -> tuple:
    """Per agent and cycle the actions, then each agent's beliefs and goals, the summaries,
    the output and the warnings of one run (with a tracer that keeps every event when
    ``traced``); the events too."""
    output, warnings, events = io.StringIO(), [], []
    system = make_system(output=output, warn=warnings.append,
                         tracer=(lambda agent, kind, text: events.append((kind, text)))
                         if traced else None)
    actions: list = []
    try:
        summaries = system.run(cycles, after_cycle=lambda agent: actions.append(
            (agent.name, agent.cycle, agent.last_report.actions)))
        final = [(agent.name, agent.beliefs(), agent.goals()) for agent in system.agents]
    finally:
        system.close()
    shown = re.sub(r"_G\d+", "_G", repr((actions, final, [str(s) for s in summaries],
                                         output.getvalue(), warnings)))
    return shown, events


def same_with_and_without_trace(make_system, cycles: int) -> list:
    plain, _ = outcome(make_system, cycles, traced=False)
    traced, events = outcome(make_system, cycles, traced=True)
    assert plain == traced
    assert EventKind.RULE_TRIED in {kind for kind, _ in events}
    return events


@pytest.mark.parametrize("name", ALONE)
def test_every_example_alone(name: str) -> None:
    same_with_and_without_trace(
        lambda **kw: MultiAgentSystem.for_agent_file(EXAMPLES / name, **kw), 40)


@pytest.mark.parametrize(("name", "env", "params"), ON_ENVIRONMENTS)
def test_every_example_on_its_environment(name: str, env: str, params: dict) -> None:
    same_with_and_without_trace(
        lambda **kw: MultiAgentSystem.for_agent_file(EXAMPLES / name, environment=env,
                                                     env_params=params, **kw), 60)


@pytest.mark.parametrize("name", SYSTEMS)
def test_every_example_system(name: str) -> None:
    same_with_and_without_trace(
        lambda **kw: MultiAgentSystem.from_mas_file(EXAMPLES / name, **kw), 60)


def test_the_garbage_disposal_robot() -> None:
    """The first trial of Experiment 1 on can o1 (learning the lid included)."""
    events = same_with_and_without_trace(
        lambda **kw: MultiAgentSystem.from_mas_file(ROOT / "agents" / "garbage_disposal.mas2g",
                                                    env_params={"trials": 1}, **kw), 12)
    kinds = {kind for kind, _ in events}
    assert {EventKind.PERCEPTS, EventKind.RULE_FIRED, EventKind.BELIEF_ADDED,
            EventKind.BELIEF_DELETED, EventKind.GOAL_ADOPTED} <= kinds


def test_the_trace_shows_every_step() -> None:
    """Rules tried with their instantiations, firings with bindings and actions, belief
    and goal changes, refused actions and failed preconditions, module calls."""
    events: list[Event] = []
    system = MultiAgentSystem.for_agent_file(EXAMPLES / "user_modules.goal",
                                             output=io.StringIO(), warn=lambda m: None)
    agent = system.agents[0]
    agent.listen(events.append)
    try:
        system.run(10)
    finally:
        system.close()
    tried = next(e for e in events if e.kind is EventKind.RULE_TRIED and len(e.instantiations) == 2)
    assert tried.pos is not None and tried.pos.line == 23 and tried.module == "main"
    assert tried.instantiations == ({"Task": Atom("dishes")}, {"Task": Atom("laundry")})
    assert tried.bindings == {}  # a tried rule has no one binding: see instantiations
    assert "[Task=dishes] [Task=laundry]" in tried.text
    fired = [e for e in events if e.kind is EventKind.RULE_FIRED]
    assert fired[0].bindings == {"Task": Atom("ironing")}
    assert fired[0].instantiations == ({"Task": Atom("ironing")},)
    assert fired[0].text.endswith("-> drop(done(ironing)) + insert(skipped(ironing))")
    kinds = [e.kind for e in events]
    for kind in (EventKind.GOAL_DROPPED, EventKind.BELIEF_ADDED, EventKind.GOAL_ACHIEVED,
                 EventKind.MODULE_ENTERED):
        assert kind in kinds
    entered = next(e for e in events if e.kind is EventKind.MODULE_ENTERED)
    assert entered.text == "module chore(dishes)"

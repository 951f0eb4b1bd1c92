"""The bw4t, elevator and hanoi examples in GOAL 6's multi-file format (agents/examples/goal6)
do exactly what their single-file counterparts do: the same rules fired with the same bindings
in the same order, the same beliefs (but received/2: GOAL 6 keeps a message one cycle, GOAL
4/5 until deleted), goals and summaries, and the same world at the end."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from goalagent.mas import MultiAgentSystem, parse_parameter

EXAMPLES = Path(__file__).resolve().parents[4] / "agents" / "examples"
GOAL6 = EXAMPLES / "goal6"


def world_of(system: MultiAgentSystem) -> object:
    """What the environment ended in."""
    env = system.environment
    if hasattr(env, "world"):
        return (env.world.sequence_index, [(b.id, b.x, b.y, b.placed) for b in env.world.blocks])
    if hasattr(env, "building"):
        return [(p.floor, p.destination, p.arrived) for p in env.building.people]
    return env.pins


def run(system: MultiAgentSystem, cycles: int) -> dict[str, object]:
    firings: list[tuple[str, str, list[str]]] = []

    def record(agent) -> None:
        for fired in agent.last_report.fired:
            bindings = re.sub(r"_G\d+", "_G", str(sorted(fired.bindings.items())))
            firings.append((agent.name, fired.module, bindings, list(fired.actions)))

    try:
        summaries = system.run(max_cycles=cycles, after_cycle=record)
        return {
            "firings": firings,
            "beliefs": [sorted(str(b) for b in agent.beliefs()
                         if not str(b).startswith(("me(", "received(")))
                        for agent in system.agents],
            "goals": [agent.goals() for agent in system.agents],
            "summaries": [(s.name, s.cycles, s.actions, s.status) for s in summaries],
            "world": world_of(system),
        }
    finally:
        system.close()


@pytest.mark.parametrize(
    ("multi", "single", "environment", "params", "cycles"),
    [
        ("bw4t/bw4t.mas2g", "bw4t_team.mas2g", None, {}, 400),
        ("elevator/elevator.mas2g", "elevator.mas2g", None, {}, 200),
        ("hanoi/hanoi.mas2g", "hanoi_solver.goal", "hanoi", {"discs": "[0,0,0,0]"}, 40),
    ],
    ids=["bw4t", "elevator", "hanoi"],
)
def test_the_same_system_in_both_formats(multi: str, single: str, environment: str | None,
                                         params: dict[str, str], cycles: int) -> None:
    goal6 = run(MultiAgentSystem.from_mas_file(GOAL6 / multi, warn=lambda m: None), cycles)
    if single.endswith(".mas2g"):
        classic = MultiAgentSystem.from_mas_file(EXAMPLES / single, warn=lambda m: None)
    else:
        classic = MultiAgentSystem.for_agent_file(
            EXAMPLES / single, environment=environment, warn=lambda m: None,
            env_params={key: parse_parameter(value) for key, value in params.items()})
    goal5 = run(classic, cycles)
    assert goal6["firings"], "the example did nothing"
    assert all(status == "terminated" for *_, status in goal6["summaries"])  # type: ignore
    if single == "hanoi_solver.goal":  # one agent, named after its file in GOAL 5
        goal5["firings"] = [("solver", *f[1:]) for f in goal5["firings"]]  # type: ignore
        goal5["summaries"] = [("solver", *s[1:]) for s in goal5["summaries"]]  # type: ignore
    assert goal6 == goal5

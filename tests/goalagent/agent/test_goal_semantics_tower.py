"""The tower agent (agents/examples/tower_agent.goal, written like the Programming Guide's
tower agent) builds both towers from every start state, whatever the seed, because an if
rule fires with an instantiation drawn at random (GOAL's semantics); always taking Prolog's
first answer, it switches between two blocks forever from some start states."""

from __future__ import annotations

import io
import random
from pathlib import Path

import pytest

from goalagent.eis.envs.blocksworld import random_towers
from goalagent.kb.terms import Atom, Struct
from goalagent.mas import MultiAgentSystem

AGENT = Path(__file__).resolve().parents[3] / "agents" / "examples" / "tower_agent.goal"
TOWERS = {("a", "b"), ("b", "c"), ("c", "table"), ("d", "e"), ("e", "f"), ("f", "table")}


def on(block: str, below: str) -> Struct:
    return Struct("on", (Atom(block), Atom(below)))


def stacking(pairs: str) -> list[Struct]:
    """``"ab bc c-"``: a on b, b on c, c on the table."""
    return [on(p[0], "table" if p[1] == "-" else p[1]) for p in pairs.split()]


START_STATES = {
    "on the table": stacking("a- b- c- d- e- f-"),
    "upside down": stacking("cb ba a- fe ed d-"),
    "one tall tower": stacking("ab bc cd de ef f-"),
    "crossed": stacking("ad d- be e- cf f-"),
    **{f"random {seed}": [on(block, below) for block, below in
                          random_towers(list("abcdef"), random.Random(seed)).items()]
       for seed in (100, 101, 102)},
}


def build(state: list[Struct], seed: int, first_answer: bool = False,
          cycles: int = 120) -> int | None:
    """The cycle at which both towers stand (None: not within ``cycles``)."""
    system = MultiAgentSystem.for_agent_file(AGENT, environment="towerworld",
                                             env_params={"state": state}, seed=seed,
                                             output=io.StringIO(), warn=lambda m: None)
    try:
        agent = system.agents[0]
        if first_answer:  # what an interpreter taking Prolog's first answer would do
            agent.random.shuffle = lambda order: None  # type: ignore[method-assign]
        world = system.environment
        while agent.cycle < cycles and not agent.terminated:
            agent.step()
            if set(world.on.items()) == TOWERS and world.holding is None:  # type: ignore
                return agent.cycle
        return None
    finally:
        system.close()


@pytest.mark.parametrize("start", list(START_STATES))
def test_the_tower_agent_builds_both_towers_from_every_start_state(start: str) -> None:
    done = [build(START_STATES[start], seed) for seed in range(3)]
    assert all(cycle is not None and cycle <= 60 for cycle in done), done


def test_with_the_first_answer_alone_it_livelocks_from_some_start_states() -> None:
    stuck = [start for start in ("one tall tower", "crossed", "upside down")
             if build(START_STATES[start], seed=0, first_answer=True) is None]
    assert stuck == ["one tall tower", "crossed"]

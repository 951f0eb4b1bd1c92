"""What ``--max-memory`` charges an agent for the terms it keeps under its own keys
(goalagent/kb/memory.pl, keys_bytes/2): a global variable is a copy on the global stack, a
word (8 bytes) a cell; a record is compiled to a compact code, charged at about its
serialized size. Charging a record by its cells ran three times ahead of what the process
grew by, so the watchdog's alarm, which follows that growth, came when an agent keeping a
record a cycle already held five budgets (CI, 2026-11-27)."""

from __future__ import annotations

import io

import pytest

from goalagent.agent import Agent
from goalagent.kb.watchdog import watchdog
from goalagent.parser import parse_agent

LENGTH = 300_000
KEEPS = {
    "nothing": "length(L, _)",
    "a global variable": "nb_setval(k, L)",
    "a record": "recordz(k, L)",
}


def _held_after_keeping(keep: str) -> int:
    """The bytes the agent holds (clauses and keys, atoms' text aside) after one cycle whose
    rule makes the list 1..LENGTH and does ``keep`` with it."""
    agent = Agent(parse_agent("main module [exit=always] { program {\n"
                              f"  if bel(numlist(1, {LENGTH}, L), {keep}) then print(kept).\n"
                              "} }", "keep.goal"), output=io.StringIO())
    try:
        agent.step()
        result = agent.ms.engine.call("held", agent.ms.belief_module, 2**62, 0, None,
                                      module="ga_memory")
        assert result is not None
        return int(result[3])
    finally:
        agent.close()


@pytest.fixture(scope="module")
def held() -> dict[str, int]:
    return {name: _held_after_keeping(keep) for name, keep in KEEPS.items()}


def test_a_global_variable_is_charged_a_word_a_cell(held: dict[str, int]):
    # a list cell is three cells ('[|]', head, tail): 3 * 8 bytes an element; the programs'
    # own clauses differ by a few hundred bytes
    assert held["a global variable"] - held["nothing"] == pytest.approx(3 * 8 * LENGTH, abs=2_000)


def test_a_record_is_charged_its_compact_size_not_its_cells(held: dict[str, int]):
    charged = held["a record"] - held["nothing"]
    # at least a byte an integer; under a third of its cells' 3 * 8 bytes an element
    assert LENGTH < charged < 8 * LENGTH


def test_a_memory_signal_for_a_closed_agent_does_nothing():
    # the watchdog's note of the running agent outlived it: its signal came into a query of
    # no agent's (reading a percept's text) and that query failed with "Unknown procedure:
    # '$ga_gm'/1" (once in a suite run)
    agent = Agent(parse_agent("main module [exit=always] { program { if true then "
                              "print(x). } }", "c.goal"), output=io.StringIO())
    engine, module = agent.ms.engine, agent.ms.belief_module
    agent.step()
    agent.close()
    assert watchdog().running is None
    for goal in ("held_check", "call_growth"):
        args = (module, 1) if goal == "held_check" else (module, 1, 0, 4096)
        assert engine.call(goal, *args, module="ga_memory") is not None, goal

"""The benchmark's three implementations of the reference agent do the same work.

bench/cycles.py compares goalagent with a one-predicate Prolog floor and python-agentspeak;
the ratios mean something only if all three compute the same thing, so each is run for a few
cycles and checked against a plain-Python model of the agent (and bench/agents.py's
measurement is run on a tiny population).
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

BENCH = Path(__file__).resolve().parents[2] / "bench"
READINGS = [3, 7, 1, 9, 4, 0, 8, 2, 6, 5]
WEIGHTS = [2, 3, 5, 7, 11, 13, 17]


def _load(name: str) -> ModuleType:
    """Imports bench/<name>.py (bench/ is a folder of scripts, not a package)."""
    spec = importlib.util.spec_from_file_location(f"bench_{name}", BENCH / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


cycles = _load("cycles")
agents = _load("agents")


def model(n: int) -> cycles.FinalState:
    """The reference agent's state after ``n`` cycles, computed directly in Python."""
    cycle, total, flag, checkpoint, high = 0, 0, "off", 10, set()
    for _ in range(n):
        threshold = cycle % 10
        high |= {i for i, v in enumerate(READINGS) if v > threshold}
        high -= {i for i in high if READINGS[i] <= threshold}
        cycle += 1
        total = (total + WEIGHTS[cycle % 7] * cycle) % 1000003
        flag = "on" if flag == "off" else "off"
        if cycle >= checkpoint:
            checkpoint = cycle + 10
    return cycles.FinalState(cycle, total, flag, checkpoint, tuple(sorted(high)))


@pytest.mark.parametrize("n", [1, 9, 75])
def test_goalagent_and_floor_match_the_model(n: int) -> None:
    expected = model(n)
    assert cycles.goalagent_run(n)[1] == expected
    assert cycles.floor_run(n)[1] == expected
    assert cycles.floor_per_rule_run(n)[1] == expected


def test_floor_restarts_from_the_initial_state() -> None:
    cycles.floor_run(30)
    assert cycles.floor_run(12)[1] == model(12)


def test_agentspeak_twin_matches_the_model() -> None:
    pytest.importorskip("agentspeak")
    assert cycles.agentspeak_run(75)[1] == model(75)


def test_model_state_is_not_trivial() -> None:
    """Guards the comparisons: after 13 cycles readings above 2 are high, checkpoint moved."""
    state = model(13)
    assert state.high == (0, 1, 3, 4, 6, 8, 9) and state.sum > 0 and state.checkpoint == 20


def test_scale_measurement_on_a_small_population() -> None:
    result = agents.measure(3, 4)
    assert (result.agents, result.cycles) == (3, 4)
    assert result.run_seconds > 0 and result.run_cpu_seconds > 0
    assert result.rss_after_kb >= result.rss_before_kb > 0


def test_small_populations_run_more_cycles() -> None:
    assert agents.cycles_for(10, 20) == agents.MIN_AGENT_CYCLES // 10
    assert agents.cycles_for(10_000, 20) == 20


def test_messaging_measurement_checks_every_ping_arrives() -> None:
    result = agents.measure(3, 4, messaging=True)  # raises unless each heard its neighbour
    assert (result.agents, result.cycles) == (3, 4)


def test_the_cycle_split_times_every_layer_of_the_reference_agent(monkeypatch) -> None:
    monkeypatch.syspath_prepend(str(BENCH))  # (cycle_split imports cycles as a script does)
    rows = _load("cycle_split").measure_layers(cycles=100, repeats=1)
    assert [name for name, _ in rows] == [
        "Agent.step", "one interpreter call (journal recorded)",
        "the C calls alone (no journal record)", "in Prolog alone",
        "floor through Engine.solve", "floor in Prolog alone"]
    assert all(micros > 0 for _, micros in rows)

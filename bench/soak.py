"""Soak benchmark: many agents for many cycles in one process, as a long run would go.

Launches ``--agents`` copies (default 100) of bench/reference_agent.goal in one
``MultiAgentSystem`` (each with the default limits: inference and time bounds, the belief
bound, private modules) and runs ``--cycles`` rounds (default 10,000) in which every agent
runs one cycle. Reported for the first and the last ``--window`` rounds: the agent-cycle
rate (agent-cycles per CPU second of this process, and per wall-clock second), and the
resident memory (VmRSS) at the start, after the first window and at the end. A long run
is healthy when the rate at the end is that of the start and memory stops growing once
the agents' belief bases are at their steady size. Any agent failure or warning fails the
run. Not a test: ``python bench/soak.py [--agents 100] [--cycles 10000]``.
"""

from __future__ import annotations

import io
import resource
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table

from goalagent.mas import MultiAgentSystem
from goalagent.parser import parse_agent_file

BENCH = Path(__file__).resolve().parent
GOAL_FILE = BENCH / "reference_agent.goal"

console = Console(highlight=False, width=110)


def resident_mb() -> float:
    """This process's resident memory now (VmRSS), in MB."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


@dataclass(frozen=True)
class Window:
    """Some rounds of the soak: how many agent-cycles, in how much CPU and wall time."""

    rounds: int
    agent_cycles: int
    cpu: float
    wall: float

    @property
    def cpu_rate(self) -> float:
        return self.agent_cycles / self.cpu

    @property
    def wall_rate(self) -> float:
        return self.agent_cycles / self.wall


def run_rounds(system: MultiAgentSystem, rounds: int) -> Window:
    """``rounds`` rounds of one cycle per agent, timed."""
    cpu0, wall0 = time.process_time(), time.perf_counter()
    for _ in range(rounds):
        for agent in system.agents:
            system.step(agent)
    cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    return Window(rounds, rounds * len(system.agents), cpu, wall)


def main(
    agents: Annotated[int, typer.Option(help="Agents in the one process.")] = 100,
    cycles: Annotated[int, typer.Option(help="Cycles each agent runs.")] = 10_000,
    window: Annotated[int, typer.Option(help="Rounds timed at the start and at the end.")] = 500,
) -> None:
    """Run the soak and print rate and memory at its start and end."""
    if not 0 < 2 * window <= cycles:
        raise typer.BadParameter("--window must be at most half of --cycles")
    warnings: list[str] = []
    program = parse_agent_file(GOAL_FILE)
    memory = {"before loading": resident_mb()}
    system = MultiAgentSystem(output=io.StringIO(), warn=warnings.append)
    for index in range(agents):
        system.launch(f"agent{index}", program)
    run_rounds(system, 1)  # init modules, compilation
    memory["start (agents loaded, 1 cycle)"] = resident_mb()
    first = run_rounds(system, window)
    memory[f"after {window + 1} cycles"] = resident_mb()
    middle = cycles - 1 - 2 * window
    step = max(middle // 10, 1)
    done = 0
    while done < middle:
        run_rounds(system, min(step, middle - done))
        done += min(step, middle - done)
        console.print(f"  ... {window + 1 + done} of {cycles} cycles, "
                      f"RSS {resident_mb():.1f} MB", markup=False)
    last = run_rounds(system, window)
    memory[f"end ({cycles} cycles)"] = resident_mb()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    failures = dict(system.failures)
    beliefs = len(system.agents[0].beliefs())
    system.close()

    table = Table(title=f"soak: {agents} agents x {cycles:,} cycles of "
                        f"{GOAL_FILE.name} ({agents * cycles:,} agent-cycles)")
    for column in ("window", "agent-cycles/s (CPU)", "agent-cycles/s (wall)", "µs/cycle (CPU)"):
        table.add_column(column, justify="left" if column == "window" else "right")
    for name, part in ((f"first {window} rounds", first), (f"last {window} rounds", last)):
        table.add_row(name, f"{part.cpu_rate:,.0f}", f"{part.wall_rate:,.0f}",
                      f"{1e6 / part.cpu_rate:.1f}")
    console.print(table)
    memory_table = Table(title="resident memory (VmRSS)")
    memory_table.add_column("when")
    memory_table.add_column("MB", justify="right")
    for when, mb in memory.items():
        memory_table.add_row(when, f"{mb:.1f}")
    memory_table.add_row("peak (ru_maxrss)", f"{peak:.1f}")
    console.print(memory_table)
    growth = memory[f"end ({cycles} cycles)"] - memory[f"after {window + 1} cycles"]
    console.print(f"end/start rate (CPU): {last.cpu_rate / first.cpu_rate:.3f}; memory growth "
                  f"after the first window: {growth:+.1f} MB; beliefs per agent at the end: "
                  f"{beliefs}", markup=False)
    if failures or warnings:
        console.print(f"FAILED: {len(failures)} agents failed, {len(warnings)} warnings: "
                      f"{list(failures.items())[:3]} {warnings[:3]}", markup=False)
        raise typer.Exit(code=1)


if __name__ == "__main__":
    typer.run(main)

"""Scale benchmark: N copies of the reference agent in one process, stepped round-robin.

For N = 10, 100, 1,000, 10,000 (up to ``--max-agents``; 100,000 with ``--huge``), a fresh
child process loads N
copies of bench/reference_agent.goal (one parse, N agents launched by one
``MultiAgentSystem``, each in its own Prolog modules), runs one untimed round, then times
``cycles`` rounds in which every agent runs one cycle. Reported per N: the per-agent cycle
rate (agent-cycles per second: how fast one agent's cycle is done when N agents share the
process; flat means no per-agent slowdown), from the process's CPU time (the machine is
shared, so wall time is shown too but is noisy), and resident memory per agent (VmRSS from
/proc/self/status, after minus before loading the N agents). Small N run more cycles so
every N does at least ``MIN_AGENT_CYCLES`` agent-cycles. ``--messaging``: the agents are
bench/messaging_agent.goal, which also sends one message a cycle to its neighbour (the
next agent, round the ring) and reads the one it gets.
Not a test: ``python bench/agents.py [--max-agents 1000] [--huge] [--messaging]``.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table

from goalagent.agent import Agent
from goalagent.kb.terms import Atom
from goalagent.mas import MultiAgentSystem
from goalagent.mas_capacity import agent_capacity
from goalagent.parser import parse_agent_file

BENCH = Path(__file__).resolve().parent
GOAL_FILE = BENCH / "reference_agent.goal"
MESSAGING_FILE = BENCH / "messaging_agent.goal"
SIZES = (10, 100, 1_000, 10_000)
HUGE = 100_000  # only with --huge: about 5 GB and minutes of CPU
MIN_AGENT_CYCLES = 20_000
TARGETS = {1_000: 0.8, 10_000: 0.7}  # per-agent rate at N agents / at 10 agents

console = Console(highlight=False, width=140)


@dataclass(frozen=True)
class ScaleResult:
    """One N: timings, memory and the end state check, as measured in a child process."""

    agents: int
    cycles: int
    load_seconds: float
    load_cpu_seconds: float
    run_seconds: float
    run_cpu_seconds: float
    close_seconds: float
    rss_before_kb: int
    rss_after_kb: int

    @property
    def agent_cycle_rate(self) -> float:
        """Agent-cycles per CPU second: the rate of one agent's cycle when N share the process."""
        return self.agents * self.cycles / self.run_cpu_seconds

    @property
    def wall_rate(self) -> float:
        """Agent-cycles per wall-clock second (includes time other processes took)."""
        return self.agents * self.cycles / self.run_seconds

    @property
    def kb_per_agent(self) -> float:
        return (self.rss_after_kb - self.rss_before_kb) / self.agents


def rss_kb() -> int:
    """Resident memory of this process in KiB (VmRSS; psutil is not a dependency)."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError("no VmRSS in /proc/self/status")


def cycles_for(agents: int, minimum: int) -> int:
    """Cycles per agent for N agents: at least ``minimum``, and enough agent-cycles in all."""
    return max(minimum, math.ceil(MIN_AGENT_CYCLES / agents))


def measure(agents: int, cycles: int, messaging: bool = False) -> ScaleResult:
    """Loads ``agents`` reference agents (messaging ones with ``messaging``), times
    ``cycles`` round-robin rounds, frees them."""
    program = parse_agent_file(MESSAGING_FILE if messaging else GOAL_FILE)
    Agent(program, name="warmup").close()  # engine, support library and caches in place
    system = MultiAgentSystem(warn=lambda message: None)
    before = rss_kb()
    start, cpu_start = time.perf_counter(), time.process_time()
    for index in range(agents):
        system.launch(f"agent{index}", program)
    population = system.agents
    loaded, cpu_loaded = time.perf_counter(), time.process_time()
    if messaging:  # each agent's neighbour: the next one, round the ring
        for index, agent in enumerate(population):
            agent.ms.delete("neighbour(nobody)")
            agent.ms.insert("neighbour(N)", {"N": Atom(population[index - 1].name)})
    for agent in population:  # first cycle (init module, first touches) is not timed
        agent.step()
    run_start, run_cpu_start = time.perf_counter(), time.process_time()
    for _ in range(cycles):
        for agent in population:
            agent.step()
    run_end, run_cpu_end = time.perf_counter(), time.process_time()
    after = rss_kb()
    expected = cycles + 1
    for agent in (population[0], population[-1]):
        counted = agent.query("bel", "cycle(C)")
        if counted != [{"C": expected}]:
            raise RuntimeError(f"{agent.name} counted {counted}, expected cycle({expected})")
        if messaging:  # it heard the agent before it, round the ring
            heard = agent.query("bel", "heard(S)")
            sender = population[(population.index(agent) + 1) % agents].name
            if heard != [{"S": Atom(sender)}]:
                raise RuntimeError(f"{agent.name} heard {heard}, expected {sender}")
    close_start = time.perf_counter()
    system.close()
    closed = time.perf_counter()
    return ScaleResult(agents, cycles, loaded - start, cpu_loaded - cpu_start,
                       run_end - run_start, run_cpu_end - run_cpu_start,
                       closed - close_start, before, after)


def run_child(agents: int, cycles: int, messaging: bool) -> ScaleResult:
    """Measures one N in a fresh Python process, so memory and engine state start clean."""
    command = [sys.executable, str(Path(__file__).resolve()), "--single", str(agents),
               "--cycles", str(cycles)] + (["--messaging"] if messaging else [])
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"N={agents} failed:\n{done.stderr.strip()[-2000:]}")
    return ScaleResult(**json.loads(done.stdout.strip().splitlines()[-1]))


def report(results: list[ScaleResult], messaging: bool) -> None:
    """The scale table and the per-agent rate at 1,000 and 10,000 against 10."""
    kind = "messaging" if messaging else "reference"
    table = Table(title=f"N {kind} agents in one process, round-robin (one child process "
                        "per N)")
    columns = ("agents", "cycles", "launch s", "launch CPU ms/agent", "run s (wall)",
               "agent-cycles/CPU s", "rate / at 10", "CPU µs/a-c", "wall µs/a-c", "RSS MiB",
               "KiB/agent", "close ms/agent")
    for column in columns:
        table.add_column(column, justify="right")
    base = next((r.agent_cycle_rate for r in results if r.agents == 10), None)
    for r in results:
        table.add_row(f"{r.agents:,}", str(r.cycles), f"{r.load_seconds:.2f}",
                      f"{1e3 * r.load_cpu_seconds / r.agents:.2f}",
                      f"{r.run_seconds:.2f}", f"{r.agent_cycle_rate:,.0f}",
                      f"{r.agent_cycle_rate / base:.3f}" if base else "-",
                      f"{1e6 / r.agent_cycle_rate:,.0f}", f"{1e6 / r.wall_rate:,.0f}",
                      f"{r.rss_after_kb / 1024:,.0f}",
                      f"{r.kb_per_agent:,.1f}", f"{1e3 * r.close_seconds / r.agents:.3f}")
    console.print(table)
    console.print("a-c: one agent's cycle; launch s: wall time to launch all N (and the CPU "
                  "time of it per agent); rate / at 10: "
                  "the per-agent rate (CPU) against 10 agents'; RSS: after the timed rounds; "
                  "KiB/agent: RSS growth from loading the agents to the end of the timed "
                  "rounds, per agent.")
    by_n = {r.agents: r for r in results}
    for n, target in TARGETS.items():
        if 10 in by_n and n in by_n:
            ratio = by_n[n].agent_cycle_rate / by_n[10].agent_cycle_rate
            wall = by_n[n].wall_rate / by_n[10].wall_rate
            met = "[green]met[/]" if ratio >= target else "[red]not met[/]"
            console.print(f"per-agent rate at {n:,} agents / at 10 agents: {ratio:.3f} on CPU "
                          f"time (target >= {target:.2f}: {met}); {wall:.3f} on wall time")


def main(
    max_agents: Annotated[int, typer.Option(
        min=10, help="Largest N to run (N = 10, 100, 1000, 10000 up to this).")] = 10_000,
    huge: Annotated[bool, typer.Option(
        help="Also 100,000 agents (about 5 GB; refused when the memory available is "
             "short).")] = False,
    messaging: Annotated[bool, typer.Option(
        help="Agents that also send a message a cycle to a neighbour.")] = False,
    cycles: Annotated[int, typer.Option(
        min=1, help="Minimum timed cycles per agent (small N run more).")] = 20,
    single: Annotated[int, typer.Option(
        min=0, hidden=True, help="Internal: measure this N here and print JSON.")] = 0,
) -> None:
    """Cycle rate and memory per agent for growing numbers of agents in one process."""
    if single:
        print(json.dumps(asdict(measure(single, cycles, messaging))))
        return
    sizes = [n for n in SIZES if n <= max_agents] + ([HUGE] if huge else [])
    if huge and agent_capacity() < HUGE:
        console.print(f"[bold red]error:[/] --huge: {HUGE:,} agents do not fit in the memory "
                      f"available ({agent_capacity():,} do, goalagent.mas_capacity)")
        raise typer.Exit(code=2)
    results = []
    for agents in sizes:
        each = cycles_for(agents, cycles)
        console.print(f"N={agents:,}: {each} cycles each ...", style="dim")
        try:
            results.append(run_child(agents, each, messaging))
        except RuntimeError as err:
            console.print(f"[bold red]error:[/] {err}")
            raise typer.Exit(code=1) from None
    report(results, messaging)


if __name__ == "__main__":
    typer.run(main)

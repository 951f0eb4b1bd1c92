"""Cache misses per agent-cycle at 10 and at 1,000 agents, simulated by valgrind.

``agents.py`` finds an agent's cycle slower when many agents share the process, with the
same instructions and inferences per cycle. This benchmark shows where the difference goes,
independently of the machine's load: it runs the reference agents under ``valgrind
--tool=callgrind --cache-sim=yes`` with a simulated first-level data cache and last-level
cache the sizes of this machine's L1d and L2 (per core; ``--ll-kib`` sets another), once
with ``rounds`` timed rounds after the warm-up and once with none, and divides the
difference by the agent-cycles. The same number of agent-cycles is counted at every N.
Printed per N and per shared object (libswipl, libpython, libc, ...): instructions, L1 and
last-level data misses per agent-cycle. Not a test: ``python bench/locality.py`` (needs
valgrind; about five minutes).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
from collections import defaultdict
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table

BENCH = Path(__file__).resolve().parent
AGENT_CYCLES = 2_000  # counted at every N: N agents times rounds
console = Console(highlight=False, width=140)

# Run inside valgrind: launch N reference agents, two untimed rounds, then `rounds` rounds.
_CHILD = """
import os, sys
from pathlib import Path
from goalagent.agent import Agent
from goalagent.mas import MultiAgentSystem
from goalagent.parser import parse_agent_file
agents, rounds = int(sys.argv[1]), int(sys.argv[2])
program = parse_agent_file(Path({goal!r}))
Agent(program, name="warmup").close()
system = MultiAgentSystem(warn=lambda message: None)
for index in range(agents):
    system.launch(f"agent{{index}}", program)
for _ in range(2 + rounds):
    for agent in system.agents:
        agent.step()
sys.stdout.flush()
os._exit(0)  # closing N agents is not what is measured
"""

Costs = dict[str, dict[str, int]]  # shared object -> event -> count


def simulate(agents: int, rounds: int, ll_kib: int) -> Costs:
    """Self costs per shared object of a run of ``agents`` agents for ``rounds`` rounds."""
    code = _CHILD.format(goal=str(BENCH / "reference_agent.goal"))
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "callgrind.out"
        done = subprocess.run(
            ["valgrind", "--tool=callgrind", "--cache-sim=yes", "--D1=32768,8,64",
             f"--LL={ll_kib * 1024},16,64", f"--callgrind-out-file={out}", sys.executable,
             "-c", code, str(agents), str(rounds)],
            capture_output=True, text=True, check=False,
            env={**os.environ, "PYTHONHASHSEED": "0"})
        if done.returncode != 0 or not out.exists():
            raise SystemExit(f"valgrind run of {agents} agents failed:\n{done.stderr[-2000:]}")
        return self_costs(out.read_text(errors="replace"))


def self_costs(text: str) -> Costs:
    """Sums callgrind's self-cost lines per object (the line after ``calls=`` is a call's
    inclusive cost and is skipped). Written here: the format is a few line kinds, and
    callgrind_annotate groups by function, not by object."""
    events: list[str] = []
    names: dict[str, str] = {}
    costs: Costs = defaultdict(lambda: defaultdict(int))
    current = "?"
    skip_next = False
    for line in text.splitlines():
        if line.startswith("events:"):
            events = line.split()[1:]
        elif line.startswith("ob="):
            current = _name(line[3:], names)
        elif line.startswith("cob="):  # a callee's object: may be where its id is named
            _name(line[4:], names)
        elif line.startswith("calls="):
            skip_next = True
        elif line[:1].isdigit() or line[:1] in "+-*":
            if skip_next:
                skip_next = False
                continue
            values = line.split()[1:]  # the first column is the position
            for event, value in zip(events, values, strict=False):  # trailing zeros are left out
                costs[current][event] += int(value)
    return costs


def _name(field: str, names: dict[str, str]) -> str:
    """An object's name from ``(id) name`` (first use) or ``(id)`` (later uses)."""
    found = re.match(r"\((\d+)\)\s*(.*)", field)
    if found is None:
        return field.strip()
    if found.group(2):
        names[found.group(1)] = Path(found.group(2)).name
    return names.get(found.group(1), "?")


def per_agent_cycle(agents: int, ll_kib: int) -> dict[str, dict[str, float]]:
    """(counted run - run of 0 rounds) / agent-cycles, per object and event."""
    rounds = max(1, AGENT_CYCLES // agents)
    counted, base = simulate(agents, rounds, ll_kib), simulate(agents, 0, ll_kib)
    result: dict[str, dict[str, float]] = {}
    for obj in set(counted) | set(base):
        result[obj] = {event: (counted.get(obj, {}).get(event, 0)
                               - base.get(obj, {}).get(event, 0)) / (agents * rounds)
                       for event in ("Ir", "D1mr", "D1mw", "DLmr", "DLmw")}
    return result


def main(sizes: Annotated[str, typer.Option(help="Agent counts, comma-separated.")] = "10,1000",
         ll_kib: Annotated[int, typer.Option(help="Simulated last-level cache (KiB): this "
                                             "machine's L2 by default.")] = 2048) -> None:
    """Instructions and simulated data-cache misses per agent-cycle, per shared object."""
    if shutil.which("valgrind") is None:
        raise SystemExit("valgrind is not installed (apt-get install valgrind)")
    counts = [int(size) for size in sizes.split(",")]
    measured = {agents: per_agent_cycle(agents, ll_kib) for agents in counts}
    table = Table(title=f"per agent-cycle, simulated L1d 32 KiB and last level {ll_kib:,} KiB")
    for column in ("object", *(f"{kind} @{agents}" for agents in counts
                               for kind in ("instr", "L1 miss", "LL miss"))):
        table.add_column(column, justify="right")
    objects = sorted({obj for costs in measured.values() for obj in costs},
                     key=lambda obj: -measured[counts[-1]].get(obj, {}).get("DLmr", 0))
    for obj in [*objects, "all"]:
        cells = []
        for agents in counts:
            rows = measured[agents].values() if obj == "all" else [measured[agents].get(obj, {})]
            total = defaultdict(float)
            for row in rows:
                for event, value in row.items():
                    total[event] += value
            if obj != "all" and abs(total["Ir"]) < 100 and abs(total["DLmr"]) < 0.5:
                cells = []
                break
            cells += [f"{total['Ir']:,.0f}", f"{total['D1mr'] + total['D1mw']:,.0f}",
                      f"{total['DLmr'] + total['DLmw']:,.1f}"]
        if cells:
            table.add_row(obj, *cells)
    console.print(table, markup=False)


if __name__ == "__main__":
    typer.run(main)

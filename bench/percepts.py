"""The percept and action path between a Python environment and an agent, in instructions.

One step: the agent's percepts of a blocksworld of ten blocks (20 percepts, written as tuple
shorthand) and of a BW4T robot (``Percept.of`` through EIS2Java's filters), taken the way a
multi-agent run takes them (``goalagent.mas_environment.EntityIO``: environment -> EIS
``Percept`` -> the agent's terms), and one blocksworld ``move`` action the other way (agent
term -> EIS ``Action`` -> the environment's method). Counted as instructions.py counts a cycle:
a run of ``--steps`` steps minus a run of none, under ``valgrind --tool=callgrind`` (load does
not matter). ``--wall``: best-of-5 wall time instead (no valgrind; swings with the load).

    .venv/bin/python bench/percepts.py [--steps N] [--wall]
"""

from __future__ import annotations

import shutil
import sys
import time
from pathlib import Path
from typing import Annotated

import typer

ROOT = Path(__file__).resolve().parents[1]
sys.path[0] = str(ROOT)  # not bench/: its sim.py would hide the sim package

from bench.instructions import counted  # noqa: E402

WARMUP = 50

_CHILD = """
import sys
sys.path.insert(0, {root!r})
from bench import percepts
percepts.steps(percepts.Bench(), {warmup} + int(sys.argv[1]))
"""


class Bench:
    """A blocksworld and a BW4T environment, each with agent ``a0`` on its first entity."""

    def __init__(self) -> None:
        from goalagent.eis import load_environment
        from goalagent.kb.terms import Atom, Struct
        from goalagent.mas_environment import EntityIO

        def started(name: str, params: dict[str, object]) -> EntityIO:
            env = load_environment(name)()
            env.init(params)
            env.start()
            env.register_agent("a0")
            env.associate_entity("a0", env.entities()[0])
            return EntityIO(env, "a0")

        blocks = [Struct("on", (Atom(block), Atom("table"))) for block in "abcdefghij"]
        self.blocksworld = started("blocksworld", {"state": blocks})
        self.bw4t = started("bw4t", {"map": "SixRooms", "agentcount": 1})
        self.moves = [Struct("move", (Atom("a"), Atom("b"))),
                      Struct("move", (Atom("a"), Atom("table")))]


def steps(bench: Bench, count: int) -> None:
    """``count`` steps: both agents perceive, the blocksworld agent moves a block."""
    for step in range(count):
        bench.blocksworld.percepts()
        bench.bw4t.percepts()
        bench.blocksworld.act(bench.moves[step % 2])


def main(count: Annotated[int, typer.Option("--steps", min=1, help="Counted steps.")] = 300,
         wall: Annotated[bool, typer.Option(help="Wall time, no valgrind.")] = False) -> None:
    """Instructions (or microseconds) per step of the percept and action path."""
    if wall:
        bench = Bench()
        steps(bench, WARMUP)
        best = float("inf")
        for _ in range(5):
            start = time.perf_counter()
            steps(bench, count)
            best = min(best, time.perf_counter() - start)
        print(f"{best / count * 1e6:,.1f} µs per step")
        return
    if shutil.which("valgrind") is None:
        raise SystemExit("valgrind is not installed (apt-get install valgrind)")
    child = _CHILD.format(root=str(ROOT), warmup=WARMUP)
    per_step = (counted(child, str(count)) - counted(child, "0")) / count
    print(f"{per_step:,.0f} instructions per step")


if __name__ == "__main__":
    typer.run(main)

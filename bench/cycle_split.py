"""Where a reasoning cycle of the reference agent goes, layer by layer (issue 29, item 3).

cycles.py gives goalagent's rate against the floor's; this script peels one warmed-up
reference agent's cycle apart, each layer timed in the same process (best of --repeats runs of
--cycles cycles), from the outside in:

- ``Agent.step``: the whole cycle as a user's program runs it;
- one interpreter call: the cycle's plan called through the engine, its journal recorded and
  released (``Engine.call_once`` and the outcome object);
- the C calls alone: the same plan through the four bare C calls, no journal recorded;
- in Prolog alone: the plan called in a Prolog loop, no C call per cycle;

and the floor, in a Prolog loop and through ``Engine.solve`` once a cycle (what cycles.py
times). The differences are what each layer adds. It reaches inside the agent on purpose (the
cycle's plan, the engine's term references): it is a diagnostic, not an API. Not a test:
``python bench/cycle_split.py``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Annotated

import typer
from cycles import FLOOR_MODULE, GOAL_FILE, check_floor_compilation, load_floor
from rich.console import Console
from rich.table import Table

from goalagent.agent import Agent
from goalagent.kb import calls
from goalagent.kb.clib import (
    PL_call_predicate,
    PL_discard_foreign_frame,
    PL_get_int64,
    PL_open_foreign_frame,
)
from goalagent.kb.engine import Engine, get_engine
from goalagent.kb.interpreter import RunOutcome
from goalagent.kb.terms import Atom, Struct, Var

console = Console(highlight=False, width=100)


def best_of(repeats: int, cycles: int, run: Callable[[int], None]) -> float:
    """The least µs per cycle of ``repeats`` timed calls of ``run(cycles)``."""
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        run(cycles)
        best = min(best, time.perf_counter() - start)
    return best / cycles * 1e6


def prolog_loop(engine: Engine, module: str, name: str, arity: int) -> Callable[[int], None]:
    """``forall(between(1, N, _), Module:Name(_, ...))`` in one Prolog call."""
    def run(cycles: int) -> None:
        goal = Struct(":", (Atom(module), Struct(name, tuple(Var(f"_V{i}")
                                                             for i in range(arity)))
                            if arity else Atom(name)))
        if engine.call("forall", Struct("between", (1, cycles, Var("_N"))), goal,
                       module="user") is None:
            raise SystemExit(f"{module}:{name}/{arity} failed")
    return run


def plan_name(engine: Engine, module: str, handle: int) -> str:
    """The name of the plan predicate whose handle is ``handle`` in ``module``."""
    for index in range(16):
        name = f"$ga_plan{index}"
        if engine.own_predicate(name, 2, module) == handle:
            return name
    raise SystemExit("the cycle's plan predicate was not found")


def measure_layers(cycles: int, repeats: int) -> list[tuple[str, float]]:
    """µs per cycle of each layer of a warmed-up reference agent's cycle, then of the floor
    through ``Engine.solve`` and in a Prolog loop."""
    engine = get_engine()
    agent = Agent.from_file(GOAL_FILE, name="reference")
    agent.run(200)  # past the init cycle, into the steady state
    runner = agent._rules  # (inside the agent: see the docstring)
    plan = runner.cycle_plans[False, False]
    module = str(runner._code._state._b)
    outputs = engine._outputs

    def steps(n: int) -> None:
        for _ in range(n):
            agent.step()

    def interpreter_calls(n: int) -> None:
        for _ in range(n):
            outcome, journal = engine.call_once(plan.handle, 2, (), 0, 1)
            RunOutcome(outcome, engine, journal)

    def bare_calls(n: int) -> None:
        handle = plan.handle
        for _ in range(n):
            frame = PL_open_foreign_frame()
            PL_call_predicate(None, calls.Q_PASS, handle, outputs)
            PL_get_int64(outputs, calls.INT_REF)
            PL_discard_foreign_frame(frame)

    layers = [
        ("Agent.step", best_of(repeats, cycles, steps)),
        ("one interpreter call (journal recorded)", best_of(repeats, cycles, interpreter_calls)),
        ("the C calls alone (no journal record)", best_of(repeats, cycles, bare_calls)),
        ("in Prolog alone", best_of(repeats, cycles, prolog_loop(
            engine, module, plan_name(engine, module, plan.handle), 2))),
    ]
    agent.close()
    load_floor(engine)
    engine.call("reset", module=FLOOR_MODULE)
    step = engine.predicate("step", 0, FLOOR_MODULE)

    def floor_calls(n: int) -> None:
        for _ in range(n):
            engine.solve(step, 0, (), 1)

    return [*layers, ("floor through Engine.solve", best_of(repeats, cycles, floor_calls)),
            ("floor in Prolog alone", best_of(repeats, cycles, prolog_loop(
                engine, FLOOR_MODULE, "step", 0)))]


def main(
    cycles: Annotated[int, typer.Option(min=100, help="Cycles per timed run.")] = 4000,
    repeats: Annotated[int, typer.Option(min=1, help="Timed runs per layer.")] = 7,
) -> None:
    """Time each layer of the reference agent's cycle and the floor's."""
    check_floor_compilation(get_engine())
    rows = measure_layers(cycles, repeats)
    agent_rows, (floor_row, floor_prolog_row) = rows[:4], rows[4:]
    floor, floor_prolog = floor_row[1], floor_prolog_row[1]
    table = Table(title=f"µs per cycle (best of {repeats} runs of {cycles:,} cycles)")
    for column in ("layer", "µs/cycle", "adds", "floor / this"):
        table.add_column(column, justify="left" if column == "layer" else "right")
    inner_layers = [*(micros for _, micros in agent_rows[1:]), 0.0]
    for (name, micros), inner in zip(agent_rows, inner_layers, strict=True):
        table.add_row(name, f"{micros:.2f}", f"{micros - inner:.2f}" if inner else "",
                      f"{floor / micros:.3f}")
    table.add_row(floor_row[0], f"{floor:.2f}", f"{floor - floor_prolog:.2f}", "1.000")
    table.add_row(floor_prolog_row[0], f"{floor_prolog:.2f}", "", "")
    console.print(table)


if __name__ == "__main__":
    typer.run(main)

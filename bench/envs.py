"""Environment benchmark: the bw4t, elevator and hanoi environments (issue 15).

Prints, as rich tables:
- a 3-robot BW4T run: three ``bw4t_robot.goal`` agents for 500 cycles each on the SixRooms map
  with ``ticks=1`` (robots slow enough that the team is still working at cycle 500): wall time
  (target: under 10 s), and the share of it spent inside the environment (perceiving, acting);
- the environments' own cost per step, each against the ``blocksworld`` environment's step
  in the same run (ratio = environment / blocksworld): one step is one entity perceiving and
  one action (for bw4t, three robots perceiving in turn with the world advancing each round,
  and a ``goTo`` every 20 steps; for the elevator, two cars and a ``goto`` every 20 steps).

Times are the best of ``--repeats`` runs.

    .venv/bin/python bench/envs.py [--repeats N] [--steps N]
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path

sys.path[0] = str(Path(__file__).resolve().parents[1])

from rich.console import Console  # noqa: E402
from rich.table import Table  # noqa: E402

from goalagent.eis import Action, Environment, load_environment  # noqa: E402
from goalagent.kb.terms import Atom, Struct  # noqa: E402
from goalagent.mas import MultiAgentSystem  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[1] / "agents" / "examples"
RUN_TARGET_S = 10.0
"""Issue 15's budget for a 3-robot BW4T run of 500 cycles."""


def started(name: str, params: dict[str, object], agents: int | None = None) -> Environment:
    """A running environment with agents ``a0``, ``a1``, ... on its first entities."""
    env = load_environment(name)()
    env.init(params)
    env.start()
    for index, entity in enumerate(env.entities()[:agents]):
        env.register_agent(f"a{index}")
        env.associate_entity(f"a{index}", entity)
    return env


def blocksworld_steps(steps: int) -> float:
    """Seconds for ``steps`` blocksworld steps: perceive, then move a block (a onto b, back)."""
    blocks = "abcdefghij"
    state = [Struct("on", (Atom(b), Atom("table"))) for b in blocks]  # ten blocks on the table
    env = started("blocksworld", {"state": state})
    moves = [Action.of("move", "a", "b"), Action.of("move", "a", "table")]
    start = time.perf_counter()
    for step in range(steps):
        env.get_all_percepts("a0")
        env.perform_action("a0", moves[step % 2])
    return time.perf_counter() - start


def bw4t_steps(steps: int) -> float:
    """Seconds for ``steps`` bw4t steps: three robots perceiving in turn, sent around."""
    env = started("bw4t", {"map": "SixRooms", "agentcount": 3})
    places = ["RoomA1", "RoomB3", "Hall2", "RoomA3", "Hall0", "RoomB1"]
    start = time.perf_counter()
    for step in range(steps):
        agent = f"a{step % 3}"
        env.get_all_percepts(agent)
        if step % 20 == step % 3:
            env.perform_action(agent, Action.of("goTo", places[(step // 20) % len(places)]))
    return time.perf_counter() - start


def elevator_steps(steps: int) -> float:
    """Seconds for ``steps`` elevator steps: two cars perceiving in turn, sent around."""
    env = started("elevator", {"simulation": "Random Rider Insertion", "cars": 2,
                               "people": 40, "insertiontime": 20000, "timefactor": 2})
    start = time.perf_counter()
    for step in range(steps):
        agent = f"a{step % 2}"
        env.get_all_percepts(agent)
        if step % 20 == step % 2:
            floor = 1 + (step // 20) % 10
            env.perform_action(agent, Action.of("goto", floor, "up" if floor < 10 else "down"))
    return time.perf_counter() - start


def hanoi_steps(steps: int) -> float:
    """Seconds for ``steps`` hanoi steps: perceive, then move the smallest of 6 discs."""
    env = started("hanoi", {"discs": [0, 0, 0, 0, 0, 0]})
    start = time.perf_counter()
    for step in range(steps):
        env.get_all_percepts("a0")
        env.perform_action("a0", Action.of("move", 6, (step + 1) % 3))
    return time.perf_counter() - start


def best(work: Callable[[int], float], steps: int, repeats: int) -> float:
    """Microseconds per step, best of ``repeats``."""
    return min(work(steps) for _ in range(repeats)) / steps * 1e6


def team_run(cycles: int) -> tuple[float, float, float, int, int]:
    """The 3-robot run: (setup s, run s, environment s, delivered, sequence length)."""
    start = time.perf_counter()
    system = MultiAgentSystem.from_mas_file(EXAMPLES / "bw4t_team.mas2g",
                                            env_params={"ticks": 1})
    setup = time.perf_counter() - start
    env = system.environment
    spent = [0.0]

    def timed(method: Callable) -> Callable:
        def wrapper(*args: object) -> object:
            begin = time.perf_counter()
            try:
                return method(*args)
            finally:
                spent[0] += time.perf_counter() - begin
        return wrapper

    env.get_all_percepts = timed(env.get_all_percepts)
    env.perform_action = timed(env.perform_action)
    try:
        start = time.perf_counter()
        summaries = system.run(max_cycles=cycles)
        run = time.perf_counter() - start
        if any(s.cycles != cycles for s in summaries):
            raise SystemExit(f"the team stopped early ({summaries}); the run is not {cycles} "
                             "cycles long")
        world = env.world
        return setup, run, spent[0], world.sequence_index, len(world.sequence)
    finally:
        system.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=3000)
    parser.add_argument("--cycles", type=int, default=500)
    args = parser.parse_args()
    console = Console(width=110)

    setup, run, in_env, delivered, wanted = team_run(args.cycles)
    table = Table(title=f"3-robot BW4T run, {args.cycles} cycles per agent (SixRooms, ticks=1)")
    for column in ("setup s", "run s", "target s", "environment s", "environment share",
                   "agent-cycles/s", "delivered"):
        table.add_column(column, justify="right")
    table.add_row(f"{setup:.2f}", f"{run:.2f}", f"< {RUN_TARGET_S:.0f}", f"{in_env:.2f}",
                  f"{in_env / run:.0%}", f"{3 * args.cycles / run:,.0f}",
                  f"{delivered}/{wanted}")
    console.print(table)

    base = best(blocksworld_steps, args.steps, args.repeats)
    steps = Table(title=f"environment cost per step (best of {args.repeats} x {args.steps} steps)")
    for column in ("environment", "µs/step", "ratio to blocksworld"):
        steps.add_column(column, justify="right")
    steps.add_row("blocksworld (baseline)", f"{base:.1f}", "1.00")
    for name, work in (("bw4t", bw4t_steps), ("elevator", elevator_steps),
                       ("hanoi", hanoi_steps)):
        cost = best(work, args.steps, args.repeats)
        steps.add_row(name, f"{cost:.1f}", f"{cost / base:.2f}")
    console.print(steps)


if __name__ == "__main__":
    main()

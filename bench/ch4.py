"""Chapter 4 benchmark: one 3-D active exploration of N_s = 300 steps, and the learners' cost.

Prints, as rich tables:
- seconds for one 3-D active run (Algorithm 3, all 300 steps, truth mode, the hand holding the
  lid of o1 and the handle of o5; target < 15 s) against two baselines measured in the same
  run: the random-exploration run with the same budget, and the active run's own 300 moves
  replayed with no learner at all (the physics and perception alone); the difference per step
  is what the learners cost inside the run;
- microseconds per step of the learners alone (forward model predict + update, CACLA sample +
  actor/critic update; target < 1 ms) against one MuJoCo physics step and one held-part move.

Times are CPU seconds of this process (``time.process_time``), medians of ``--repeats`` runs:
the machine is shared, and wall-clock times there swing several-fold with others' load while
the work itself (single-threaded numpy and MuJoCo) does not change.

    MUJOCO_GL=egl .venv/bin/python bench/ch4.py [--repeats N]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
# Run as a script, this file's folder comes first on sys.path: put the repository root there.
sys.path[0] = str(Path(__file__).resolve().parents[1])

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
from rich.console import Console  # noqa: E402
from rich.table import Table  # noqa: E402

from behaviours.contact import PartContact  # noqa: E402
from behaviours.learners.exploration import ActiveExplorer  # noqa: E402
from sim.world import GarbageWorld  # noqa: E402

BUDGET = 300
"""N_s of Algorithm 3 for 3-D actions (thesis §4.6.1)."""
RUN_TARGET_S = 15.0
STEP_TARGET_US = 1000.0
CONFIGURATIONS = (("o1", "lid"), ("o5", "handle"))


def held_world(can: str, part: str, seed: int) -> tuple[GarbageWorld, PartContact]:
    """A fresh world with the hand holding ``part`` (3-D moves, truth mode)."""
    world = GarbageWorld(can, seed=seed)
    return world, PartContact(world, part, dims=3).start()


def explore_seconds(can: str, part: str, mode: str, seed: int) -> tuple[float, np.ndarray]:
    """Seconds for one run of all BUDGET steps of ``mode``, and the actions it took."""
    world, contact = held_world(can, part, seed)
    try:
        start = time.process_time()
        explorer = ActiveExplorer(mode=mode, n_max=BUDGET, random_state=seed,
                                  stop=False).explore(contact)
        return time.process_time() - start, explorer.history_.actions
    finally:
        world.close()


def replay_seconds(can: str, part: str, actions: np.ndarray, seed: int) -> float:
    """Seconds for the same moves and observations with no learner: physics and perception."""
    world, contact = held_world(can, part, seed)
    try:
        start = time.process_time()
        for action in actions:
            contact.observe()
            contact.step(action)
        return time.process_time() - start
    finally:
        world.close()


class SyntheticLid:
    """A 3-D held part without physics: the opening moves with the first action dimension."""

    action_bounds = [(-0.01, 0.01)] * 3

    def __init__(self) -> None:
        self.state = 0.0
        self.noise = np.random.RandomState(0)

    def observe(self) -> float:
        return self.state

    def step(self, action: np.ndarray) -> float:
        effect = float(action[0]) + 0.001 * self.noise.normal()
        self.state = min(max(self.state + effect, 0.0), 0.08)
        return self.state


def learner_step_us(steps: int) -> float:
    """Microseconds per step of Algorithm 3's learners alone (forward model predict + update,
    CACLA sample + actor/critic update, the check of each observed state) on a synthetic
    3-D world: ``ActiveExplorer`` as the runs use it, with no physics behind it."""
    explorer = ActiveExplorer(mode="active", n_max=steps, n_random=0, random_state=0,
                              stop=False)
    start = time.process_time()
    explorer.explore(SyntheticLid())
    return 1e6 * (time.process_time() - start) / steps


def physics_step_us(steps: int) -> float:
    """Microseconds per MuJoCo step of the o1 scene at rest."""
    world = GarbageWorld("o1")
    try:
        start = time.process_time()
        for _ in range(steps):
            mujoco.mj_step(world.model, world.data)
        return 1e6 * (time.process_time() - start) / steps
    finally:
        world.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    console = Console()

    runs = Table(title=f"One 3-D exploration of N_s = {BUDGET} steps, truth mode "
                       f"(target < {RUN_TARGET_S:g} s; medians of {args.repeats})")
    for column in ("can", "active (s)", "random (s)", "same moves, no learner (s)",
                   "active / random", "active / moves", "learners (µs/step)"):
        runs.add_column(column, justify="right")
    move_ms = []
    for can, part in CONFIGURATIONS:
        active, random, moves, inside = [], [], [], []
        for _ in range(args.repeats):
            seconds, actions = explore_seconds(can, part, "active", 0)
            active.append(seconds)
            random.append(explore_seconds(can, part, "random", 0)[0])
            moves.append(replay_seconds(can, part, actions, 0))
            inside.append(1e6 * (active[-1] - moves[-1]) / BUDGET)
        a, r, m = (statistics.median(times) for times in (active, random, moves))
        move_ms.append(1000 * m / BUDGET)
        runs.add_row(f"{can} {part}", f"{a:.2f}", f"{r:.2f}", f"{m:.2f}", f"{a / r:.2f}",
                     f"{a / m:.2f}", f"{statistics.median(inside):.0f}")
    console.print(runs)

    learner = statistics.median(learner_step_us(5000) for _ in range(args.repeats))
    physics = statistics.median(physics_step_us(20_000) for _ in range(args.repeats))
    move = statistics.median(move_ms)
    costs = Table(title=f"The learners' own cost per step (target < {STEP_TARGET_US:g} µs)")
    for column in ("learners (µs)", "mj_step (µs)", "held-part move (ms)", "learners / mj_step",
                   "learners / move"):
        costs.add_column(column, justify="right")
    costs.add_row(f"{learner:.1f}", f"{physics:.1f}", f"{move:.1f}", f"{learner / physics:.1f}",
                  f"{learner / (1000 * move):.4f}")
    console.print(costs)


if __name__ == "__main__":
    main()

"""Chapter-5 benchmark: ``ch5-transfer`` for the five thesis cans and one seed, truth mode.

Target (issue 11): under 60 s. Printed against a baseline measured in the same run: the same
number of physical actions (each can's functional skill at θ = 0.06 m from a closed can,
observed before and after in truth mode, as the learners measure eq. 5.3/5.15), so the ratio
says what the learners, the similarity model and the bookkeeping add to the physics.

    MUJOCO_GL=egl .venv/bin/python bench/transfer.py [--seed S]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
sys.path[0] = str(Path(__file__).resolve().parents[1])  # the repository, not bench/, first

from rich.console import Console  # noqa: E402
from rich.table import Table  # noqa: E402

from behaviours.part_learning import CanUnderTest  # noqa: E402
from behaviours.perception import make_perception  # noqa: E402
from robot.reproduce.studies.common.ch5 import (  # noqa: E402
    THESIS_CANS,
    PartLearningConfig,
    transfer_run,
)
from sim.scene import CANS  # noqa: E402
from sim.world import GarbageWorld  # noqa: E402

TARGET_SECONDS = 60.0


def physics_baseline(actions: int) -> float:
    """Seconds for ``actions`` functional skills from a closed can, observed in truth mode."""
    world = GarbageWorld("o1", seed=0)
    started = time.perf_counter()
    for index in range(actions):
        spec = CANS[THESIS_CANS[index % len(THESIS_CANS)]]
        if world.can != spec.name:
            world.reset(spec, seed=0)
        CanUnderTest(world, make_perception("truth")).perform(*spec.functional, 0.06)
    seconds = time.perf_counter() - started
    world.close()
    return seconds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=0)
    seed = parser.parse_args().seed
    started = time.perf_counter()
    runs = transfer_run(seed, PartLearningConfig(), "truth").values()
    study = time.perf_counter() - started
    actions = sum(r.n_with + r.n_without for r in runs)
    baseline = physics_baseline(actions)
    table = Table("measure", "seconds", "actions", "ms / action", title="ch5-transfer, truth")
    table.add_row("ch5-transfer (5 cans, with and without transfer)", f"{study:.1f}",
                  str(actions), f"{1000 * study / actions:.1f}")
    table.add_row("baseline: the same number of skills + observations", f"{baseline:.1f}",
                  str(actions), f"{1000 * baseline / actions:.1f}")
    console = Console(highlight=False)
    console.print(table)
    console.print(f"ratio study / baseline: {study / baseline:.2f}; target: study under "
                  f"{TARGET_SECONDS:.0f} s -> {'met' if study < TARGET_SECONDS else 'NOT met'}",
                  markup=False)


if __name__ == "__main__":
    main()

"""Simulation benchmark: physics, motor skills, rendering and segmentation (issue 4).

Prints physics steps/s (and real-time factor), ms per arm skill with truth and with camera
perception of its effect, and ms per rendered + segmented 320x240 head-camera frame with its
two parts measured alone (render, segmentation) as the baselines it is compared with.

    MUJOCO_GL=egl .venv/bin/python bench/sim.py [--repeats N]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
# Run as a script, this file's folder comes first on sys.path and its name would hide the
# `sim` package: put the repository root there instead.
sys.path[0] = str(Path(__file__).resolve().parents[1])

from rich.console import Console  # noqa: E402
from rich.table import Table  # noqa: E402

from behaviours.perception import make_perception, observe_image  # noqa: E402
from behaviours.skills import perform_skill  # noqa: E402
from sim.world import GarbageWorld  # noqa: E402

FUNCTIONAL = {"o1": ("extend_arm", "lid"), "o2": ("lift_up", "handle"),
              "o3": ("extend_arm", "lid"), "o4": ("lift_up", "handle"),
              "o5": ("contract_arm", "handle")}


def best_ms(work: Callable[[], object], repeats: int) -> float:
    """The fastest of ``repeats`` runs of ``work``, in milliseconds."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        work()
        times.append(time.perf_counter() - start)
    return 1000 * min(times)


def skill_ms(can: str, action: str, part: str, mode: str, repeats: int) -> float:
    """Best ms for one skill from a closed can plus perceiving the result in ``mode``."""
    perception = make_perception(mode)
    world = GarbageWorld(can)

    def skill() -> None:
        world.set_opening(0.0)
        perform_skill(world, action, part, 0.06)
        perception.observe(world)

    try:
        return best_ms(skill, repeats)
    finally:
        world.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20, help="repetitions per measure")
    args = parser.parse_args()
    console = Console()

    world = GarbageWorld("o1", width=320, height=240)
    steps = 20_000
    start = time.perf_counter()
    world.step(steps)
    elapsed = time.perf_counter() - start
    timestep = world.model.opt.timestep
    physics = Table(title="Physics (o1, arm at rest)")
    for column in ("steps/s", "real-time factor"):
        physics.add_column(column, justify="right")
    physics.add_row(f"{steps / elapsed:,.0f}", f"{steps * timestep / elapsed:,.0f}x")
    console.print(physics)

    skills = Table(title="One arm skill (the functional one, θ = 0.06 m), then perceive")
    for column in ("can", "skill", "truth ms", "camera ms", "camera / truth"):
        skills.add_column(column, justify="right")
    for can, (action, part) in FUNCTIONAL.items():
        row = [can, f"{action}({part})"]
        measured = [skill_ms(can, action, part, mode, max(3, args.repeats // 4))
                    for mode in ("truth", "camera")]
        row += [f"{measured[0]:.1f}", f"{measured[1]:.1f}", f"{measured[1] / measured[0]:.2f}"]
        skills.add_row(*row)
    console.print(skills)

    world.set_opening(0.08)
    frame = world.render("head")
    render = best_ms(lambda: world.render("head"), args.repeats)
    segment = best_ms(lambda: observe_image(frame), args.repeats)
    both = best_ms(lambda: observe_image(world.render("head")),
                   args.repeats)
    frames = Table(title="Head camera, 320x240 (target: render + segment <= 60 ms)")
    for column in ("measure", "ms", "share of render + segment"):
        frames.add_column(column, justify="right")
    frames.add_row("render alone (baseline)", f"{render:.2f}", f"{render / both:.2f}")
    frames.add_row("segment alone (baseline)", f"{segment:.2f}", f"{segment / both:.2f}")
    frames.add_row("render + segment", f"{both:.2f}", "1.00")
    console.print(frames)
    console.print(f"render + segment within target: {'yes' if both <= 60 else 'no'}")
    world.close()


if __name__ == "__main__":
    main()

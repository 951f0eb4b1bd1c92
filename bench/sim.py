"""Simulation benchmark: physics, motor skills, rendering and segmentation (issue 4).

Prints, as rich tables:
- physics steps/s (and real-time factor) with the arm at rest and inside arm skills (contacts);
- per can, ms for the functional arm skill (θ = 0.06 m from a closed can) alone, and with its
  effect perceived in truth and in camera mode (one observation before, one after, as the
  learner measures eq. 5.3), with the camera / truth ratio;
- ms per rendered + segmented 320x240 head-camera frame against its two baselines, rendering
  alone and segmentation alone, and the truth observation for scale (target: <= 60 ms).

Times are medians of ``--repeats`` runs (``min`` is shown for the frame measures too).

    MUJOCO_GL=egl .venv/bin/python bench/sim.py [--repeats N]
"""

from __future__ import annotations

import argparse
import os
import statistics
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

from behaviours.perception import Perception, make_perception, observe_image  # noqa: E402
from behaviours.skills import perform_skill  # noqa: E402
from sim.scene import CANS  # noqa: E402
from sim.world import GarbageWorld  # noqa: E402

THETA = 0.06
"""Skill parameter (m) of every timed skill: opens each can part way."""
FRAME_TARGET_MS = 60.0
"""Issue 4's budget for one rendered + segmented 320x240 frame on 2 CPU cores."""


def timings(work: Callable[[], object], repeats: int) -> list[float]:
    """Wall-clock milliseconds of ``repeats`` runs of ``work``."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        work()
        times.append(1000 * (time.perf_counter() - start))
    return times


def physics_rates(repeats: int) -> tuple[float, float, float]:
    """Steps/s with the arm at rest, steps/s inside skills, and the model's timestep (s)."""
    world = GarbageWorld("o1")
    try:
        steps = 20_000
        start = time.perf_counter()
        world.step(steps)
        idle = steps / (time.perf_counter() - start)
        total_steps, total_time = 0, 0.0
        for _ in range(repeats):
            world.set_opening(0.0)
            before = world.steps
            start = time.perf_counter()
            perform_skill(world, "extend_arm", "lid", THETA)
            total_time += time.perf_counter() - start
            total_steps += world.steps - before
        return idle, total_steps / total_time, float(world.model.opt.timestep)
    finally:
        world.close()


def skill_row(can: str, repeats: int) -> list[str]:
    """One table row: the can's functional skill alone, with truth, with camera perception."""
    part, action = CANS[can].functional
    world = GarbageWorld(can)
    world.render("head")  # create the GL context outside the timings

    def skill(perception: Perception | None) -> Callable[[], object]:
        def run() -> None:
            world.set_opening(0.0)
            if perception is not None:
                perception.observe(world)
            perform_skill(world, action, part, THETA)
            if perception is not None:
                perception.observe(world)
        return run

    try:
        alone = statistics.median(timings(skill(None), repeats))
        truth = statistics.median(timings(skill(make_perception("truth")), repeats))
        camera = statistics.median(timings(skill(make_perception("camera")), repeats))
    finally:
        world.close()
    return [can, f"{action}({part})", f"{alone:.1f}", f"{truth:.1f}", f"{camera:.1f}",
            f"{camera / truth:.2f}"]


def frame_rows(repeats: int) -> tuple[list[list[str]], float]:
    """Rows for render alone, segment alone, both, truth; and the median ms of both."""
    world = GarbageWorld("o2", width=320, height=240)
    try:
        world.set_opening(0.08)
        frame = world.render("head")
        truth = make_perception("truth")
        measures = {
            "render alone (baseline)": timings(lambda: world.render("head"), repeats),
            "segment alone (baseline)": timings(lambda: observe_image(frame), repeats),
            "render + segment": timings(lambda: observe_image(world.render("head")), repeats),
            "truth observation (no image)": timings(lambda: truth.observe(world), repeats),
        }
    finally:
        world.close()
    both = statistics.median(measures["render + segment"])
    rows = [[name, f"{statistics.median(ms):.2f}", f"{min(ms):.2f}",
             f"{statistics.median(ms) / both:.2f}"] for name, ms in measures.items()]
    return rows, both


def main() -> None:
    """Run every measure and print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20, help="repetitions per measure")
    args = parser.parse_args()
    if args.repeats < 1:
        parser.error("--repeats must be at least 1")
    console = Console()

    idle, loaded, timestep = physics_rates(max(3, args.repeats // 4))
    physics = Table(title=f"Physics (o1, timestep {timestep * 1000:g} ms)")
    for column in ("situation", "steps/s", "real-time factor"):
        physics.add_column(column, justify="right")
    physics.add_row("arm at rest", f"{idle:,.0f}", f"{idle * timestep:,.0f}x")
    physics.add_row(f"inside extend_arm(lid, {THETA})", f"{loaded:,.0f}",
                    f"{loaded * timestep:,.0f}x")
    console.print(physics)

    skills = Table(title=f"Functional arm skill (θ = {THETA} m from closed), ms (median)")
    for column in ("can", "skill", "alone", "+ truth", "+ camera", "camera / truth"):
        skills.add_column(column, justify="right")
    for can in sorted(CANS):
        skills.add_row(*skill_row(can, max(3, args.repeats // 4)))
    console.print(skills)

    rows, both = frame_rows(args.repeats)
    frames = Table(title=f"Head camera frame, 320x240 (target: render + segment <= "
                         f"{FRAME_TARGET_MS:g} ms)")
    for column in ("measure", "median ms", "min ms", "/ render + segment"):
        frames.add_column(column, justify="right")
    for row in rows:
        frames.add_row(*row)
    console.print(frames)
    verdict = "within" if both <= FRAME_TARGET_MS else "OVER"
    console.print(f"render + segment {both:.2f} ms: {verdict} the {FRAME_TARGET_MS:g} ms target "
                  f"({FRAME_TARGET_MS / both:.1f}x headroom)")


if __name__ == "__main__":
    main()

"""Simulation benchmark: physics, motor skills, rendering and segmentation (issue 4).

Prints, as rich tables:
- physics steps/s (and real-time factor) with the arm at rest and inside arm skills (contacts);
- per can, ms for the functional arm skill (θ = 0.06 m from a closed can) alone, and with its
  effect perceived in truth and in camera mode (one observation before, one after, as the
  learner measures eq. 5.3), with the camera / truth ratio;
- ms per rendered + segmented 320x240 head-camera frame against its two baselines, rendering
  alone and segmentation alone, and the truth observation for scale (target: <= 60 ms);
- the XCS task experiments of thesis ch. 3 and App. A (issue 9), in truth and in camera mode:
  seconds per experiment (target: a 20-trial navigation experiment in truth mode < 30 s), the
  camera / truth ratio, and where the time of an action goes (physics, rendering, image
  segmentation or ground-truth projection, XCS and the rest).

Times are medians of ``--repeats`` runs (``min`` is shown for the frame measures too).

    MUJOCO_GL=egl .venv/bin/python bench/sim.py [--repeats N] [--trials N]
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

from behaviours.blob_grid import make_grid_perception  # noqa: E402
from behaviours.object_state import make_object_perception  # noqa: E402
from behaviours.perception import Perception, make_perception, observe_image  # noqa: E402
from behaviours.skills import perform_skill  # noqa: E402
from behaviours.xcs_tasks import NavigationTask, SearchTask, StackingTask  # noqa: E402
from behaviours.xcs_trials import N_STEP, SEARCH_STEPS, make_learner, run_experiment  # noqa: E402
from sim.navigation import NavigationWorld  # noqa: E402
from sim.scene import CANS  # noqa: E402
from sim.search import SearchWorld  # noqa: E402
from sim.stacking import StackingWorld  # noqa: E402
from sim.world import GarbageWorld  # noqa: E402

THETA = 0.06
"""Skill parameter (m) of every timed skill: opens each can part way."""
FRAME_TARGET_MS = 60.0
"""Issue 4's budget for one rendered + segmented 320x240 frame on 2 CPU cores."""
NAVIGATION_TARGET_S = 30.0
"""Issue 9's budget for a 20-trial navigation experiment in truth mode."""
PARTS = ("physics", "render", "seg/proj", "XCS", "rest")
"""Where an action's time goes: world calls, rendering, segmentation (camera) or projection
(truth) of the state, the learner, and the rest (the loop, the affordance table)."""


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


class Stopwatch:
    """Seconds spent inside wrapped callables, summed per part."""

    def __init__(self) -> None:
        """Nothing timed yet."""
        self.spent = dict.fromkeys(PARTS, 0.0)

    def wrap(self, obj: object, method: str, part: str) -> None:
        """Replace ``obj.method`` (on that instance only) by a timed call of the original."""
        original = getattr(obj, method)

        def timed(*args: object, **kwargs: object) -> object:
            start = time.perf_counter()
            try:
                return original(*args, **kwargs)
            finally:
                self.spent[part] += time.perf_counter() - start

        setattr(obj, method, timed)


def task_row(name: str, mode: str, trials: int) -> tuple[list[str], float]:
    """One experiment of ``trials`` trials, timed; the table row and the total seconds."""
    watch = Stopwatch()
    if name == "navigation":
        world: NavigationWorld | StackingWorld | SearchWorld = NavigationWorld()
        for method in ("walk", "push", "reset"):
            watch.wrap(world, method, "physics")
        task = NavigationTask(world, make_object_perception(mode, name), exchange_after=trials // 2)
        learner, n_step = make_learner(task.actions, "affordance_xcs", 0), N_STEP
    elif name == "stacking":
        world = StackingWorld()
        for method in ("choose", "push", "reset"):
            watch.wrap(world, method, "physics")
        task = StackingTask(world, make_object_perception(mode, name))
        learner, n_step = make_learner(task.actions, "affordance_xcs", 0), N_STEP
    else:
        world = SearchWorld()
        for method in ("turn_to", "place_target"):  # look and rest both turn_to
            watch.wrap(world, method, "physics")
        task = SearchTask(world, make_grid_perception(mode), move_after=trials // 2)
        learner = make_learner(task.actions, "standard_xcs", 0, consistent_actions=True)
        n_step = SEARCH_STEPS
    world.render("head")  # the GL context is made once per process, outside the timing
    watch.wrap(world, "render", "render")
    watch.wrap(task.perception, "observe", "seg/proj")
    for method in ("act", "reward"):
        watch.wrap(learner.learner, method, "XCS")
    try:
        start = time.perf_counter()
        records = run_experiment(task, learner, trials=trials, n_step=n_step)
        total = time.perf_counter() - start
    finally:
        world.close()
    watch.spent["seg/proj"] -= watch.spent["render"]  # observe() includes render
    watch.spent["rest"] = total - sum(watch.spent.values())
    actions = sum(r.steps for r in records)
    per_action = [1000 * watch.spent[p] / actions for p in PARTS]
    return ([name, mode, f"{total:.1f}", str(actions), f"{1000 * total / actions:.1f}",
             *(f"{ms:.1f}" for ms in per_action)], total)


def main() -> None:
    """Run every measure and print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20, help="repetitions per measure")
    parser.add_argument("--trials", type=int, default=20,
                        help="trials per XCS task experiment (the search task runs twice as many)")
    args = parser.parse_args()
    if args.repeats < 1:
        parser.error("--repeats must be at least 1")
    if args.trials < 2:
        parser.error("--trials must be at least 2")
    console = Console(width=110)  # the task table is wider than 80 columns

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

    tasks = Table(title=f"XCS task experiments ({args.trials} trials; search {2 * args.trials}),"
                        " ms per action by part")
    for column in ("task", "mode", "s", "actions", "ms/act", *PARTS):
        tasks.add_column(column, justify="right")
    totals = {}
    for name in ("navigation", "stacking", "search"):
        for mode in ("truth", "camera"):
            trials = 2 * args.trials if name == "search" else args.trials
            row, totals[name, mode] = task_row(name, mode, trials)
            tasks.add_row(*row)
    console.print(tasks)
    for name in ("navigation", "stacking", "search"):
        console.print(f"{name}: camera / truth = "
                      f"{totals[name, 'camera'] / totals[name, 'truth']:.2f}")
    navigation = totals["navigation", "truth"] * 20 / args.trials
    verdict = "within" if navigation <= NAVIGATION_TARGET_S else "OVER"
    console.print(f"navigation, truth, scaled to 20 trials: {navigation:.1f} s: {verdict} the "
                  f"{NAVIGATION_TARGET_S:g} s target ({NAVIGATION_TARGET_S / navigation:.1f}x "
                  "headroom)")


if __name__ == "__main__":
    main()

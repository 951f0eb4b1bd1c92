"""The research workbench's speed targets (issue 27), as ratios against a baseline measured in
the same run:

1. Ray backend vs local pool: a 10-seed ``xcs-mux`` run on a Ray cluster started here (one
   node, as many CPUs as ``--jobs``) against the local pool with the same ``--jobs``; each run
   fresh (nothing from the cache), driver start included, the two alternated over ``--rounds``.
   Target: ray / local <= 1.10.
2. Resume: an ``xcs-mux`` sweep killed with SIGKILL once some seeds finished, then run again.
   Target: finished seeds run again / finished seeds = 0; the rerun of the finished sweep runs
   nothing (its time is printed against the whole sweep's).

    MUJOCO_GL=egl .venv/bin/python bench/workbench.py [--scale 1.0] [--jobs 2] [--rounds 2]
"""

from __future__ import annotations

import argparse
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
sys.path[0] = str(Path(__file__).resolve().parents[1])  # the repository, not bench/, first

from rich.console import Console  # noqa: E402
from rich.table import Table  # noqa: E402

from robot.reproduce.framework.local_cluster import local_cluster  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
TALLY = re.compile(r"seeds run: (\d+), from the cache: (\d+)")


def goalagent(*args: str, environment: dict[str, str] | None = None) -> tuple[float, str]:
    """Run ``goalagent ARGS``; (wall seconds, stderr)."""
    started = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "goalagent", *args], cwd=ROOT,
                          capture_output=True, text=True, env=environment)
    if done.returncode != 0:
        raise SystemExit(f"goalagent {' '.join(args)} failed:\n{done.stderr}")
    return time.perf_counter() - started, done.stderr


def tally(text: str) -> tuple[int, int]:
    """(seeds run, seeds from the cache) as the command printed them."""
    match = TALLY.search(text)
    if match is None:
        raise SystemExit(f"no tally in:\n{text}")
    return int(match[1]), int(match[2])


def ray_against_local(scale: float, jobs: int, rounds: int, folder: Path) -> list[tuple]:
    """Per round: (local seconds, ray seconds)."""
    common = ["reproduce", "xcs-mux", "--seeds", "10", "--set", f"scale={scale}", "--fresh",
              "--out", str(folder / "out"), "--cache", str(folder / "cache")]
    times = []
    with local_cluster((jobs,)) as cluster:
        for _ in range(rounds):
            local, _ = goalagent(*common, "--jobs", str(jobs))
            ray, _ = goalagent(*common, "--ray", cluster.address,
                               environment=cluster.environment)
            times.append((local, ray))
    return times


def resume(scale: float, jobs: int, folder: Path) -> dict[str, float]:
    """Kill a sweep once about a third of its seeds finished, run it again, then again."""
    cache = folder / "cache"
    command = [sys.executable, "-m", "goalagent", "sweep", "xcs-mux", "--grid", "N=200,400",
               "--seeds", "4", "--set", f"scale={scale}", "--jobs", str(jobs), "--out",
               str(folder / "out"), "--cache", str(cache)]
    total = 8
    started = time.perf_counter()
    killed = subprocess.Popen(command, cwd=ROOT, stderr=subprocess.DEVNULL,
                              start_new_session=True)
    while (finished := len(list(cache.rglob("*.json")))) < total // 3:
        if killed.poll() is not None:
            raise SystemExit("the sweep ended before it could be killed")
        time.sleep(0.05)
    os.killpg(killed.pid, signal.SIGKILL)
    killed.wait()
    finished = len(list(cache.rglob("*.json")))
    before_kill = time.perf_counter() - started
    resumed_seconds, text = goalagent(*command[3:])
    run, cached = tally(text)
    again_seconds, text = goalagent(*command[3:])
    rerun, _ = tally(text)
    return {"finished before the kill": finished, "seconds before the kill": before_kill,
            "run on resume": run, "from the cache on resume": cached,
            "finished run again": finished - cached, "resumed seconds": resumed_seconds,
            "rerun of the finished sweep: seeds run": rerun, "rerun seconds": again_seconds}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scale", type=float, default=1.0,
                        help="xcs-mux's run size (1: Wilson's full runs)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--rounds", type=int, default=2)
    options = parser.parse_args()
    console = Console()
    with tempfile.TemporaryDirectory() as scratch:
        times = ray_against_local(options.scale, options.jobs, options.rounds,
                                  Path(scratch) / "ray")
        table = Table("round", "local pool (s)", "Ray (s)", "ray / local",
                      title=f"10-seed xcs-mux, scale {options.scale:g}, {options.jobs} CPUs")
        for index, (local, ray) in enumerate(times, start=1):
            table.add_row(str(index), f"{local:.1f}", f"{ray:.1f}", f"{ray / local:.3f}")
        ratio = statistics.median(ray / local for local, ray in times)
        table.add_row("median", "", "", f"{ratio:.3f} (target <= 1.10)")
        console.print(table)
        found = resume(min(options.scale, 0.1), options.jobs, Path(scratch) / "resume")
        table = Table("measure", "value", title="xcs-mux sweep, 2 cells x 4 seeds, killed "
                      "with SIGKILL and run again")
        for key, value in found.items():
            table.add_row(key, f"{value:.1f}" if isinstance(value, float) else str(value))
        recomputed = found["finished run again"] / found["finished before the kill"]
        table.add_row("finished run again / finished", f"{recomputed:.2f} (target 0)")
        console.print(table)


if __name__ == "__main__":
    main()

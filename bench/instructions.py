"""Instructions per cycle of the reference agent and of the floor, counted by valgrind.

Wall-clock ratios (``cycles.py``) swing with what else runs on a shared machine; the number
of instructions a cycle executes does not. Each implementation runs under
``valgrind --tool=callgrind`` twice, with 0 and with ``--cycles`` cycles after the same
warm-up; the difference divided by the cycles is its cost per cycle (loading, start-up and
warm-up cancel out). Prints both and the floor / goalagent ratio, the instruction-count
counterpart of cycles.py's goalagent / floor rate ratio. Not a test:
``python bench/instructions.py --cycles 2000`` (needs ``valgrind``; a few minutes).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Annotated

import typer

BENCH = Path(__file__).resolve().parent
WARMUP = 300

# Run inside valgrind: sys.argv = [what, cycles]; warm up, then run the counted cycles.
_CHILD = """
import sys
sys.path.insert(0, {bench!r})
import cycles
what, count = sys.argv[1], int(sys.argv[2])
if what == "goalagent":
    from goalagent.agent import Agent
    agent = Agent.from_file(cycles.GOAL_FILE, name="reference")
    agent.run({warmup} + count)
else:
    cycles.floor_run({warmup} + count)
"""


def instructions(what: str, count: int) -> int:
    """The instructions valgrind counts for a run of ``count`` cycles after the warm-up."""
    return counted(_CHILD.format(bench=str(BENCH), warmup=WARMUP), what, str(count))


def counted(code: str, *args: str) -> int:
    """The instructions valgrind counts for ``python -c code args`` (hash seed fixed, so
    two trees compare on the same dict and set orders)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "callgrind.out"
        done = subprocess.run(
            ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", sys.executable,
             "-c", code, *args], capture_output=True, text=True, check=False,
            env={**os.environ, "PYTHONHASHSEED": "0"})
    found = re.search(r"Collected : (\d+)", done.stderr)
    if done.returncode != 0 or found is None:
        raise SystemExit(f"valgrind run of {' '.join(args)} failed:\n{done.stderr[-2000:]}")
    return int(found.group(1))


def main(cycles: Annotated[int, typer.Option(min=1, help="Counted cycles per run.")] = 2000
         ) -> None:
    """Instructions per cycle of goalagent and of the floor, and their ratio."""
    if shutil.which("valgrind") is None:
        raise SystemExit("valgrind is not installed (apt-get install valgrind)")
    per_cycle = {}
    for what in ("goalagent", "floor"):
        per_cycle[what] = (instructions(what, cycles) - instructions(what, 0)) / cycles
        print(f"{what:10} {per_cycle[what]:>10,.0f} instructions/cycle")
    print(f"floor / goalagent {per_cycle['floor'] / per_cycle['goalagent']:.3f} "
          "(cycles.py's goalagent / floor rate ratio, counted in instructions)")


if __name__ == "__main__":
    typer.run(main)

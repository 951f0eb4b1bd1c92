"""Instructions per learning trial of goalagent's XCS on bench/xcs.py's multiplexers, counted by
valgrind.

The trials/s ratios of ``xcs.py`` swing with what else runs on a shared machine; the number of
instructions a trial executes does not. Each count runs ``xcs.py``'s goalagent loop (its
problems, Wilson's parameters, its seed) under ``valgrind --tool=callgrind`` with
instrumentation off while Python, numpy and the learner load (most of a process's
instructions, and under full instrumentation most of its minutes), switched on by
``callgrind_control`` just before the trials; a run of no trials is counted the same way, and
the difference divided by the trials is what one trial costs. The learner's parameters are
checked before the count (a query, which learns nothing). Not a test:
``python bench/xcs_instructions.py`` (needs ``valgrind``; about a minute per problem).
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

BENCH_FILE = Path(__file__).resolve().parent / "xcs.py"

# Run inside valgrind: sys.argv = [problem, trials]. Loads xcs.py by path (its name would
# shadow the `xcs` package), prepares the trials, says "ready", waits for a line, runs them.
_CHILD = """
import importlib.util, os, sys
spec = importlib.util.spec_from_file_location("bench_xcs", {bench!r})
bench = importlib.util.module_from_spec(spec)
spec.loader.exec_module(bench)
problem_name, trials = sys.argv[1], int(sys.argv[2])
address_bits, population = bench.PROBLEMS[problem_name]
problem = bench.Problem(address_bits, population, max(trials, 1), {seed})
learner = bench.XCS(2, N=population, random_state={seed}, **bench.WILSON)
states = ["".join(map(str, row)) for row in problem.inputs][:trials]
answers = problem.answers.tolist()
learner.prediction_array(states[0] if states else "0" * problem.length)  # checks parameters
print("ready", flush=True)
sys.stdin.readline()
for state, answer in zip(states, answers):
    action = learner.act(state, explore=True)
    learner.reward(bench.REWARD if action == answer else 0.0, done=True)
os._exit(0)
"""


def counted(problem: str, trials: int, seed: int) -> int:
    """The instructions of ``trials`` learning trials on ``problem`` and what follows them
    (the process's exit), counted from just before the first trial."""
    code = _CHILD.format(bench=str(BENCH_FILE), seed=seed)
    with tempfile.TemporaryDirectory() as tmp:
        log = Path(tmp) / "valgrind.log"
        child = subprocess.Popen(
            ["valgrind", "--tool=callgrind", "--instr-atstart=no", f"--log-file={log}",
             f"--callgrind-out-file={Path(tmp) / 'callgrind.out'}", sys.executable, "-c", code,
             problem, str(trials)],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
            env={**os.environ, "PYTHONHASHSEED": "0"})
        assert child.stdin is not None and child.stdout is not None
        if child.stdout.readline().strip() != "ready":
            child.wait()
            raise SystemExit(f"the {problem} run failed before its trials:\n"
                             f"{log.read_text()[-2000:]}")
        subprocess.run(["callgrind_control", "--instr=on", str(child.pid)],
                       capture_output=True, check=True)
        child.stdin.write("go\n")
        child.stdin.close()
        child.wait()
        found = re.search(r"Collected : (\d+)", log.read_text())
    if child.returncode != 0 or found is None:
        raise SystemExit(f"valgrind run of {problem} ({trials} trials) failed")
    return int(found.group(1))


def main(trials_6: Annotated[int, typer.Option(min=1, help="6-mux trials.")] = 3000,
         trials_11: Annotated[int, typer.Option(min=1, help="11-mux trials.")] = 2000,
         seed: Annotated[int, typer.Option(help="xcs.py's --seed.")] = 0) -> None:
    """Instructions per learning trial of goalagent's XCS on the 6- and 11-multiplexer."""
    for tool in ("valgrind", "callgrind_control"):
        if shutil.which(tool) is None:
            raise SystemExit(f"{tool} is not installed (apt-get install valgrind)")
    for problem, trials in (("6-mux", trials_6), ("11-mux", trials_11)):
        per_trial = (counted(problem, trials, seed) - counted(problem, 0, seed)) / trials
        print(f"{problem:7} {per_trial:>10,.0f} instructions/trial ({trials} trials)")


if __name__ == "__main__":
    typer.run(main)

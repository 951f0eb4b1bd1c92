"""The ``goalagent`` command in a child process, measured: exit code, output, wall-clock
seconds, the CPU seconds it used (what a bound on work should check: a loaded machine
stretches wall-clock time, not CPU time) and peak resident memory (the child reports its own
``VmHWM`` when it exits: not ``ru_maxrss``, which Linux carries over from the parent a child
was forked from, so a child of a large pytest process would report the parent's size).

:func:`goalagent_measured_each` runs several commands one after the other in one child, each
measured alone (its own streams at the file-descriptor level, its own peak: the child resets
``VmHWM`` before each): for many small inputs checked the same way, where starting an
interpreter for each was most of the cost."""

from __future__ import annotations

import json
import math
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from tests.conftest import ROOT, python

_LAUNCHER = (
    "import atexit, os, sys\n"
    "def _report():\n"
    "    with open('/proc/self/status') as status:\n"
    "        peak = next(line.split()[1] for line in status if line.startswith('VmHWM:'))\n"
    "    times = os.times()\n"
    "    with open(os.environ['GOALAGENT_TEST_RSS'], 'w') as out:\n"
    "        out.write(f'{peak} {times.user + times.system}')\n"
    "atexit.register(_report)\n"
    "sys.argv = ['goalagent', *sys.argv[1:]]\n"
    "from goalagent.cli import main\n"
    "main()\n"
)


@dataclass(frozen=True)
class Measured:
    """What one command did."""

    returncode: int
    stdout: str
    stderr: str
    seconds: float
    peak_mb: float
    cpu_seconds: float


def goalagent_measured(*args: str, timeout: float = 120, cwd: Path = ROOT) -> Measured:
    """Runs ``goalagent ARGS`` in a child Python; a child still running after ``timeout``
    seconds (a hang) fails the calling test through ``subprocess.TimeoutExpired``."""
    with tempfile.NamedTemporaryFile(suffix=".rss", delete=False) as handle:
        rss_file = Path(handle.name)
    try:
        start = time.monotonic()
        result = python(_LAUNCHER, *args, cwd=cwd, timeout=timeout,
                        env={"GOALAGENT_TEST_RSS": str(rss_file)})
        seconds = time.monotonic() - start
        text = rss_file.read_text().split()
        peak, cpu = (int(text[0]) / 1024, float(text[1])) if text else (math.nan, math.nan)
    finally:
        rss_file.unlink(missing_ok=True)
    return Measured(result.returncode, result.stdout, result.stderr, seconds, peak, cpu)


_EACH = (
    "import json, os, sys, tempfile, time, traceback\n"
    "from goalagent.cli import main\n"
    "def _peak():\n"
    "    with open('/proc/self/status') as status:\n"
    "        return int(next(line.split()[1] for line in status if line.startswith('VmHWM:')))\n"
    "def _one(args):\n"
    "    with open('/proc/self/clear_refs', 'w') as refs:\n"
    "        refs.write('5')  # the peak starts again from here\n"
    "    streams = [tempfile.TemporaryFile(), tempfile.TemporaryFile()]\n"
    "    kept = [os.dup(1), os.dup(2)]\n"
    "    os.dup2(streams[0].fileno(), 1)\n"
    "    os.dup2(streams[1].fileno(), 2)\n"
    "    before, start = os.times(), time.monotonic()\n"
    "    try:\n"
    "        sys.argv = ['goalagent', *args]\n"
    "        main()\n"
    "        code = 0\n"
    "    except SystemExit as stop:\n"
    "        code = stop.code if isinstance(stop.code, int) else int(stop.code is not None)\n"
    "    except BaseException:  # as Python would show it, ending the process\n"
    "        traceback.print_exc()\n"
    "        code = 1\n"
    "    finally:\n"
    "        sys.stdout.flush()\n"
    "        sys.stderr.flush()\n"
    "        os.dup2(kept[0], 1)\n"
    "        os.dup2(kept[1], 2)\n"
    "    after, seconds = os.times(), time.monotonic() - start\n"
    "    for stream in streams:\n"
    "        stream.seek(0)\n"
    "    out, err = (stream.read().decode() for stream in streams)\n"
    "    cpu = after.user + after.system - before.user - before.system\n"
    "    return [code, out, err, seconds, _peak() / 1024, cpu]\n"
    "with open(sys.argv[2], 'w') as results:\n"
    "    for args in json.loads(sys.argv[1]):\n"
    "        results.write(json.dumps(_one(args)) + '\\n')\n"
    "        results.flush()\n"
)


def goalagent_measured_each(*commands: list[str], timeout: float = 120,
                            cwd: Path = ROOT) -> list[Measured]:
    """Runs ``goalagent ARGS`` for each ARGS of ``commands`` in turn in one child Python,
    each measured as :func:`goalagent_measured` measures one; the child still running after
    ``timeout`` seconds in all (a hang) fails the calling test, and a command that ended
    the child is named."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as handle:
        results = Path(handle.name)
    try:
        child = python(_EACH, json.dumps(commands), str(results), cwd=cwd, timeout=timeout)
        measured = [Measured(*json.loads(line)) for line in results.read_text().splitlines()]
    finally:
        results.unlink(missing_ok=True)
    assert len(measured) == len(commands), (
        f"the child ended (exit {child.returncode}) in goalagent "
        f"{' '.join(commands[len(measured)])}: {child.stderr}")
    return measured

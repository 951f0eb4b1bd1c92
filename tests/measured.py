"""The ``goalagent`` command in a child process, measured: exit code, output, wall-clock
seconds, the CPU seconds it used (what a bound on work should check: a loaded machine
stretches wall-clock time, not CPU time) and peak resident memory (the child reports its own
``VmHWM`` when it exits: not ``ru_maxrss``, which Linux carries over from the parent a child
was forked from, so a child of a large pytest process would report the parent's size)."""

from __future__ import annotations

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

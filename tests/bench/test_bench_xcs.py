"""bench/xcs.py runs end to end at a tiny size and prints every measure it promises."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_xcs_bench_prints_rates_accuracies_and_ratios_for_all_four():
    result = subprocess.run([sys.executable, "bench/xcs.py", "--trials-6", "50",
                             "--trials-11", "50"], cwd=ROOT, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
    out = result.stdout
    for expected in ("goalagent", "xcs 1.0.0", "scikit-XCS 1.0.8", "xcsf", "trials/s",
                     "accuracy", "6-mux: goalagent / faster of xcs and scikit-XCS",
                     "11-mux: goalagent / faster of xcs and scikit-XCS", "goalagent / xcsf",
                     "target >= 3×", "target >= 0.8×", "target >= 1×"):
        assert expected in out, expected


@pytest.mark.parametrize(("args", "message"), [
    (["--trials-6", "0"], "--trials-6 must be at least 1"),
    (["--trials-11", "-3"], "--trials-11 must be at least 1"),
    (["--repeats", "0"], "--repeats must be at least 1"),
])
def test_xcs_bench_refuses_a_silly_trial_count(args, message, refused):
    assert message in refused("xcs.py", *args)

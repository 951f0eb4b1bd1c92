"""bench/sim.py runs end to end and prints every measure it promises (kept short: --repeats 1);
a silly count is refused before anything runs."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_sim_bench_prints_physics_skills_and_frame_tables():
    result = subprocess.run([sys.executable, "bench/sim.py", "--repeats", "1", "--trials", "2"],
                            cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    out = result.stdout
    for expected in ("steps/s", "arm at rest", "inside extend_arm", "contract_arm(handle)",
                     "camera / truth", "render alone (baseline)", "segment alone (baseline)",
                     "render + segment", "ms target", "XCS task experiments", "seg/proj",
                     "navigation: camera / truth", "s target"):
        assert expected in out, expected
    assert all(f"│  {can} │" in out for can in ("o1", "o2", "o3", "o4", "o5"))
    assert all(f" {task} │" in out for task in ("navigation", "stacking", "search"))


@pytest.mark.parametrize(("args", "message"), [
    (["--repeats", "0"], "--repeats must be at least 1"),
    (["--trials", "1"], "--trials must be at least 2"),
])
def test_sim_bench_refuses_a_silly_repeat_count(args, message, refused):
    assert message in refused("sim.py", *args)

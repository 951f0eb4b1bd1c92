"""The example agents of the XCS task environments run from the CLI and reach their goals."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def run(mas: str, *params: str) -> subprocess.CompletedProcess[str]:
    args = [a for p in params for a in ("--env-param", p)]
    return subprocess.run(
        [sys.executable, "-m", "goalagent", "run", str(ROOT / "agents" / mas), *args,
         "--max-cycles", "400"],
        capture_output=True, text=True, timeout=600, cwd=ROOT)


@pytest.mark.parametrize("exchanged", ["false", "true"])
def test_the_navigation_agent_learns_then_walks_past_the_fixed_box(exchanged):
    result = run("navigation.mas2g", f"exchanged={exchanged}")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[-1].startswith("arrived(steps(")
    assert any(line.startswith("trial(explore,") for line in lines)  # it learned first
    assert "learned(afford('1001',push_ahead,moved))" in lines
    if exchanged == "true":
        assert "learned(afford('1100',push_ahead,unmoved))" in lines
        assert lines[-1] == "arrived(steps(5))"  # two steps left, three pushes
    assert "0 goals left" in result.stderr


def test_the_stacking_agent_builds_a_stack_as_high_as_the_table():
    result = run("stacking.mas2g")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[-1] == "built(height(0.36),steps(2))"  # choose the box, push it once
    assert any(line.startswith("learned(afford('1001',push_") and line.endswith("moved))")
               for line in lines)


def test_the_search_agent_learns_again_after_the_target_moves():
    result = run("search.mas2g", "move_after=4")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[-1].startswith("tracked(trial(")
    trial = int(lines[-1].split("trial(")[1].split(")")[0])
    assert trial > 4  # after the move

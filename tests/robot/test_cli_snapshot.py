"""The ``goalagent snapshot`` command (perception itself is tested in test_perception.py)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_snapshot_command_writes_an_annotated_png(tmp_path):
    out = tmp_path / "frame.png"
    result = subprocess.run([sys.executable, "-m", "goalagent", "snapshot", "--can", "o2",
                             "--out", str(out), "--opening", "0.08"],
                            capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert "parts body, handle, lid, opening 0.08" in result.stderr
    assert out.stat().st_size > 5_000

"""What the benchmark scripts' tests share."""

from __future__ import annotations

import runpy
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def refused(monkeypatch: pytest.MonkeyPatch,
            capsys: pytest.CaptureFixture[str]) -> Callable[..., str]:
    """Runs ``bench/SCRIPT ARGS`` as ``__main__`` in this process, which must refuse ARGS
    (exit status 2): what it said on stderr. In this process: a child Python would import
    MuJoCo, OpenCV or scikit-learn only to read the arguments (the script as a script is
    each module's end-to-end test)."""
    def run(script: str, *args: str) -> str:
        monkeypatch.setattr(sys, "argv", [f"bench/{script}", *args])
        monkeypatch.setattr(sys, "path", list(sys.path))  # the script puts the root first
        with pytest.raises(SystemExit) as exit_:
            runpy.run_path(str(ROOT / "bench" / script), run_name="__main__")
        assert exit_.value.code == 2
        return capsys.readouterr().err
    return run

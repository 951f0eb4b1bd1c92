"""mypy finds no error in the public API's modules, nor in the documentation site's Python
samples that use it as a user would (against the package's own types: ``py.typed``)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PUBLIC = [
    "goalagent/__init__.py", "goalagent/agent/__init__.py", "goalagent/agent/cycle.py",
    "goalagent/agent/events.py", "goalagent/agent/reports.py", "goalagent/agent/actions.py",
    "goalagent/agent/messages.py", "goalagent/mas.py", "goalagent/mas_building.py",
    "goalagent/testing.py",
    "goalagent/eis/__init__.py", "goalagent/eis/interface.py", "goalagent/eis/pyenv.py",
    "goalagent/eis/terms.py", "goalagent/eis/registry.py", "goalagent/eis/exceptions.py",
    "goalagent/eis/reference.py", "goalagent/kb/terms.py", "goalagent/kb/limits.py",
    "goalagent/extensions.py", "goalagent/events.py", "goalagent/swi.py", "goalagent/extras.py",
]


def _mypy(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "mypy", "--no-incremental",
                           "--follow-imports=silent", "--python-version", "3.10", *args],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module")
def checked(tmp_path_factory: pytest.TempPathFactory) -> tuple[list[str],
                                                                subprocess.CompletedProcess[str]]:
    """One mypy run (its analysis of the package is most of its time) over the public API
    and the documentation's samples of it, each page's blocks one file, with
    --check-untyped-defs (the samples are scripts without annotations): the samples' paths
    and what mypy said."""
    folder = tmp_path_factory.mktemp("samples")
    samples = []
    for page in sorted((ROOT / "docs").rglob("*.md")):
        blocks = re.findall(r"^```python\n(.*?)^```", page.read_text(), re.M | re.S)
        if any("from goalagent" in block for block in blocks):  # samples of this API
            target = folder / f"sample_{page.stem.replace('-', '_')}.py"
            target.write_text("\n".join(blocks))
            samples.append(str(target))
    result = _mypy("--check-untyped-defs", *PUBLIC, *samples)
    assert result.returncode in (0, 1), result.stderr  # 1: errors found, 2: mypy failed
    assert f"{len(PUBLIC) + len(samples)} source files" in result.stdout, result.stdout
    return samples, result


def _errors(result: subprocess.CompletedProcess[str], in_samples: bool,
            samples: list[str]) -> list[str]:
    """mypy's error lines about the samples (or about anything else)."""
    return [line for line in result.stdout.splitlines() if ": error:" in line
            and line.startswith(tuple(samples)) == in_samples]


def test_mypy_finds_no_error_in_the_public_api(
        checked: tuple[list[str], subprocess.CompletedProcess[str]]) -> None:
    samples, result = checked
    assert not _errors(result, False, samples), result.stdout[-4000:]


def test_the_documented_python_samples_type_check(
        checked: tuple[list[str], subprocess.CompletedProcess[str]]) -> None:
    samples, result = checked
    assert samples
    assert not _errors(result, True, samples), result.stdout[-4000:]

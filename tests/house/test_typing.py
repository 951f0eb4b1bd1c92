"""mypy finds no error in the public API's modules, nor in the documentation site's Python
samples that use it as a user would (against the package's own types: ``py.typed``)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

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


def test_mypy_finds_no_error_in_the_public_api() -> None:
    result = _mypy(*PUBLIC)
    assert result.returncode == 0, result.stdout[-4000:]
    assert "Success: no issues found" in result.stdout


def test_the_documented_python_samples_type_check(tmp_path: Path) -> None:
    samples = []
    for page in sorted((ROOT / "docs").rglob("*.md")):
        blocks = re.findall(r"^```python\n(.*?)^```", page.read_text(), re.M | re.S)
        if any("from goalagent" in block for block in blocks):  # samples of this API
            target = tmp_path / f"sample_{page.stem.replace('-', '_')}.py"
            target.write_text("\n".join(blocks))
            samples.append(str(target))
    assert samples
    result = _mypy("--check-untyped-defs", *samples)
    assert result.returncode == 0, result.stdout[-4000:]

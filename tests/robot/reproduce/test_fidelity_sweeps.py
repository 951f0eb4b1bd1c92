"""Issue 28's committed sensitivity sweeps: each page, each claim's verdict per cell, is what
the code makes of the measured seeds. The sweeps at reduced size, the way a user runs them
(``goalagent sweep``), are in test_studies.py, where they share their seeds with the quick
runs."""

from __future__ import annotations

from pathlib import Path

import pytest

from robot.reproduce.framework import documents, sweeps
from robot.reproduce.framework.registry import find

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

RESULTS = Path(__file__).resolve().parents[3] / "docs" / "results"
COMMITTED = sorted(RESULTS.glob("*-sweep-*.json"))


@pytest.mark.parametrize("document", COMMITTED, ids=lambda path: path.stem)
def test_each_committed_sweep_page_is_what_its_json_gives(document):
    """A committed sweep's statistics and page (its verdicts included) are what the current
    code computes from its measured seeds: ``goalagent sweep --replot`` would leave them as
    they are, and the page says per claim which cells make the claim hold. Computed in
    memory, as the committed reproductions are in test_studies.py, instead of ``replot`` on a
    copy writing every file again (5.7 -> 4.7 s CPU for the six); ``replot`` writing what it
    redraws is tested on a toy sweep (test_workbench.py) and through ``goalagent sweep
    --replot`` (test_workbench_cli.py)."""
    committed = documents.read(document)
    study = find(committed.study)
    rebuilt = sweeps.restated(study, committed)
    assert rebuilt == committed
    text = document.with_suffix(".md").read_text()
    assert sweeps.page(study, rebuilt) == text
    assert "## Verdicts: which settings make each claim hold" in text
    assert "## Deviations and open choices" in text

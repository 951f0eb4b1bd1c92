"""Issue 28's sensitivity sweeps at reduced size, the way a user runs them
(``goalagent sweep``), and the committed full ones: each page, each claim's verdict per cell."""

from __future__ import annotations

from pathlib import Path

import pytest

from robot.reproduce.framework import documents, sweeps
from robot.reproduce.framework.backends import LocalBackend
from robot.reproduce.framework.registry import find
from robot.reproduce.framework.settings import apply, parse_grid
from robot.reproduce.framework.sweeps import sweep

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

RESULTS = Path(__file__).resolve().parents[3] / "docs" / "results"
SMALL = {
    "ch3-navigation": ({"learn_in_exploit": "false,true"}, {}),
    "ch4-exploration": ({"state_scale": "100"}, {}),
    "ch5-transfer": ({"sensor_noise": "0.01"}, {}),
    "appA-search": ({"consistent_actions": "true,false"}, {}),
}
"""Each committed sweep's first parameter at the study's quick size (the default values of
ch4's and ch5's run in tests/robot/reproduce/test_studies.py)."""


@pytest.mark.parametrize("name", sorted(SMALL))
def test_each_sweep_runs_small_and_says_which_cells_hold_each_claim(name, tmp_path):
    study = find(name)
    grid_text, settings = SMALL[name]
    base = apply(study, study.quick_config(), [f"{k}={v}" for k, v in settings.items()])
    grid = parse_grid(study, base, [f"{k}={v}" for k, v in grid_text.items()])
    outcome = sweep(study, base, grid, [0], LocalBackend(1), tmp_path)
    assert [cell.values for cell in outcome.document.cells] == [
        {key: value} for key, values in grid.items() for value in values]
    page = (tmp_path / f"{name}-sweep-{next(iter(grid))}.md").read_text()
    assert "## Deviations and open choices" in page and "| swept |" in page
    claims = outcome.document.cells[0].summary.comparisons
    assert page.count("By cell: ") == len(claims) > 0


COMMITTED = sorted(RESULTS.glob("*-sweep-*.json"))


@pytest.mark.parametrize("document", COMMITTED, ids=lambda path: path.stem)
def test_each_committed_sweep_page_is_what_its_json_gives(document):
    """A committed sweep's statistics and page (its verdicts included) are what the current
    code computes from its measured seeds: ``goalagent sweep --replot`` would leave them as
    they are, and the page says per claim which cells make the claim hold. Computed in
    memory, as the committed reproductions are in test_studies.py: writing the JSON again
    (indented, Python's slow encoder) was 3 of these tests' 7.6 s, and ``replot`` writing
    what it redraws is tested on a toy sweep (test_workbench.py) and through ``goalagent
    sweep --replot`` (test_workbench_cli.py)."""
    committed = documents.read(document)
    study = find(committed.study)
    rebuilt = sweeps.restated(study, committed)
    assert rebuilt == committed
    text = document.with_suffix(".md").read_text()
    assert sweeps.page(study, rebuilt) == text
    assert "## Verdicts: which settings make each claim hold" in text
    assert "## Deviations and open choices" in text

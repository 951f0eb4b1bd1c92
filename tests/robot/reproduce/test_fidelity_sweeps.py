"""Issue 28's sensitivity sweeps at reduced size, the way a user runs them
(``goalagent sweep``), and the committed full ones: each page, each claim's verdict per cell."""

from __future__ import annotations

from pathlib import Path

import pytest

from robot.reproduce.framework import documents, sweeps
from robot.reproduce.framework.backends import LocalBackend
from robot.reproduce.framework.registry import find
from robot.reproduce.framework.settings import apply, parse_grid
from robot.reproduce.framework.sweeps import replot, sweep

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
def test_each_committed_sweep_page_is_what_its_json_gives(document, tmp_path, monkeypatch):
    """A committed sweep's page (its verdicts included) is written from its measured seeds:
    redrawn from the JSON alone it comes out the same, and it says per claim which cells make
    the claim hold. Only the page is compared, so the plots are not drawn (half of the time
    here; what a sweep's plot holds is tested in test_workbench.py, with a sweep's replot)."""
    monkeypatch.setattr(sweeps, "render_sweep", lambda *args: b"")
    study = find(documents.read(document).study)
    (tmp_path / document.name).write_bytes(document.read_bytes())
    replot(study, tmp_path)
    page = document.with_suffix(".md")
    assert (tmp_path / page.name).read_text() == page.read_text()
    text = page.read_text()
    assert "## Verdicts: which settings make each claim hold" in text
    assert "## Deviations and open choices" in text

"""The ch5-baseline and ch5-transfer reproductions (Tables 5.3 and 5.4) at reduced size."""

from __future__ import annotations

import json
from pathlib import Path

from robot.reproduce.framework import find
from robot.reproduce.runner import run
from robot.transfer_study import baseline_seed, baseline_summary, transfer_seed, transfer_summary


def test_transfer_reports_table_5_4_keys_and_o3_learns_from_o1_in_one_action():
    rows = [transfer_seed(0, ("o1", "o3"), "truth")]
    summary = transfer_summary(rows)
    assert set(summary) == {"o1", "o3"}
    for can in summary:
        assert {"n_without", "n_with", "source", "part", "action"} <= set(summary[can])
    assert summary["o1"]["source"] is None and summary["o1"]["n_with"] == 39
    assert (summary["o3"]["source"], summary["o3"]["part"], summary["o3"]["action"]) == (
        "o1", "lid", "extend_arm")
    assert summary["o3"]["n_with"] == 1 < summary["o3"]["n_without"] == 39
    assert rows[0]["o3"]["theta"] > 0 and rows[0]["o3"]["opening"] >= 0.1


def test_baseline_lists_every_pair_model():
    rows = [baseline_seed(1, ("o1",), "truth")]
    summary = baseline_summary(rows)
    assert summary["o1"]["n_without"] == 39 and summary["o1"]["found"] == 1
    models = rows[0]["o1"]["models"]
    assert len(models) == 12 and all({"g", "h", "n"} <= set(m) for m in models)


def test_reproduce_writes_tables_5_3_and_5_4_beside_the_thesis(tmp_path: Path):
    for name, row in (("ch5-transfer", "| o3 | 39.0 | 1.0 | o1 | extend_arm(lid) (1/1) | direct "
                                       "| True | 53, 1, o1 |"),
                      ("ch5-baseline", "| o1 | lid | **extend_arm** |")):
        reproduction = find(name)
        run(reproduction, seeds=1, scale=reproduction.quick_scale, jobs=1, out=tmp_path,
            command=f"test {name}")
        assert row in (tmp_path / f"{name}.md").read_text()
        summary = json.loads((tmp_path / f"{name}.json").read_text())["summary"]
        assert summary["o1"]["part"] == "lid" and summary["o1"]["action"] == "extend_arm"

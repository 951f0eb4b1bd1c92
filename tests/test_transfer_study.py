"""The ch5-baseline and ch5-transfer studies (Tables 5.3 and 5.4) at reduced size."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from robot.transfer_study import baseline_study, main, markdown, transfer_study


def test_transfer_study_reports_table_5_4_keys():
    result = transfer_study(cans=("o1", "o3"), seeds=[0], perception="truth")
    summary = result["summary"]
    assert set(summary) == {"o1", "o3"}
    for can in summary:
        assert {"n_without", "n_with", "source", "part", "action"} <= set(summary[can])
    assert summary["o1"]["source"] is None and summary["o1"]["n_with"] == 39
    assert (summary["o3"]["source"], summary["o3"]["part"], summary["o3"]["action"]) == (
        "o1", "lid", "extend_arm")
    assert summary["o3"]["n_with"] == 1 < summary["o3"]["n_without"] == 39
    seed = result["seeds"]["0"]["o3"]
    assert seed["theta"] > 0 and seed["opening"] >= 0.1
    text = markdown(result)
    assert "| o3 | 39.0 | 1.0 | o1 | extend_arm(lid) (1/1) | direct | True | 53, 1, o1 |" in text


def test_baseline_study_lists_every_pair_model_with_the_functional_one_in_bold():
    result = baseline_study(cans=("o1",), seeds=[1], perception="truth")
    assert result["summary"]["o1"]["n_without"] == 39 and result["summary"]["o1"]["found"] == 1
    models = result["seeds"]["1"]["o1"]["models"]
    assert len(models) == 12 and all({"g", "h", "n"} <= set(m) for m in models)
    assert "| o1 | lid | **extend_arm** |" in markdown(result)


def test_the_command_writes_json_and_markdown(tmp_path: Path, capsys):
    assert main(["ch5-transfer", "--cans", "o1", "--seeds", "1", "--out", str(tmp_path)]) == 0
    data = json.loads((tmp_path / "ch5-transfer-truth.json").read_text())
    assert data["summary"]["o1"]["part"] == "lid"
    assert (tmp_path / "ch5-transfer-truth.md").read_text().startswith("## ch5-transfer")
    with pytest.raises(SystemExit) as caught:
        main(["ch5-transfer", "--cans", "o1,o9"])
    assert caught.value.code == 2
    assert "unknown can 'o9'" in capsys.readouterr().err

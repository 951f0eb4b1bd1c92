"""The chapter-3 and Appendix-A reproductions at their quick size: the summary keys issue 9
names, movability rows, rule listings, and the helpers that aggregate over seeds."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from robot.reproduce.framework import find
from robot.reproduce.runner import run
from robot.reproduce.task_runs import experienced_rules, majority_movability, seeds_with

LISTINGS = {"ch3-navigation": ("## Learned movability (Table 3.3", "## XCS rules of seed 0"),
            "ch3-stacking": ("## Learned movability (Table 3.3, stacking rows)",),
            "appA-search": ("## XCS rules of seed 0, truth (Table 7.2 style",)}


def _run(name: str, tmp_path: Path) -> dict:
    reproduction = find(name)
    run(reproduction, seeds=2, scale=reproduction.quick_scale, jobs=1, out=tmp_path,
        command=f"test {name}")
    document = json.loads((tmp_path / f"{name}.json").read_text())
    assert len(document["seeds"]) == 2
    page = (tmp_path / f"{name}.md").read_text()
    assert "| quantity |" in page
    assert all(heading in page for heading in LISTINGS[name])  # the tables hook's markdown
    assert sorted(tmp_path.glob(f"{name}-*.png"))
    return document


def _is_movability(rows: list) -> bool:
    return all(len(r) == 3 and set(r[0]) <= {"0", "1"} and len(r[0]) == 4 and
               set(r[1]) <= {"0", "1"} and len(r[1]) == 3 and r[2] in (0, 1) for r in rows)


def test_ch3_navigation_summary_per_method_and_mode(tmp_path: Path):
    document = _run("ch3-navigation", tmp_path)
    summary = document["summary"]
    for part in (summary, summary["camera"]):
        for method in ("affordance_xcs", "standard_xcs"):
            assert {"mean_steps_11_20", "success_rate_11_20", "movability"} <= set(part[method])
            assert 0.0 <= part[method]["success_rate_11_20"] <= 1.0
            assert 1.0 <= part[method]["mean_steps_11_20"] <= 10.0
            assert _is_movability(part[method]["movability"])
    # every push taught the table the box's true movability
    for seed in document["seeds"]:
        for mode in ("truth", "camera"):
            for method in ("affordance_xcs", "standard_xcs"):
                for obj, _, effect in seed[mode][method]["movability"]:
                    assert effect == {"1001": 1, "1100": 0}[obj]
    assert summary["rules"] and all(len(row) == 9 for row in summary["rules"])


def test_ch3_stacking_summary_has_movability_and_the_chosen_object(tmp_path: Path):
    summary = _run("ch3-stacking", tmp_path)["summary"]
    for part in (summary, summary["camera"]):
        assert _is_movability(part["movability"])
        assert part["chosen_object"] in ("box", "foam", "none")
    truth = {(o, a): e for o, a, e in summary["movability"]}
    assert truth.get(("0010", "101"), 1) == 1 and truth.get(("1001", "100"), 1) == 1


def test_appA_search_summary_before_and_after_the_move(tmp_path: Path):
    summary = _run("appA-search", tmp_path)["summary"]
    for part in (summary, summary["camera"]):
        for place in ("up_left", "right"):
            steps = part[place]["last_exploit_steps"]
            assert len(steps) == 2 and all(3 <= s <= 20 for s in steps)
    assert 1 <= len(summary["rules"]) <= 5


def test_majority_movability_keeps_first_appearance_order_and_breaks_ties_to_unmoved():
    tables = [[["1100", "010", 0], ["1001", "010", 1]],
              [["1001", "010", 1], ["1100", "010", 1]],
              [["0010", "100", 0]]]
    assert majority_movability(tables) == [["1100", "010", 0], ["1001", "010", 1],
                                           ["0010", "100", 0]]
    assert seeds_with(tables, ["1001", "010", 1]) == pytest.approx(2 / 3)


def test_experienced_rules_are_the_most_used_listed_by_id():
    rules = [[1, "1###", "010", 5.0, 1.0, 0.2, 2.0, 3, 1],
             [2, "#0##", "000", 5.0, 1.0, 0.2, 2.0, 9, 1],
             [3, "##1#", "001", 5.0, 1.0, 0.2, 2.0, 0, 1],
             [4, "###0", "011", 5.0, 1.0, 0.2, 2.0, 7, 1]]
    assert [row[0] for row in experienced_rules(rules, 2)] == [2, 4]

"""The chapter 4 reproductions: their summaries on hand-made seeds, and small real runs."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from behaviours.learners.convergence import VARIANTS, first_convergence
from robot.reproduce import ch4_exploration, ch4_skills
from robot.reproduce._ch4 import CONFIGURATIONS, METHODS, SETUPS, budget
from robot.reproduce.framework import find
from robot.reproduce.runner import run


def seed_with(steps: dict[tuple[str, str], int | None]) -> dict:
    """A hand-made ch4-exploration seed: only the convergence steps matter to the summary."""
    averaged = [None] * 19 + [0.5, 0.6, 0.60005, 0.7, 0.70002]  # (4.10) holds at 2 of 4
    return {"configurations": {name: {method: {"converged_at": steps.get((name, method)),
                                               "states": [0.0, 0.01, 0.004],
                                               "td_errors": [0.1, -0.2, 0.0, 0.3] * 6,
                                               "effects": [0.02] * 20 + [0.0, 0.005, 0.03, 0.0],
                                               "averaged": averaged,
                                               "surface": [[-0.01, 0.0, 0.02]] * 5}
                                      for method in METHODS} for name in CONFIGURATIONS}}


def test_exploration_summary_counts_converged_seeds_and_their_median_step() -> None:
    seeds = [seed_with({("lid-1d", "active"): 30, ("lid-1d", "random"): None}),
             seed_with({("lid-1d", "active"): 41, ("lid-1d", "random"): 25}),
             seed_with({("lid-1d", "active"): 35})]
    summary = ch4_exploration.summarize(seeds)
    assert summary["lid-1d"] == {"active": {"converged": 3, "median_step": 35.0},
                                 "random": {"converged": 1, "median_step": 25.0}}
    assert summary["handle-3d"]["random"] == {"converged": 0, "median_step": None}
    assert set(summary) == {"lid-1d", "lid-3d", "handle-1d", "handle-3d", "variants"}
    assert summary["variants"]["sustained"]["lid-1d"]["active"] == {  # 24 steps < 2N
        "converged": 0, "median_step": None}
    rows = {row.quantity: row for row in ch4_exploration.compare(summary, seeds)}
    share = rows["lid-1d random: share of seeds converged (4.10)"]
    assert share.measured == pytest.approx(1 / 3) and share.reference == 0.0
    assert rows["lid-1d active: step of convergence"].measured == pytest.approx(106 / 3)
    assert rows["lid-1d random: largest s_o reached in N_s steps"].measured == 0.01
    assert rows["lid-1d random: share of steps with δ > 0"].measured == 0.5
    assert rows["lid-1d random: share of steps k > N with |e_o| < 0.01"].measured == 0.75
    firing = rows["lid-1d active: share of steps k > N at which (4.10) holds"]
    assert firing.measured == pytest.approx(2 / 4)
    spread = rows["lid-1d active: spread (std) of |δ| over steps k > N"].measured
    assert spread == pytest.approx(float(np.std([0.1, 0.2, 0.0, 0.3])))
    assert rows["lid-1d active: averaged |δ| (4.11) at step N_s"].measured == 0.70002
    opening = "F predicts opening for Δx of Fig. {}'s sign at every s_o slice"
    assert rows["lid-1d active: " + opening.format("4.4")].measured == 1.0  # rises: extend
    assert rows["handle-1d random: " + opening.format("4.5")].measured == 0.0  # opens
    assert "lid-3d active: " + opening.format("4.4") not in rows
    one_slice_wrong = {"surface": [[-0.01, 0.0, 0.02]] * 4 + [[0.01, 0.0, 0.0]]}
    assert not ch4_exploration._opens_as_thesis(one_slice_wrong, 1.0)


def test_variants_are_summarized_beside_the_thesis_on_the_recorded_td_errors() -> None:
    """Active: |δ| constant (after-transient at 41, sustained and window-to-window at 40);
    random: one error of 0.01 more at k = 35 in a spike every 10 steps (75, 41, 75, 75)."""
    spiky = [0.01 if k % 10 == 0 or k == 35 else 0.0 for k in range(1, 101)]
    seed = seed_with({})
    for name in CONFIGURATIONS:
        runs = seed["configurations"][name]
        runs["active"].update(converged_at=21, td_errors=[-0.05] * 100,
                              averaged=[None] * 19 + [0.05] * 81)
        runs["random"].update(converged_at=None, td_errors=spiky,
                              averaged=[None] * 19 + [0.001] * 81)
    summary = ch4_exploration.summarize([seed, seed])
    assert summary["lid-1d"]["random"] == {"converged": 0, "median_step": None}  # the thesis's
    variants = summary["variants"]
    assert set(variants) == {"after-transient", "sustained", "window-to-window"}
    assert variants["after-transient"]["lid-3d"] == {
        "active": {"converged": 2, "median_step": 41.0},
        "random": {"converged": 2, "median_step": 41.0}}
    assert variants["sustained"]["handle-1d"]["random"] == {"converged": 2, "median_step": 75.0}
    assert variants["window-to-window"]["handle-3d"]["active"]["median_step"] == 40.0
    listing = ch4_exploration.REPRODUCTION.listings(summary, [seed, seed])
    assert "VARIANT stop criteria — NOT the thesis's (4.10)" in listing
    assert "| lid-1d | thesis (4.10) | 2/2, 21 | 0/2, — | 2 / 0 / 0 | 0.0500 / — |" in listing
    assert ("| lid-1d | sustained (VARIANT) | 2/2, 40 | 2/2, 75 | 2 / 0 / 0 | 0.0500 / 0.0010 |"
            in listing)
    assert "| handle-3d | after-transient (VARIANT) | 2/2, 41 | 2/2, 41 | 0 / 2 / 0 |" in listing


def test_budgets_follow_the_thesis_and_shrink_with_the_scale() -> None:
    assert [SETUPS[name].budget for name in CONFIGURATIONS] == [100, 300, 100, 300]
    assert budget(SETUPS["lid-3d"], 1.0) == 300 and budget(SETUPS["lid-3d"], 0.5) == 150
    assert budget(SETUPS["lid-1d"], 0.05) == 22  # never below N + 2


def row(fm: str, part: str, phase: str, dx: float, training: str = "algorithm3") -> dict:
    return {"fm": fm, "part": part, "phase": phase, "training": training,
            "first_action": [dx, 0.0, 0.0], "goal": 0.01, "effect": 0.005, "states": []}


def test_skills_summary_checks_table_4_1_signs() -> None:
    seeds = [{"sequences": [row("FM1", "lid", "open", 0.01), row("FM1", "lid", "close", -0.01),
                            row("FM5", "handle", "open", 0.01),
                            row("FM5", "handle", "close", 0.01, "full_budget")]},
             {"sequences": [row("FM1", "lid", "open", -0.002)]}]
    summary = ch4_skills.summarize(seeds)
    assert summary["expected_sign"]["algorithm3"] == {"FM1-open": 1, "FM1-close": 1,
                                                      "FM5-open": 0}
    assert summary["expected_sign"]["full_budget"] == {"FM5-close": 1}
    assert [r["seed"] for r in summary["rows"]] == [0, 0, 0, 0, 1]
    assert all("states" not in r for r in summary["rows"])


def test_exploration_runs_small_and_reports_every_configuration(tmp_path: Path) -> None:
    reproduction = find("ch4-exploration")
    run(reproduction, seeds=1, scale=reproduction.quick_scale, jobs=1, out=tmp_path,
        command="test")
    document = json.loads((tmp_path / "ch4-exploration.json").read_text())
    for name in CONFIGURATIONS:
        for method in METHODS:
            result = document["summary"][name][method]
            assert set(result) == {"converged", "median_step"}
            measured = document["seeds"][0]["configurations"][name][method]
            assert measured["steps"] == 22 == len(measured["averaged"])  # N_s at 5 %: 22
            assert result["converged"] == int(measured["converged_at"] is not None)
            assert first_convergence(measured["td_errors"], "thesis") == measured["converged_at"]
            for criterion in VARIANTS:  # 22 steps: too few for any variant (k >= 2N)
                assert document["summary"]["variants"][criterion][name][method] == {
                    "converged": 0, "median_step": None}
    seed = document["seeds"][0]["configurations"]
    assert seed["lid-1d"]["active"]["actions"][:20] == seed["lid-1d"]["random"]["actions"][:20]
    assert len(seed["handle-1d"]["active"]["surface"]) == 5
    assert len(list(tmp_path.glob("ch4-exploration-*.png"))) == 6


def test_skills_run_small_and_report_table_4_1_rows(tmp_path: Path) -> None:
    reproduction = find("ch4-skills")
    run(reproduction, seeds=1, scale=reproduction.quick_scale, jobs=1, out=tmp_path,
        command="test")
    rows = json.loads((tmp_path / "ch4-skills.json").read_text())["summary"]["rows"]
    assert len(rows) == 8 * 2 * 2  # forward models x trainings x phases
    keys = {"fm", "part", "policy", "dims", "phase", "first_action", "last_action", "goal",
            "effect"}
    assert all(keys <= set(r) for r in rows)
    assert {(r["fm"], r["part"], r["policy"], r["dims"]) for r in rows} == {
        (fm, part, policy, dims) for fm, part, policy, dims, _ in ch4_skills.FORWARD_MODELS}
    assert all(len(r["first_action"]) == 3 and abs(r["first_action"][0]) <= 0.01 for r in rows)
    assert all(r["first_action"][1:] == [0.0, 0.0] for r in rows if r["dims"] == 1)


def agent_run(ended: bool, actions: int, learns: int) -> dict:
    return {"ended_as_thesis": ended, "exploratory_actions": actions, "learn_actions": learns}


def test_agent_summary_compares_the_modes_exploratory_actions() -> None:
    from robot.reproduce import ch4_agent

    seeds = [{"random": {"experiment1": agent_run(True, 24, 5),
                         "experiment2": agent_run(True, 60, 11)},
              "active": {"experiment1": agent_run(True, 155, 5),
                         "experiment2": agent_run(False, 296, 9)}},
             {"random": {"experiment1": agent_run(True, 30, 6),
                         "experiment2": agent_run(True, 50, 10)},
              "active": {"experiment1": agent_run(True, 121, 4),
                         "experiment2": agent_run(True, 250, 9)}}]
    summary = ch4_agent.summarize(seeds)
    assert summary["random"]["experiment1"] == {
        "ended_as_thesis": 2, "exploratory_actions_mean": 27.0, "exploratory_actions_min": 24,
        "exploratory_actions_max": 30, "learn_actions_mean": 5.5}
    assert summary["active"]["experiment2"]["ended_as_thesis"] == 1
    rows = {row.quantity: row for row in ch4_agent.compare(summary, seeds)}
    assert rows["experiment2 active: share of seeds ending as in §6.4.2"].measured == 0.5
    assert rows["experiment1 active: exploratory actions"].measured == 138.0
    assert find("ch4-agent").default_seeds == 5

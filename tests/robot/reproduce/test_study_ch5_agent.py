"""``ch5-agent``'s statistics and listing on hand-made seeds (its runs are the agent runs of
tests/robot/reproduce/test_transfer_agent.py, through the same helpers:
studies/common/ch5_agent.py)."""

from __future__ import annotations

import pytest

from robot.reproduce.framework.statistics import summarize
from robot.reproduce.studies import ch5_agent

CONFIG = ch5_agent.Config(orders={"thesis": ("o1", "o4")}, perceptions=("truth",))


def can_run(finished: bool, exploratory: int, n: int | None = None) -> dict:
    run = {"finished": finished, "disposed": 5 if finished else 2,
           "exploratory_actions": exploratory, "robot_actions": 20, "total_actions": 90,
           "cycles": 30, "learn_requests": 1, "gave_up": False}
    return run if n is None else {**run, "algorithm6_n": n}


def seed(o1: tuple[bool, int], o4: tuple[bool, int], random: tuple[int, int]):
    return ch5_agent.Result.model_validate({"perceptions": {"truth": {
        "orders": {"thesis": {"o1": can_run(*o1, 39), "o4": can_run(*o4, 1)}},
        "random": {"o1": can_run(True, random[0]), "o4": can_run(True, random[1])}}}})


SEEDS = [seed((True, 8), (True, 1), (16, 30)), seed((True, 20), (False, 9), (12, 26))]


def test_the_agent_beside_algorithm_6_and_random_learning():
    summary = summarize(ch5_agent.metrics(CONFIG), ch5_agent.claims(CONFIG), SEEDS)
    rows = {row.key: row for row in summary.metrics}
    assert rows["truth.thesis.o4.finished"].mean == 0.5
    assert rows["truth.thesis.o4.exploratory_actions"].mean == 5.0
    assert rows["truth.thesis.o4.exploratory_actions"].reference == 3  # Table 5.4's N_tran
    assert rows["truth.thesis.o1.exploratory_actions"].reference is None
    assert rows["truth.thesis.o1.algorithm6_n"].mean == 39.0
    assert rows["truth.random.o1.exploratory_actions"].mean == 14.0
    fewer = next(c for c in summary.comparisons
                 if c.metric == "truth.thesis.o4.exploratory_actions")
    assert fewer.versus == "truth.random.o4.exploratory_actions"
    assert fewer.mean_difference == -23.0


def test_the_listing_counts_the_seeds_within_n_plus_5_and_within_random_learning():
    listing = ch5_agent.listings(CONFIG, SEEDS)
    assert "| o1 | 2/2 | 14.0 | 39.0 | 14.0 | 2/2 | 20.0 | 90.0 | 2/2 | 1/2 |" in listing
    assert "| o4 | 1/2 | 5.0 | 1.0 | 28.0 | 2/2 | 20.0 | 90.0 | 1/2 | 2/2 |" in listing


def test_an_order_naming_an_unknown_can_is_refused():
    with pytest.raises(ValueError, match="unknown can 'o9'"):
        ch5_agent.Config(orders={"thesis": ("o1", "o9")})
    with pytest.raises(ValueError, match="each once"):
        ch5_agent.Config(orders={"twice": ("o1", "o1")})

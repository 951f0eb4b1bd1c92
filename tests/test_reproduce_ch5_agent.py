"""``ch5-agent``'s summary, table and listing on hand-made seeds (its runs are the agent runs of
tests/test_transfer_agent.py, through the same helpers)."""

from __future__ import annotations

from robot.reproduce import ch5_agent
from robot.reproduce.framework import find


def can_run(finished: bool, exploratory: int, n: int) -> dict:
    return {"finished": finished, "disposed": 5 if finished else 2,
            "exploratory_actions": exploratory, "robot_actions": 20, "total_actions": 90,
            "cycles": 30, "learn_requests": 1, "gave_up": False, "algorithm6_n": n}


def random_run(exploratory: int) -> dict:
    return {"finished": True, "disposed": 5, "exploratory_actions": exploratory,
            "robot_actions": 30, "total_actions": 120, "cycles": 40, "learn_requests": 4,
            "gave_up": False}


SEEDS = [
    {"seed": 0, "truth": {"orders": {"thesis": {"o1": can_run(True, 8, 39),
                                                "o4": can_run(True, 1, 1)}},
                          "random": {"o1": random_run(16), "o4": random_run(30)}}},
    {"seed": 1, "truth": {"orders": {"thesis": {"o1": can_run(True, 20, 39),
                                                "o4": can_run(False, 9, 1)}},
                          "random": {"o1": random_run(12), "o4": random_run(26)}}},
]


def test_the_summary_sets_the_agent_beside_algorithm_6_and_random_learning():
    summary = ch5_agent.summarize(SEEDS)
    assert summary["truth"]["thesis"]["o1"] == {
        "finished": 2, "exploratory_actions": 14.0, "algorithm6_n": 39.0,
        "random_exploratory_actions": 14.0, "random_finished": 2, "robot_actions": 20.0,
        "total_actions": 90.0, "within_n_plus_5": 2, "at_most_random": 1}
    o4 = summary["truth"]["thesis"]["o4"]
    assert (o4["finished"], o4["within_n_plus_5"], o4["at_most_random"]) == (1, 1, 2)


def test_the_table_gives_finishes_and_exploratory_actions_beside_table_5_4():
    rows = {row.quantity: row for row in ch5_agent.compare(ch5_agent.summarize(SEEDS), SEEDS)}
    finished = rows["o4 (thesis order, truth): share of seeds finished"]
    assert (finished.measured, finished.reference) == (0.5, 1.0)
    explored = rows["o4 (thesis order, truth): exploratory actions"]
    assert (explored.measured, explored.reference) == (5.0, 3)
    assert rows["o1 (thesis order, truth): exploratory actions"].reference is None
    listing = ch5_agent.listings(ch5_agent.summarize(SEEDS), SEEDS)
    assert "| o4 | 1/2 | 5.0 | 1.0 | 28.0 | 2/2 | 20.0 | 90.0 | 1/2 | 2/2 |" in listing


def test_it_is_registered_with_five_seeds():
    assert find("ch5-agent").default_seeds == 5

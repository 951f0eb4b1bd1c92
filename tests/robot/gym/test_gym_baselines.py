"""The ch3-baselines study (issue 31) at its quick size, and the tabular Q-learning agent it
runs beside XCS and stable-baselines3's DQN (hand-computed updates)."""

from __future__ import annotations

import tempfile

import pytest

from robot.gym.qlearning import QLearning
from robot.reproduce.framework.backends import LocalBackend
from robot.reproduce.framework.registry import find
from robot.reproduce.framework.runner import reproduce
from robot.reproduce.studies.ch3_baselines import METHODS, TASKS


def test_q_learning_updates_by_sutton_and_bartos_eq_6_8():
    agent = QLearning(3, 2, alpha=0.5, gamma=0.9, initial=10.0, random_state=0)
    assert agent.update(0, 1, -100.0, 2, terminal=False) == -100.0 + 0.9 * 10.0 - 10.0
    assert agent.q[0, 1] == 10.0 + 0.5 * (-101.0)  # -40.5
    assert agent.update(2, 0, 1000.0, 1, terminal=True) == 990.0  # no future past the goal
    assert agent.q[2, 0] == 505.0
    agent.update(1, 0, 0.0, 2, terminal=False)  # 0 + 0.9 * 505 - 10 = 444.5, half of it
    assert agent.q[1, 0] == pytest.approx(10.0 + 0.5 * 444.5)
    assert [agent.act(0, explore=False) for _ in range(5)] == [0] * 5  # Q(0, 0)=10 > -40.5
    assert {agent.act(0, explore=True) for _ in range(50)} == {0, 1}  # ε = 1: at random
    ties = QLearning(1, 4, random_state=1)
    assert {ties.act(0, explore=False) for _ in range(100)} == {0, 1, 2, 3}
    with pytest.raises(ValueError, match="alpha must lie in"):
        QLearning(2, 2, alpha=1.5)


def test_ch3_baselines_runs_every_learner_through_gymnasium(tmp_path, monkeypatch):
    """One seed: every check reads each trial of each learner on each task (the protocol,
    eqs. 3.14 and 3.15) and which payoff the metric takes; a second seed made the same checks
    on other draws (2.1 s CPU, half the test). The mean over seeds is summarize's, tested on
    hand-made seeds (test_studies.py)."""
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    monkeypatch.setenv("TMPDIR", str(scratch))  # seeds run in child processes too
    monkeypatch.setattr(tempfile, "tempdir", None)
    study = find("ch3-baselines")
    config = study.quick_config()
    outcome = reproduce(study, config, [0], LocalBackend(1), tmp_path)
    seeds = outcome.document.results(study)
    assert [s.trials for s in seeds] == [4]
    for seed, task, method in ((s, t, m) for s in seeds for t in TASKS for m in METHODS):
        run = getattr(getattr(seed, task), method)
        assert run.explore == [1, 0, 1, 0] and all(1 <= n <= 10 for n in run.steps)
        for payoff, steps, success in zip(run.payoff, run.steps, run.success, strict=True):
            assert payoff % 100 == 0 and -100 * steps <= payoff <= 1000  # eq. 3.14, 3.15
            assert success == (payoff > 0) or task == "stacking"
    metrics = {row.key: row for row in outcome.document.summary.metrics}
    key = "navigation.dqn.exploit_payoff_after"
    assert metrics[key].mean == seeds[0].navigation.dqn.payoff[3]  # trial 4: exploit, after
    page = (tmp_path / "ch3-baselines.md").read_text()
    assert "## Claims and tests" in page and "tabular Q-learning" in page
    # DQN's learn() left no SB3-<time> log folders (torch keeps its one compile cache there)
    assert [p.name for p in scratch.iterdir() if p.name.startswith("SB3-")] == []

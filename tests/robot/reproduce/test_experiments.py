"""Thesis §6.4.2 on the simulated cans: Experiments 1 and 2 of the garbage disposal agent."""

from __future__ import annotations

import io
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest

from goalagent.agent import Agent
from goalagent.beliefs import load_beliefs, save_beliefs
from goalagent.kb.terms import Atom
from goalagent.mas import MultiAgentSystem
from robot.affordance import AFFORD, affordances
from tests.conftest import cli

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

ROOT = Path(__file__).resolve().parents[3]
MAS = ROOT / "agents" / "garbage_disposal.mas2g"
TAU = 0.6
R2 = 0.05
SEEDS = [0, 1, 2]


@dataclass
class Trail:
    """The actions of a run, each with the number of balls disposed of before it."""

    actions: list[tuple[int, str]] = field(default_factory=list)

    def record(self, agent: Agent) -> None:
        done = agent.query("bel", "disposed(K)")
        trial = int(done[0]["K"]) + 1 if done else 1
        report = agent.last_report
        if report is not None:
            self.actions.extend((trial, text) for text in report.actions)

    def trials_with(self, prefix: str) -> set[int]:
        return {trial for trial, text in self.actions if text.startswith(prefix)}

    def parts_learned(self) -> list[str]:
        return [text.split("(")[1].split(",")[0] for _, text in self.actions
                if text.startswith("learn(")]


def run(can: str, seed: int, models: Path, beliefs: Path | None = None,
        trials: int = 5, learning: str = "random",
        active_n_max: int = 100) -> tuple[MultiAgentSystem, Trail]:
    params = {"can": Atom(can), "seed": seed, "models": str(models), "trials": trials,
              "learning": Atom(learning), "active_n_max": active_n_max}
    system = MultiAgentSystem.from_mas_file(MAS, env_params=params, seed=seed,
                                            output=io.StringIO(), warn=lambda message: None)
    (agent,) = system.agents
    if beliefs is not None:
        load_beliefs(agent, beliefs)
    trail = Trail()
    system.run(max_cycles=400, after_cycle=trail.record)
    return system, trail


def table(agent: Agent) -> dict[tuple[str, str], tuple[int, int, float]]:
    return {(a.obj, a.act): (a.tot, a.suc, a.rel) for a in affordances(agent)}


def check_experiment_1(system: MultiAgentSystem, trail: Trail) -> None:
    """§6.4.2, Experiment 1: learning in trial 1 only, then the lid pushed open five times."""
    (agent,) = system.agents
    assert agent.terminated, "the agent did not finish its five trials"
    assert agent.query("bel", "disposed(5)")
    assert trail.trials_with("learn(") == {1}
    assert trail.trials_with("apply(lid,extend_arm)") == {1, 2, 3, 4, 5}
    rows = table(agent)
    assert rows[("lid", "extend_arm")] == (5, 5, 1.0)
    for (obj, act), (_, _, rel) in rows.items():
        if (obj, act) != ("lid", "extend_arm"):
            assert rel < TAU, (obj, act, rel)
    tried = {text.split(",")[1] for _, text in trail.actions if text.startswith("learn(")}
    assert all(rows[("lid", act)][2] < TAU for act in tried - {"extend_arm"})


def check_experiment_2(system: MultiAgentSystem, trail: Trail) -> None:
    """§6.4.2, Experiment 2: the lid fails on o2, learning moves on to the handle."""
    (agent,) = system.agents
    assert agent.terminated and agent.query("bel", "disposed(5)")
    rows = table(agent)
    # the lid affordance decays through failures (eq. 6.3) until it is not reliable ...
    tot, suc, rel = rows[("lid", "extend_arm")]
    assert suc == 5 and tot >= 9 and rel < TAU
    failures = [t for t, text in trail.actions if text.startswith("apply(lid,extend_arm)")]
    assert len(failures) == 4 and set(failures) == {1}
    # ... learning restarts on the lid, is abandoned, and moves to the handle
    learned = trail.parts_learned()
    assert "lid" in learned and "handle" in learned
    assert learned.index("handle") > max(i for i, p in enumerate(learned) if p == "lid")
    assert all(rel < TAU for (obj, _), (_, _, rel) in rows.items() if obj == "lid")
    assert rows[("handle", "lift_up")][2] == 1.0
    assert trail.trials_with("learn(") == {1}


def exploratory_actions(system: MultiAgentSystem) -> int:
    """The agent's own count of the exploratory actions its learning took."""
    (agent,) = system.agents
    (answer,) = agent.query("bel", "exploratory_actions(T)")
    return int(answer["T"])


@pytest.mark.parametrize("seed", SEEDS)
def test_experiment_1_learns_once_and_experiment_2_relearns_from_its_beliefs(tmp_path: Path,
                                                                            seed: int):
    """Experiment 1 on o1, then Experiment 2 on o2 from the beliefs Experiment 1 saved."""
    models, saved = tmp_path / "models.json", tmp_path / "exp1.pl"
    first, trail = run("o1", seed, models)
    try:
        check_experiment_1(first, trail)
        assert exploratory_actions(first) >= 4 * len(trail.parts_learned())  # n_min = 4
        save_beliefs(first.agents, [AFFORD], saved)
    finally:
        first.close()
    system, trail = run("o2", seed, models, beliefs=saved)
    try:
        check_experiment_2(system, trail)
    finally:
        system.close()


def test_both_experiments_end_the_same_when_the_agent_learns_actively(tmp_path: Path):
    """learning=active: Algorithm 3 explores each θ (at most 25 tries here, at least 21)."""
    models = tmp_path / "models.json"
    first, trail = run("o1", 0, models, learning="active", active_n_max=25)
    try:
        check_experiment_1(first, trail)
        learns = len(trail.parts_learned())
        assert 21 * learns <= exploratory_actions(first) <= 25 * learns
        assert all(",active)" in text for _, text in trail.actions if text.startswith("learn("))
        saved = tmp_path / "exp1.pl"
        save_beliefs(first.agents, [AFFORD], saved)
    finally:
        first.close()
    system, trail = run("o2", 0, models, beliefs=saved, learning="active", active_n_max=25)
    try:
        check_experiment_2(system, trail)
    finally:
        system.close()


def test_experiments_from_the_command_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """The README's commands: Experiment 1 saves its beliefs and plots its reliabilities,
    Experiment 2 starts from them (one trial here: all its learning happens in the first).
    The command runs in this process (cli()): what is checked is its exit code, its files
    and its messages, which two child Pythons only paid a start-up each for."""
    from matplotlib.image import imread

    saved = tmp_path / "exp1.pl"
    models = f"models={tmp_path / 'models.json'}"
    common = ["run", str(MAS), "--env-param", models]
    monkeypatch.chdir(tmp_path)
    first = cli(*common, "--save-beliefs", str(saved), "--plot", str(tmp_path / "exp1.png"))
    assert first.exit_code == 0, first.stderr
    assert "afford(lid,extend_arm,opened,5,5,1.0)." in saved.read_text()
    plot = imread(tmp_path / "exp1.png")
    assert plot.shape[:2] == (550, 990)  # 9 x 5 inches at 110 dpi
    from matplotlib import colormaps

    drawn = [colour for colour in colormaps["tab20"].colors
             if np.all(np.abs(plot[..., :3] - colour) < 0.02, axis=-1).sum() > 20]
    assert len(drawn) >= 3  # several affordances' reliability steps, one tab20 colour each
    second = cli(*common, "--env-param", "can=o2", "--env-param", "trials=1",
                 "--load-beliefs", str(saved))
    assert second.exit_code == 0, second.stderr
    assert "robot: terminated" in second.stderr
    table = [line for line in second.stderr.splitlines() if "lift_up" in line]
    assert any("handle" in line and "1.000" in line for line in table), second.stderr

"""``ch4-agent``: the garbage disposal agent's Experiments 1 and 2 (thesis §6.4.2) learning in
random and in active mode (chapter 4): do they end the same, and how many exploratory actions
does learning take in each mode?"""

from __future__ import annotations

import io
from pathlib import Path

from robot.reproduce.framework import Comparison, Figure, Panel, Progress, Reproduction, Series

MODES = ("random", "active")
EXPERIMENTS = ("experiment1", "experiment2")
TAU = 0.6
MAS = Path(__file__).resolve().parents[2] / "agents" / "garbage_disposal.mas2g"


def _run(can: str, seed: int, mode: str, models: Path, beliefs: Path | None) -> dict:
    """One experiment: did it end as §6.4.2 says, and what did learning cost?"""
    from goalagent.beliefs import load_beliefs, save_beliefs
    from goalagent.kb.terms import Atom
    from goalagent.mas import MultiAgentSystem
    from robot.affordance import AFFORD, affordances

    params = {"can": Atom(can), "seed": seed, "models": str(models), "learning": Atom(mode)}
    system = MultiAgentSystem.from_mas_file(MAS, env_params=params, seed=seed,
                                            output=io.StringIO(), warn=lambda message: None)
    try:
        (agent,) = system.agents
        if beliefs is not None:
            load_beliefs(agent, beliefs)
        learns = []

        def record(agent) -> None:
            report = agent.last_report
            if report is not None:
                learns.extend(text for text in report.actions if text.startswith("learn("))

        system.run(max_cycles=400, after_cycle=record)
        rows = {(a.obj, a.act): (a.tot, a.suc, a.rel) for a in affordances(agent)}
        (total,) = agent.query("bel", "exploratory_actions(T)")
        lid_unreliable = all(rel < TAU for (obj, _), (_, _, rel) in rows.items() if obj == "lid")
        if can == "o1":
            ended = rows.get(("lid", "extend_arm")) == (5, 5, 1.0)
        else:
            ended = rows.get(("handle", "lift_up"), (0, 0, 0.0))[2] == 1.0 and lid_unreliable
        if beliefs is None:
            save_beliefs(system.agents, [AFFORD], models.with_suffix(".pl"))
        return {"ended_as_thesis": bool(ended and agent.query("bel", "disposed(5)")),
                "exploratory_actions": int(total["T"]), "learn_actions": len(learns),
                "affordances": {f"{obj}/{act}": list(value) for (obj, act), value in rows.items()}}
    finally:
        system.close()


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    """Experiments 1 (o1) and 2 (o2, starting from Experiment 1's beliefs) in both modes.

    ``scale`` does not shrink these runs (an experiment is what it is); the quick size only
    runs fewer seeds.
    """
    import tempfile

    result: dict = {}
    with tempfile.TemporaryDirectory() as folder:
        for done, mode in enumerate(MODES):
            models = Path(folder) / f"models-{mode}.json"
            first = _run("o1", seed, mode, models, None)
            second = _run("o2", seed, mode, models, models.with_suffix(".pl"))
            result[mode] = {"experiment1": first, "experiment2": second}
            progress((done + 1) / len(MODES))
    return result


def summarize(seeds: list[dict]) -> dict:
    """Per mode and experiment: seeds that ended as §6.4.2 says, and the exploratory actions
    (mean, min, max over seeds)."""
    summary: dict = {}
    for mode in MODES:
        summary[mode] = {}
        for experiment in EXPERIMENTS:
            runs = [seed[mode][experiment] for seed in seeds]
            counts = [run["exploratory_actions"] for run in runs]
            summary[mode][experiment] = {
                "ended_as_thesis": sum(run["ended_as_thesis"] for run in runs),
                "exploratory_actions_mean": sum(counts) / len(counts),
                "exploratory_actions_min": min(counts),
                "exploratory_actions_max": max(counts),
                "learn_actions_mean": sum(run["learn_actions"] for run in runs) / len(runs),
            }
    return summary


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    """Share of seeds ending as the thesis's experiments do, and the cost of learning."""
    from robot.reproduce.framework import mean_and_std

    rows = []
    for experiment in EXPERIMENTS:
        for mode in MODES:
            runs = [seed[mode][experiment] for seed in seeds]
            mean, spread = mean_and_std([float(run["ended_as_thesis"]) for run in runs])
            rows.append(Comparison(f"{experiment} {mode}: share of seeds ending as in §6.4.2",
                                   mean, spread, 1.0, "§6.4.2"))
            mean, spread = mean_and_std([run["exploratory_actions"] for run in runs])
            rows.append(Comparison(f"{experiment} {mode}: exploratory actions", mean, spread))
            mean, spread = mean_and_std([run["learn_actions"] for run in runs])
            rows.append(Comparison(f"{experiment} {mode}: learn actions", mean, spread))
    return rows


def figures(seeds: list[dict]) -> list[Figure]:
    """Exploratory actions per experiment, one point per seed, random vs active."""
    x = [1, 2]
    series = [Series(mode, x, [[seed[mode][e]["exploratory_actions"] for e in EXPERIMENTS]
                               for seed in seeds]) for mode in MODES]
    return [Figure("exploratory-actions", "Exploratory actions of learning per experiment",
                   [Panel("experiment (1: o1 from scratch, 2: o2 from Experiment 1)",
                          "exploratory actions", series)])]


NOTES = """\
The agent is `agents/garbage_disposal.mas2g` unchanged, told its learning mode by the
environment (`--env-param learning=random|active`, percept `learning_mode(M)`); ground-truth
perception. Random mode explores θ uniformly and stops when the fitted line settles (eq. 5.19,
at least 4 tries, at most 10); active mode runs Algorithm 3 over θ (the first 20 tries
uniform, then CACLA, stopping where (4.10) holds, at most N_s = 100) and reads e_max and θ_max
off the forward model. "Exploratory actions" is the agent's own count (the sum of the
`exploration(Part, Act, Mode, N)` percepts); Experiment 2 starts from Experiment 1's beliefs
and models of the same mode. "Ending as in §6.4.2": Experiment 1 ends with
afford(lid, extend_arm, opened, 5, 5, 1); Experiment 2 with afford(handle, lift_up, ...) at
reliability 1 and every lid affordance below τ; both with five balls disposed of.
"""

REPRODUCTION = Reproduction(
    name="ch4-agent",
    description="Experiments 1 and 2 of the garbage disposal agent, learning randomly vs actively",
    run_seed=run_seed,
    summarize=summarize,
    compare=compare,
    figures=figures,
    notes=NOTES,
    default_seeds=5,
)

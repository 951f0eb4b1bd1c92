"""``ch3-baselines``: standard RL agents beside affordance-based and standard XCS in the
navigation and stacking tasks (issue 31), all four through the Gymnasium API.

Each seed runs, in each task, the chapter-3 experiment (§3.5.7: 20 trials, odd ones exploring,
even ones exploiting; the boxes exchanged after trial 10) with affordance-based XCS
(Algorithm 2), standard XCS, tabular Q-learning and stable-baselines3's DQN, each on the
``goalagent/Navigation-v0`` / ``goalagent/Stacking-v0`` environment
(``robot.gym.experiments``).
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from itertools import product
from typing import Annotated, Literal

from pydantic import Field

from robot.reproduce.framework import (
    Claim,
    Figure,
    Metric,
    Panel,
    Progress,
    Reference,
    SeedResult,
    Series,
    Study,
    in_turn,
)
from robot.reproduce.studies.common.tasks import NavigationConfig
from robot.reproduce.studies.common.xcs import Rate, xcs_keywords

TASKS = ("navigation", "stacking")
ENV_IDS = {"navigation": "goalagent/Navigation-v0", "stacking": "goalagent/Stacking-v0"}
METHODS = ("affordance_xcs", "standard_xcs", "q_learning", "dqn")
BASELINES = ("q_learning", "dqn")


class Config(NavigationConfig):
    """§3.5.7's experiment in both tasks; Table 7.1's XCS; the baselines' own settings."""

    perception: Literal["truth", "camera"] = "truth"
    """How every learner perceives the state bits (eq. 3.12): ground truth or the camera
    (they agree trial by trial: ch3-navigation, ch3-stacking)."""
    q_alpha: Rate = 0.2
    """Q-learning's step size α (Sutton & Barto eq. 6.8); XCS's prediction rate β_p (Table
    7.1). Q-learning's discount is ``gamma`` and its initial values ``prediction_init``, as
    XCS's."""
    dqn_learning_rate: Annotated[float, Field(gt=0.0)] = 1e-3
    """DQN's Adam step size (stable-baselines3's default 1e-4 learns nothing in 100 steps)."""
    dqn_batch_size: Annotated[int, Field(ge=1)] = 32
    """Transitions per gradient step (stable-baselines3's default)."""
    dqn_target_update: Annotated[int, Field(ge=1)] = 20
    """Steps between copies of the online network into the target network (the default,
    10,000, is fifty experiments)."""
    dqn_hidden: Annotated[int, Field(ge=1)] = 64
    """Units in each of the Q-network's two hidden layers (the default)."""
    dqn_buffer: Annotated[int, Field(ge=1)] = 10_000
    """Replay buffer size (holds every step of an experiment)."""


class Trials(SeedResult):
    """One experiment, trial by trial."""

    payoff: list[float]
    steps: list[int]
    success: list[int]
    explore: list[int]


class Methods(SeedResult):
    affordance_xcs: Trials
    standard_xcs: Trials
    q_learning: Trials
    dqn: Trials


class Result(SeedResult):
    trials: int
    navigation: Methods
    stacking: Methods


def run(config: Config, seed: int, progress: Progress) -> Result:
    import gymnasium

    from behaviours.xcs_trials import TrialRecord
    from robot.gym.experiments import DqnSettings, dqn_run, q_learning_run, xcs_run
    from robot.gym.registration import register_envs

    register_envs()

    trials = config.scaled_trials()
    settings = DqnSettings(config.gamma, config.dqn_learning_rate, config.dqn_batch_size,
                           config.dqn_buffer, config.dqn_target_update, config.dqn_hidden)
    runs: dict[str, dict[str, Trials]] = {task: {} for task in TASKS}
    for task, method in in_turn(product(TASKS, METHODS), progress):
        change = ({"exchange_after": trials // 2, "start": config.start}
                  if task == "navigation" else {})
        make_env = functools.partial(gymnasium.make, ENV_IDS[task], n_step=config.n_step,
                                     perception=config.perception, **change)
        records: list[TrialRecord]
        if method == "q_learning":
            records = q_learning_run(make_env, seed, trials, alpha=config.q_alpha,
                                     gamma=config.gamma, initial=config.prediction_init)
        elif method == "dqn":
            records = dqn_run(make_env, seed, trials, settings)
        else:
            records = xcs_run(make_env, method, seed, trials, **xcs_keywords(config))
        runs[task][method] = Trials(
            payoff=[r.payoff for r in records], steps=[r.steps for r in records],
            success=[int(r.success) for r in records], explore=[int(r.explore) for r in records])
    return Result(trials=trials, **{task: Methods(**runs[task]) for task in TASKS})


def second_half(run: Trials, values: Sequence[float], exploit_only: bool) -> float:
    """The mean of ``values`` over the second half of the trials (after the exchange in the
    navigation task), exploit trials only with ``exploit_only``."""
    half = len(values) // 2
    chosen = [values[t] for t in range(half, len(values))
              if not exploit_only or not run.explore[t]]
    return sum(chosen) / len(chosen)


def _get(task: str, method: str):
    return lambda seed: getattr(getattr(seed, task), method)


def metrics(config: Config) -> list[Metric[Result]]:
    trials = config.scaled_trials()
    after = f"trials {trials // 2 + 1}-{trials}"
    rows: list[Metric[Result]] = []
    for task, method in product(TASKS, METHODS):
        get, key = _get(task, method), f"{task}.{method}"
        rows += [
            Metric(f"{key}.exploit_success_after", f"{task}, {method}: exploit success rate, "
                   f"{after}", lambda s, get=get: second_half(get(s), get(s).success, True)),
            Metric(f"{key}.exploit_payoff_after", f"{task}, {method}: exploit payoff, {after}",
                   lambda s, get=get: second_half(get(s), get(s).payoff, True)),
            Metric(f"{key}.steps_after", f"{task}, {method}: steps per trial, {after}",
                   lambda s, get=get: second_half(get(s), get(s).steps, False)),
        ]
    return rows


def claims(config: Config) -> list[Claim]:
    rows = []
    for task, baseline in product(TASKS, BASELINES):
        when = "after the boxes are exchanged" if task == "navigation" else "in the second half"
        rows.append(Claim(f"{task}: affordance-based XCS succeeds more often in exploit trials "
                          f"than {baseline} {when}",
                          f"{task}.affordance_xcs.exploit_success_after",
                          f"{task}.{baseline}.exploit_success_after"))
        rows.append(Claim(f"{task}: affordance-based XCS earns more in exploit trials than "
                          f"{baseline} {when}", f"{task}.affordance_xcs.exploit_payoff_after",
                          f"{task}.{baseline}.exploit_payoff_after"))
    rows += [Claim(f"{task}: standard XCS and tabular Q-learning (which XCS generalises, "
                   "§3.3.3) earn the same in exploit trials",
                   f"{task}.standard_xcs.exploit_payoff_after",
                   f"{task}.q_learning.exploit_payoff_after", "same") for task in TASKS]
    return rows


def figures(config: Config, seeds: Sequence[Result]) -> list[Figure]:
    trials = seeds[0].trials
    x = list(range(1, trials + 1))
    result = []
    for task in TASKS:
        marks = [Reference(1000.0 if task == "navigation" else 900.0, "best payoff")]
        if task == "navigation":
            marks.append(Reference(trials / 2 + 0.5, "boxes exchanged", vertical=True))
        series = [Series(method, x, [[float(v) for v in _get(task, method)(s).payoff]
                                     for s in seeds]) for method in METHODS]
        result.append(Figure(f"{task}-payoff", f"Payoff per trial, {task} task", [
            Panel("trial (odd: explore, even: exploit)", "payoff (eq. 3.16)", series, marks)]))
    return result


STUDY = Study(
    name="ch3-baselines",
    description="Tabular Q-learning and stable-baselines3's DQN beside affordance-based and "
                "standard XCS in the navigation and stacking tasks, all through Gymnasium",
    config=Config, result=Result, run=run, metrics=metrics, claims=claims, figures=figures,
    quick={"scale": 0.2}, default_seeds=10,
    headline=("navigation.affordance_xcs.exploit_success_after",
              "navigation.q_learning.exploit_success_after",
              "navigation.dqn.exploit_success_after",
              "stacking.dqn.exploit_payoff_after"),
    notes="""\
**Setup**: every learner runs §3.5.7's experiment on the Gymnasium environments
(`goalagent/Navigation-v0`, `goalagent/Stacking-v0`; docs/gymnasium.md): 20 trials of at most
n_step = 10 actions, odd trials exploring, even ones exploiting; in the navigation task the
boxes are exchanged after trial 10. Rewards eq. 3.14 and 3.15; the payoff of a trial is eq.
3.16. All four learn in explore trials only and act greedily in exploit trials, as XCS does
(App. A): the thesis's trial budget is 10 explore trials, at most 100 learning steps.

- *affordance_xcs*, *standard_xcs*: XCS with Table 7.1's parameters, filtered by the
  affordance table (Algorithm 2) or not, driven through the environment by
  `robot.gym.adapters.EnvTask` (the same records as driving the task directly: tested).
- *q_learning*: tabular Q-learning (`robot/gym/qlearning.py`) over the 256 states of the
  integer observation, α = 0.2, γ = 0.7, initial values 10 (XCS's β_p, γ and p_I), random
  actions in explore trials.
- *dqn*: stable-baselines3's DQN over the 8 state bits, an MLP of two hidden layers of 64,
  Adam at 1e-3, batches of 32 from the start, target network copied every 20 steps, γ = 0.7,
  random actions in explore trials (ε = 1), one gradient step per environment step; its
  defaults (learning from step 100, a target update every 10,000 steps) would not learn
  within the budget. Explore trials run in `learn`, exploit trials in a second environment
  of the same task (`robot/gym/experiments.py`).

The claims compare affordance-based XCS with each baseline, paired by seed, in the second half
of the trials: after the exchange in the navigation task (where the thesis's claim about
standard XCS lies), the learned policy in the stacking task.""",
)

"""Running XCS on a task: trials (Algorithm 2's loop), experiments, Table 7.1's parameters.

An experiment alternates explore and exploit trials, odd trials exploring (§3.5.8); a trial
ends at the goal, when the robot falls, or after ``n_step`` actions (n_step = 10 in chapter 3,
N_s = 20 in App. A's search), and the task is set up as before for the next one. The payoff
of a trial is the sum of its rewards (eq. 3.16). Every action that has an effect on the object
in front updates the affordance table, in explore and exploit trials alike (Algorithm 2, line
11); XCS itself learns in explore trials only (App. A, "Performance Component") unless it is
made with ``learn_in_exploit``. A task's ``applicable`` actions (preconditions) bound each
choice.
"""

from __future__ import annotations

from dataclasses import dataclass

from behaviours.learners.affordance_xcs import AffordanceXCS
from behaviours.learners.xcs import XCS
from behaviours.xcs_tasks import Task

TABLE_7_1: dict[str, float | int] = {
    "N": 100, "gamma": 0.7, "beta_p": 0.2, "beta_e": 0.2, "beta_f": 0.2, "chi": 0.8,
    "mu": 0.04, "epsilon_0": 10.0, "alpha": 0.1, "nu": 5.0, "prediction_init": 10.0,
    "error_init": 0.0, "fitness_init": 0.01, "p_hash": 0.6, "theta_ga": 5, "theta_del": 20,
}
"""XCS parameters of App. A's Table 7.1, used by both chapter-3 tasks as well (§3.5.7)."""
N_STEP = 10
"""Actions per trial at most in the chapter-3 tasks (§3.5.7)."""
SEARCH_STEPS = 20
"""Actions per trial at most in the search task (Table 7.1's N_s)."""
METHODS = ("affordance_xcs", "standard_xcs")
"""Algorithm 2 (XCS filtered by the affordance table) and the plain XCS baseline."""


@dataclass(frozen=True)
class TrialRecord:
    """One trial: its number (from 1), mode, payoff (eq. 3.16), steps, success, actions."""

    trial: int
    explore: bool
    payoff: float
    steps: int
    success: bool
    actions: tuple[str, ...]


def make_learner(actions: tuple[str, ...], method: str, seed: int,
                 filter_scope: str = "choice", **overrides: float | int | bool) -> AffordanceXCS:
    """XCS with Table 7.1's parameters (and ``overrides``), filtered or not by affordances
    (``filter_scope``: see ``AffordanceXCS``)."""
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; use {' or '.join(METHODS)}")
    xcs = XCS(len(actions), **{**TABLE_7_1, **overrides}, random_state=seed)
    return AffordanceXCS(xcs, actions, use_affordances=method == "affordance_xcs",
                         filter_scope=filter_scope)


def run_trial(task: Task, learner: AffordanceXCS, trial: int, explore: bool,
              n_step: int = N_STEP) -> TrialRecord:
    """Trial number ``trial`` (0-based): Algorithm 2 until the goal, a fall or ``n_step``."""
    view = task.reset(trial)
    payoff, done, success, taken = 0.0, False, False, []
    while not done and len(taken) < n_step:
        action = learner.act(view.bits, view.obj, explore, task.applicable(view))
        before = view
        outcome, view = task.perform(action)
        if outcome.effect is not None and before.obj is not None:
            learner.observe_effect(before.obj, action, outcome.effect)
        learner.reward(outcome.reward, outcome.done)
        payoff += outcome.reward
        done, success = outcome.done, outcome.success
        taken.append(task.actions[action])
    if not done:
        learner.end_trial()
    return TrialRecord(trial + 1, explore, payoff, len(taken), success, tuple(taken))


def run_experiment(task: Task, learner: AffordanceXCS, trials: int = 20,
                   n_step: int = N_STEP) -> list[TrialRecord]:
    """``trials`` trials, alternately exploring (odd trial numbers) and exploiting."""
    if trials < 1 or n_step < 1:
        raise ValueError(f"need at least one trial of at least one step, got trials={trials}, "
                         f"n_step={n_step}")
    return [run_trial(task, learner, t, explore=t % 2 == 0, n_step=n_step)
            for t in range(trials)]

"""The chapter-3 experiment (§3.5.7) for any learner, through the Gymnasium API.

Trials alternate, odd ones exploring and even ones exploiting (§3.5.8); each is one episode of a
goalagent task environment, set up as the experiment's trial k (so the boxes are exchanged from
trial ``exchange_after`` on), and its payoff is the sum of its rewards (eq. 3.16). The learners
learn in explore trials only and act greedily in exploit trials, as XCS does (App. A,
"Performance Component"):

- ``affordance_xcs`` / ``standard_xcs``: ``behaviours.xcs_trials`` on the environment through
  ``robot.gym.adapters.EnvTask`` (Algorithm 2, or XCS without the affordance filter);
- ``q_learning``: ``robot.gym.qlearning.QLearning`` on the integer state (``Discrete``);
- ``dqn``: stable-baselines3's DQN on the state bits (``MultiBinary``). Its ``learn`` runs one
  explore trial at a time (``StopTrainingOnMaxEpisodes``) in a training environment whose
  k-th episode is trial 2k-1; the exploit trials run ``predict(deterministic=True)`` in a second
  environment of the same task set up as the even trials. The two environments are the same
  task, and every trial starts from the same setting (§3.5.7), so this is one experiment.

Every run returns ``behaviours.xcs_trials.TrialRecord``s, one per trial.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import gymnasium as gym

from behaviours.xcs_trials import TrialRecord, make_learner, run_experiment
from robot.gym.adapters import EnvTask
from robot.gym.qlearning import QLearning

METHODS = ("affordance_xcs", "standard_xcs", "q_learning", "dqn")
EnvFactory = Callable[..., gym.Env]
"""Makes the task's environment with the given keywords (``observation=...``)."""


def xcs_run(make_env: EnvFactory, method: str, seed: int, trials: int,
            **xcs: Any) -> list[TrialRecord]:
    """Affordance-based or standard XCS (Table 7.1 with ``xcs``) through ``EnvTask``."""
    env = make_env()
    task = EnvTask(env, seed=seed)
    records = run_experiment(task, make_learner(task.actions, method, seed, **xcs),
                             trials=trials, n_step=env.unwrapped.n_step)
    env.close()
    return records


def q_learning_run(make_env: EnvFactory, seed: int, trials: int, *, alpha: float, gamma: float,
                   initial: float) -> list[TrialRecord]:
    """Tabular Q-learning, random actions in explore trials (ε = 1), greedy in exploit ones."""
    env = make_env(observation="discrete")
    agent = QLearning(env.observation_space.n, env.action_space.n, alpha=alpha, gamma=gamma,
                      initial=initial, epsilon=1.0, random_state=seed)
    codes = env.unwrapped.action_codes
    records = []
    for trial in range(trials):
        explore = trial % 2 == 0
        state, _ = env.reset(seed=seed if trial == 0 else None, options={"trial": trial})
        payoff, taken, over, info = 0.0, [], False, {"success": False}
        while not over:
            action = agent.act(int(state), explore)
            after, reward, terminated, truncated, info = env.step(action)
            if explore:
                agent.update(int(state), action, float(reward), int(after), terminated)
            payoff, state, over = payoff + float(reward), after, terminated or truncated
            taken.append(codes[action])
        records.append(TrialRecord(trial + 1, explore, payoff, len(taken),
                                   bool(info["success"]), tuple(taken)))
    env.close()
    return records


@dataclass(frozen=True)
class DqnSettings:
    """DQN's settings for an experiment of a few dozen trials (see the study's notes)."""

    gamma: float
    learning_rate: float
    batch_size: int
    buffer_size: int
    target_update_interval: int
    hidden: int


class ExploreTrials(gym.Wrapper):
    """The training environment: its k-th episode is explore trial 2k-1 (from 1), and every
    episode it finishes is recorded."""

    def __init__(self, env: gym.Env):
        """Wrap ``env``; no trial has run yet."""
        super().__init__(env)
        self.records: list[TrialRecord] = []
        self._resets, self._trial, self._payoff, self._taken = 0, 0, 0.0, []

    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[Any, dict[str, Any]]:
        """Set up the next explore trial (the options are this wrapper's to give)."""
        self._trial, self._resets = 2 * self._resets, self._resets + 1
        self._payoff, self._taken = 0.0, []
        return self.env.reset(seed=seed, options={"trial": self._trial})

    def step(self, action: Any) -> tuple[Any, float, bool, bool, dict[str, Any]]:
        """Step, and record the trial when it ends."""
        observation, reward, terminated, truncated, info = self.env.step(action)
        self._payoff += float(reward)
        self._taken.append(self.env.unwrapped.action_codes[int(action)])
        if terminated or truncated:
            self.records.append(TrialRecord(self._trial + 1, True, self._payoff,
                                            len(self._taken), bool(info["success"]),
                                            tuple(self._taken)))
        return observation, reward, terminated, truncated, info


def dqn_run(make_env: EnvFactory, seed: int, trials: int,
            settings: DqnSettings) -> list[TrialRecord]:
    """stable-baselines3's DQN, random actions in explore trials (ε = 1), greedy in exploit
    trials; one CPU thread (seeds run in parallel processes)."""
    import torch
    from stable_baselines3 import DQN
    from stable_baselines3.common.callbacks import StopTrainingOnMaxEpisodes
    from stable_baselines3.common.logger import Logger

    torch.set_num_threads(1)
    train, evaluate = ExploreTrials(make_env()), make_env()
    model = DQN("MlpPolicy", train, learning_rate=settings.learning_rate,
                buffer_size=settings.buffer_size, learning_starts=0,
                batch_size=settings.batch_size, gamma=settings.gamma, train_freq=1,
                gradient_steps=1, target_update_interval=settings.target_update_interval,
                exploration_initial_eps=1.0, exploration_final_eps=1.0,
                policy_kwargs={"net_arch": [settings.hidden, settings.hidden]}, seed=seed,
                device="cpu")
    # Without a logger of its own, every learn() makes a log folder tempdir/SB3-<time> and
    # leaves it there, empty: one per explore trial of every seed.
    model.set_logger(Logger(folder=None, output_formats=[]))
    codes = evaluate.unwrapped.action_codes
    exploits = []
    for trial in range(trials):
        if trial % 2 == 0:
            model.learn(total_timesteps=evaluate.unwrapped.n_step,
                        callback=StopTrainingOnMaxEpisodes(max_episodes=1),
                        reset_num_timesteps=trial == 0)
            continue
        state, _ = evaluate.reset(seed=seed if trial == 1 else None, options={"trial": trial})
        payoff, taken, over, info = 0.0, [], False, {"success": False}
        while not over:
            action, _ = model.predict(state, deterministic=True)
            state, reward, terminated, truncated, info = evaluate.step(int(action))
            payoff, over = payoff + float(reward), terminated or truncated
            taken.append(codes[int(action)])
        exploits.append(TrialRecord(trial + 1, False, payoff, len(taken),
                                    bool(info["success"]), tuple(taken)))
    train.close()
    evaluate.close()
    return sorted(train.records[:(trials + 1) // 2] + exploits, key=lambda r: r.trial)

"""CACLA, the continuous actor-critic of thesis §4.4.3 (eq. 4.5–4.9), and its stop test (4.10).

Actor Act(s) and critic V(s) are one-hidden-layer tanh networks (``network.TanhNetwork``, as
§4.6.1 says: 10 hidden units, weights uniform in [−0.3, 0.3]); actions are in [−1, 1] per
dimension. Per transition (s, a, r, s'):

- δ = r + γ V(s') − V(s)                              (4.7)
- if δ > 0: Act ← Act + ζ (a − Act(s)) ∇Act            (4.8, one SGD step towards a)
- always:   V ← V + β δ ∇V                             (4.9)

Exploration draws a ~ N(Act(s), σ²) per dimension (4.5), clipped to [−1, 1]: the robot may
not leave its action space (§4.6.1, footnote 4). ``TDConvergence`` is the termination test:
|δ̄_{k+1} − δ̄_k| < ε with δ̄_k the mean |δ| of the last N steps (4.10, 4.11).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import ClassVar

import numpy as np
from sklearn.base import BaseEstimator
from sklearn.exceptions import NotFittedError
from sklearn.utils import check_consistent_length, check_random_state
from sklearn.utils._param_validation import validate_params

from behaviours.learners.network import TanhNetwork
from behaviours.learners.persist import (
    LearnerFileError,
    json_params,
    read_learner,
    write_learner,
)
from behaviours.learners.validation import POSITIVE, POSITIVE_INT, RATE, as_rows

__all__ = ["CACLA", "TDConvergence", "td_error"]

KIND = "cacla"
NOT_FITTED = "this %(name)s has no actor yet; call sample or partial_fit first"


def td_error(reward: float, value: float, next_value: float, gamma: float) -> float:
    """δ = r + γ V(s') − V(s) (eq. 4.7)."""
    return reward + gamma * next_value - value


class CACLA(BaseEstimator):
    """Continuous Actor-Critic Learning Automaton over states (rows) and unit actions.

    Parameters:
        action_dims: dimensions of the action (1 or 3 in chapter 4).
        n_hidden: tanh units of the actor's and the critic's hidden layer (thesis: 10).
        sigma: Gaussian exploration per dimension, in unit-action terms (eq. 4.5; 0.2).
        gamma: discount γ of eq. 4.7 (0.9).
        actor_rate: ζ of eq. 4.8 (0.3).
        critic_rate: β of eq. 4.9 (0.3).
        init_scale: initial weights uniform in [−init_scale, init_scale] (0.3).
        random_state: seeds the initial weights and the exploration noise.

    CACLA learns from transitions (s, a, r, s'), not from (X, y), so scikit-learn's checks
    that need a ``fit`` do not apply; its parameters follow scikit-learn (checked once, at
    the first use).
    """

    _parameter_constraints: ClassVar[dict[str, list]] = {
        "action_dims": [POSITIVE_INT], "n_hidden": [POSITIVE_INT], "sigma": [POSITIVE],
        "gamma": [RATE], "actor_rate": [RATE], "critic_rate": [RATE],
        "init_scale": [POSITIVE], "random_state": ["random_state"],
    }

    def __init__(
        self,
        action_dims: int = 1,
        n_hidden: int = 10,
        sigma: float = 0.2,
        gamma: float = 0.9,
        actor_rate: float = 0.3,
        critic_rate: float = 0.3,
        init_scale: float = 0.3,
        random_state: int | np.random.RandomState | None = None,
    ) -> None:
        self.action_dims = action_dims
        self.n_hidden = n_hidden
        self.sigma = sigma
        self.gamma = gamma
        self.actor_rate = actor_rate
        self.critic_rate = critic_rate
        self.init_scale = init_scale
        self.random_state = random_state

    # ------------------------------------------------------------------ set-up
    def _init(self, n_state: int) -> None:
        """Check the parameters and draw actor and critic weights for states of width
        ``n_state`` (first use only)."""
        if hasattr(self, "actor_"):
            return
        self._validate_params()
        self.rng_ = check_random_state(self.random_state)
        self.actor_ = TanhNetwork.uniform(n_state, int(self.n_hidden), int(self.action_dims),
                                          float(self.init_scale), self.rng_)
        self.critic_ = TanhNetwork.uniform(n_state, int(self.n_hidden), 1,
                                           float(self.init_scale), self.rng_)
        self.n_features_in_ = n_state
        self.td_errors_: list[float] = []

    def _check_fitted(self) -> None:
        """NotFittedError before the first use (scikit-learn's check_is_fitted needs a fit)."""
        if not hasattr(self, "actor_"):
            raise NotFittedError(NOT_FITTED % {"name": type(self).__name__})

    def _states(self, states: object, name: str = "states") -> np.ndarray:
        rows = as_rows(states, name, getattr(self, "n_features_in_", None))
        self._init(rows.shape[1])
        return rows

    # ------------------------------------------------------------------ policy and value
    def predict(self, states: object) -> np.ndarray:
        """The actor's action Act(s) for each state row, clipped to [−1, 1]: (n, action_dims)."""
        self._check_fitted()
        return np.clip(self.actor_.predict(self._states(states)), -1.0, 1.0)

    def value(self, states: object) -> np.ndarray:
        """The critic's V(s) for each state row: (n,)."""
        self._check_fitted()
        return self.critic_.predict(self._states(states))[:, 0]

    def sample(self, state: object) -> np.ndarray:
        """An exploratory unit action a ~ N(Act(s), σ²) per dimension (4.5), clipped to [−1, 1]."""
        return self._sample(self._states(np.atleast_1d(np.asarray(state, dtype=float))[None, :],
                                         "state"))

    def _sample(self, row: np.ndarray) -> np.ndarray:
        """`sample` on one checked state row (Algorithm 3 calls it with rows it checked)."""
        self._init(row.shape[1])
        mean = self.actor_.predict(row)[0]
        noise = self.rng_.normal(0.0, float(self.sigma), size=mean.shape)
        return np.clip(mean + noise, -1.0, 1.0)

    # ------------------------------------------------------------------ learning
    def partial_fit(
        self, states: object, actions: object, rewards: object, next_states: object
    ) -> CACLA:
        """Learn from transitions (s, a, r, s'), one row each, in order; appends δ to td_errors_."""
        if not hasattr(self, "actor_"):
            self._validate_params()  # before action_dims shapes the actions
        s = as_rows(states, "states", getattr(self, "n_features_in_", None))
        s_next = as_rows(next_states, "next_states", s.shape[1])
        a = as_rows(actions, "actions", int(self.action_dims))
        r = as_rows(rewards, "rewards", 1)[:, 0]
        check_consistent_length(s, s_next, a, r)
        if np.any(np.abs(a) > 1.0):
            raise ValueError(f"actions must be unit actions in [-1, 1], got {a.tolist()}")
        self._learn(s, a, r, s_next)
        return self

    def _learn(self, s: np.ndarray, a: np.ndarray, r: np.ndarray, s_next: np.ndarray) -> None:
        """Eq. 4.7-4.9 on checked transitions (Algorithm 3 calls it with rows it checked)."""
        self._init(s.shape[1])
        gamma, zeta, beta = float(self.gamma), float(self.actor_rate), float(self.critic_rate)
        for state, action, reward, nxt in zip(s, a, r, s_next, strict=True):
            value = self.critic_.predict(state[None, :])[0, 0]
            next_value = self.critic_.predict(nxt[None, :])[0, 0]
            delta = td_error(float(reward), value, next_value, gamma)  # 4.7
            if delta > 0:  # 4.8: the action was better than expected
                self.actor_.nudge(state, action - self.actor_.predict(state[None, :])[0], zeta)
            self.critic_.nudge(state, np.array([delta]), beta)  # 4.9
            self.td_errors_.append(float(delta))

    # ------------------------------------------------------------------ persistence
    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write parameters, actor and critic as versioned JSON, atomically."""
        self._check_fitted()
        state = {"actor": self.actor_.to_dict(), "critic": self.critic_.to_dict(),
                 "n_features_in": self.n_features_in_, "td_errors": self.td_errors_}
        return write_learner(path, KIND, json_params(self), state)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> CACLA:
        """Read a CACLA written by ``save`` (its exploration noise restarts from its seed)."""
        params, state = read_learner(path, KIND)
        try:
            learner = cls(**params)
            actor = TanhNetwork.from_dict(state["actor"])
            critic = TanhNetwork.from_dict(state["critic"])
            n_state = int(state["n_features_in"])
            if (actor.n_inputs, critic.n_inputs, actor.n_outputs, critic.n_outputs) != (
                    n_state, n_state, int(learner.action_dims), 1):
                raise ValueError("the weights do not match the learner's states and actions")
            learner.rng_ = check_random_state(learner.random_state)
            learner.actor_, learner.critic_, learner.n_features_in_ = actor, critic, n_state
            learner.td_errors_ = [float(d) for d in state["td_errors"]]
        except (KeyError, TypeError, ValueError) as exc:
            raise LearnerFileError(f"learner file {str(path)!r} has a bad CACLA: {exc}") from None
        return learner


class TDConvergence:
    """Eq. 4.10–4.11: converged when |δ̄_{k+1} − δ̄_k| < ε, δ̄_k = mean |δ| of the last N."""

    @validate_params({"window": [POSITIVE_INT], "tol": [POSITIVE]},
                     prefer_skip_nested_validation=True)
    def __init__(self, window: int = 20, tol: float = 1e-4) -> None:
        """N = ``window`` (thesis: 20), ε = ``tol`` (thesis: 1e-4)."""
        self.window = int(window)
        self.tol = float(tol)
        self.magnitudes: list[float] = []
        self.averages: list[float] = []
        """δ̄_k for every step k ≥ N (eq. 4.11)."""

    def update(self, delta: float) -> bool:
        """Add |δ_k|; True when (4.10) holds for the last two averages."""
        if not np.isfinite(delta):
            raise ValueError(f"a TD error must be a finite number, got {delta!r}")
        self.magnitudes.append(abs(float(delta)))
        if len(self.magnitudes) >= self.window:
            self.averages.append(float(np.mean(self.magnitudes[-self.window:])))
        return self.converged

    @property
    def converged(self) -> bool:
        """Whether the last update satisfied (4.10)."""
        return len(self.averages) >= 2 and abs(self.averages[-1] - self.averages[-2]) < self.tol

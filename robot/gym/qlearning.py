"""Tabular Q-learning (Watkins 1989; Sutton & Barto 2018, §6.5), the standard baseline that
XCS generalises (thesis §3.3.3: "a generalization of tabular Q-learning").

One step updates one state-action value:

    Q(s, a) <- Q(s, a) + α [r + γ max_a' Q(s', a') - Q(s, a)]      (Sutton & Barto eq. 6.8)

with max_a' Q(s', a') = 0 past a terminal state (a truncated trial still bootstraps). Written
here (a table and two methods) because the libraries that offer it bring a framework of agents
around a numpy array; it works on any Gymnasium environment with ``Discrete`` observations and
actions (``observation="discrete"`` for the goalagent tasks).
"""

from __future__ import annotations

import numpy as np


class QLearning:
    """A table of Q(s, a), ε-greedy in explore trials, greedy in exploit trials."""

    def __init__(self, n_states: int, n_actions: int, *, alpha: float = 0.2, gamma: float = 0.7,
                 initial: float = 10.0, epsilon: float = 1.0, random_state: int | None = None):
        """``alpha``: step size; ``gamma``: discount; ``initial``: every Q(s, a) at first;
        ``epsilon``: the share of random actions in explore trials (1: all, as XCS's pure
        explore trials); ties between the best actions are broken at random."""
        if n_states < 1 or n_actions < 1:
            raise ValueError(f"need states and actions, got {n_states} and {n_actions}")
        for name, value in (("alpha", alpha), ("gamma", gamma), ("epsilon", epsilon)):
            if not 0.0 <= value <= 1.0:
                raise ValueError(f"{name} must lie in [0, 1], got {value}")
        self.alpha, self.gamma, self.epsilon = alpha, gamma, epsilon
        self.q = np.full((n_states, n_actions), float(initial))
        self.rng = np.random.default_rng(random_state)

    def act(self, state: int, explore: bool) -> int:
        """A random action with probability ε when exploring, else a best one."""
        if explore and self.rng.random() < self.epsilon:
            return int(self.rng.integers(self.q.shape[1]))
        values = self.q[state]
        return int(self.rng.choice(np.flatnonzero(values == values.max())))

    def update(self, state: int, action: int, reward: float, next_state: int,
               terminal: bool) -> float:
        """Eq. 6.8 for one transition; returns the TD error."""
        future = 0.0 if terminal else self.gamma * float(self.q[next_state].max())
        error = reward + future - float(self.q[state, action])
        self.q[state, action] += self.alpha * error
        return error

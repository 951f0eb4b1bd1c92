"""Algorithm 3 of the thesis (§4.4.3): active affordance learning, and its random baseline.

Written against a small protocol, ``ContinuousWorld`` (observe a state, perform a bounded
action, observe the next state), so the same loop runs on a MuJoCo can, on a camera, or on a
synthetic function in a test. Per step k: observe s, choose a, predict ê = F(s, a) (4.2),
act and observe s', e = s' − s (4.20), η = e − ê (4.3), update F (4.4), r = |η| (4.6),
δ (4.7), actor if δ > 0 (4.8), critic (4.9); stop when (4.10) holds or after N_s steps.

Modes: ``active`` draws the first ``n_random`` actions uniformly in the bounds, then from
the actor (4.5); ``random`` (the thesis's baseline, "a random actor") draws every action
uniformly. Both compute the same TD errors with the same critic, so their averaged TD-error
curves (Figs 4.6–4.9) are comparable.
"""

from __future__ import annotations

import copy
from collections.abc import Sequence
from dataclasses import dataclass
from numbers import Integral
from typing import ClassVar, Protocol, runtime_checkable

import numpy as np
from sklearn.base import BaseEstimator
from sklearn.utils import check_random_state
from sklearn.utils._param_validation import Interval, StrOptions

from behaviours.learners.cacla import CACLA, TDConvergence
from behaviours.learners.forward_model import ForwardModel
from behaviours.learners.validation import POSITIVE, POSITIVE_INT, RATE, ActionBounds, as_rows

__all__ = ["EXPLORATION_MODES", "ActiveExplorer", "ContinuousWorld", "ExplorationHistory"]

EXPLORATION_MODES = ("active", "random")


@runtime_checkable
class ContinuousWorld(Protocol):
    """What Algorithm 3 needs of a world: a state, bounded actions, and their outcome."""

    @property
    def action_bounds(self) -> Sequence[Sequence[float]]:
        """One (lo, hi) pair per action dimension, in the world's units."""
        ...

    def observe(self) -> float | Sequence[float]:
        """The object state s_o now (a number or a vector); asked at the start of every step."""
        ...

    def step(self, action: np.ndarray) -> float | Sequence[float]:
        """Perform ``action`` (within the bounds) and return the state s'_o right after it
        (a world that puts the object back between tries observes the start state again)."""
        ...


@dataclass(frozen=True)
class ExplorationHistory:
    """Everything one exploration measured, one row per step k = 1..n."""

    states: np.ndarray  # s_o^k, (n, state dims)
    actions: np.ndarray  # a^k in world units, (n, action dims)
    effects: np.ndarray  # e_o^k = s' − s (4.20), (n, state dims)
    predictions: np.ndarray  # ê_o^k (4.2), before the update
    rewards: np.ndarray  # r = |η_k| (4.6)
    td_errors: np.ndarray  # δ^k (4.7)
    averaged: np.ndarray  # δ̄^k (4.11), NaN while k < N
    converged_at: int | None  # the step k at which (4.10) held, if it did

    @property
    def steps(self) -> int:
        """How many exploratory actions were performed."""
        return int(len(self.actions))


class ActiveExplorer(BaseEstimator):
    """Algorithm 3 (``mode="active"``) or the random baseline (``mode="random"``).

    Parameters (thesis §4.6.1 defaults):
        mode: ``"active"`` or ``"random"``.
        n_max: N_s, the most steps (100 for 1-D actions, 300 for 3-D).
        n_random: the first actions drawn at random in active mode (20).
        window, tol: N and ε of the convergence test (20, 1e-4).
        sigma, gamma, alpha, zeta, beta: σ (0.2), γ (0.9), α (0.3), ζ (0.3), β (0.3).
        n_hidden, init_scale: hidden tanh units (10) and initial weight range (0.3).
        random_state: seeds the networks, the exploration noise and the random actions.
        stop: end at the first step where (4.10) holds (Algorithm 3). False runs all n_max
            steps and still records that step: the same run up to it, and the whole curve.

    It learns from a world it acts on (`explore`), not from (X, y): scikit-learn's checks
    that need a ``fit`` do not apply.
    """

    _parameter_constraints: ClassVar[dict[str, list]] = {
        "mode": [StrOptions(set(EXPLORATION_MODES))], "n_max": [POSITIVE_INT],
        "n_random": [Interval(Integral, 0, None, closed="left")], "window": [POSITIVE_INT],
        "tol": [POSITIVE], "sigma": [POSITIVE], "gamma": [RATE], "alpha": [RATE],
        "zeta": [RATE], "beta": [RATE], "n_hidden": [POSITIVE_INT], "init_scale": [POSITIVE],
        "random_state": ["random_state"], "stop": ["boolean"],
    }

    def __init__(
        self,
        mode: str = "active",
        n_max: int = 100,
        n_random: int = 20,
        window: int = 20,
        tol: float = 1e-4,
        sigma: float = 0.2,
        gamma: float = 0.9,
        alpha: float = 0.3,
        zeta: float = 0.3,
        beta: float = 0.3,
        n_hidden: int = 10,
        init_scale: float = 0.3,
        random_state: int | np.random.RandomState | None = None,
        stop: bool = True,
    ) -> None:
        self.mode = mode
        self.n_max = n_max
        self.n_random = n_random
        self.window = window
        self.tol = tol
        self.sigma = sigma
        self.gamma = gamma
        self.alpha = alpha
        self.zeta = zeta
        self.beta = beta
        self.n_hidden = n_hidden
        self.init_scale = init_scale
        self.random_state = random_state
        self.stop = stop

    def explore(self, world: ContinuousWorld) -> ActiveExplorer:
        """Run the loop on ``world``; sets forward_model_, cacla_, history_, converged_, and
        stopped_model_: F as Algorithm 3 returns it (at the step (4.10) held, else at n_max),
        which differs from forward_model_ only when ``stop`` is False."""
        self._validate_params()
        bounds = ActionBounds(world.action_bounds)
        rng = check_random_state(self.random_state)
        model = ForwardModel(action_bounds=bounds.as_list(), n_hidden=self.n_hidden,
                             learning_rate=self.alpha, init_scale=self.init_scale,
                             random_state=rng)
        cacla = CACLA(action_dims=bounds.dims, n_hidden=self.n_hidden, sigma=self.sigma,
                      gamma=self.gamma, actor_rate=self.zeta, critic_rate=self.beta,
                      init_scale=self.init_scale, random_state=rng)
        test = TDConvergence(self.window, self.tol)
        rows: dict[str, list] = {key: [] for key in (
            "states", "actions", "effects", "predictions", "rewards", "td_errors", "averaged")}
        converged_at = None
        for k in range(1, self.n_max + 1):
            state = _state(world.observe(), "the world's state")  # step 4: observe s_o^k
            # the learners' own steps on rows built here from checked values: scikit-learn's
            # validation of every row would cost more than the learning itself
            if self.mode == "active" and k > self.n_random:
                unit = cacla._sample(state[None, :])  # 4.5
            else:
                unit = rng.uniform(-1.0, 1.0, size=bounds.dims)
            action = bounds.from_unit(unit)
            if k == 1:
                model.initialize(state.size, state.size)
            if np.isfinite(action).all():  # within the bounds: from_unit made it so
                network_inputs = np.hstack([state[None, :], bounds.unit_rows(action[None, :])])
            else:  # an actor gone to NaN: the forward model's own check says so
                network_inputs = model._inputs(np.concatenate([state, action])[None, :])
            predicted = model.network_.predict(network_inputs)[0]  # 4.2
            next_state = _state(world.step(action.copy()), "the world's next state")
            if next_state.shape != state.shape:
                raise ValueError(f"the world's state changed shape from {state.shape} to "
                                 f"{next_state.shape}")
            effect = next_state - state  # 4.20
            reward = float(np.linalg.norm(effect - predicted))  # 4.3, 4.6
            model._learn(network_inputs, effect[None, :])  # 4.4
            cacla._learn(state[None, :], unit[None, :], np.array([reward]), next_state[None, :])
            delta = cacla.td_errors_[-1]
            stop = test.update(delta)  # (4.10)
            for key, value in (("states", state), ("actions", action), ("effects", effect),
                               ("predictions", predicted), ("rewards", reward),
                               ("td_errors", delta)):
                rows[key].append(value)
            rows["averaged"].append(test.averages[-1] if test.averages else np.nan)
            if stop and converged_at is None:
                converged_at = k
                if self.stop:
                    break
                self.stopped_model_ = copy.deepcopy(model)
        self.forward_model_ = model
        if self.stop or converged_at is None:
            self.stopped_model_ = model
        self.cacla_ = cacla
        self.history_ = ExplorationHistory(
            **{key: np.asarray(value, dtype=float) for key, value in rows.items()},
            converged_at=converged_at,
        )
        self.converged_ = converged_at is not None
        self.n_steps_ = self.history_.steps
        return self


def _state(value: object, what: str) -> np.ndarray:
    """A world's state as a finite 1-D float vector, or a clear error naming ``what``
    (scikit-learn's, from ``as_rows``: only asked for when the vector is empty or not finite,
    since check_array at every step cost more than the learners' steps)."""
    row = np.atleast_1d(np.asarray(value, dtype=float))[None, :]
    if row.size and np.isfinite(row).all():
        return row[0]
    return as_rows(row, what)[0]


"""The forward model F_ψ(s_o, a) of thesis chapter 4 (eq. 4.1–4.4), a scikit-learn regressor.

An input row is the object state followed by the action in physical units (e.g. metres),
``X = [s_o..., a...]``; the last ``len(action_bounds)`` columns are the action, normalised to
[−1, 1] per dimension inside the model (§4.6.1); an action outside its bounds is refused. The
target is the effect e_o. ``partial_fit`` takes one online backpropagation step per row, in
order (eq. 4.2–4.4): η = e − F(s, a), w ← w + α η ∇_w F. The network (one hidden layer of 10
tanh units, linear output, weights uniform in [−0.3, 0.3]) is ``behaviours.learners.network``,
whose docstring says why it is numpy rather than ``MLPRegressor``.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from numbers import Integral, Real
from pathlib import Path
from typing import ClassVar

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin, _fit_context
from sklearn.utils import Tags, check_random_state
from sklearn.utils._param_validation import Interval
from sklearn.utils.validation import check_is_fitted, check_scalar, validate_data

from behaviours.learners.network import TanhNetwork
from behaviours.learners.persist import (
    LearnerFileError,
    json_params,
    read_learner,
    write_learner,
)
from behaviours.learners.tags import with_domain
from behaviours.learners.validation import ActionBounds, as_rows

__all__ = ["ForwardModel"]

KIND = "forward_model"
NOT_FITTED = ("this %(name)s has seen no data yet; call partial_fit (or fit) before "
              "predict")


class ForwardModel(RegressorMixin, BaseEstimator):
    """F_ψ: (state, action) → effect, learned online by per-sample backpropagation (eq. 4.4).

    Parameters:
        action_bounds: one (lo, hi) pair per action dimension (physical units).
        n_hidden: tanh units in the hidden layer (thesis: 10).
        learning_rate: α of eq. 4.4 (thesis: 0.3).
        init_scale: initial weights uniform in [−init_scale, init_scale] (thesis: 0.3).
        random_state: seeds the initial weights (drawn at the first ``partial_fit``).

    Tags: ``bounded_actions`` (the last columns of X are refused outside ``action_bounds``),
    multi-output effects, and a poor score on scikit-learn's test data: `fit` is one online
    pass of Algorithm 3's per-sample updates, not a fit to convergence.
    """

    _parameter_constraints: ClassVar[dict[str, list]] = {
        "action_bounds": ["array-like"],
        "n_hidden": [Interval(Integral, 1, None, closed="left")],
        "learning_rate": [Interval(Real, 0.0, 1.0, closed="both")],
        "init_scale": [Interval(Real, 0.0, None, closed="neither")],
        "random_state": ["random_state"],
    }

    def __init__(
        self,
        action_bounds: Sequence[Sequence[float]] = ((-0.01, 0.01),),
        n_hidden: int = 10,
        learning_rate: float = 0.3,
        init_scale: float = 0.3,
        random_state: int | np.random.RandomState | None = None,
    ) -> None:
        self.action_bounds = action_bounds
        self.n_hidden = n_hidden
        self.learning_rate = learning_rate
        self.init_scale = init_scale
        self.random_state = random_state

    def __sklearn_tags__(self) -> Tags:
        tags = with_domain(super().__sklearn_tags__(), bounded_actions=True)
        tags.target_tags.multi_output = True
        tags.regressor_tags.poor_score = True
        return tags

    # ------------------------------------------------------------------ inputs
    def _inputs(self, X: np.ndarray) -> np.ndarray:
        """Validated rows [state, action] as [state, action in [−1, 1]] (the actions checked
        against the bounds)."""
        bounds = ActionBounds(self.action_bounds)
        n_state = X.shape[1] - bounds.dims
        unit = bounds.to_unit(X[:, n_state:], "actions (the last columns of X)")
        return np.hstack([X[:, :n_state], unit])

    def _min_features(self) -> int:
        """At least one state column before the action columns."""
        return ActionBounds(self.action_bounds).dims + 1

    # ------------------------------------------------------------------ learning
    @_fit_context(prefer_skip_nested_validation=True)
    def partial_fit(self, X: object, y: object) -> ForwardModel:
        """One backpropagation step (eq. 4.4) per row of (X, y), in order."""
        first = not hasattr(self, "network_")
        X, y = validate_data(self, X, y, reset=first, dtype=np.float64, multi_output=True,
                             y_numeric=True,
                             ensure_min_features=self._min_features() if first else 1)
        targets = y.reshape(y.shape[0], -1)
        if not first and targets.shape[1] != self.n_outputs_:
            raise ValueError(f"y has {targets.shape[1]} effect column(s), the model was "
                             f"fitted with {self.n_outputs_}")
        inputs = self._inputs(X)
        if first:
            self._draw_weights(inputs.shape[1], targets.shape[1])
        self._learn(inputs, targets)
        return self

    def _learn(self, inputs: np.ndarray, targets: np.ndarray) -> None:
        """Eq. 4.3-4.4 row by row on network inputs (actions already in [−1, 1])."""
        rate = float(self.learning_rate)
        for x, target in zip(inputs, targets, strict=True):
            error = target - self.network_.predict(x[None, :])[0]  # η_k, eq. 4.3
            self.network_.nudge(x, error, rate)
        self.n_samples_seen_ += inputs.shape[0]

    def initialize(self, n_state: int, n_outputs: int = 1) -> ForwardModel:
        """Draw the initial weights before any data, so the untrained model can already
        predict (Algorithm 3 predicts ê before the first update); a no-op once weights exist."""
        if not hasattr(self, "network_"):
            self._validate_params()
            n_state = check_scalar(n_state, "n_state", Integral, min_val=1)
            n_outputs = check_scalar(n_outputs, "n_outputs", Integral, min_val=1)
            self._draw_weights(int(n_state) + ActionBounds(self.action_bounds).dims,
                               int(n_outputs))
        return self

    def _draw_weights(self, n_inputs: int, n_outputs: int) -> None:
        """Weights uniform in [−init_scale, init_scale] (§4.6.1) from ``random_state``."""
        self.network_ = TanhNetwork.uniform(n_inputs, int(self.n_hidden), n_outputs,
                                            float(self.init_scale),
                                            check_random_state(self.random_state))
        self.n_features_in_ = n_inputs
        self.n_outputs_ = n_outputs
        self.n_samples_seen_ = 0

    def fit(self, X: object, y: object) -> ForwardModel:
        """Fresh initial weights, then one online pass over the rows in order."""
        for name in ("network_", "n_features_in_", "n_outputs_", "n_samples_seen_"):
            self.__dict__.pop(name, None)
        return self.partial_fit(X, y)

    def predict(self, X: object) -> np.ndarray:
        """Predicted effects ê = F(s, a) (eq. 4.2); shape (n,) for a one-dimensional effect."""
        check_is_fitted(self, "network_", msg=NOT_FITTED)
        X = validate_data(self, X, reset=False, dtype=np.float64)
        out = self.network_.predict(self._inputs(X))
        return out[:, 0] if self.n_outputs_ == 1 else out

    def predict_effects(self, state: object, actions: object) -> np.ndarray:
        """F(s, a) for one state and many actions (the internal rehearsal of eq. 4.12)."""
        check_is_fitted(self, "network_", msg=NOT_FITTED)
        state_row = as_rows(np.atleast_1d(np.asarray(state, dtype=float))[None, :], "state")
        action_rows = as_rows(actions, "actions", ActionBounds(self.action_bounds).dims)
        return self.predict(np.hstack([np.repeat(state_row, len(action_rows), axis=0),
                                       action_rows]))

    # ------------------------------------------------------------------ persistence
    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write parameters and weights as versioned JSON, atomically."""
        check_is_fitted(self, "network_", msg=NOT_FITTED)
        state = {"network": self.network_.to_dict(), "n_features_in": self.n_features_in_,
                 "n_outputs": self.n_outputs_, "n_samples_seen": self.n_samples_seen_}
        return write_learner(path, KIND, json_params(self), state)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> ForwardModel:
        """Read a model written by ``save``; LearnerFileError if the file is not one."""
        params, state = read_learner(path, KIND)
        return _restore(cls, path, params, state)


def _restore(cls: type, path: str | os.PathLike[str], params: dict, state: dict) -> ForwardModel:
    """Rebuild a ForwardModel from saved params and state (errors name the file)."""
    try:
        params = dict(params)
        params["action_bounds"] = tuple(tuple(pair) for pair in params["action_bounds"])
        model = cls(**params)
        network = TanhNetwork.from_dict(state["network"])
        n_features, n_outputs = int(state["n_features_in"]), int(state["n_outputs"])
        if (network.n_inputs, network.n_outputs) != (n_features, n_outputs) or (
                n_features <= ActionBounds(params["action_bounds"]).dims):
            raise ValueError("the weights do not match the model's inputs and outputs")
        model.network_ = network
        model.n_features_in_, model.n_outputs_ = n_features, n_outputs
        model.n_samples_seen_ = int(state["n_samples_seen"])
    except (KeyError, TypeError, ValueError) as exc:
        raise LearnerFileError(f"learner file {str(path)!r} has a bad forward model: "
                               f"{exc}") from None
    return model

"""XCS as a scikit-learn classifier over binary features (single-step problems).

Each training sample is one explore problem: XCS acts on the sample's bits, and is rewarded
``reward`` when the action is the sample's class and 0 otherwise (Wilson's multiplexer
protocol). Prediction is exploitation: the class whose prediction array entry (eq. 3.8) is
highest.

Features must be bits (the ``binary`` input tag) unless ``binarize`` gives a threshold, as in
scikit-learn's ``BernoulliNB``: a feature above it is 1, otherwise 0.
"""

from __future__ import annotations

from numbers import Integral, Real
from typing import ClassVar

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin, _fit_context
from sklearn.utils import Tags
from sklearn.utils._param_validation import Interval
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import check_is_fitted, validate_data

from .tags import with_domain
from .xcs_agent import XCS
from .xcs_params import CONSTRAINTS, make_generator

PREDICT_CHUNK = 4096
"""Rows matched at once in `predict` (bounds the rows x classifiers match matrix)."""
XCS_PARAMETERS = ("N", "beta", "beta_p", "beta_e", "beta_f", "alpha", "epsilon_0", "nu",
                  "theta_ga", "chi", "mu", "theta_del", "delta", "theta_sub", "p_hash",
                  "prediction_init", "error_init", "fitness_init", "ga_subsumption",
                  "action_set_subsumption")
"""The parameters passed on to the `XCS` inside."""


class XCSClassifier(ClassifierMixin, BaseEstimator):
    """XCS trained online on (X, y) with X binary; parameters as `XCS` (no ``gamma`` or
    ``consistent_actions``: every problem is one step), plus ``n_iter`` passes over the data
    in random order per `fit`, the ``reward`` for a correct class and ``binarize``.

    Learned: ``xcs_`` (the `XCS`), ``classes_``, ``n_features_in_``.
    """

    _parameter_constraints: ClassVar[dict[str, list]] = {
        **{name: CONSTRAINTS[name] for name in XCS_PARAMETERS},
        "n_iter": [Interval(Integral, 1, None, closed="left")],
        "reward": [Interval(Real, None, None, closed="neither")],
        "binarize": [None, Interval(Real, None, None, closed="neither")],
        "random_state": CONSTRAINTS["random_state"],
    }

    def __init__(self, *, N: int = 400, beta: float = 0.2, beta_p: float | None = None,
                 beta_e: float | None = None, beta_f: float | None = None, alpha: float = 0.1,
                 epsilon_0: float = 10.0, nu: float = 5.0, theta_ga: float = 25,
                 chi: float = 0.8, mu: float = 0.04, theta_del: int = 20, delta: float = 0.1,
                 theta_sub: int = 20, p_hash: float = 0.33, prediction_init: float = 10.0,
                 error_init: float = 0.0, fitness_init: float = 0.01,
                 ga_subsumption: bool = True, action_set_subsumption: bool = False,
                 n_iter: int = 50, reward: float = 1000.0, random_state: object = None,
                 binarize: float | None = None) -> None:
        self.N, self.beta, self.beta_p, self.beta_e, self.beta_f = N, beta, beta_p, beta_e, beta_f
        self.alpha, self.epsilon_0, self.nu, self.theta_ga = alpha, epsilon_0, nu, theta_ga
        self.chi, self.mu, self.theta_del, self.delta = chi, mu, theta_del, delta
        self.theta_sub, self.p_hash = theta_sub, p_hash
        self.prediction_init, self.error_init = prediction_init, error_init
        self.fitness_init = fitness_init
        self.ga_subsumption = ga_subsumption
        self.action_set_subsumption = action_set_subsumption
        self.n_iter = n_iter
        self.reward = reward
        self.random_state = random_state
        self.binarize = binarize

    def __sklearn_tags__(self) -> Tags:
        return with_domain(super().__sklearn_tags__(), binary=self.binarize is None)

    @_fit_context(prefer_skip_nested_validation=True)
    def fit(self, X: object, y: object) -> XCSClassifier:
        """Learn from scratch: ``n_iter`` passes over the samples, each in a random order."""
        X, y = self._check_data(X, y, reset=True)
        self._start(np.unique(y))
        for _ in range(self.n_iter):
            self._learn(X, y, self._order_rng.permutation(X.shape[0]))
        return self

    @_fit_context(prefer_skip_nested_validation=True)
    def partial_fit(self, X: object, y: object, classes: object = None) -> XCSClassifier:
        """One pass over the samples in the given order; ``classes`` is required on the first
        call (all the labels that will ever be seen)."""
        first = not hasattr(self, "xcs_")
        if first and classes is None:
            raise ValueError("XCSClassifier: classes must be given on the first "
                             "partial_fit call")
        X, y = self._check_data(X, y, reset=first)
        if first:
            self._start(np.unique(np.asarray(classes)))
        unknown = np.setdiff1d(y, self.classes_)
        if unknown.size:
            raise ValueError(f"y holds labels not in classes: {unknown[:5].tolist()}")
        self._learn(X, y, np.arange(X.shape[0]))
        return self

    def predict(self, X: object) -> np.ndarray:
        """The class with the highest system prediction for each row (the most frequent
        training class where no classifier matches)."""
        check_is_fitted(self, "xcs_")
        X = self._bits(validate_data(self, X, reset=False))
        return self.classes_[self._best_actions(X)]

    # -- helpers -------------------------------------------------------------------------------

    def _start(self, classes: np.ndarray) -> None:
        seeds = make_generator(self.random_state).integers(0, 2**63 - 1, size=2)
        self.classes_ = classes
        self.xcs_ = XCS(int(classes.size), gamma=0.0, random_state=int(seeds[0]),
                        **{name: getattr(self, name) for name in XCS_PARAMETERS})
        self._order_rng = np.random.default_rng(int(seeds[1]))
        self._class_counts = np.zeros(classes.size, np.int64)

    def _learn(self, X: np.ndarray, y: np.ndarray, order: np.ndarray) -> None:
        targets = np.searchsorted(self.classes_, y)
        self._class_counts += np.bincount(targets, minlength=self.classes_.size)
        xcs, reward = self.xcs_, float(self.reward)
        for row in order:
            action = xcs.act(X[row], explore=True)
            xcs.reward(reward if action == targets[row] else 0.0, done=True)

    def _best_actions(self, X: np.ndarray) -> np.ndarray:
        """Eq. 3.8/3.9 for many rows at once: rows x classifiers match matrix products."""
        records = self.xcs_.classifiers()
        fallback = int(np.argmax(self._class_counts))
        if not records:
            return np.full(X.shape[0], fallback)
        conditions = np.array([list(record.condition) for record in records])
        one_hot = np.zeros((len(records), self.classes_.size))
        one_hot[np.arange(len(records)), [record.action for record in records]] = 1.0
        fitness = np.array([record.fitness for record in records])
        prediction = np.array([record.prediction for record in records])
        care = (conditions != "#").astype(np.int32)
        required = (conditions == "1").astype(np.int32)
        actions = np.empty(X.shape[0], np.int64)
        for start in range(0, X.shape[0], PREDICT_CHUNK):
            chunk = X[start:start + PREDICT_CHUNK].astype(np.int32)
            mismatches = chunk @ care.T - 2 * (chunk @ required.T) + (required.sum(axis=1))
            matched = (mismatches == 0).astype(float)
            weights = matched @ (one_hot * fitness[:, None])
            weighted = matched @ (one_hot * (fitness * prediction)[:, None])
            with np.errstate(invalid="ignore", divide="ignore"):
                system = np.where(weights > 0, weighted / weights, -np.inf)
            best = np.argmax(system, axis=1)
            best[~np.isfinite(system.max(axis=1))] = fallback
            actions[start:start + chunk.shape[0]] = best
        return actions

    def _bits(self, X: np.ndarray) -> np.ndarray:
        """Validated features as 0/1 bytes: thresholded by ``binarize``, or checked to be
        bits already."""
        if self.binarize is not None:
            return (X > self.binarize).astype(np.uint8)
        if not np.isin(X, (0, 1)).all():
            raise ValueError("X must hold 0/1 features (or set binarize to a threshold), got "
                             f"values such as {X[~np.isin(X, (0, 1))][:3].tolist()}")
        return X.astype(np.uint8)

    def _check_data(self, X: object, y: object, *, reset: bool) -> tuple[np.ndarray, np.ndarray]:
        X, y = validate_data(self, X, y, reset=reset)
        check_classification_targets(y)
        return self._bits(X), y

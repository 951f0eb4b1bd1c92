"""Learned effect models Ĥ(θ) (thesis eq. 6.7/5.16) and their on-disk store.

``LinearEffectModel`` is a scikit-learn regressor e = b + c·θ (θ: the action parameters, one
in the thesis's uses) that also tracks the residual sum of squares after every (partial) fit,
so a learner can tell when the regression has settled (eq. 5.18/5.19). ``ModelStore`` keeps
one model per key, normally (can, part, action), oldest first, in a JSON file that is replaced
atomically on every change, so a crash never leaves a half-written store and models survive
the process.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from numbers import Real
from pathlib import Path
from typing import ClassVar

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin, _fit_context
from sklearn.linear_model import LinearRegression
from sklearn.utils.validation import check_is_fitted, validate_data

from behaviours.learners.persist import check_store, read_store, write_text_atomically
from behaviours.learners.validation import check_bounds

STORE_FORMAT = "goalagent-effect-models"
STORE_VERSION = 1


class LinearEffectModel(RegressorMixin, BaseEstimator):
    """Ĥ(θ) = b + c·θ by least squares (thesis 5.16, 6.7), refit on all samples seen so far.

    X holds the action parameters θ, one row per sample; a number or a 1-D array is one
    parameter per sample, as the behaviours call it (so scikit-learn's checks that a 1-D X
    is refused are expected to fail). Learned: ``coef_`` c (one slope per parameter) and
    ``intercept_`` b, the samples ``theta_`` (n, parameters) and ``effect_``, ``rss_`` and
    ``rss_history_``. `maximum` and the store take one-parameter models.
    """

    _parameter_constraints: ClassVar[dict[str, list]] = {"fit_intercept": ["boolean"]}

    def __init__(self, fit_intercept: bool = True) -> None:
        self.fit_intercept = fit_intercept

    @_fit_context(prefer_skip_nested_validation=True)
    def fit(self, X: object, y: object) -> LinearEffectModel:
        """Fit on exactly these samples (X: θ, y: the effects), forgetting earlier ones."""
        for name in ("theta_", "effect_", "rss_history_", "n_features_in_"):
            self.__dict__.pop(name, None)
        return self.partial_fit(X, y)

    @_fit_context(prefer_skip_nested_validation=True)
    def partial_fit(self, X: object, y: object) -> LinearEffectModel:
        """Add samples (X: θ, y: the effects) and refit on all of them; appends the new RSS
        S_m (eq. 5.18)."""
        first = not hasattr(self, "theta_")
        y = [y] if isinstance(y, Real) else y  # one number: one sample
        X, y = validate_data(self, self._one_column(X), y, reset=first, dtype=np.float64,
                             y_numeric=True)
        if first:
            self.theta_, self.effect_ = np.empty((0, X.shape[1])), np.empty(0)
            self.rss_history_: list[float] = []
        self.theta_ = np.concatenate([self.theta_, X])
        self.effect_ = np.concatenate([self.effect_, y])
        regression = LinearRegression(fit_intercept=self.fit_intercept)
        regression.fit(self.theta_, self.effect_)
        self.coef_ = regression.coef_.copy()
        self.intercept_ = float(regression.intercept_)
        residuals = self.effect_ - self._line(self.theta_)
        self.rss_ = float(residuals @ residuals)
        self.rss_history_.append(self.rss_)
        self.n_samples_ = self.theta_.shape[0]
        return self

    def predict(self, X: object) -> np.ndarray:
        """Predicted effect for each θ."""
        check_is_fitted(self, "coef_")
        X = validate_data(self, self._one_column(X), reset=False, dtype=np.float64)
        return self._line(X)

    def _one_column(self, theta: object) -> object:
        """A number or a 1-D array of θ as one column where the model takes one parameter
        (or is fitted anew); anything else goes to validate_data as it is."""
        if getattr(self, "n_features_in_", 1) != 1:
            return theta
        array = np.asarray(theta) if not hasattr(theta, "ndim") else theta
        return np.reshape(array, (-1, 1)) if array.ndim < 2 else theta

    def _line(self, theta: np.ndarray) -> np.ndarray:
        """b + c·θ for rows of θ."""
        return self.intercept_ + theta @ self.coef_

    def settled(self, tol: float) -> bool:
        """Eq. 5.19: the last sample changed the RSS by less than ``tol`` (|S_m+1 − S_m| < δ3)."""
        history = getattr(self, "rss_history_", [])
        return len(history) >= 2 and abs(history[-1] - history[-2]) < tol

    def maximum(self, bounds: tuple[float, float]) -> tuple[float, float]:
        """(θ_max, e_max) of eq. 6.13/6.8 over lo < θ <= hi, with e_max = Ĥ(θ_max).

        A non-decreasing line peaks at hi. A decreasing one peaks at the open end lo, which
        no action can use, so θ_max is then the smallest θ explored: the best valid one known.
        """
        low, high = check_bounds(bounds)
        theta = self._one_parameter()
        if self.coef_[0] >= 0:
            theta_max = high
        else:
            inside = theta[(theta > low) & (theta <= high)]
            theta_max = float(inside.min()) if inside.size else high
        return theta_max, float(self._line(np.array([[theta_max]]))[0])

    def _one_parameter(self) -> np.ndarray:
        """The θ samples of a one-parameter model (the thesis's Ĥ(θ))."""
        check_is_fitted(self, "coef_")
        if self.n_features_in_ != 1:
            raise ValueError(f"this LinearEffectModel has {self.n_features_in_} action "
                             f"parameters; Ĥ(θ)'s maximum and the store take one")
        return self.theta_[:, 0]


@dataclass(frozen=True)
class StoredModel:
    """One stored model: its key, the action bounds it was learned in, and the fitted model."""

    key: tuple[str, ...]
    bounds: tuple[float, float]
    model: LinearEffectModel

    def to_record(self) -> dict:
        """A JSON-ready record; the samples are the truth, the rest is there for readers."""
        theta_max, e_max = self.model.maximum(self.bounds)
        return {
            "key": list(self.key),
            "bounds": list(self.bounds),
            "theta": self.model._one_parameter().tolist(),
            "effect": self.model.effect_.tolist(),
            "fit_intercept": self.model.fit_intercept,
            "intercept": self.model.intercept_,
            "slope": float(self.model.coef_[0]),
            "theta_max": theta_max,
            "e_max": e_max,
        }

    @classmethod
    def from_record(cls, record: dict) -> StoredModel:
        """Rebuild from a record that passed the schema by refitting its samples (ValueError
        if they do not fit: two lengths, or bounds not lo < hi)."""
        key = tuple(record["key"])
        model = LinearEffectModel(fit_intercept=record["fit_intercept"])
        model.fit(record["theta"], record["effect"])
        return cls(key=key, bounds=check_bounds(record["bounds"]), model=model)


class StoreError(ValueError):
    """A model store file that cannot be read as a goalagent effect-model store."""


class ModelStore:
    """Effect models by key, persisted as JSON at ``path`` and rewritten atomically on change."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path)
        self._models: dict[tuple[str, ...], StoredModel] = {}
        if self.path.exists():
            self._load()

    def _load(self) -> None:
        """Read every model from the file (a regular file of bounded size, see
        ``read_json``), checked by ``schemas/effect_models.schema.json``, or raise StoreError
        naming the file and where in it."""
        data = read_store(self.path, "effect-model store", STORE_FORMAT, STORE_VERSION,
                          StoreError)
        check_store(data, "effect_models", self.path, "effect-model store", StoreError)
        for index, record in enumerate(data["models"]):
            try:
                stored = StoredModel.from_record(record)
            except ValueError as exc:
                raise StoreError(f"effect-model store {str(self.path)!r} has a bad record "
                                 f"(model {index}): {exc}") from None
            self._models[stored.key] = stored

    def get(self, key: Sequence[str]) -> StoredModel | None:
        """The model stored under key, if any."""
        return self._models.get(tuple(key))

    def lookup(self, can: str, part: str, action: str) -> StoredModel | None:
        """The model for (can, part, action), else the newest for (part, action) on another can.

        That is what the robot knows of the part from elsewhere: Experiment 2 (§6.4.2) first
        uses the lid model learned on o1 for o2's lid.
        """
        exact = self._models.get((can, part, action))
        if exact is not None:
            return exact
        for key in reversed(self._models):
            if len(key) == 3 and key[1:] == (part, action):
                return self._models[key]
        return None

    def __contains__(self, key: object) -> bool:
        return isinstance(key, (tuple, list)) and tuple(key) in self._models

    def __iter__(self) -> Iterator[tuple[str, ...]]:
        """Keys from the oldest stored to the newest."""
        return iter(list(self._models))

    def __len__(self) -> int:
        return len(self._models)

    def put(
        self, key: Sequence[str], bounds: tuple[float, float], model: LinearEffectModel
    ) -> None:
        """Store (or replace) the model under key; the store changes only if the write succeeds."""
        if not key or not all(isinstance(part, str) and part for part in key):
            raise ValueError(f"a model key is a tuple of non-empty strings, got {key!r}")
        models = {k: v for k, v in self._models.items() if k != tuple(key)}  # newest last
        models[tuple(key)] = StoredModel(tuple(key), check_bounds(bounds), model)
        self._write(models)
        self._models = models

    def _write(self, models: dict[tuple[str, ...], StoredModel]) -> None:
        """Write models atomically (``write_text_atomically``)."""
        payload = {
            "format": STORE_FORMAT,
            "version": STORE_VERSION,
            "models": [stored.to_record() for stored in models.values()],
        }
        write_text_atomically(self.path, json.dumps(payload, indent=1))

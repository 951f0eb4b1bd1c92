"""XCS's parameters: their scikit-learn constraints, and the checked values for the hot path.

Each bad value is scikit-learn's ``InvalidParameterError`` (a ValueError) naming the parameter
and the learner; the one constraint between two parameters (N >= n_actions, so that covering
fits) is checked by `Settings.resolve`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from numbers import Integral, Real

import numpy as np
from sklearn.utils._param_validation import Interval

_RATE = Interval(Real, 0.0, 1.0, closed="right")
_PROBABILITY = Interval(Real, 0.0, 1.0, closed="both")
_POSITIVE = Interval(Real, 0.0, None, closed="neither")
_NON_NEGATIVE = Interval(Real, 0.0, None, closed="left")
RANDOM_STATE = [None, Interval(Integral, 0, None, closed="left"), np.random.Generator,
                np.random.RandomState]
"""None, a seed >= 0, or a numpy Generator or RandomState (a Generator is used as it is)."""

CONSTRAINTS: dict[str, list] = {
    "n_actions": [Interval(Integral, 1, None, closed="left")],
    "N": [Interval(Integral, 1, None, closed="left")],
    "beta": [_RATE], "alpha": [_RATE],
    "beta_p": [_RATE, None], "beta_e": [_RATE, None], "beta_f": [_RATE, None],
    "gamma": [_PROBABILITY], "chi": [_PROBABILITY], "mu": [_PROBABILITY],
    "delta": [_PROBABILITY], "p_hash": [_PROBABILITY],
    "epsilon_0": [_POSITIVE], "nu": [_POSITIVE], "fitness_init": [_POSITIVE],
    "theta_ga": [_NON_NEGATIVE], "theta_del": [_NON_NEGATIVE], "theta_sub": [_NON_NEGATIVE],
    "error_init": [_NON_NEGATIVE],
    "prediction_init": [Interval(Real, None, None, closed="neither")],  # any finite number
    "ga_subsumption": ["boolean"], "action_set_subsumption": ["boolean"],
    "consistent_actions": ["boolean"], "learn_in_exploit": ["boolean"],
    "random_state": RANDOM_STATE,
}
"""`XCS._parameter_constraints` (thesis Table 7.1's ranges: rates in (0, 1], probabilities in
[0, 1], thresholds >= 0)."""

_FLAGS = ("ga_subsumption", "action_set_subsumption", "consistent_actions", "learn_in_exploit")
_OPTIONAL_RATES = ("beta_p", "beta_e", "beta_f")


def make_generator(random_state: object) -> np.random.Generator:
    """A numpy Generator from a checked ``random_state`` (a RandomState seeds a new one)."""
    if isinstance(random_state, np.random.Generator):
        return random_state
    if isinstance(random_state, np.random.RandomState):
        return np.random.default_rng(random_state.randint(0, 2**32 - 1, size=4))
    return np.random.default_rng(None if random_state is None else int(random_state))


@dataclass(frozen=True)
class Settings:
    """The checked parameters as plain numbers for the hot path; β_p, β_ε, β_F resolved to β
    where they were left None."""

    n_actions: int
    N: int
    beta: float
    beta_p: float
    beta_e: float
    beta_f: float
    gamma: float
    alpha: float
    epsilon_0: float
    nu: float
    theta_ga: float
    chi: float
    mu: float
    theta_del: float
    delta: float
    theta_sub: float
    p_hash: float
    prediction_init: float
    error_init: float
    fitness_init: float
    ga_subsumption: bool
    action_set_subsumption: bool
    consistent_actions: bool
    learn_in_exploit: bool

    @classmethod
    def resolve(cls, owner: str, values: Mapping[str, object]) -> Settings:
        """Settings from parameters that passed `CONSTRAINTS`; N < n_actions is a ValueError
        (covering needs room for one classifier per action)."""
        n_actions, size = int(values["n_actions"]), int(values["N"])
        if size < n_actions:
            raise ValueError(f"{owner}: N must be an integer >= n_actions ({n_actions}) so "
                             f"covering fits, got {values['N']!r}")
        beta = float(values["beta"])
        numbers_ = {name: float(values[name]) for name in (
            "gamma", "alpha", "epsilon_0", "nu", "theta_ga", "chi", "mu", "theta_del", "delta",
            "theta_sub", "p_hash", "prediction_init", "error_init", "fitness_init")}
        rates = {name: beta if values[name] is None else float(values[name])
                 for name in _OPTIONAL_RATES}
        flags = {name: bool(values[name]) for name in _FLAGS}
        return cls(n_actions=n_actions, N=size, beta=beta, **rates, **numbers_, **flags)

"""Checking XCS parameters: each bad value is a ValueError that names the argument."""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

DEFAULTS: dict[str, object] = {
    "N": 400, "beta": 0.2, "beta_p": None, "beta_e": None, "beta_f": None, "gamma": 0.71,
    "alpha": 0.1, "epsilon_0": 10.0, "nu": 5.0, "theta_ga": 25, "chi": 0.8, "mu": 0.04,
    "theta_del": 20, "delta": 0.1, "theta_sub": 20, "p_hash": 0.33, "prediction_init": 10.0,
    "error_init": 0.0, "fitness_init": 0.01, "ga_subsumption": True,
    "action_set_subsumption": False, "consistent_actions": False, "random_state": None,
}
"""The learner's keyword parameters and their defaults (Wilson's multiplexer settings)."""

_RATES = ("beta", "alpha")
_OPTIONAL_RATES = ("beta_p", "beta_e", "beta_f")
_PROBABILITIES = ("gamma", "chi", "mu", "delta", "p_hash")
_POSITIVE = ("epsilon_0", "nu", "fitness_init")
_NON_NEGATIVE = ("theta_ga", "theta_del", "theta_sub", "error_init")
_FLAGS = ("ga_subsumption", "action_set_subsumption", "consistent_actions")


def _is_real(value: object) -> bool:
    return (isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)
            and math.isfinite(float(value)))


def _is_integer(value: object) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool | np.bool_)


def _fail(owner: str, name: str, requirement: str, value: object) -> ValueError:
    return ValueError(f"{owner}: {name} must be {requirement}, got {value!r}")


def check_parameters(owner: str, n_actions: object, values: Mapping[str, object]) -> None:
    """Raise ValueError naming the first bad argument among ``n_actions`` and ``values``."""
    if not _is_integer(n_actions) or int(n_actions) < 1:
        raise _fail(owner, "n_actions", "an integer >= 1", n_actions)
    size = values["N"]
    if not _is_integer(size) or int(size) < int(n_actions):
        raise _fail(owner, "N", f"an integer >= n_actions ({n_actions}) so covering fits", size)
    for name in _RATES + _OPTIONAL_RATES:
        value = values[name]
        if value is None and name in _OPTIONAL_RATES:
            continue
        if not _is_real(value) or not 0.0 < float(value) <= 1.0:
            raise _fail(owner, name, "a number in (0, 1]", value)
    for name in _PROBABILITIES:
        value = values[name]
        if not _is_real(value) or not 0.0 <= float(value) <= 1.0:
            raise _fail(owner, name, "a number in [0, 1]", value)
    for name in _POSITIVE:
        value = values[name]
        if not _is_real(value) or float(value) <= 0.0:
            raise _fail(owner, name, "a finite number > 0", value)
    for name in _NON_NEGATIVE:
        value = values[name]
        if not _is_real(value) or float(value) < 0.0:
            raise _fail(owner, name, "a finite number >= 0", value)
    if not _is_real(values["prediction_init"]):
        raise _fail(owner, "prediction_init", "a finite number", values["prediction_init"])
    for name in _FLAGS:
        if not isinstance(values[name], bool | np.bool_):
            raise _fail(owner, name, "True or False", values[name])
    check_random_state(owner, values["random_state"])


def check_random_state(owner: str, random_state: object) -> None:
    """Accept None, a non-negative int, a numpy Generator or a numpy RandomState."""
    if random_state is None or isinstance(random_state,
                                          np.random.Generator | np.random.RandomState):
        return
    if not _is_integer(random_state) or int(random_state) < 0:
        raise _fail(owner, "random_state",
                    "None, an integer >= 0 or a numpy Generator", random_state)


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

    @classmethod
    def resolve(cls, n_actions: int, values: Mapping[str, object]) -> Settings:
        """Settings from parameters already passed through `check_parameters`."""
        beta = float(values["beta"])
        numbers_ = {name: float(values[name]) for name in (
            "gamma", "alpha", "epsilon_0", "nu", "theta_ga", "chi", "mu", "theta_del", "delta",
            "theta_sub", "p_hash", "prediction_init", "error_init", "fitness_init")}
        rates = {name: beta if values[name] is None else float(values[name])
                 for name in _OPTIONAL_RATES}
        flags = {name: bool(values[name]) for name in _FLAGS}
        return cls(n_actions=int(n_actions), N=int(values["N"]), beta=beta,
                   **rates, **numbers_, **flags)

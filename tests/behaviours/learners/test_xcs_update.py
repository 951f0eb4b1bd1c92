"""UPDATE SET's two forms (behaviours/learners/xcs_update.py): the array form for large action
sets and the Python-float form for small ones must give the same numbers bit for bit (down to
numpy's order of summation), and a large action set follows eq. 7.1, 7.4-7.7 through the array
form."""

from __future__ import annotations

import numpy as np
import pytest

from behaviours.learners.xcs import XCS
from behaviours.learners.xcs_params import Settings
from behaviours.learners.xcs_update import (
    SMALL_SET,
    UpdateConstants,
    numpy_sum,
    update_columns,
    update_set,
)
from tests.xcs_helpers import by_condition, cl, make


def _settings(**params: float) -> Settings:
    return Settings.resolve("XCS", XCS(2, **params).get_params(deep=False))


def _columns(rng: np.random.Generator, size: int) -> np.ndarray:
    """Random action-set columns: errors on both sides of epsilon_0 (10), some exactly 0,
    new and experienced classifiers, numerosities 1-5."""
    error = rng.choice([0.0, 3.0, 9.999, 10.0, 10.001, 250.0], size) * rng.uniform(0.5, 1.5, size)
    return np.array([rng.uniform(0.0, 1000.0, size), error, rng.uniform(0.001, 1.0, size),
                     rng.uniform(1.0, 30.0, size), rng.integers(0, 12, size).astype(float),
                     rng.integers(1, 6, size).astype(float), rng.integers(0, 99, size)])


@pytest.mark.parametrize("params", [{}, {"beta_p": 0.5, "beta_e": 0.05, "beta_f": 0.3},
                                    {"nu": 2.5, "alpha": 0.3, "epsilon_0": 1.0}])
def test_the_python_float_form_equals_the_array_form_bit_for_bit(params):
    settings = _settings(**params)
    constant = UpdateConstants.of(settings)
    rng = np.random.default_rng(7)
    for size in range(1, SMALL_SET):
        for _ in range(200):
            stats = _columns(rng, size)
            set_size, payoff = float(rng.integers(1, 40)), float(rng.choice([0.0, 1000.0]))
            columns = stats.tolist()
            update_set(stats, set_size, payoff, settings, constant)
            update_columns(columns, set_size, payoff, settings, constant)
            assert np.array(columns).tobytes() == stats.tobytes()


def test_both_forms_agree_when_every_accuracy_underflows():
    """Errors of 1e300 (rewards that large are finite input) make every accuracy 0: the
    array form divides by a zero sum into inf and NaN; the float form must do the same, not
    raise ZeroDivisionError."""
    settings = _settings()
    constant = UpdateConstants.of(settings)
    stats = _columns(np.random.default_rng(5), 5)
    stats[0], stats[1], stats[4] = 0.0, 1e300, 10.0  # predictions far off, errors stay huge
    columns = stats.tolist()
    with np.errstate(all="ignore"):
        update_set(stats, 7.0, 1e300, settings, constant)
        update_columns(columns, 7.0, 1e300, settings, constant)
    assert np.isnan(stats[2]).all()
    assert np.array(columns).tobytes() == stats.tobytes()


def test_numpy_sum_adds_in_numpy_order_up_to_128_terms():
    rng = np.random.default_rng(3)
    for count in range(1, 129):
        for _ in range(20):
            values = rng.random(count) * 10.0 ** rng.uniform(-3, 3, count)
            assert numpy_sum(values.tolist()) == np.add.reduce(values)
    values = [1.0, 1e16, -1e16, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]  # order shows: not 8.0
    assert numpy_sum(values) == np.add.reduce(np.array(values)) != sum(values)


def test_a_large_action_set_follows_eq_7_1_and_7_4_to_7_7():
    # SMALL_SET + 1 conditions over 0 and #, all matching 00000
    conditions = [f"{code:05b}".replace("1", "#") for code in range(SMALL_SET + 1)]
    records = [cl(condition, 0, prediction=1000.0, error=5.0 if index % 2 else 40.0,
                  fitness=0.3, experience=50, numerosity=1 + index % 3, action_set_size=4.0)
               for index, condition in enumerate(conditions)]
    xcs = make(records, beta=0.2, epsilon_0=10.0, alpha=0.1, nu=5.0)
    xcs.act("00000", explore=True, allowed={0})
    xcs.reward(1000.0, done=True)
    after = by_condition(xcs)
    set_size = sum(record.numerosity for record in records)
    errors = [record.error * 0.8 for record in records]  # eq. 7.4 with P = p
    kappas = [1.0 if error < 10.0 else 0.1 * (error / 10.0) ** -5.0 for error in errors]
    total = sum(kappa * record.numerosity for kappa, record in zip(kappas, records, strict=True))
    for record, error, kappa in zip(records, errors, kappas, strict=True):
        updated = after[(record.condition, 0)]
        assert updated.prediction == pytest.approx(1000.0)  # eq. 7.1
        assert updated.error == pytest.approx(error)
        assert updated.experience == 51
        assert updated.action_set_size == pytest.approx(4.0 + 0.2 * (set_size - 4.0))
        relative = kappa * record.numerosity / total  # eq. 7.7
        assert updated.fitness == pytest.approx(0.3 + 0.2 * (relative - 0.3))  # eq. 7.5

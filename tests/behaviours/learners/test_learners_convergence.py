"""The thesis's (4.10)–(4.11) and its labelled variants on hand-made TD-error series."""

from __future__ import annotations

import numpy as np
import pytest

from behaviours.learners.cacla import TDConvergence
from behaviours.learners.convergence import (
    CRITERIA,
    VARIANTS,
    averaged_magnitudes,
    first_convergence,
    holds,
)

# N = 3, ε = 0.01: (4.10) at k is ||δ_k| − |δ_(k−3)|| < 0.03 (k ≥ 4).
HAND = [0.5, -0.3, 0.2, -0.52, 0.0, 0.2, -0.5, 0.1, 0.14, -0.5, 0.1, -0.14]


def test_averages_are_eq_4_11_over_absolute_errors() -> None:
    averaged = averaged_magnitudes(HAND, window=3)
    assert np.isnan(averaged[:2]).all()
    assert averaged[2:6] == pytest.approx([1.0 / 3, 1.02 / 3, 0.72 / 3, 0.72 / 3])


def test_thesis_holds_where_two_errors_n_apart_agree_within_n_epsilon() -> None:
    # |0.52 − 0.5| = 0.02 (k=4), |0.2 − 0.2| (6), |0.5 − 0.52| (7), |0.5 − 0.5| (10),
    # |0.1 − 0.1| (11), |0.14 − 0.14| (12); k = 5, 8, 9 differ by 0.3, 0.1, 0.06.
    flags = holds(HAND, "thesis", window=3, tol=0.01)
    assert np.flatnonzero(flags).tolist() == [3, 5, 6, 9, 10, 11]
    assert first_convergence(HAND, "thesis", window=3, tol=0.01) == 4


def test_after_transient_ignores_steps_before_2n_plus_1() -> None:
    assert first_convergence(HAND, "after-transient", window=3, tol=0.01) == 7


def test_window_to_window_compares_disjoint_window_averages() -> None:
    # δ̄9 − δ̄6 = (0.5 + 0.1 + 0.14 − 0.52 − 0 − 0.2) / 3 = 0.0067 < 0.01; at k = 6, 7, 8
    # the differences are 0.093, 0.107, 0.027.
    flags = holds(HAND, "window-to-window", window=3, tol=0.01)
    assert not flags[:8].any() and flags[8]
    assert first_convergence(HAND, "window-to-window", window=3, tol=0.01) == 9


def test_sustained_needs_n_consecutive_steps_of_4_10() -> None:
    # (4.10) at 6, 7 then not at 8, 9; then 10, 11, 12: three in a row end at 12.
    assert first_convergence(HAND, "sustained", window=3, tol=0.01) == 12
    assert first_convergence(HAND[:11], "sustained", window=3, tol=0.01) is None


def test_constant_errors_meet_each_criterion_at_its_earliest_step() -> None:
    """N = 20: thesis from k = 21, sustained and window-to-window at 40, after-transient 41."""
    steady = [0.05] * 60
    firsts = {name: first_convergence(steady, name) for name in CRITERIA}
    assert firsts == {"thesis": 21, "after-transient": 41, "sustained": 40,
                      "window-to-window": 40}


def test_one_occasional_error_delays_sustained_and_window_to_window_only() -> None:
    """|δ| = 0.01 every 10th step, else 0 (N = 20): steps N apart match, so every criterion
    holds as early as it can. One extra error of 0.01 at k = 35 breaks (4.10) where it enters
    (35) and leaves (55) the window, and makes the two windows' sums differ by 0.01
    (δ̄ by 5e-4 ≥ ε) for every k from 40 to 74."""
    regular = [0.01 if k % 10 == 0 else 0.0 for k in range(1, 101)]
    assert {name: first_convergence(regular, name) for name in CRITERIA} == {
        "thesis": 21, "after-transient": 41, "sustained": 40, "window-to-window": 40}
    regular[34] = 0.01
    flags = holds(regular, "thesis")
    assert np.flatnonzero(~flags[20:]).tolist() == [14, 34]  # k = 35 and 55
    assert {name: first_convergence(regular, name) for name in CRITERIA} == {
        "thesis": 21, "after-transient": 41, "sustained": 75, "window-to-window": 75}


def test_thesis_criterion_is_what_algorithm_3_tests_online() -> None:
    rng = np.random.default_rng(3)
    series = rng.normal(0.0, 0.002, size=300)
    online = TDConvergence(20, 1e-4)
    fired = np.array([online.update(d) for d in series])
    assert fired.any() and not fired.all()
    assert np.array_equal(holds(series, "thesis"), fired)
    assert averaged_magnitudes(series)[19:] == pytest.approx(online.averages, abs=1e-15)


def test_never_met_and_too_short_series_give_none() -> None:
    growing = np.linspace(0.0, 1.0, 80)  # δ̄ rises by 0.0127 a step: (4.10) never holds
    assert all(first_convergence(growing, name) is None for name in CRITERIA)
    assert all(first_convergence([0.1] * 19, name) is None for name in CRITERIA)
    assert holds([], "thesis").size == 0


@pytest.mark.parametrize(("call", "message"), [
    (lambda: holds([0.1, 0.2], "median"), "'criterion' parameter of holds must be a str among"),
    (lambda: holds([0.1, float("nan")], "thesis"), "Input td_errors contains NaN"),
    (lambda: holds([[0.1, 0.2]], "thesis"), "1-D series"),
    (lambda: holds([0.1], "sustained", window=0), "'window' parameter of holds must be an int"),
    (lambda: first_convergence([0.1], "thesis", tol=-1.0), "'tol' parameter of holds must be"),
])
def test_bad_input_is_refused_clearly(call, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        call()


def test_variants_are_every_criterion_but_the_thesis() -> None:
    assert CRITERIA[0] == "thesis" and set(VARIANTS) == set(CRITERIA) - {"thesis"}

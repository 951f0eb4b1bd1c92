"""The random-mode ``learn`` behaviour on analytic effect functions (thesis §6.3.4, eq. 5.19)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from sklearn.base import clone

from behaviours.learners.effect_models import LinearEffectModel
from behaviours.learning import (
    AffordanceEvidence,
    LearningModeUnavailable,
    RandomExplorer,
    learn,
    verify_effect,
)

EXTEND = (0.0, 0.1)
WIDE_NEGATIVE = (-0.1, 0.0)


def linear(theta: float) -> float:
    """The thesis's learned extend_arm model on the lid: Ĥ = 0.007 + 1.293 θ (§6.4.2)."""
    return 0.007 + 1.293 * theta


def saturating(theta: float) -> float:
    """A lid that opens quickly and then stops at 0.15 m."""
    return 0.15 * (1.0 - math.exp(-theta / 0.02))


def noisy_flat(seed: int, sd: float = 0.002):
    """No effect at all, measured with Gaussian noise of ``sd`` metres."""
    rng = np.random.default_rng(seed)
    return lambda theta: float(rng.normal(0.0, sd))


def run(effect_fn, bounds=EXTEND, **kwargs):
    """learn() with the thesis's δ = 0.1 m and small defaults for the rest."""
    options = dict(
        obj="lid",
        action="extend_arm",
        effect_name="opened",
        bounds=bounds,
        delta=0.1,
        n_max=12,
        random_state=0,
    )
    options.update(kwargs)
    return learn(effect_fn, **options)


def test_linear_effect_settles_at_once_and_predicts_opening() -> None:
    result = run(linear)
    assert result.settled and result.samples == 4  # exact line: RSS stays 0; n_min = 4
    assert result.model.coef_ == pytest.approx(1.293)
    assert result.model.intercept_ == pytest.approx(0.007, abs=1e-12)
    assert result.theta_max == 0.1
    assert result.e_max == pytest.approx(0.1363)
    assert result.evidence == AffordanceEvidence("lid", "extend_arm", "opened", 0, 0, 0.3)
    assert type(result.evidence.tot) is int and type(result.evidence.rel) is float


def test_ineffective_action_reports_r2_with_a_usable_theta_max() -> None:
    """A decreasing line peaks at the open end θ -> 0: θ_max is the smallest θ explored."""
    result = run(lambda t: 0.003 - 0.021 * t, action="contract_arm")
    assert result.model.coef_ == pytest.approx(-0.021)
    assert result.theta_max == result.model.theta_.min() > 0.0
    assert result.e_max == pytest.approx(0.003 - 0.021 * result.theta_max)
    evidence = result.evidence
    assert (evidence.tot, evidence.suc, evidence.rel) == (0, 0, 0.05)


def test_an_effective_decreasing_action_still_gets_a_valid_theta_max() -> None:
    result = run(lambda t: 0.2 - t, bounds=(0.02, 0.1))
    assert 0.02 < result.theta_max <= 0.1
    assert result.e_max == pytest.approx(0.2 - result.theta_max)
    assert result.evidence.rel == 0.3


def test_flat_noisy_effect_settles_and_reports_r2() -> None:
    result = run(noisy_flat(1), n_max=20)
    assert result.settled and result.samples < 20
    assert abs(result.e_max) < 0.02
    assert result.evidence.rel == 0.05


def test_saturating_effect_settles_later_under_a_stricter_tolerance() -> None:
    strict = [run(saturating, settle_tol=1e-6, n_max=15, random_state=s) for s in range(5)]
    loose = [run(saturating, settle_tol=1e-3, n_max=15, random_state=s) for s in range(5)]
    assert all(a.samples >= b.samples for a, b in zip(strict, loose, strict=True))
    assert sum(r.samples for r in strict) > sum(r.samples for r in loose) + 10
    assert any(not r.settled and r.samples == 15 for r in strict)  # the curve never fits
    assert all(r.e_max >= 0.1 and r.evidence.rel == 0.3 for r in strict + loose)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_stop_follows_eq_5_19_on_recorded_samples(seed: int) -> None:
    """Recompute S_m with numpy's own least squares and find where |S_m - S_m-1| < tol."""
    tol = 2e-5
    result = run(noisy_flat(seed, sd=0.006), random_state=seed, settle_tol=tol, n_max=25)
    theta, effect = result.model.theta_[:, 0], result.model.effect_  # one parameter θ
    rss = []
    for m in range(1, len(theta) + 1):
        slope, intercept = np.polyfit(theta[:m], effect[:m], 1) if m > 1 else (0.0, effect[0])
        rss.append(float(np.sum((effect[:m] - (intercept + slope * theta[:m])) ** 2)))
    stops = [m for m in range(4, 26) if m <= len(rss) and abs(rss[m - 1] - rss[m - 2]) < tol]
    expected = stops[0] if stops else 25
    assert result.samples == expected == len(theta)
    assert result.settled == bool(stops)
    assert result.model.rss_history_ == pytest.approx(rss, abs=1e-12)


def test_samples_stay_in_the_bounds_and_are_seeded() -> None:
    first = run(saturating, bounds=WIDE_NEGATIVE, n_max=30, settle_tol=1e-9, random_state=5)
    again = run(saturating, bounds=WIDE_NEGATIVE, n_max=30, settle_tol=1e-9, random_state=5)
    other = run(saturating, bounds=WIDE_NEGATIVE, n_max=30, settle_tol=1e-9, random_state=6)
    assert np.all((first.model.theta_ > -0.1) & (first.model.theta_ <= 0.0))
    assert np.array_equal(first.model.theta_, again.model.theta_)
    assert first.e_max == again.e_max and first.theta_max == again.theta_max
    assert not np.array_equal(first.model.theta_, other.model.theta_)


def test_transfer_is_refused_as_the_whole_object_behaviour() -> None:
    calls = []
    with pytest.raises(LearningModeUnavailable, match="is the whole-object behaviour"):
        run(lambda t: calls.append(t) or 0.0, mode="transfer")
    assert calls == []  # refused before touching the world
    assert issubclass(LearningModeUnavailable, NotImplementedError)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"mode": "greedy"}, "unknown learning mode 'greedy'"),
        ({"bounds": (0.1, 0.0)}, "low < high"),
        ({"bounds": "wide"}, "pair of numbers"),
        ({"n_max": 0}, "n_max must be a positive"),
        ({"n_min": 1}, "n_min must be"),
        ({"obj": ""}, "obj must be a non-empty name"),
        ({"r1": 0.01}, "0 < r2 < r1 < 1"),
        ({"delta": float("nan")}, "delta must be a finite number"),
    ],
)
def test_user_mistakes_give_clear_errors(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        run(linear, **kwargs)


def test_a_bad_effect_value_is_named() -> None:
    with pytest.raises(ValueError, match="returned nan for theta="):
        run(lambda t: float("nan"))
    with pytest.raises(ValueError, match="returned 'wide' for theta="):
        run(lambda t: "wide")
    assert run(lambda t: np.float32(t)).model.coef_ == pytest.approx(1.0)  # any real number


def test_verification_follows_6_3_3() -> None:
    success = verify_effect(
        obj="lid", action="extend_arm", effect_name="opened", observed_effect=0.156, delta=0.1
    )
    failure = verify_effect(
        obj="lid", action="extend_arm", effect_name="opened", observed_effect=0.02, delta=0.1
    )
    assert success == AffordanceEvidence("lid", "extend_arm", "opened", 1, 1, 1)
    assert failure == AffordanceEvidence("lid", "extend_arm", "opened", 1, 0, 0)
    assert all(type(n) is int for n in (success.tot, success.suc, success.rel, failure.rel))


def test_effect_model_follows_sklearn_conventions() -> None:
    model = LinearEffectModel()
    assert clone(model).get_params() == {"fit_intercept": True}
    with pytest.raises(ValueError, match="not fitted yet"):
        model.predict([0.05])
    theta = np.array([0.01, 0.04, 0.07, 0.09])
    effect = 0.01 + 0.9 * theta + np.array([0.001, -0.002, 0.0015, -0.0005])
    whole = LinearEffectModel().fit(theta[:, None], effect)
    stepwise = LinearEffectModel()
    for t, e in zip(theta, effect, strict=True):
        stepwise.partial_fit(t, e)
    assert stepwise.coef_ == pytest.approx(whole.coef_)
    assert stepwise.intercept_ == pytest.approx(whole.intercept_)
    assert len(stepwise.rss_history_) == 4 and len(whole.rss_history_) == 1
    assert whole.score(theta, effect) > 0.99
    explorer = RandomExplorer(bounds=EXTEND, random_state=3)
    assert clone(explorer).get_params()["random_state"] == 3

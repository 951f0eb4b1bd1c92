"""CACLA (thesis eq. 4.5–4.9) and the TD-error convergence test (4.10–4.11) on hand numbers."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from sklearn.base import clone
from sklearn.exceptions import NotFittedError

from behaviours.learners.cacla import CACLA, TDConvergence, td_error
from behaviours.learners.network import TanhNetwork
from behaviours.learners.persist import LearnerFileError


def one_unit(w_in: float, b_in: float, w_out: float, b_out: float) -> TanhNetwork:
    """out(s) = w_out · tanh(w_in · s + b_in) + b_out."""
    return TanhNetwork([np.array([[w_in]]), np.array([[w_out]])],
                       [np.array([b_in]), np.array([b_out])])


def hand_learner() -> CACLA:
    """Critic V(s) = 0.4 tanh(0.5 s + 0.1) + 0.2, actor Act(s) = 0.5 tanh(s)."""
    learner = CACLA(n_hidden=1, random_state=0)
    learner.sample([0.0])  # creates the networks; replaced by hand-made ones
    learner.critic_ = one_unit(0.5, 0.1, 0.4, 0.2)
    learner.actor_ = one_unit(1.0, 0.0, 0.5, 0.0)
    return learner


def critic(s: float) -> float:
    return 0.4 * math.tanh(0.5 * s + 0.1) + 0.2


def test_td_error_is_eq_4_7() -> None:
    assert td_error(reward=0.02, value=0.1, next_value=0.15, gamma=0.9) == pytest.approx(0.055)
    assert td_error(reward=0.0, value=0.3, next_value=0.3, gamma=0.9) == pytest.approx(-0.03)


def test_positive_td_error_moves_the_actor_towards_the_action_and_updates_the_critic() -> None:
    s, s_next, r, a = 0.2, 0.4, 0.05, 0.6
    delta = r + 0.9 * critic(s_next) - critic(s)
    assert delta == pytest.approx(0.055923, abs=1e-6) and delta > 0
    learner = hand_learner()
    assert learner.value([s]) == pytest.approx([critic(s)])
    assert learner.predict([s])[0, 0] == pytest.approx(0.5 * math.tanh(s))
    learner.partial_fit([s], [a], [r], [s_next])
    assert learner.td_errors_ == [pytest.approx(delta)]
    # 4.8 in network form: one SGD step of size ζ = 0.3 on ½(a − Act(s))²
    h = math.tanh(s)
    err = a - 0.5 * h
    actor = learner.actor_
    assert actor.coefs[1][0, 0] == pytest.approx(0.5 + 0.3 * err * h)
    assert actor.intercepts[1][0] == pytest.approx(0.3 * err)
    assert actor.coefs[0][0, 0] == pytest.approx(1.0 + 0.3 * 0.5 * err * (1 - h * h) * s)
    assert 0.5 * h < learner.predict([s])[0, 0]  # Act(s) moved towards a
    # 4.9 in network form: V ← V + β δ ∇V with β = 0.3
    hc = math.tanh(0.5 * s + 0.1)
    assert learner.critic_.intercepts[1][0] == pytest.approx(0.2 + 0.3 * delta)
    assert learner.critic_.coefs[1][0, 0] == pytest.approx(0.4 + 0.3 * delta * hc)
    assert learner.critic_.coefs[0][0, 0] == pytest.approx(
        0.5 + 0.3 * delta * 0.4 * (1 - hc * hc) * s)


def test_non_positive_td_error_leaves_the_actor_alone_but_still_updates_the_critic() -> None:
    s = 0.2
    delta = 0.0 + 0.9 * critic(s) - critic(s)
    assert delta == pytest.approx(-0.1 * critic(s)) and delta < 0
    learner = hand_learner()
    learner.partial_fit([s], [0.9], [0.0], [s])
    assert learner.td_errors_ == [pytest.approx(delta)]
    assert learner.actor_.coefs[1][0, 0] == 0.5 and learner.actor_.coefs[0][0, 0] == 1.0
    assert learner.actor_.intercepts[1][0] == 0.0
    assert learner.critic_.intercepts[1][0] == pytest.approx(0.2 + 0.3 * delta)
    assert learner.value([s])[0] < critic(s)


def test_exploration_is_gaussian_around_the_actor_and_stays_in_bounds() -> None:
    learner = hand_learner()
    samples = np.array([learner.sample([0.2]) for _ in range(4000)])
    assert samples.shape == (4000, 1)
    assert samples.mean() == pytest.approx(0.5 * math.tanh(0.2), abs=0.015)
    assert samples.std() == pytest.approx(0.2, abs=0.01)  # σ = 0.2 (4.5)
    learner.actor_ = one_unit(0.0, 0.0, 0.0, 0.95)  # the actor near the upper bound
    clipped = np.array([learner.sample([0.2]) for _ in range(2000)])
    assert clipped.max() == 1.0 and clipped.min() > 0.2
    assert 0.35 < np.mean(clipped == 1.0) < 0.45  # P(N(0.95, 0.2) > 1) = 0.40


def test_three_dimensional_actions_and_seeding() -> None:
    first = CACLA(action_dims=3, random_state=7)
    again = clone(first)
    a1 = [first.sample([0.05]) for _ in range(3)]
    a2 = [again.sample([0.05]) for _ in range(3)]
    assert all(np.array_equal(x, y) for x, y in zip(a1, a2, strict=True))
    assert a1[0].shape == (3,) and first.predict([[0.05]]).shape == (1, 3)
    first.partial_fit([[0.05], [0.06]], a1[:2], [0.01, 0.02], [[0.06], [0.07]])
    assert len(first.td_errors_) == 2


def test_convergence_test_follows_eq_4_10_and_4_11() -> None:
    """N = 3, ε = 0.01: δ̄ = 0.333, 0.25, 0.253, 0.32: |0.253 − 0.25| < 0.01 at step 5 only."""
    test = TDConvergence(window=3, tol=0.01)
    fired = [test.update(d) for d in (0.5, -0.3, 0.2, 0.25, -0.31, 0.4)]
    assert fired == [False, False, False, False, True, False]
    assert test.averages == pytest.approx([1 / 3, 0.25, 0.76 / 3, 0.96 / 3])


def test_thesis_setting_fires_when_two_errors_n_steps_apart_match_within_n_epsilon() -> None:
    """N = 20, ε = 1e-4: δ̄_{k+1} − δ̄_k = (|δ_{k+1}| − |δ_{k−19}|) / 20."""
    test = TDConvergence()
    fired = [test.update(d) for d in [0.05] * 20 + [-0.0535, 0.0515]]
    assert fired[:21] == [False] * 21  # |0.0535 − 0.05| / 20 = 1.75e-4 ≥ ε
    assert fired[21]  # |0.0515 − 0.05| / 20 = 7.5e-5 < ε
    assert test.averages[-1] - test.averages[-2] == pytest.approx((0.0515 - 0.05) / 20)
    with pytest.raises(ValueError, match="finite number"):
        test.update(float("nan"))


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda c: c.partial_fit([0.1], [1.5], [0.0], [0.1]), "unit actions in"),
        (lambda c: c.partial_fit([0.1], [0.5], [float("nan")], [0.1]), "rewards contains NaN"),
        (lambda c: c.partial_fit([0.1], [0.5], [0.0], [[0.1, 0.2]]), "must have 1 column"),
        (lambda c: c.partial_fit([0.1, 0.2], [0.5], [0.0], [0.1]), "inconsistent numbers"),
        (lambda c: c.sample([float("inf")]), "Input state contains infinity"),
    ],
)
def test_bad_input_is_refused_and_changes_nothing(call, message: str) -> None:
    learner = hand_learner()
    with pytest.raises(ValueError, match=message):
        call(learner)
    assert learner.td_errors_ == [] and learner.actor_.coefs[1][0, 0] == 0.5
    assert learner.critic_.intercepts[1][0] == 0.2


def test_asking_before_anything_is_learned_is_a_clear_error() -> None:
    with pytest.raises(NotFittedError, match="no actor yet"):
        CACLA().predict([0.0])
    with pytest.raises(NotFittedError, match="no actor yet"):
        CACLA().value([0.0])
    fresh = CACLA()
    with pytest.raises(ValueError, match="unit actions"):
        fresh.partial_fit([0.1], [2.0], [0.0], [0.1])
    assert not hasattr(fresh, "actor_")  # a refused first call draws no weights
    with pytest.raises(ValueError, match="'gamma' parameter of CACLA must be"):
        CACLA(gamma=1.5).partial_fit([0.1], [0.5], [0.0], [0.1])


def test_save_and_load_round_trip_and_corrupt_files(tmp_path: Path) -> None:
    learner = CACLA(action_dims=3, random_state=1)
    learner.partial_fit([[0.1]], [[0.2, -0.3, 1.0]], [0.01], [[0.12]])
    path = learner.save(tmp_path / "cacla.json")
    loaded = CACLA.load(path)
    assert np.array_equal(loaded.predict([[0.1]]), learner.predict([[0.1]]))
    assert loaded.value([[0.3]]) == pytest.approx(learner.value([[0.3]]))
    assert loaded.td_errors_ == learner.td_errors_ and loaded.get_params() == learner.get_params()
    path.write_text(path.read_text().replace('"action_dims": 3', '"action_dims": 2'))
    with pytest.raises(LearnerFileError, match="bad CACLA"):
        CACLA.load(path)
    path.write_text(path.read_text()[:40])
    with pytest.raises(LearnerFileError, match="cannot read learner file"):
        CACLA.load(path)

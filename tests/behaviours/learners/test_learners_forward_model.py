"""The forward model F_ψ of thesis §4.4.2 (eq. 4.1–4.4) and its tanh network, on hand numbers."""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from sklearn.base import clone
from sklearn.exceptions import NotFittedError
from sklearn.neural_network import MLPRegressor

from behaviours.learners.forward_model import ForwardModel
from behaviours.learners.network import TanhNetwork
from behaviours.learners.persist import LearnerFileError

W1 = [[0.1, -0.2], [0.3, 0.4]]
B1 = [0.0, 0.1]
W2 = [[0.5], [-0.3]]
B2 = [0.05]


def tiny() -> TanhNetwork:
    """2 inputs, 2 tanh units, 1 linear output, hand-picked weights."""
    return TanhNetwork([np.array(W1), np.array(W2)], [np.array(B1), np.array(B2)])


def test_one_backprop_step_matches_the_hand_computation() -> None:
    """Eq. 4.2–4.4 with x = (1, 0.5), target 0.2, α = 0.3, worked out with scalars."""
    x1, x2, target, alpha = 1.0, 0.5, 0.2, 0.3
    h1 = math.tanh(0.1 * x1 + 0.3 * x2 + 0.0)  # tanh(0.25)
    h2 = math.tanh(-0.2 * x1 + 0.4 * x2 + 0.1)  # tanh(0.1)
    out = 0.5 * h1 - 0.3 * h2 + 0.05
    eta = target - out  # eq. 4.3
    assert out == pytest.approx(0.142559, abs=1e-6) and eta == pytest.approx(0.057441, abs=1e-6)
    g1 = 0.5 * eta * (1 - h1 * h1)  # error reaching hidden unit 1, through the old W2
    g2 = -0.3 * eta * (1 - h2 * h2)
    net = tiny()
    assert net.predict(np.array([[x1, x2]]))[0, 0] == pytest.approx(out)
    net.nudge(np.array([x1, x2]), np.array([eta]), alpha)
    assert net.coefs[1][:, 0] == pytest.approx([0.5 + alpha * eta * h1, -0.3 + alpha * eta * h2])
    assert net.intercepts[1] == pytest.approx([0.05 + alpha * eta])
    assert net.coefs[0] == pytest.approx(np.array([
        [0.1 + alpha * g1 * x1, -0.2 + alpha * g2 * x1],
        [0.3 + alpha * g1 * x2, 0.4 + alpha * g2 * x2],
    ]))
    assert net.intercepts[0] == pytest.approx([0.0 + alpha * g1, 0.1 + alpha * g2])


def test_the_step_equals_sklearn_mlp_partial_fit_with_plain_sgd() -> None:
    """MLPRegressor with plain SGD, batch 1, no momentum, no L2 is the reference for eq. 4.4."""
    rng = np.random.RandomState(0)
    net = TanhNetwork.uniform(4, 10, 3, 0.3, rng)
    reference = MLPRegressor(hidden_layer_sizes=(10,), activation="tanh", solver="sgd",
                             learning_rate="constant", learning_rate_init=0.3, momentum=0.0,
                             nesterovs_momentum=False, alpha=0.0, batch_size=1, shuffle=False)
    x, y = rng.uniform(-1, 1, size=(5, 4)), rng.uniform(-0.05, 0.05, size=(5, 3))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        reference.partial_fit(x[:1], y[:1])  # creates its weights; replaced in place below
    for mine, theirs in zip(net.coefs + net.intercepts,
                            reference.coefs_ + reference.intercepts_, strict=True):
        theirs[...] = mine
    for row, target in zip(x, y, strict=True):
        net.nudge(row, target - net.predict(row[None, :])[0], 0.3)
        reference.partial_fit(row[None, :], target[None, :])
    for mine, theirs in zip(net.coefs + net.intercepts,
                            reference.coefs_ + reference.intercepts_, strict=True):
        assert mine == pytest.approx(theirs, abs=1e-12)


def test_forward_model_normalises_actions_and_takes_the_hand_step() -> None:
    """X = [s_o, a] with a in metres; a = 0.005 m of (−0.01, 0.01) enters the net as 0.5."""
    model = ForwardModel(action_bounds=[(-0.01, 0.01)], n_hidden=2).initialize(1)
    model.network_ = tiny()
    assert model.predict([[1.0, 0.005]]) == pytest.approx([0.142559], abs=1e-6)
    assert model.partial_fit([[1.0, 0.005]], [0.2]) is model
    expected = tiny()
    expected.nudge(np.array([1.0, 0.5]), np.array([0.2 - 0.142559]), 0.3)
    assert model.predict([[1.0, 0.005]]) == pytest.approx(
        expected.predict(np.array([[1.0, 0.5]]))[:, 0], abs=1e-6)
    assert model.n_samples_seen_ == 1


def test_initial_weights_are_uniform_in_the_thesis_range_and_seeded() -> None:
    first = ForwardModel(action_bounds=[(-0.01, 0.01)] * 3, random_state=4).initialize(1)
    again = ForwardModel(action_bounds=[(-0.01, 0.01)] * 3, random_state=4).initialize(1)
    weights = np.concatenate([a.ravel() for a in first.network_.coefs
                              + first.network_.intercepts])
    assert first.network_.coefs[0].shape == (4, 10) and first.network_.coefs[1].shape == (10, 1)
    assert np.all(np.abs(weights) <= 0.3) and weights.std() > 0.1
    assert np.array_equal(first.network_.coefs[0], again.network_.coefs[0])


def lid_effect(state: np.ndarray, action: np.ndarray) -> np.ndarray:
    """A known push-lid response: pushing opens, less so the wider it already is."""
    return 1.5 * action * (1.0 - state / 0.3)


def test_training_reduces_the_error_on_a_known_function() -> None:
    rng = np.random.RandomState(1)
    states, actions = rng.uniform(0, 0.2, 3000), rng.uniform(-0.01, 0.01, 3000)
    X, y = np.column_stack([states, actions]), lid_effect(states, actions)
    grid = np.array([[s, a] for s in np.linspace(0, 0.2, 10) for a in np.linspace(-0.01, 0.01, 10)])
    truth = lid_effect(grid[:, 0], grid[:, 1])
    model = ForwardModel(random_state=0).partial_fit(X[:1], y[:1])
    before = np.sqrt(np.mean((model.predict(grid) - truth) ** 2))
    for row, target in zip(X[1:], y[1:], strict=True):
        model.partial_fit(row[None, :], [target])
    after = np.sqrt(np.mean((model.predict(grid) - truth) ** 2))
    assert after < before / 10, (before, after)  # the untrained guess was far off
    assert after < np.sqrt(np.mean(truth**2)), after  # better than predicting "no effect"
    assert model.predict([[0.0, 0.01]])[0] > 0.005 > 0 > -0.005 > model.predict([[0.0, -0.01]])[0]


def test_sklearn_conventions() -> None:
    model = ForwardModel(action_bounds=((-0.01, 0.01),), n_hidden=5, random_state=3)
    twin = clone(model)
    assert twin.get_params() == model.get_params() and not hasattr(twin, "network_")
    X = np.array([[0.0, 0.01], [0.05, -0.004], [0.1, 0.002]])
    y = np.array([0.01, -0.004, 0.001])
    first = model.fit(X, y).predict(X)
    assert np.array_equal(first, twin.fit(X, y).predict(X))  # same seed, same model
    assert np.array_equal(model.fit(X, y).predict(X), first)  # fit starts afresh
    assert first.shape == (3,)
    assert np.isfinite(model.score(X, y))
    vector = ForwardModel(random_state=0).fit(X, np.column_stack([y, -y]))
    assert vector.predict(X).shape == (3, 2)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda m: m.partial_fit([[0.0, float("nan")]], [0.0]), "Input X contains NaN"),
        (lambda m: m.partial_fit([[0.0, 0.0]], [float("inf")]), "Input y contains infinity"),
        (lambda m: m.partial_fit([[0.0, 0.02]], [0.0]), "out of bounds"),
        (lambda m: m.partial_fit([[0.0, 0.0, 0.0]], [0.0]), "X has 3 features, but ForwardModel "
                                                           "is expecting 2"),
        (lambda m: m.partial_fit([[0.0, 0.0], [0.1, 0.0]], [0.0]), "inconsistent numbers"),
        (lambda m: m.partial_fit([["a", 0.0]], [0.0]), "could not convert string to float"),
        (lambda m: m.partial_fit([[0.0, 0.0]], [[0.0, 1.0]]), "2 effect column"),
        (lambda m: m.predict([[0.0, -0.011]]), "out of bounds"),
    ],
)
def test_bad_input_is_refused_and_changes_nothing(call, message: str) -> None:
    model = ForwardModel(random_state=0).partial_fit([[0.0, 0.001]], [0.001])
    before = [w.copy() for w in model.network_.coefs + model.network_.intercepts]
    with pytest.raises(ValueError, match=message):
        call(model)
    after = model.network_.coefs + model.network_.intercepts
    assert all(np.array_equal(b, a) for b, a in zip(before, after, strict=True))
    assert model.n_samples_seen_ == 1


def test_predict_before_any_data_is_a_clear_error() -> None:
    with pytest.raises(NotFittedError, match="seen no data yet"):
        ForwardModel().predict([[0.0, 0.0]])
    with pytest.raises(ValueError, match=r"1 feature\(s\) .* a minimum of 2 is required"):
        ForwardModel().partial_fit([[0.0]], [0.0])
    with pytest.raises(ValueError, match="lo < hi"):
        ForwardModel(action_bounds=[(0.01, -0.01)]).partial_fit([[0.0, 0.0]], [0.0])
    with pytest.raises(ValueError, match="'learning_rate' parameter of ForwardModel must be"):
        ForwardModel(learning_rate=2).partial_fit([[0.0, 0.0]], [0.0])


def test_save_and_load_round_trip(tmp_path: Path) -> None:
    model = ForwardModel(action_bounds=[(-0.01, 0.01)] * 3, random_state=2)
    X = np.array([[0.0, 0.01, 0.0, -0.01], [0.1, -0.01, 0.005, 0.0]])
    model.partial_fit(X, [0.02, -0.01])
    path = model.save(tmp_path / "sub" / "fm.json")
    loaded = ForwardModel.load(path)
    assert np.array_equal(loaded.predict(X), model.predict(X))
    assert loaded.get_params()["action_bounds"] == ((-0.01, 0.01),) * 3
    assert loaded.n_samples_seen_ == 2
    assert [p.name for p in path.parent.iterdir()] == ["fm.json"]  # no temporary file left
    data = json.loads(path.read_text())
    assert (data["format"], data["version"], data["kind"]) == (
        "goalagent-learner", 1, "forward_model")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{not json", "cannot read learner file"),
        ('{"format": "other"}', "is not a goalagent learner file"),
        ('{"format": "goalagent-learner", "version": 99}', "has version 99"),
        ('{"format": "goalagent-learner", "version": 1, "kind": "cacla", "params": {}, '
         '"state": {}}', "holds a 'cacla'"),
        ('{"format": "goalagent-learner", "version": 1, "kind": "forward_model", '
         '"params": {"action_bounds": [[-0.01, 0.01]]}, "state": {"network": {"coefs": [[1]], '
         '"intercepts": []}}}', r"params: must contain \[.*'n_hidden'.*\] properties"),
        ('{"format": "goalagent-learner", "version": 1, "kind": "forward_model", '
         '"params": {"action_bounds": [[-0.01, 0.01]], "n_hidden": 1, "learning_rate": 0.3, '
         '"init_scale": 0.3, "random_state": null}, "state": {"network": {"coefs": [[[1]], '
         '[[1]]], "intercepts": [[0], [0]]}, "n_features_in": 3, "n_outputs": 1, '
         '"n_samples_seen": 0}}', "bad forward model"),
    ],
)
def test_corrupt_files_give_clear_errors(tmp_path: Path, text: str, message: str) -> None:
    path = tmp_path / "fm.json"
    path.write_text(text)
    with pytest.raises(LearnerFileError, match=message):
        ForwardModel.load(path)
    with pytest.raises(LearnerFileError, match="cannot read learner file"):
        ForwardModel.load(tmp_path / "missing.json")


def test_saving_an_empty_model_is_refused_and_writes_nothing(tmp_path: Path) -> None:
    with pytest.raises(NotFittedError):
        ForwardModel().save(tmp_path / "fm.json")
    assert list(tmp_path.iterdir()) == []

"""XCS learns what XCS is known to learn, at reduced size: the 6-multiplexer (single step),
Woods1 (multi-step, Wilson's animat world), and the scikit-learn face on the multiplexer."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.base import clone
from sklearn.exceptions import NotFittedError

from behaviours.learners.xcs import XCS, XCSClassifier

MUX6_TABLE = np.array([[int(bit) for bit in format(index, "06b")] for index in range(64)])


def mux6(bits: np.ndarray) -> int:
    return int(bits[2 + 2 * bits[0] + bits[1]])


def test_xcs_learns_the_6_multiplexer_and_generalises():
    xcs = XCS(2, N=400, gamma=0.0, random_state=0)
    rng = np.random.default_rng(0)
    for _ in range(3000):
        state = rng.integers(0, 2, 6)
        action = xcs.act(state, explore=True)
        xcs.reward(1000.0 if action == mux6(state) else 0.0, done=True)
    predicted = [int(np.nanargmax(xcs.prediction_array(row))) for row in MUX6_TABLE]
    assert predicted == [mux6(row) for row in MUX6_TABLE]
    best = [c for c in xcs.classifiers() if c.experience > 20 and c.error < 10.0]
    assert any(c.condition.count("#") == 3 for c in best)  # e.g. "01#1##" -> 1: maximally general
    assert xcs.macro_count < 200


WOODS1 = (".....",
          ".....",
          "TTF..",
          "TTT..",
          "TTT..")
"""Wilson's Woods1 tile (as in Lanzi's xcslib), repeated on a torus; T tree, F food."""
CODES = {".": "00", "T": "10", "F": "11"}
MOVES = ((-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1))


def neighbour(cell: tuple[int, int], action: int) -> tuple[int, int]:
    return (cell[0] + MOVES[action][0]) % 5, (cell[1] + MOVES[action][1]) % 5


def sense(cell: tuple[int, int]) -> str:
    return "".join(CODES[WOODS1[r][c]] for r, c in (neighbour(cell, a) for a in range(8)))


def trial(xcs: XCS, start: tuple[int, int], explore: bool, limit: int = 30) -> int:
    """Steps to food from ``start`` (``limit`` when not reached)."""
    cell = start
    for step in range(1, limit + 1):
        action = xcs.act(sense(cell), explore=explore)
        target = neighbour(cell, action)
        symbol = WOODS1[target[0]][target[1]]
        if symbol == "F":
            xcs.reward(1000.0, done=True)
            return step
        if symbol == ".":
            cell = target
        xcs.reward(0.0, done=False)
    xcs.end_trial()
    return limit


def test_xcs_learns_the_shortest_way_to_food_in_woods1():
    free = [(r, c) for r in range(5) for c in range(5) if WOODS1[r][c] == "."]
    xcs = XCS(8, N=800, gamma=0.71, random_state=0)
    rng = np.random.default_rng(0)
    before = np.mean([trial(xcs, cell, explore=False) for cell in free])
    for _ in range(400):
        trial(xcs, free[int(rng.integers(len(free)))], explore=True)
    after = np.mean([trial(xcs, cell, explore=False) for cell in free])
    optimum = 1.6875  # mean shortest path to food over the 16 blank cells
    assert after <= optimum + 0.15 < 3 < before


# -- the scikit-learn face ---------------------------------------------------------------------

def test_xcs_classifier_fits_the_6_multiplexer_table():
    labels = np.array(["low", "high"])[[mux6(row) for row in MUX6_TABLE]]
    model = XCSClassifier(n_iter=50, random_state=3)
    assert model.fit(MUX6_TABLE, labels) is model
    assert model.score(MUX6_TABLE, labels) == 1.0
    assert set(model.classes_) == {"high", "low"} and model.n_features_in_ == 6
    again = XCSClassifier(n_iter=50, random_state=3).fit(MUX6_TABLE, labels)
    assert again.xcs_.classifiers() == model.xcs_.classifiers()


def test_xcs_classifier_learns_online_with_partial_fit():
    targets = np.array([mux6(row) for row in MUX6_TABLE])
    model = XCSClassifier(random_state=1)
    rng = np.random.default_rng(1)
    for _ in range(50):
        order = rng.permutation(64)
        model.partial_fit(MUX6_TABLE[order], targets[order], classes=[0, 1])
    assert model.score(MUX6_TABLE, targets) == 1.0


def test_xcs_classifier_follows_scikit_learn_conventions():
    model = XCSClassifier(N=200, p_hash=0.5, n_iter=3, random_state=0)
    assert clone(model).get_params() == model.get_params()
    assert model.set_params(mu=0.01).mu == 0.01
    with pytest.raises(NotFittedError):
        model.predict(MUX6_TABLE)


@pytest.mark.parametrize(("X", "y", "message"), [
    ([[0, 1, 2]], [0], "0/1 features"), ([0, 1, 1], [0, 1, 1], "Expected 2D array"),
    (np.zeros((3, 0)), [0, 1, 1], r"0 feature\(s\)"), ([["a", "b"]], [0], "numeric"),
    ([[0, 1], [1, 0]], [0], "inconsistent numbers of samples"),
])
def test_xcs_classifier_rejects_bad_data(X, y, message):
    with pytest.raises(ValueError, match=message):
        XCSClassifier().fit(X, y)


def test_xcs_classifier_rejects_bad_parameters_and_unknown_labels():
    with pytest.raises(ValueError, match="'n_iter' parameter of XCSClassifier must be"):
        XCSClassifier(n_iter=0).fit(MUX6_TABLE, np.zeros(64))
    with pytest.raises(ValueError, match="'beta' parameter of XCSClassifier must be"):
        XCSClassifier(beta=2.0).fit(MUX6_TABLE, np.zeros(64))
    with pytest.raises(ValueError, match="classes must be given"):
        XCSClassifier().partial_fit(MUX6_TABLE, np.zeros(64))
    model = XCSClassifier().partial_fit(MUX6_TABLE, np.zeros(64), classes=[0, 1])
    with pytest.raises(ValueError, match="labels not in classes"):
        model.partial_fit(MUX6_TABLE, np.full(64, 7))
    with pytest.raises(ValueError, match="X has 5 features, but XCSClassifier is expecting 6"):
        model.predict(np.zeros((2, 5)))


def test_xcs_classifier_binarizes_real_features_when_asked():
    reals = np.where(MUX6_TABLE == 1, 0.7, -0.2)
    targets = np.array([mux6(row) for row in MUX6_TABLE])
    model = XCSClassifier(n_iter=5, random_state=2, binarize=0.0).fit(reals, targets)
    bits = XCSClassifier(n_iter=5, random_state=2).fit(MUX6_TABLE, targets)
    assert model.xcs_.classifiers() == bits.xcs_.classifiers()
    assert np.array_equal(model.predict(reals), bits.predict(MUX6_TABLE))
    with pytest.raises(ValueError, match="0/1 features"):
        bits.predict(reals)

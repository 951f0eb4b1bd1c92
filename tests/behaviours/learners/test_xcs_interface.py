"""The XCS interface: exploration, the allowed-action hook, consistent actions, bad input
(clear ValueErrors naming the argument) and saving/loading (atomic, versioned, checked)."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

from behaviours.learners.xcs import XCS, Classifier
from tests.xcs_helpers import by_condition, cl, make

# -- exploration and the action filter ---------------------------------------------------------

def test_exploration_draws_among_all_advocated_actions_and_only_allowed_ones():
    xcs = make([cl("##", action, prediction=100.0 * action) for action in range(4)],
               n_actions=4)
    seen, seen_allowed = set(), set()
    for _ in range(200):
        seen.add(xcs.act("01", explore=True))
        xcs.reward(0.0, done=True)
        seen_allowed.add(xcs.act("01", explore=True, allowed=[1, 3]))
        xcs.reward(0.0, done=True)
    assert seen == {0, 1, 2, 3}
    assert seen_allowed == {1, 3}


def test_states_can_be_strings_lists_tuples_or_arrays():
    xcs = make([cl("1#0", 0, prediction=500.0), cl("##1", 1, prediction=700.0)])
    expected = xcs.prediction_array("110")
    for state in ([1, 1, 0], (1, 1, 0), np.array([1, 1, 0]), np.array([True, True, False])):
        np.testing.assert_array_equal(xcs.prediction_array(state), expected)


@pytest.mark.parametrize("n_bits", [63, 64, 65, 128])
def test_a_deleted_classifier_never_matches_whatever_the_state_length(n_bits):
    # the dead-slot mark is a bit past the state: at 64 bits it starts a word of its own
    state = "1" * n_bits
    xcs = make([cl("#" * n_bits, 0), cl("#" * n_bits, 1, prediction=500.0)], n_actions=2)
    population = xcs.population_
    population.kill(population.find(0, 0, 0))
    prediction = xcs.prediction_array(state)
    assert np.isnan(prediction[0]) and prediction[1] == 500.0  # action 0: no advocate left
    assert xcs.act(state, explore=True, allowed=[0]) == 0  # so action 0 is covered anew
    xcs.reward(1000.0, done=True)
    assert xcs.macro_count == 2 and np.isfinite(xcs.prediction_array(state)).all()


def test_consistent_actions_keep_the_action_while_the_action_set_still_matches():
    records = [cl("0#", 0, fitness=1.0), cl("0#", 1, fitness=1.0),
               cl("10", 0, fitness=1.0), cl("10", 1, fitness=1.0)]
    kept, changed = [], set()
    for seed in range(40):
        xcs = XCS(2, random_state=seed, consistent_actions=True, theta_ga=10**9)
        xcs.set_classifiers(records)
        first = xcs.act("00", explore=True)
        xcs.reward(0.0, done=False)
        kept.append(xcs.act("01", explore=True) == first)  # "0#" still matches "01"
        xcs.reward(0.0, done=False)
        changed.add(xcs.act("10", explore=True))  # no classifier of [A]-1 matches "10"
        xcs.reward(0.0, done=True)
    assert all(kept)
    assert changed == {0, 1}


def test_without_consistent_actions_exploration_ignores_the_previous_action():
    records = [cl("0#", 0, fitness=1.0), cl("0#", 1, fitness=1.0)]
    repeats = 0
    for seed in range(60):
        xcs = XCS(2, random_state=seed, theta_ga=10**9)
        xcs.set_classifiers(records)
        first = xcs.act("00", explore=True)
        xcs.reward(0.0, done=False)
        repeats += xcs.act("01", explore=True) == first
        xcs.reward(0.0, done=True)
    assert 15 < repeats < 45


def test_the_same_seed_gives_the_same_run():
    def run(seed: int) -> list[Classifier]:
        xcs = XCS(2, N=40, random_state=seed)
        rng = np.random.default_rng(5)
        for _ in range(200):
            state = rng.integers(0, 2, 6)
            action = xcs.act(state, explore=True)
            xcs.reward(1000.0 * (action == state[state[0] * 2 + state[1] + 2]), done=True)
        return xcs.classifiers()

    assert run(7) == run(7)
    assert run(7) != run(8)


# -- bad input ---------------------------------------------------------------------------------

@pytest.mark.parametrize(("params", "argument"), [
    ({"n_actions": 0}, "n_actions"), ({"n_actions": 2.5}, "n_actions"),
    ({"N": 1}, "N"), ({"N": True}, "N"), ({"beta": 0.0}, "beta"), ({"beta": 1.5}, "beta"),
    ({"beta_p": -0.1}, "beta_p"), ({"beta_e": "0.2"}, "beta_e"), ({"beta_f": 2}, "beta_f"),
    ({"gamma": 1.2}, "gamma"), ({"alpha": float("nan")}, "alpha"),
    ({"epsilon_0": 0.0}, "epsilon_0"), ({"nu": -5}, "nu"), ({"theta_ga": -1}, "theta_ga"),
    ({"chi": 1.1}, "chi"), ({"mu": -0.01}, "mu"), ({"theta_del": -3}, "theta_del"),
    ({"delta": 2.0}, "delta"), ({"theta_sub": float("inf")}, "theta_sub"),
    ({"p_hash": 1.5}, "p_hash"), ({"prediction_init": float("inf")}, "prediction_init"),
    ({"error_init": -1.0}, "error_init"), ({"fitness_init": 0.0}, "fitness_init"),
    ({"ga_subsumption": 1}, "ga_subsumption"),
    ({"action_set_subsumption": "yes"}, "action_set_subsumption"),
    ({"consistent_actions": None}, "consistent_actions"),
    ({"random_state": -4}, "random_state"), ({"random_state": "seed"}, "random_state"),
])
def test_invalid_parameters_are_value_errors_naming_the_argument(params, argument):
    n_actions = params.pop("n_actions", 2)
    xcs = XCS(n_actions, **params)  # stored as given (scikit-learn), checked at first use
    assert xcs.get_params()[argument] is {"n_actions": n_actions, **params}[argument]
    with pytest.raises(ValueError, match=rf"'{argument}' parameter of XCS must be|"
                                         rf"XCS: {argument} must be"):
        xcs.act("01")


def test_parameters_are_checked_once_and_again_after_set_params():
    xcs = XCS(2, random_state=0)
    xcs.act("01")
    xcs.reward(0.0, done=True)
    xcs.beta = 5.0  # not through set_params: the checked settings stay in force
    xcs.act("01")
    xcs.reward(0.0, done=True)
    xcs.set_params(beta=5.0)
    with pytest.raises(ValueError, match="'beta' parameter of XCS must be"):
        xcs.act("01")
    xcs.set_params(beta=0.5, N=3)
    xcs.act("10")
    xcs.reward(0.0, done=True)
    assert xcs.micro_count <= 3 and xcs.time_ == 3  # the run went on under the new N
    xcs.set_params(n_actions=1)
    with pytest.raises(ValueError, match="n_actions cannot drop"):
        xcs.act("01")


@pytest.mark.parametrize(("state", "message"), [
    ("0101", "must have 3 bits"), ("01", "must have 3 bits"), ("0a1", "0/1"), ("0 1", "0/1"),
    ("", "non-empty"), ([0, 2, 1], "0/1"), ([[0, 1, 1]], "state must be"), (None, "state"),
    (7, "state must be"), (["0", "1", "1"], "state must be"), ("01ü", "state"),
])
def test_bad_states_are_value_errors(state, message):
    xcs = make([cl("##1", 0)])
    with pytest.raises(ValueError, match=message):
        xcs.act(state)
    with pytest.raises(ValueError, match=message):
        xcs.prediction_array(state)


@pytest.mark.parametrize(("allowed", "message"), [
    (set(), "at least one action"), ({3}, "not an action index"), ({-1}, "not an action index"),
    ({1.0}, "not an action index"), ("01", "allowed must be"), (5, "allowed must be"),
    ({True}, "not an action index"),
])
def test_bad_allowed_sets_are_value_errors(allowed, message):
    xcs = XCS(3, random_state=0)
    with pytest.raises(ValueError, match=message):
        xcs.act("01", allowed=allowed)
    assert xcs.classifiers() == [] and xcs.time_ == 0


def test_reward_without_act_and_act_without_reward_are_value_errors():
    xcs = XCS(2, random_state=0)
    with pytest.raises(ValueError, match="call act"):
        xcs.reward(1.0, done=True)
    xcs.act("01", explore=True)
    xcs.reward(1.0, done=False)
    with pytest.raises(ValueError, match="call act"):
        xcs.reward(1.0, done=True)
    xcs.act("01", explore=True)
    with pytest.raises(ValueError, match="call reward"):
        xcs.act("01", explore=True)
    for r, done, message in ((float("nan"), True, "r must be"), ("1", True, "r must be"),
                             (True, True, "r must be"), (1.0, "yes", "done must be")):
        with pytest.raises(ValueError, match=message):
            xcs.reward(r, done)
    xcs.reward(1.0, done=True)
    with pytest.raises(ValueError, match="explore must be"):
        xcs.act("01", explore="no")


@pytest.mark.parametrize(("records", "message"), [
    ([cl("0x", 0)], r"classifiers\[0\]\.condition"),
    ([cl("01", 2)], r"classifiers\[0\]\.action"),
    ([cl("01", 0, fitness=0.0)], r"classifiers\[0\]\.fitness"),
    ([cl("01", 0, error=-1.0)], r"classifiers\[0\]\.error"),
    ([cl("01", 0, numerosity=0)], r"classifiers\[0\]\.numerosity"),
    ([cl("01", 0, experience=-1)], r"classifiers\[0\]\.experience"),
    ([cl("01", 0, prediction=float("nan"))], r"classifiers\[0\]\.prediction"),
    ([cl("01", 0), cl("011", 1)], r"classifiers\[1\]\.condition has 3"),
    ([cl("01", 0), cl("01", 0)], r"classifiers\[1\] repeats"),
    ([cl("01", 0, numerosity=600)], "exceeds N"),
    ([("01", 0, 1.0)], r"classifiers\[0\]: must contain at least 9 items, got \['01', 0, 1.0\]"),
    ([["01", 0, 10.0, 0.0, 0.01, 0, 1, 1.0, 0, "extra"]],
     r"classifiers\[0\]: must contain less than or equal to 9"),
    ([cl("01", 0, time_stamp=1.5)], r"classifiers\[0\]\.time_stamp: must be integer, got 1.5"),
    ("01", "classifiers must be a list"),
])
def test_bad_hand_built_populations_are_value_errors(records, message):
    xcs = XCS(2, N=500)
    with pytest.raises(ValueError, match=message):
        xcs.set_classifiers(records)


# -- saving and loading ------------------------------------------------------------------------

def trained(seed: int = 0) -> XCS:
    xcs = XCS(2, N=60, random_state=seed)
    rng = np.random.default_rng(seed)
    for _ in range(300):
        state = "".join(rng.choice(["0", "1"], size=6))
        action = xcs.act(state, explore=True)
        xcs.reward(1000.0 if action == int(state[2 + int(state[:2], 2)]) else 0.0, done=True)
    return xcs


def continue_run(xcs: XCS) -> list[int]:
    actions = []
    for index in range(100):
        state = format(index * 37 % 64, "06b")
        actions.append(xcs.act(state, explore=True))
        xcs.reward(1000.0 if actions[-1] == int(state[2 + int(state[:2], 2)]) else 0.0, True)
    return actions


def test_a_loaded_learner_has_the_same_classifiers_and_continues_identically(tmp_path):
    xcs = trained()
    path = tmp_path / "xcs.json"
    xcs.save(path)
    loaded = XCS.load(path)
    assert loaded.classifiers() == xcs.classifiers()
    assert loaded.get_params() == xcs.get_params()
    assert loaded.time_ == xcs.time_
    assert continue_run(loaded) == continue_run(xcs)
    assert loaded.classifiers() == xcs.classifiers()
    assert [p.name for p in tmp_path.iterdir()] == ["xcs.json"]


def test_an_unused_learner_saves_and_loads(tmp_path):
    XCS(3, N=10, random_state=np.random.default_rng(1)).save(tmp_path / "empty.json")
    loaded = XCS.load(tmp_path / "empty.json")
    assert loaded.classifiers() == [] and loaded.n_actions == 3 and loaded.random_state is None


def test_saving_into_a_missing_folder_creates_it(tmp_path):
    trained().save(tmp_path / "new" / "xcs.json")
    assert XCS.load(tmp_path / "new" / "xcs.json").classifiers() == trained().classifiers()


def test_a_failed_save_leaves_the_old_file_and_no_temporary_file(tmp_path):
    path = tmp_path / "xcs.json"
    trained(0).save(path)
    before = path.read_bytes()
    target = tmp_path / "occupied"
    target.mkdir()
    with pytest.raises(OSError):
        trained(1).save(target)  # os.replace onto a folder fails
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["occupied", "xcs.json"]


def corrupt(document: dict, change) -> dict:
    document = json.loads(json.dumps(document))
    change(document)
    return document


@pytest.mark.parametrize(("change", "message"), [
    (lambda d: d.update(format="something-else"), "not a goalagent learner file"),
    (lambda d: d.update(version=99), "has version 99"),
    (lambda d: d.update(kind="forward_model"), "holds a 'forward_model', not a 'xcs'"),
    (lambda d: d["params"].pop("beta"), r"params: must contain \['beta'\] properties"),
    (lambda d: d["params"].update(colour=3), r"params: must not contain {'colour'} properties"),
    (lambda d: d["params"].update(N=-1), "'N' parameter of XCS must be"),
    (lambda d: d["params"].update(n_actions="two"), "'n_actions' parameter of XCS must be"),
    (lambda d: d["state"]["classifiers"][0].__setitem__(0, "01?#01"),
     r"classifiers\[0\]\.condition"),
    (lambda d: d["state"]["classifiers"][0].__setitem__(4, -1.0), r"classifiers\[0\]\.fitness"),
    (lambda d: d["state"].update(classifiers={}), "classifiers"),
    (lambda d: d["state"].update(time=-5), "state.time: must be bigger than or equal to 0, got -5"),
    (lambda d: d["state"]["classifiers"][0].__setitem__(1, True), r"classifiers\[0\]\.action"),
    (lambda d: d["state"]["classifiers"][0].__setitem__(2, float("nan")),
     "NaN is not a JSON number"),
    (lambda d: d["state"].update(n_bits=7), "n_bits is 7"),
    (lambda d: d["state"]["random_generator"].update(bit_generator="Nope"),
     "state.random_generator.bit_generator: must be one of"),
    (lambda d: d["state"]["random_generator"].update(state="x"), "random_generator"),
])
def test_corrupt_or_foreign_files_are_value_errors_naming_the_file(tmp_path, change, message):
    good = tmp_path / "good.json"
    trained().save(good)
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(corrupt(json.loads(good.read_text()), change)))
    with pytest.raises(ValueError, match=message) as raised:
        XCS.load(bad)
    assert "bad.json" in str(raised.value)


@pytest.mark.parametrize("content", [b"", b"not json at all", b'{"format": "goalagent-xcs"',
                                     b"\xff\xfe\x00", b"[1, 2, 3]"])
def test_garbage_files_are_value_errors(tmp_path, content):
    path = tmp_path / "garbage.json"
    path.write_bytes(content)
    with pytest.raises(ValueError, match="garbage.json"):
        XCS.load(path)


def test_a_missing_file_is_a_value_error(tmp_path):
    with pytest.raises(ValueError, match="cannot read"):
        XCS.load(tmp_path / "nothing.json")
    assert not os.path.exists(tmp_path / "nothing.json")


def test_hand_built_population_records_round_trip():
    records = [cl("1#0", 1, 250.5, 3.25, 0.75, 12, 3, 4.5, 9)]
    xcs = make(records)
    assert xcs.classifiers() == records
    assert by_condition(xcs)[("1#0", 1)].numerosity == 3
    assert xcs.time_ == 0

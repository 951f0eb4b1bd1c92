"""Algorithm 1's affordance table: replacement, the eq. 3.10 filter, atomic files, bad files."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from behaviours.learners.affordance_table import AffordanceTable, LearnerFileError

PUSH, LEFT, STAND, SQUAT = "010", "000", "100", "101"


def test_a_new_pair_is_added_and_a_known_one_replaced_by_the_latest_effect():
    table = AffordanceTable()
    assert table.update("1100", PUSH, 0) is True
    assert table.update("1001", PUSH, 1) is True
    assert table.update("1100", PUSH, 0) is False  # the same triple again: nothing changes
    assert table.update("1100", PUSH, 1) is True  # the box became movable: replaced
    assert table.triples() == [("1100", PUSH, 1), ("1001", PUSH, 1)]
    assert len(table) == 2 and table.effect("1100", PUSH) == 1
    assert table.effect("1100", LEFT) is None


def test_eq_3_10_filters_the_actions_with_an_undesired_known_effect_on_that_object():
    table = AffordanceTable()
    table.update("0010", STAND, 0)  # standing push passes over the low foam
    table.update("0010", SQUAT, 1)
    table.update("1001", STAND, 1)
    actions = (STAND, SQUAT, "110", "111")
    assert table.undesired_actions("0010", actions) == {STAND}
    assert table.undesired_actions("1001", actions) == set()
    assert table.undesired_actions("1111", actions) == set()  # an unknown object: no filter
    moving_forbidden = AffordanceTable(undesired_effects=(1,))
    moving_forbidden.update("0010", SQUAT, 1)
    assert moving_forbidden.undesired_actions("0010", actions) == {SQUAT}


def test_bad_triples_are_refused():
    table = AffordanceTable()
    with pytest.raises(ValueError, match="an object must be a string of 0s and 1s"):
        table.update("1a00", PUSH, 1)
    with pytest.raises(ValueError, match="an action must be"):
        table.update("1100", "", 1)
    with pytest.raises(ValueError, match="an effect must be an integer"):
        table.update("1100", PUSH, "moved")
    assert len(table) == 0


def test_save_and_load_round_trip_atomically(tmp_path: Path):
    table = AffordanceTable()
    table.update("1100", PUSH, 0)
    table.update("1001", PUSH, 1)
    path = table.save(tmp_path / "sub" / "table.json")
    assert [p.name for p in path.parent.iterdir()] == ["table.json"]  # no temporary left
    loaded = AffordanceTable.load(path)
    assert loaded.triples() == table.triples()
    assert loaded.undesired_effects == (0,)


@pytest.mark.parametrize(("content", "message"), [
    ("{not json", "cannot read learner file"),
    ('{"format": "other"}', "is not a goalagent learner file"),
    (json.dumps({"format": "goalagent-learner", "version": 1, "kind": "forward_model",
                 "params": {}, "state": {}}), "holds a 'forward_model'"),
    (json.dumps({"format": "goalagent-learner", "version": 1, "kind": "affordance_table",
                 "params": {"undesired_effects": [0]}, "state": {}}),
     r"state: must contain \['triples'\] properties"),
    (json.dumps({"format": "goalagent-learner", "version": 1, "kind": "affordance_table",
                 "params": {"undesired_effects": [0]},
                 "state": {"triples": [["1100", "010"]]}}),
     r"state\.triples\[0\]: must contain at least 3 items"),
    (json.dumps({"format": "goalagent-learner", "version": 1, "kind": "affordance_table",
                 "params": {"undesired_effects": [0]},
                 "state": {"triples": [["11x0", "010", 0]]}}),
     r"state\.triples\[0\]\.object: must match pattern \^\[01\]\+\$, got '11x0'"),
    (json.dumps({"format": "goalagent-learner", "version": 1, "kind": "affordance_table",
                 "params": {"undesired_effects": [0.5]}, "state": {"triples": []}}),
     r"params\.undesired_effects\[0\]: must be integer, got 0\.5"),
])
def test_a_corrupt_file_is_a_clear_error(tmp_path: Path, content: str, message: str):
    path = tmp_path / "table.json"
    path.write_text(content)
    with pytest.raises(LearnerFileError, match=message):
        AffordanceTable.load(path)


def test_a_missing_file_is_a_clear_error(tmp_path: Path):
    with pytest.raises(LearnerFileError, match="cannot read learner file"):
        AffordanceTable.load(tmp_path / "nowhere.json")

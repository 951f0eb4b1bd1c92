"""The learners' JSON stores against their schemas (behaviours/learners/schemas/): every schema
is a valid draft-07 schema, a bad field is named by its path in the file, and what no store
writes (NaN, Infinity) is refused."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from jsonschema import Draft7Validator

from behaviours.learners.effect_models import LinearEffectModel, ModelStore, StoreError
from behaviours.learners.known_objects import DatabaseError, KnownObjectDatabase
from behaviours.learners.persist import LearnerFileError
from behaviours.learners.schemas import SCHEMA_DIR, SchemaError, check
from behaviours.learners.xcs import XCS

SCHEMAS = sorted(SCHEMA_DIR.glob("*.schema.json"))

OBJECT = {"name": "o1", "parts": {"lid": [0.0021, 0.4, 1.0], "body": [0.0047, 0.46, 1.0]},
          "above": [["lid", "body"]], "bounds": {"extend_arm": [0.0, 0.1]},
          "models": [{"part": "lid", "action": "extend_arm", "theta": [0.05, 0.1],
                      "displacement": [0.06, 0.12], "effect": [0.05, 0.11]}],
          "functional": {"part": "lid", "action": "extend_arm", "theta": 0.1}}


def database(tmp_path: Path, *objects: dict) -> Path:
    path = tmp_path / "known.json"
    path.write_text(json.dumps({"format": "goalagent-known-objects", "version": 1,
                                "objects": list(objects)}))
    return path


@pytest.mark.parametrize("path", SCHEMAS, ids=lambda p: p.name)
def test_every_schema_is_a_valid_draft_7_schema(path: Path):
    Draft7Validator.check_schema(json.loads(path.read_text()))


def test_the_learner_kinds_and_stores_have_schemas():
    assert {p.name.split(".")[0] for p in SCHEMAS} == {
        "xcs", "forward_model", "cacla", "affordance_table", "effect_models", "known_objects"}


def test_a_good_known_object_database_loads(tmp_path: Path):
    loaded = KnownObjectDatabase(database(tmp_path, OBJECT))
    assert loaded.names() == ["o1"] and loaded.get("o1").functional.theta == 0.1


@pytest.mark.parametrize(("change", "where"), [
    (lambda o: o["models"][0]["theta"].__setitem__(1, "x"),
     r"objects\[1\]\.models\[0\]\.theta\[1\]: must be number, got 'x'"),
    (lambda o: o.pop("bounds"), r"objects\[1\]: must contain \['bounds'\] properties"),
    (lambda o: o["parts"].__setitem__("lid", []), r"objects\[1\]\.parts\.lid: must contain"),
    (lambda o: o["above"].append(["lid"]), r"objects\[1\]\.above\[1\]: must contain at least 2"),
    (lambda o: o.update(functional={"part": "lid"}), r"objects\[1\]\.functional: cannot be"),
    (lambda o: o.update(n_actions=-1), r"objects\[1\]\.n_actions: must be bigger than or equal"),
    (lambda o: o.update(colour="red"), r"objects\[1\]: must not contain {'colour'}"),
])
def test_a_bad_known_object_is_named_by_its_path(tmp_path: Path, change, where: str):
    bad = json.loads(json.dumps({**OBJECT, "name": "o2"}))
    change(bad)
    with pytest.raises(DatabaseError, match=rf"known\.json': {where}"):
        KnownObjectDatabase(database(tmp_path, OBJECT, bad))


def test_a_bad_effect_model_is_named_by_its_path(tmp_path: Path):
    path = tmp_path / "effects.json"
    store = ModelStore(path)
    store.put(("o1", "lid", "extend_arm"), (0.0, 0.1),
              LinearEffectModel().fit([0.01, 0.05], [0.01, 0.06]))
    document = json.loads(path.read_text())
    document["models"][0]["fit_intercept"] = "yes"
    path.write_text(json.dumps(document))
    with pytest.raises(StoreError, match=r"effects\.json': models\[0\]\.fit_intercept: must be "
                                         r"boolean, got 'yes'"):
        ModelStore(path)


@pytest.mark.parametrize("constant", ["NaN", "Infinity", "-Infinity"])
def test_stores_refuse_what_json_cannot_hold(tmp_path: Path, constant: str):
    path = database(tmp_path, OBJECT)
    path.write_text(path.read_text().replace("0.05, 0.1]", f"0.05, {constant}]", 1))
    with pytest.raises(DatabaseError, match=f"{constant} is not a JSON number"):
        KnownObjectDatabase(path)
    xcs = tmp_path / "xcs.json"
    XCS(2, random_state=0).save(xcs)
    xcs.write_text(xcs.read_text().replace('"time": 0', f'"time": {constant}'))
    with pytest.raises(LearnerFileError, match=f"{constant} is not a JSON number"):
        XCS.load(xcs)


def test_check_names_a_tuple_position_by_its_title():
    with pytest.raises(SchemaError, match=r"^classifiers\[2\]\.numerosity: must be bigger "
                                          r"than or equal to 1, got 0$"):
        check(["01#", 0, 10.0, 0.0, 0.01, 0, 0, 1.0, 0], "xcs", at=("classifiers", 2),
              definition="classifier")


def test_what_a_schema_cannot_state_is_still_checked_and_named(tmp_path: Path):
    path = tmp_path / "effects.json"
    path.write_text(json.dumps({"format": "goalagent-effect-models", "version": 1, "models": [
        {"key": ["o1"], "bounds": [0.1, 0.0], "theta": [0.05], "effect": [0.01],
         "fit_intercept": True}]}))
    with pytest.raises(StoreError, match=r"bad record \(model 0\): bounds must be finite with "
                                         r"low < high"):
        ModelStore(path)

"""The known-object database: round trip, versioning, atomic writes and located errors."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from behaviours.learners.known_objects import (
    DATABASE_VERSION,
    DatabaseError,
    KnownObject,
    KnownObjectDatabase,
)
from behaviours.learners.transfer import TransferLearner
from tests.synthetic_cans import thesis_cans


def _learn(name: str, database: KnownObjectDatabase) -> KnownObject:
    learner = TransferLearner(database=database, random_state=0).fit(thesis_cans()[name])
    known = KnownObject.learned(name, learner, extra={"file": f"{name}.toml"})
    database.add(known)
    return known


def test_round_trip_keeps_parts_relations_models_and_functional_pair(tmp_path: Path):
    path = tmp_path / "db" / "known.json"
    database = KnownObjectDatabase(path)
    first, second = _learn("o1", database), _learn("o3", database)
    again = KnownObjectDatabase(path)
    assert again.names() == ["o1", "o3"]
    for original in (first, second):
        loaded = again.get(original.name)
        assert loaded.above == original.above
        assert loaded.functional == original.functional
        assert (loaded.n_actions, loaded.source) == (original.n_actions, original.source)
        assert loaded.extra == original.extra
        assert set(loaded.parts) == set(original.parts)
        for name in original.parts:
            np.testing.assert_allclose(loaded.parts[name], original.parts[name])
        assert set(loaded.models) == set(original.models)
        for pair, model in original.models.items():
            copy = loaded.models[pair]
            assert (copy.g_intercept_, copy.g_slope_) == pytest.approx(
                (model.g_intercept_, model.g_slope_))
            assert (copy.h_intercept_, copy.h_slope_) == pytest.approx(
                (model.h_intercept_, model.h_slope_))
    assert again.get("o3").source == "o1" and again.get("o3").n_actions == 1
    assert sorted(p.name for p in path.parent.iterdir()) == ["known.json"]  # no temp files
    # a reloaded database is a working source: o3 again learns with one action
    learner = TransferLearner(database=again, random_state=0).fit(thesis_cans()["o3"])
    assert (learner.source_, learner.n_actions_) in {("o1", 1), ("o3", 1)}


def test_adding_an_object_again_replaces_it_as_the_newest(tmp_path: Path):
    database = KnownObjectDatabase(tmp_path / "known.json")
    _learn("o1", database)
    _learn("o2", database)
    _learn("o1", database)
    assert database.names() == ["o2", "o1"]
    assert len(database) == 2 and "o1" in database and "o5" not in database


def test_forget_removes_and_saves(tmp_path: Path):
    path = tmp_path / "known.json"
    database = KnownObjectDatabase(path)
    _learn("o1", database)
    forgotten = database.forget("o1")
    assert forgotten.name == "o1" and len(database) == 0
    assert KnownObjectDatabase(path).names() == []
    with pytest.raises(DatabaseError, match="no known object 'o1'; known objects: none"):
        database.forget("o1")


def test_unreadable_files_are_clear_errors(tmp_path: Path):
    path = tmp_path / "known.json"
    path.write_text('{"format": "goalagent-known-objects",\n "version": 1,\n "objects": [}\n')
    with pytest.raises(DatabaseError, match=r"known.json:3:14: not JSON"):
        KnownObjectDatabase(path)
    path.write_text(json.dumps({"format": "something else"}))
    with pytest.raises(DatabaseError, match="is not a goalagent known-object database"):
        KnownObjectDatabase(path)
    path.write_text(json.dumps({"format": "goalagent-known-objects",
                                "version": DATABASE_VERSION + 1, "objects": []}))
    with pytest.raises(DatabaseError, match="version 2; this goalagent reads version 1"):
        KnownObjectDatabase(path)
    path.write_text(json.dumps({"format": "goalagent-known-objects", "version": 1,
                                "objects": [{"name": "o1", "parts": {"lid": [1, "x"]}}]}))
    with pytest.raises(DatabaseError, match=r"known.json': objects\[0\]: must contain"):
        KnownObjectDatabase(path)


def test_a_failed_write_leaves_the_database_as_it_was(tmp_path: Path):
    path = tmp_path / "known.json"
    database = KnownObjectDatabase(path)
    known = _learn("o1", database)
    before = path.read_text()
    bad = KnownObject("bad", known.parts, known.above, known.bounds, known.models,
                      extra={"thing": object()})
    with pytest.raises(TypeError, match="cannot store object"):
        database.add(bad)
    assert path.read_text() == before and database.names() == ["o1"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["known.json"]
    with pytest.raises(ValueError, match="model for unknown part"):
        KnownObject("x", {}, frozenset(), known.bounds, known.models)


def test_the_saved_file_is_an_ordinary_file(tmp_path: Path):
    import os

    database = KnownObjectDatabase(tmp_path / "known.json")
    _learn("o1", database)
    umask = os.umask(0o022)
    try:
        database.forget("o1")
    finally:
        os.umask(umask)
    assert (tmp_path / "known.json").stat().st_mode & 0o777 == 0o644  # not mkstemp's 0600

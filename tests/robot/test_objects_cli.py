"""``goalagent objects list | show | forget`` over a known-object database."""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from behaviours.learners.known_objects import KnownObject, KnownObjectDatabase
from behaviours.learners.transfer import TransferLearner
from goalagent.cli import create_app
from robot.extension import EXTENSION
from tests.synthetic_cans import thesis_cans

APP = create_app([EXTENSION])


def database(tmp_path: Path) -> Path:
    path = tmp_path / "objects.json"
    db = KnownObjectDatabase(path)
    for name in ("o1", "o3"):
        learner = TransferLearner(database=db, random_state=0).fit(thesis_cans()[name])
        db.add(KnownObject.learned(name, learner, extra={"can_file": f"[red]{name}.yaml"}))
    return path


def invoke(*args: str):
    return CliRunner().invoke(APP, list(args))


def test_list_show_and_forget(tmp_path: Path):
    path = database(tmp_path)
    listed = invoke("objects", "list", "--db", str(path))
    assert listed.exit_code == 0, listed.output
    assert "o1" in listed.stdout and "o3" in listed.stdout
    assert "extend_arm(lid," in listed.stdout and "[red]o1.yaml" in listed.stdout  # not markup
    shown = invoke("objects", "show", "o3", "--db", str(path))
    assert shown.exit_code == 0, shown.output
    assert "object o3 (learned with 1 actions, transferred from o1)" in shown.stdout
    assert "above(lid, body)" in shown.stdout and "functional: extend_arm on lid" in shown.stdout
    assert invoke("robot", "objects", "show", "o1", "--db", str(path)).exit_code == 0
    forgot = invoke("objects", "forget", "o1", "--db", str(path))
    assert forgot.exit_code == 0 and "forgot o1; 1 known objects left" in forgot.output
    assert [o["name"] for o in json.loads(path.read_text())["objects"]] == ["o3"]


def test_mistakes_are_one_line_errors(tmp_path: Path):
    path = database(tmp_path)
    for args, message in ((("show", "o9"), "no known object 'o9'; known objects: o1, o3"),
                          (("forget", "o9"), "no known object 'o9'"),
                          (("list", "--db", str(tmp_path / "none.json")),
                           "no known-object database at")):
        extra = () if "--db" in args else ("--db", str(path))
        result = invoke("objects", *args, *extra)
        assert result.exit_code == 2 and message in result.output, result.output
        assert "Traceback" not in result.output
    path.write_text('{"format": "goalagent-known-objects", "version": 7, "objects": []}')
    result = invoke("objects", "list", "--db", str(path))
    assert result.exit_code == 2 and "has version 7" in result.output

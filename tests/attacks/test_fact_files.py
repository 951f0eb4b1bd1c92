"""--load-beliefs files and the learners' stores: bad ones are located errors, nothing in
them runs, nothing on disk changes (issue 14 item 4, issue 19 item 5)."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from behaviours.learners.effect_models import ModelStore, StoreError
from behaviours.learners.known_objects import DatabaseError, KnownObjectDatabase
from behaviours.learners.persist import LearnerFileError, read_learner
from goalagent.agent import Agent
from goalagent.beliefs import load_beliefs, read_belief_file
from goalagent.parser import GoalSyntaxError
from robot.affordance import AFFORD
from tests.measured import goalagent_measured

AGENT = "main module [exit=always] { program { if true then print(ok). } }\n"
GOOD = "afford(lid, extend_arm, opened, 5, 5, 1.0).\n"


def _beliefs(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "beliefs.pl"
    path.write_text(text)
    return path


@pytest.mark.parametrize("text, line, col, says", [
    (GOOD + ":- shell('touch PWNED').\n", 2, 1, "a directive; a file of facts holds facts only"
                                                " (nothing was run)"),
    (GOOD + "?- halt.\n", 2, 1, "a directive"),
    (GOOD + "\n  p :- q.\n", 3, 3, "a rule; a file of facts holds facts only"),
    ("p --> [a].\n", 1, 1, "a grammar rule"),
    ("visited(X, 1).\n", 1, 1, "a fact must be ground: X is a variable"),
    ("atom(a).\n", 1, 1, "atom/1 is a built-in predicate, not a belief"),
    ("user:p(a).\n", 1, 1, "a module-qualified clause"),
    ("'$ga_gm'(x).\n", 1, 1, "'$ga_gm'/1 is reserved for the runtime"),
    ("(p, q).\n", 1, 1, "','/2 is a control construct"),
    ("42.\n", 1, 1, "42 is not a fact"),
    (GOOD + "p(a\n", 2, 4, "syntax error"),
    ('p("a\\=b").\n', 1, 5, "Unknown character escape"),
    ("p(" + "f(" * 300 + ")" * 300 + ").\n", 1, 401, "nested more than 200 levels"),
    # afford/6 types (eq. 6.1), as the robot application declares them
    ("afford(lid,push,opened,abc,1,x).\n", 1, 1, "Tot must be a non-negative integer"),
    (GOOD + "afford(lid, push, opened, 3, 4, 0.5).\n", 2, 1, "Suc must not exceed Tot"),
    ("afford(lid, push, opened, 3, -1, 0.5).\n", 1, 1, "Suc must be a non-negative integer"),
    ("afford(lid, push, opened, 3, 1, 1.5).\n", 1, 1, "Rel must be a number in [0, 1]"),
    ("afford(lid, push, opened, 3, 1, nan).\n", 1, 1, "Rel must be a number in [0, 1]"),
    ("afford(\"lid\", push, opened, 3, 1, 0.3).\n", 1, 1, "Obj must be an atom"),
    ("afford(lid, f(x), opened, 3, 1, 0.3).\n", 1, 1, "Act must be an atom"),
])
def test_a_bad_clause_is_refused_at_its_position(tmp_path: Path, text: str, line: int,
                                                 col: int, says: str):
    path = _beliefs(tmp_path, text)
    with pytest.raises(GoalSyntaxError) as caught:
        read_belief_file(path, [AFFORD])
    assert (caught.value.line, caught.value.col) == (line, col), str(caught.value)
    assert says in caught.value.message
    assert not (tmp_path / "PWNED").exists()


def test_the_cli_refuses_a_bad_file_before_anything_runs_or_is_saved(tmp_path: Path):
    program = tmp_path / "agent.goal"
    program.write_text(AGENT)
    path = _beliefs(tmp_path, GOOD + ":- shell('touch PWNED').\n")
    saved = tmp_path / "saved.pl"
    saved.write_text("% the previous save\n")
    result = goalagent_measured("run", str(program), "--load-beliefs", str(path),
                                "--save-beliefs", str(saved), cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.strip() == (f"error: {path}:2:1: a directive; a file of facts holds "
                                     "facts only (nothing was run)")
    assert result.stdout == ""  # the agent never ran
    assert saved.read_text() == "% the previous save\n"
    assert not (tmp_path / "PWNED").exists()


@pytest.mark.parametrize("kind", ["device", "fifo", "folder"])
def test_only_regular_files_are_read(tmp_path: Path, kind: str):
    path = {"device": Path("/dev/zero"), "folder": tmp_path}.get(kind, tmp_path / "fifo.pl")
    if kind == "fifo":
        os.mkfifo(path)
    with pytest.raises(GoalSyntaxError, match="not a regular file"):
        read_belief_file(path)


def test_good_facts_load_once_each_in_file_order_with_comments_and_layout(tmp_path: Path):
    path = _beliefs(tmp_path, "% saved\nvisited(a, 1).\n/* both */ visited(b,\n 2).\n"
                              "visited(a, 1).\nhere('B c').\n")
    agent = Agent.from_string(AGENT, "a.goal")
    try:
        assert load_beliefs(agent, path) == 4
        assert [str(f) for f in agent.beliefs()] == ["here('B c')", "visited(a,1)",
                                                     "visited(b,2)"]
        assert load_beliefs(agent, path) == 4  # loading again adds nothing
        assert len(agent.beliefs()) == 3
    finally:
        agent.close()


# ------------------------------------------------------------------ stores of behaviours

@pytest.mark.parametrize("content, says", [
    (b"{not json", "not JSON"),
    (b"[" * 100_000 + b"]" * 100_000, "nested too deeply"),
    (b'{"format": 1, "x": ' + b"1" * 5000 + b"}", "cannot read"),
    (b"\xff\xfe", "not UTF-8"),
])
def test_corrupt_stores_are_clear_errors_and_stay_as_they_were(tmp_path: Path, content: bytes,
                                                               says: str):
    for make, error in ((ModelStore, StoreError), (KnownObjectDatabase, DatabaseError),
                        (lambda p: read_learner(p, "cacla"), LearnerFileError)):
        path = tmp_path / "store.json"
        path.write_bytes(content)
        with pytest.raises(error, match=says):
            make(path)
        assert path.read_bytes() == content


def test_a_bad_model_record_is_named(tmp_path: Path):
    path = tmp_path / "models.json"
    good = {"key": ["o1", "lid", "push"], "bounds": [0, 1], "theta": [0.1, 0.2],
            "effect": [0.0, 0.1], "fit_intercept": True}
    path.write_text(json.dumps({"format": "goalagent-effect-models", "version": 1,
                                "models": [good, {**good, "theta": ["x", 1]}]}))
    with pytest.raises(StoreError, match=r"models\[1\]\.theta\[0\]: must be number"):
        ModelStore(path)


@pytest.mark.parametrize("target", ["/dev/zero", "fifo", "folder"])
def test_stores_read_only_regular_files(tmp_path: Path, target: str):
    path = {"/dev/zero": Path("/dev/zero"), "folder": tmp_path}.get(target, tmp_path / "f.json")
    if target == "fifo":
        os.mkfifo(path)
    with pytest.raises(StoreError, match="not a regular file"):
        ModelStore(path)

"""Init parameters an environment declares as paths take a typed file name as written.

``--env-param objects=db.json`` is the Prolog term '.'(db, json) when read as a term; for a
parameter declared ``Path`` it is the file name ``db.json``. Other parameters read as before.
"""

from __future__ import annotations

import io
import subprocess
import sys
from pathlib import Path

import pytest

from goalagent.eis import ManagementException, PythonEnvironment
from goalagent.eis.registry import register_environment
from goalagent.kb.terms import Atom, Struct
from goalagent.mas import MultiAgentSystem, ParameterText, looks_like_file_name, read_parameter

ROOT = Path(__file__).resolve().parents[3]


class Files(PythonEnvironment):
    """Remembers its init parameters: a path, a flag-or-path, a name and a number."""

    name = "files-under-test"
    parameters = {"store": Path, "record": bool | Path, "label": str | Path, "size": float,
                  "tag": str}

    def on_init(self, params: dict[str, object]) -> None:
        self.seen = params


register_environment(Files.name, Files)

AGENT = """
main module [exit=nogoals] { program { if true then print(ok). } }
"""


def started(tmp_path: Path, **typed: str) -> dict[str, object]:
    """The parameters the environment got from values typed as on the command line."""
    agent = tmp_path / "a.goal"
    agent.write_text(AGENT)
    system = MultiAgentSystem.for_agent_file(
        agent, environment=Files.name, output=io.StringIO(), warn=lambda message: None,
        env_params={key: ParameterText(text) for key, text in typed.items()})
    try:
        return system.environment.seen  # type: ignore[union-attr]
    finally:
        system.close()


@pytest.mark.parametrize(("text", "expected"), [
    ("db.json", True), ("out/db", True), ("../cans/x.yaml", True), ("'db.json'", False),
    ('"db.json"', False), ("db", False), ("", False)])
def test_what_looks_like_a_file_name(text: str, expected: bool):
    assert looks_like_file_name(text) is expected


def test_a_path_parameter_takes_the_file_name_as_typed(tmp_path: Path):
    seen = started(tmp_path, store="db.json", record="runs/one.mp4", label="cans/my.can.yaml",
                   size="0.5", tag="plain")
    assert seen == {"store": Path("db.json"), "record": Path("runs/one.mp4"),
                    "label": "cans/my.can.yaml", "size": 0.5, "tag": "plain"}


def test_quoted_and_plain_names_still_read_as_terms(tmp_path: Path):
    seen = started(tmp_path, store="'db.json'", record="false", label="o1")
    assert seen == {"store": Path("db.json"), "record": False, "label": "o1"}


def test_a_parameter_that_is_not_a_path_is_still_read_as_a_term(tmp_path: Path):
    with pytest.raises(ManagementException, match=r"'tag' must be a name or string"):
        started(tmp_path, tag="db.json")


def test_read_parameter_keeps_terms_and_reads_text():
    assert read_parameter(Atom("x"), path=True) == Atom("x")
    assert read_parameter(ParameterText("db.json"), path=True) == "db.json"
    assert read_parameter(ParameterText("db.json"), path=False) == Struct(
        ".", (Atom("db"), Atom("json")))


def test_a_mas_file_names_a_file_quoted_as_before(tmp_path: Path):
    """A .mas2g's init values are Prolog terms already (the file is parsed as such)."""
    (tmp_path / "a.goal").write_text(AGENT)
    (tmp_path / "run.mas2g").write_text(
        f'environment {{ env = "{Files.name}". init = [store = \'data.json\', size = 2]. }}\n'
        'agentfiles { "a.goal". }\nlaunchpolicy { launch a : a. }\n')
    system = MultiAgentSystem.from_mas_file(tmp_path / "run.mas2g", output=io.StringIO(),
                                            warn=lambda message: None)
    try:
        seen = system.environment.seen  # type: ignore[union-attr]
        assert seen == {"store": Path("data.json"), "size": 2.0}
    finally:
        system.close()


def test_the_garbage_objects_database_from_the_command_line(tmp_path: Path):
    """The issue's command without double quoting (it was refused: "must be a name or
    string, got '.'(db,json)")."""
    result = subprocess.run(
        [sys.executable, "-m", "goalagent", "run", str(ROOT / "agents" / "garbage_disposal.mas2g"),
         "--env-param", "objects=db.json", "--env-param", "models=out/models.json",
         "--env-param", "learning=transfer", "--max-cycles", "0"],
        capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "robot:" in result.stderr and "must be" not in result.stderr

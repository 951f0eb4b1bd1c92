"""Every program in docs/language.md runs as the guide says.

A fenced block ```` ```goal file=NAME ```` (or ``mas2g``) is saved as NAME; a block
```` ```text output=NAME ```` is exactly what running NAME prints on stdout, without a warning.
A first line ``% run: ARGS`` gives the ``--env`` / ``--env-param`` options of its run (the
garbage environment's model and object stores are put in the test's folder). Every saved
file also passes ``goalagent check``'s validation."""

from __future__ import annotations

import io
import re
import shlex
from pathlib import Path

import pytest

from goalagent.agent import validate_program
from goalagent.mas import MultiAgentSystem, parse_parameter
from goalagent.parser import load_agents, parse_agent_file, parse_mas_file

ROOT = Path(__file__).resolve().parents[2]
GUIDE = ROOT / "docs" / "language.md"
_FENCE = re.compile(r"^```(\w+)([^\n]*)\n(.*?)^```", re.MULTILINE | re.DOTALL)
MAX_CYCLES = 20


def _blocks() -> tuple[dict[str, str], dict[str, str]]:
    """The guide's files and expected outputs, by name."""
    files: dict[str, str] = {}
    outputs: dict[str, str] = {}
    for language, info, body in _FENCE.findall(GUIDE.read_text()):
        attributes = dict(item.split("=", 1) for item in info.split() if "=" in item)
        if language in ("goal", "mas2g") and "file" in attributes:
            assert attributes["file"] not in files, f"two blocks save {attributes['file']}"
            files[attributes["file"]] = body
        elif language == "text" and "output" in attributes:
            outputs[attributes["output"]] = body
    return files, outputs


FILES, OUTPUTS = _blocks()


@pytest.fixture
def saved(tmp_path: Path) -> Path:
    for name, text in FILES.items():
        (tmp_path / name).write_text(text)
    return tmp_path


def test_the_guide_has_samples_of_every_kind_the_issue_asks_for() -> None:
    assert len(OUTPUTS) >= 10
    assert {"market.mas2g", "robot.goal", "modules.goal", "tower.goal"} <= set(OUTPUTS)
    assert set(OUTPUTS) <= set(FILES)
    assert "docs/language.md" in (ROOT / "README.md").read_text()  # linked from the README


@pytest.mark.parametrize("name", sorted(FILES))
def test_every_sample_file_passes_validation(saved: Path, name: str) -> None:
    path = saved / name
    programs = (load_agents(parse_mas_file(path)).values() if path.suffix == ".mas2g"
                else [parse_agent_file(path)])
    for program in programs:
        validate_program(program)


@pytest.mark.parametrize("name", sorted(OUTPUTS))
def test_every_sample_prints_what_the_guide_says(saved: Path, name: str) -> None:
    path = saved / name
    environment, params = _run_options(FILES[name], saved)
    output, warnings = io.StringIO(), []
    options = dict(output=output, warn=warnings.append)
    system = (MultiAgentSystem.from_mas_file(path, **options) if path.suffix == ".mas2g"
              else MultiAgentSystem.for_agent_file(path, environment=environment,
                                                   env_params=params, **options))
    try:
        system.run(MAX_CYCLES)
    finally:
        system.close()
    assert warnings == []
    assert output.getvalue() == OUTPUTS[name]


def _run_options(text: str, folder: Path) -> tuple[str | None, dict]:
    """``--env`` and ``--env-param`` of a ``% run:`` first line."""
    first = text.splitlines()[0]
    if not first.startswith("% run:"):
        return None, {}
    args = shlex.split(first.removeprefix("% run:"))
    environment = args[args.index("--env") + 1]
    params = {}
    for index, arg in enumerate(args):
        if arg == "--env-param":
            key, _, value = args[index + 1].partition("=")
            params[key] = parse_parameter(value)
    if environment == "garbage":
        params["models"] = parse_parameter(str(folder / "models.json"))
        params["objects"] = parse_parameter(str(folder / "objects.json"))
    return environment, params

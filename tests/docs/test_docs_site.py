"""The documentation site builds with ``mkdocs build --strict`` (a broken link, a page missing
from the navigation, an API reference naming what the code does not have, a docstring whose
arguments do not match its signature: each fails), and the pages generated from the code say
what the code has."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The site built with --strict into a fresh folder."""
    target = tmp_path_factory.mktemp("site")
    environment = dict(os.environ, MUJOCO_GL="egl", NO_MKDOCS_2_WARNING="1")
    build = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir",
                            str(target)], cwd=ROOT, capture_output=True, text=True,
                           env=environment, timeout=600)
    assert build.returncode == 0, build.stderr[-4000:]
    return target


def test_the_site_builds_strictly_with_every_section(site: Path) -> None:
    for page in ("getting-started", "language", "goal6", "testing", "environments/reference",
                 "seeing-inside", "robot", "reproductions", "architecture", "coming-from",
                 "api", "cli"):
        assert (site / page / "index.html").is_file(), page


def test_the_api_reference_is_generated_from_the_docstrings(site: Path) -> None:
    api = (site / "api" / "index.html").read_text()
    for name in ("Agent", "from_string", "for_agent_text", "from_mas_file", "MultiAgentSystem",
                 "instantiations", "run_test_file", "PythonEnvironment"):
        assert name in api, name
    assert "the agents launched so far" in api  # MultiAgentSystem.agents, from its docstring


def test_the_api_reference_shows_every_public_method_of_agent(site: Path) -> None:
    """Including those ``Agent`` inherits from ``AgentView`` (mkdocstrings leaves inherited
    members out unless told)."""
    from goalagent.agent import Agent
    from goalagent.agent.view import AgentView

    api = (site / "api" / "index.html").read_text()
    public = [name for name in dir(Agent) if not name.startswith("_")
              and callable(getattr(Agent, name))]
    assert "query" in public and "query" in vars(AgentView)
    for name in public:
        assert f'id="goalagent.agent.Agent.{name}"' in api, name


def test_the_environment_reference_lists_every_environment(site: Path) -> None:
    shipped = subprocess.run(  # (not this process's: a sample registers an environment)
        [sys.executable, "-c", "from goalagent.eis import known_environments; "
                               "print(*known_environments())"],
        capture_output=True, text=True, check=True).stdout.split()
    reference = (site / "environments" / "reference" / "index.html").read_text()
    assert "blocksworld" in shipped
    for name in shipped:
        assert f"<code>{name}</code>" in reference, name
    assert "<code>move</code>" in reference and "<code>on/2</code>" in reference

"""Every code sample of the documentation site (docs/) runs as the page says.

Conventions of the pages (docs/index.md says them to writers):

- A fenced block ```` ```goal title="NAME" ```` (or ``mas2g``, ``mod2g``, ``act2g``,
  ``pl``, ``test2g``; the site shows NAME above the block) is saved under NAME (a path under
  the page's folder) and checked as ``goalagent check`` checks it.
- ```` ```text title="output of NAME" ```` is exactly what running NAME prints on stdout:
  a ``.goal`` or ``.mas2g`` run for at most 20 cycles, or the report of a ``.test2g`` file
  (``goalagent test``). The run gives no warning unless a block
  ```` ```text title="warnings of NAME" ```` lists them, one a line (paths as NAME's folder).
  A ``% run: ARGS`` first line of a ``.goal`` file gives its ``--env``, ``--env-param`` and
  ``--trace`` options.
- ```` ```python ```` blocks run, in order, in one namespace per page, in the page's folder
  (where its files are saved); then every ``test_*`` function they define is called.
- In ```` ```sh ```` blocks every ``goalagent`` command is parsed by the command line itself
  (its command and options must exist) and the files it names in this repository must
  exist; they are not run (some take an hour).

Other blocks (``text`` without ``output=``, ``mermaid``) are not samples.
"""

from __future__ import annotations

import io
import os
import re
import shlex
from pathlib import Path

import pytest
import typer
from rich.console import Console

from goalagent.agent import validate_program
from goalagent.checking import check_file
from goalagent.cli import create_app
from goalagent.mas import MultiAgentSystem, parse_parameter
from goalagent.parser import load_agents, parse_agent_file, parse_mas_file
from goalagent.testing import run_test_file
from goalagent.trace import TracePrinter, parse_kinds

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
PAGES = sorted(path for path in DOCS.rglob("*.md") if "results" not in path.parts)
_FENCE = re.compile(r"^```(\w+)([^\n]*)\n(.*?)^```", re.MULTILINE | re.DOTALL)
_TITLE = re.compile(r'title="([^"]+)"')
SAVED_KINDS = ("goal", "mas2g", "mod2g", "act2g", "pl", "test2g")
MAX_CYCLES = 20


class Page:
    """One page's samples: files to save, expected outputs, Python blocks, shell lines."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.files: dict[str, str] = {}
        self.outputs: dict[str, str] = {}
        self.warnings: dict[str, str] = {}
        self.python: list[str] = []
        self.shell: list[str] = []
        for language, info, body in _FENCE.findall(path.read_text()):
            title = _TITLE.search(info)
            name = title.group(1) if title else None
            if language in SAVED_KINDS and name is not None:
                assert name not in self.files, f"two blocks save {name}"
                self.files[name] = body
            elif language == "text" and name is not None and name.startswith("output of "):
                self.outputs[name.removeprefix("output of ")] = body
            elif language == "text" and name is not None and name.startswith("warnings of "):
                self.warnings[name.removeprefix("warnings of ")] = body
            elif language == "python":
                self.python.append(body)
            elif language == "sh":
                self.shell += _commands(body)

    @property
    def name(self) -> str:
        return str(self.path.relative_to(DOCS))

    def save(self, folder: Path) -> None:
        for name, text in self.files.items():
            target = folder / name
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(text)


def _commands(block: str) -> list[str]:
    """The ``goalagent`` command lines of a shell block (continuations joined)."""
    joined = re.sub(r"\\\n\s*", " ", block)
    lines = [line.split("  #")[0].strip() for line in joined.splitlines()]
    return [line for line in lines if re.match(r"(nice -n \d+ )?(\.venv/bin/)?goalagent ", line)]


SITE = [Page(path) for path in PAGES]
FILES = [(page, name) for page in SITE for name in page.files]
OUTPUTS = [(page, name) for page in SITE for name in page.outputs]
PYTHON = [page for page in SITE if page.python]
SHELL = [(page, line) for page in SITE for line in page.shell]


def _id(item: object) -> str:
    if isinstance(item, tuple):
        return f"{item[0].name}:{item[1]}"
    return item.name if isinstance(item, Page) else str(item)


def test_the_site_has_the_samples_the_issue_asks_for() -> None:
    by_page = {page.name: page for page in SITE}
    assert len(by_page["language.md"].outputs) >= 10
    assert {"market.mas2g", "robot.goal", "modules.goal", "tower.goal"} <= set(
        by_page["language.md"].outputs)
    assert "tower/tower.mas2g" in by_page["goal6.md"].outputs
    testing = by_page["testing.md"]
    assert any(name.endswith(".test2g") for name in testing.outputs)
    assert testing.python, "testing.md shows pytest tests with the Python API"
    for page in SITE:
        assert set(page.outputs) <= set(page.files), page.name
        assert set(page.warnings) <= set(page.outputs), page.name


@pytest.mark.parametrize(("page", "name"), FILES, ids=_id)
def test_every_sample_file_passes_validation(tmp_path: Path, page: Page, name: str) -> None:
    page.save(tmp_path)
    path = tmp_path / name
    if path.suffix == ".mas2g":
        for program in load_agents(parse_mas_file(path)).values():
            validate_program(program)
    elif path.suffix == ".goal":
        validate_program(parse_agent_file(path))
    else:  # module, action, Prolog and test files: as goalagent check reads them
        problems: list[str] = []
        assert check_file(path, False, problems.append), problems


@pytest.mark.parametrize(("page", "name"), OUTPUTS, ids=_id)
def test_every_sample_prints_what_the_page_says(tmp_path: Path, page: Page, name: str,
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    page.save(tmp_path)
    path = tmp_path / name
    if path.suffix == ".test2g":
        monkeypatch.chdir(path.parent)
        report = run_test_file(path.name, output=io.StringIO(), warn=lambda line: None)
        assert report.text() + "\n" == page.outputs[name]
        return
    environment, params, trace = _run_options(page.files[name], path.parent)
    output, warnings = io.StringIO(), []
    listeners = []
    if trace is not None:
        kinds, idle = parse_kinds(trace)
        console = Console(file=output, width=200, soft_wrap=True, highlight=False,
                          color_system=None)
        listeners.append(TracePrinter(kinds, idle, console=console))
    options = dict(output=output, warn=warnings.append, listeners=listeners)
    system = (MultiAgentSystem.from_mas_file(path, **options) if path.suffix == ".mas2g"
              else MultiAgentSystem.for_agent_file(path, environment=environment,
                                                   env_params=params, **options))
    try:
        system.run(MAX_CYCLES)
    finally:
        system.close()
    shown = [warning.replace(f"{tmp_path}{os.sep}", "") for warning in warnings]
    assert shown == page.warnings.get(name, "").splitlines()
    assert output.getvalue() == page.outputs[name]


def _run_options(text: str, folder: Path) -> tuple[str | None, dict, str | None]:
    """``--env``, ``--env-param`` and ``--trace`` of a ``% run:`` first line."""
    first = text.splitlines()[0]
    if not first.startswith("% run:"):
        return None, {}, None
    args = shlex.split(first.removeprefix("% run:"))
    environment = args[args.index("--env") + 1] if "--env" in args else None
    params = {}
    trace = None
    for index, arg in enumerate(args):
        if arg == "--env-param":
            key, _, value = args[index + 1].partition("=")
            params[key] = parse_parameter(value)
        elif arg.startswith("--trace"):
            trace = arg.partition("=")[2] or "all"
    if environment == "garbage":
        params["models"] = parse_parameter(str(folder / "models.json"))
        params["objects"] = parse_parameter(str(folder / "objects.json"))
    return environment, params, trace


@pytest.mark.parametrize("page", PYTHON, ids=_id)
def test_every_python_sample_runs(tmp_path: Path, page: Page,
                                  monkeypatch: pytest.MonkeyPatch) -> None:
    page.save(tmp_path)
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {"__name__": f"docs_{page.path.stem}"}
    for index, block in enumerate(page.python):
        source = tmp_path / f"sample_{index}.py"  # (code that reads its own source finds it)
        source.write_text(block)
        exec(compile(block, str(source), "exec"), namespace)
    for name, value in list(namespace.items()):
        if name.startswith("test_") and callable(value):
            value()


@pytest.mark.parametrize(("page", "line"), SHELL, ids=_id)
def test_every_command_on_the_site_is_one_the_command_line_takes(page: Page,
                                                                  line: str) -> None:
    words = shlex.split(line)
    args = words[words.index(next(w for w in words if w.endswith("goalagent"))) + 1:]
    command = typer.main.get_command(create_app())
    name = "goalagent"
    while hasattr(command, "get_command") and args and not args[0].startswith("-"):
        context = command.make_context(name, [], resilient_parsing=True)
        name = args.pop(0)
        command = command.get_command(context, name)
        assert command is not None, f"{line}: no command {name}"
    command.make_context(name, list(args))  # raises on an unknown option or a bad value
    for arg in words:
        if re.match(r"(agents|docs|sim|tests|bench)/\S+\.\w+$", arg):
            assert (ROOT / arg).exists() or os.path.exists(arg), f"{line}: {arg} is missing"

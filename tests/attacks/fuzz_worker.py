"""The child process of tests/attacks/test_fuzz_inputs.py: reads one JSON request per line,
feeds it to a loader or the command line in-process, and answers one JSON line (what happened, and
whether anything escaped as a traceback). The parent kills it when an answer is late, so a
hang is a failure that names its input instead of a stuck test run."""

from __future__ import annotations

import json
import os
import re
import resource
import sys
import tempfile
import traceback
from pathlib import Path

from typer.testing import CliRunner

from behaviours.learners.effect_models import ModelStore, StoreError
from behaviours.learners.persist import LearnerFileError, read_learner
from goalagent.agent import AgentError, validate_program
from goalagent.beliefs import read_belief_file
from goalagent.cli import create_app
from goalagent.kb.engine import KBError
from goalagent.parser import GoalSyntaxError, load_agents, parse_agent, parse_mas

LOCATED = re.compile(r"^\S.*:\d+:\d+: \S")
APP = create_app()


def _agent(text: str, folder: Path) -> str:
    program = parse_agent(text, str(folder / "fuzz.goal"))
    validate_program(program)
    return "ok"


def _mas(text: str, folder: Path) -> str:
    (folder / "a.goal").write_text("main module [exit=always] { program { if true then "
                                   "print(hi). } }\n")
    mas = parse_mas(text, str(folder / "fuzz.mas2g"))
    for program in load_agents(mas).values():
        validate_program(program)
    return "ok"


def _facts(text: str, folder: Path) -> str:
    path = folder / "fuzz.pl"
    path.write_text(text)
    with read_belief_file(path) as facts:
        return f"ok {facts.count}"


def _store(text: str, folder: Path) -> str:
    path = folder / "store.json"
    path.write_text(text)
    try:
        ModelStore(path)
    except StoreError as error:
        return f"refused {error}"
    try:
        read_learner(path, "cacla")
    except LearnerFileError as error:
        return f"refused {error}"
    return "ok"


def _cli(args: list[str], folder: Path) -> str:
    os.mkfifo(folder / "fifo")
    args = [arg.replace("{tmp}", str(folder)) for arg in args]
    result = CliRunner().invoke(APP, args, catch_exceptions=True)
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    output = result.stdout + result.stderr
    if "Traceback" in output:
        raise AssertionError(f"a traceback was printed: {output[-2000:]}")
    if result.exit_code not in (0, 1, 2):
        raise AssertionError(f"exit code {result.exit_code}: {output[-500:]}")
    return f"exit {result.exit_code}"


HANDLERS = {"agent": _agent, "mas": _mas, "facts": _facts, "store": _store, "cli": _cli}
USER_ERRORS = (GoalSyntaxError, AgentError)


def serve() -> None:
    """Answers requests until stdin closes."""
    for line in sys.stdin:
        request = json.loads(line)
        answer: dict[str, object] = {}
        with tempfile.TemporaryDirectory() as folder:
            try:
                answer["outcome"] = HANDLERS[request["kind"]](request["input"], Path(folder))
            except USER_ERRORS as error:
                message = str(error)
                answer["outcome"] = "user error"
                if isinstance(error, GoalSyntaxError) and not LOCATED.match(message):
                    answer["escaped"] = f"not located: {message}"
            except KBError as error:  # only the fact-file reader may raise it (located)
                answer["outcome"] = "kb error"
                answer["escaped"] = f"KBError escaped: {error}"
            except BaseException as error:  # noqa: BLE001 - anything else is the finding
                answer["escaped"] = "".join(traceback.format_exception(error))[-3000:]
        answer["rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        sys.stdout.write(json.dumps(answer) + "\n")
        sys.stdout.flush()


if __name__ == "__main__":
    serve()

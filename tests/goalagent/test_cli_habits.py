"""The command line's habits, each as a user meets it: ``-h``, shell completion, readable
metavars, ``--trace KINDS`` after a space and kinds that filter exactly, ``goalagent test``'s
report apart from the agents' output, ``GOALAGENT_DEBUG=1`` showing the traceback of an
environment's own code, and what follows an action the environment refuses (GOAL's
semantics), the robot's afford/6 saved only where it applies. What the shell or the process
is part of (completion, the debug traceback, the streams kept apart) runs the installed
script in a child process; help and runs whose output is the point run in this process."""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import cli

ROOT = Path(__file__).resolve().parents[2]
GOALAGENT = str(Path(sys.executable).with_name("goalagent"))
COUNTER = """
init module { beliefs { count(0). } goals { count(2). } }
main module [exit=nogoals] {
    program {
        if bel(count(N), N < 2, M is N + 1) then delete(count(N)) + insert(count(M)) + print(M).
    }
}
"""
LABELS = {  # what each trace kind may print, by line label
    "percepts": {"percepts"}, "rules": {"rule", "fired"},
    "actions": {"action", "refused", "precondition"}, "beliefs": {"inserted", "deleted"},
    "goals": {"adopted", "dropped", "achieved"}, "messages": {"received"},
    "warnings": {"warning"}, "modules": {"entered", "left"},
}


def goalagent(*args: str, cwd: Path = ROOT, **env: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([GOALAGENT, *args], cwd=cwd, capture_output=True, text=True,
                          timeout=300, env=dict(os.environ, COLUMNS="100", **env))


def shown(*args: str) -> str:
    """What ``goalagent ARGS`` prints on stdout, run in this process (ending with 0)."""
    result = cli(*args, env={"COLUMNS": "100"})
    assert result.exit_code == 0, result.stderr
    return result.stdout


@pytest.fixture
def counter(tmp_path: Path) -> Path:
    path = tmp_path / "counter.goal"
    path.write_text(COUNTER)
    return path


@pytest.mark.parametrize("command", [[], ["run"], ["check"], ["test"], ["snapshot"],
                                     ["reproduce"], ["robot"]])
def test_dash_h_is_help(command: list[str]) -> None:
    short = shown(*command, "-h")
    assert short == shown(*command, "--help") and short.startswith("Usage: goalagent")


def test_shell_completion_completes_commands_and_options() -> None:
    commands = goalagent(_GOALAGENT_COMPLETE="complete_bash", COMP_WORDS="goalagent ru",
                         COMP_CWORD="1")
    assert commands.stdout.split() == ["run"]
    options = goalagent(_GOALAGENT_COMPLETE="complete_bash", COMP_WORDS="goalagent run --tr",
                        COMP_CWORD="2")
    assert options.stdout.split() == ["--trace", "--trace-file"]
    script = subprocess.run(  # from a bash, as a user asks (Typer detects the shell)
        ["bash", "-c", f"{shlex.quote(GOALAGENT)} --show-completion; true"],
        capture_output=True, text=True, timeout=300)
    assert "_goalagent_completion" in script.stdout, script.stderr
    assert "--install-completion" in shown("-h")  # the command's own help (as the script's)


@pytest.mark.parametrize("command", [["run"], ["check"], ["test"], ["snapshot"],
                                     ["reproduce"], ["objects", "list"]])
def test_help_shows_readable_metavars(command: list[str]) -> None:
    help_text = shown(*command, "-h")
    assert not re.search(r"<[a-zA-Z]+(\[[^\]]*\])?>", help_text), help_text
    if command == ["run"]:
        for option in ("--env NAME", "--env-param KEY=VALUE", "--trace KINDS",
                       "--save-predicate NAME/ARITY", "--max-cycles N"):
            assert option in help_text


def test_trace_kinds_after_a_space_or_an_equals_sign(counter: Path) -> None:
    spaced = shown("run", str(counter), "--trace", "goals,beliefs")
    assert spaced == shown("run", str(counter), "--trace=goals,beliefs")
    assert "achieved count(2)" in spaced
    labels = {line.split()[2] for line in spaced.splitlines() if " #" in line}
    assert labels == {"inserted", "deleted", "achieved"}  # no rule or action lines
    bare = shown("run", "--trace", str(counter))  # --trace alone: everything
    assert "fired" in bare and "inserted" in bare


@pytest.mark.parametrize("kind", sorted(LABELS))
def test_each_trace_kind_shows_only_its_lines(kind: str) -> None:
    run = cli("run", str(ROOT / "agents/examples/coffee.mas2g"), f"--trace={kind}",
              "--max-cycles", "12")
    assert run.exit_code in (0, 1), run.stderr
    traced = [line.split()[2] for line in run.stdout.splitlines()
              if re.match(r"\S+ #\d+ ", line)]
    assert set(traced) <= LABELS[kind], (kind, set(traced))
    if kind in ("rules", "actions", "beliefs", "goals", "messages"):
        assert traced, f"coffee shows {kind}"


def test_goalagent_test_keeps_the_agents_output_apart(tmp_path: Path) -> None:
    folder = ROOT / "agents" / "examples" / "goal6" / "coffee"
    run = goalagent("test", "coffee.test2g", cwd=folder)
    assert run.returncode == 0, run.stdout + run.stderr
    lines = run.stdout.splitlines()
    assert lines[0] == "coffee.test2g:" and re.match(r"  \d+ passed, 0 failed", lines[-1])
    assert all(line.startswith("  ") for line in lines[1:])  # the report and nothing else
    assert "made(coffee)" in run.stderr  # what the maker agent prints


BOOM = '''
from goalagent.eis import PythonEnvironment, action


class Boom(PythonEnvironment):
    name = "boom"

    @action("explode")
    def explode(self, entity: str, times: int) -> None:
        self.light_the_fuse(times)

    def light_the_fuse(self, times: int) -> None:
        print(1 / (times - times))
'''
BOOM_AGENT = """
init module { actionspec { explode(N) { pre { true } post { true } } } }
main module [exit=always] { program { if true then explode(2) + print(after). } }
"""


def test_goalagent_debug_shows_the_traceback_of_the_environments_code(tmp_path: Path) -> None:
    (tmp_path / "boom.py").write_text(BOOM)
    (tmp_path / "boom.goal").write_text(BOOM_AGENT)
    plain = goalagent("run", "boom.goal", "--env", "boom:Boom", cwd=tmp_path)
    assert "ZeroDivisionError" in plain.stderr and "Traceback" not in plain.stderr
    debug = goalagent("run", "boom.goal", "--env", "boom:Boom", cwd=tmp_path,
                      GOALAGENT_DEBUG="1")
    assert "Traceback (most recent call last)" in debug.stderr
    assert "in light_the_fuse" in debug.stderr and "boom.py" in debug.stderr
    assert debug.stdout == plain.stdout == "after\n"  # the agent goes on, as without it


REFUSED = """
init module {
    actionspec {
        move(X, Y) { pre { true } post { tried(X, Y) } }
        fly(X) { pre { true } post { true } }
    }
}
main module [exit=always] {
    program { if true then ACTION + print(next). }
}
"""


def test_a_refused_action_counts_as_performed_as_in_goal(tmp_path: Path) -> None:
    """GOAL's runtime (RunState.doPerformAction): the environment's refusal is a warning,
    the postcondition follows and the rule's next actions run."""
    agent = tmp_path / "refused.goal"
    agent.write_text(REFUSED.replace("ACTION", "move(a, b)"))
    run = cli("run", str(agent), "--env", "blocksworld", "--env-param",
              "state=[on(a,table),on(b,a)]", "--trace=beliefs")
    assert run.exit_code == 0, run.stderr
    assert "could not perform move(a,b): move(a,b): a is not clear" in run.stderr
    assert "inserted tried(a,b)" in run.stdout and run.stdout.endswith("next\n")


def test_an_action_the_environment_cannot_take_stops_the_agent_as_in_goal(
        tmp_path: Path) -> None:
    agent = tmp_path / "unknown.goal"
    agent.write_text(REFUSED.replace("ACTION", "fly(a)"))
    run = cli("run", str(agent), "--env", "blocksworld")
    assert run.exit_code == 1
    assert "has no action 'fly'" in run.stderr and "the agent is stopped" in run.stderr
    assert "unknown: failed after 1 cycles" in run.stderr and run.stdout == ""


def test_a_plain_agent_saves_no_afford_beliefs(counter: Path, tmp_path: Path) -> None:
    saved = tmp_path / "beliefs.pl"
    run = cli("run", str(counter), "--save-beliefs", str(saved))
    assert run.exit_code == 0, run.stderr
    assert "afford" not in saved.read_text() and "afford" not in run.stderr
    assert "saved no beliefs" in run.stderr
    named = cli("run", str(counter), "--save-beliefs", str(saved),
                "--save-predicate", "count/1")
    assert "saved 1 count/1 beliefs" in named.stderr
    assert saved.read_text().splitlines()[-1] == "count(2)."


def test_an_agent_with_afford_beliefs_saves_them(tmp_path: Path) -> None:
    agent = tmp_path / "learner.goal"
    agent.write_text("init module { beliefs { afford(lid, push, opened, 2, 1, 0.5). } }\n"
                     "main module [exit=always] { program { if true then print(done). } }\n")
    saved = tmp_path / "learned.pl"
    run = cli("run", str(agent), "--save-beliefs", str(saved))
    assert run.exit_code == 0, run.stderr
    assert "saved 1 afford/6 beliefs" in run.stderr
    assert "afford(lid,push,opened,2,1,0.5)." in saved.read_text()

"""``--trace``: every output path shows user data as written (no Rich markup), trace lines
carry agent and cycle, kinds filter, percepts as changes, idle rules left out, refused
actions shown, trace files in text and JSON lines."""

from __future__ import annotations

import json
import os
import re
import shlex
from pathlib import Path

import pytest
from rich.console import Console

from goalagent.agent import Agent, EventKind
from goalagent.trace import TraceKindError, TracePrinter, parse_kinds
from tests.conftest import ROOT, cli

# Text Rich would read as markup: a list, a style tag, a closing tag, a quoted atom.
MARKUP_AGENT = r"""
init module {
    beliefs { label('[bold]x[/]'). items([c]). afford('[c]', push, opened, 1, 1, 1.0). }
    goals { shown([c]). }
}
main module [exit=nogoals] { program {
    if bel(X is [c] + '[red]') then print(never).
    if bel(items(L), label(T)) then print(L) + print(T) + log(L) + insert(shown([c])).
} }
"""

WIDE = {"COLUMNS": "200"}
"""A terminal wide enough that no line is wrapped."""


def test_every_output_path_shows_brackets_and_quoted_atoms(tmp_path: Path) -> None:
    program = tmp_path / "markup.goal"
    program.write_text(MARKUP_AGENT)
    trace_file = tmp_path / "trace.txt"
    result = cli("run", str(program), "--trace", "--plot", str(tmp_path / "p.png"),
                 env=WIDE)
    assert result.exit_code == 0, result.stderr
    # print/1 on stdout, the trace on stdout
    assert "[c]\n[bold]x[/]\n" in result.stdout
    assert "fired main" in result.stdout and "L=[c], T='[bold]x[/]'" in result.stdout
    assert "insert(shown([c]))" in result.stdout and "achieved shown([c])" in result.stdout
    # log/1, the warning of a Prolog error (its message names the list), the afford table
    assert "log: agent markup: [c]" in result.stderr
    assert "warning: agent markup: module main, rule at" in result.stderr
    assert "[c]+'[red]'" in result.stderr or "[c]" in result.stderr.split("Prolog error")[1]
    assert "[c]" in result.stderr.split("afford/6 beliefs of markup")[1]
    # the same in a trace file
    filed = cli("run", str(program), "--trace-file", str(trace_file), "--plot",
                str(tmp_path / "p2.png"))
    assert filed.exit_code == 0, filed.stderr
    assert "L=[c], T='[bold]x[/]'" in trace_file.read_text()
    assert "L=[c]" not in filed.stdout
    # a user error naming a list; check's warnings
    error = cli("run", str(ROOT / "agents/examples/blocks_builder.goal"), "--env", "blocksworld",
                "--env-param", "robots=[x]")
    assert error.exit_code == 2 and "got [x]" in error.stderr
    single = tmp_path / "single.goal"
    single.write_text("main module { program {\n if bel(p([X])) then print('[b]y[/b]').\n} }\n")
    checked = cli("check", str(single))
    assert "singleton variable X" in checked.stderr and f"{single}: ok" in checked.stderr


def test_trace_lines_name_agent_and_cycle_and_show_percept_changes(tmp_path: Path) -> None:
    result = cli("run", str(ROOT / "agents/examples/blocks_builder.goal"), "--env", "blocksworld",
                 "--env-param", "state=[on(c,a), on(a,table), on(b,table)]",
                 "--trace=percepts,rules")
    assert result.exit_code == 0, result.stderr
    lines = result.stdout.splitlines()
    percepts = [line for line in lines if "percepts" in line]
    assert percepts[0].startswith("blocks_builder #1 ")
    assert "+on(c,a)" in percepts[0]
    assert percepts[1].split("percepts ")[1] == "+on(c,table) -on(c,a)"  # only the change
    assert not any("0 instantiation(s)" in line for line in lines)  # idle rules left out
    assert any("T=[c]" in line for line in lines)  # a macro's variable by its own name
    assert not any("inserted" in line for line in lines)  # beliefs not asked for
    idle = cli("run", str(ROOT / "agents/examples/blocks_builder.goal"), "--env", "blocksworld",
               "--env-param", "state=[on(c,a), on(a,table), on(b,table)]",
               "--trace=idle")
    assert "0 instantiation(s)" in idle.stdout


def test_json_lines_trace_file_holds_positions_bindings_and_refusals(tmp_path: Path) -> None:
    target = tmp_path / "coffee.jsonl"
    result = cli("run", str(ROOT / "agents/examples/coffee.mas2g"), "--trace-file", str(target))
    assert result.exit_code == 0, result.stderr
    records = [json.loads(line) for line in target.read_text().splitlines()]
    kinds = {record["kind"] for record in records}
    assert {"rule_fired", "message_received", "action_refused"} <= kinds
    fired = next(r for r in records if r["kind"] == "rule_fired" and r["bindings"][0])
    assert fired["pos"].endswith(f":{fired['pos'].split(':')[-2]}:{fired['pos'].split(':')[-1]}")
    assert {record["agent"] for record in records} == {"maker", "grinder"}
    assert all(record["cycle"] >= 1 for record in records)
    assert oct(target.stat().st_mode & 0o777) == oct(0o666 & ~_umask())
    assert not list(tmp_path.glob(".coffee.jsonl.*"))  # no temporary left


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_unknown_kind_is_refused_with_a_suggestion() -> None:
    with pytest.raises(TraceKindError, match="did you mean rules"):
        parse_kinds("percepts,rulez")
    result = cli("run", str(ROOT / "agents/examples/hello_world.goal"), "--trace=belifs")
    assert result.exit_code == 2 and "did you mean beliefs?" in result.stderr


def test_refused_actions_and_warnings_are_traced_with_fresh_variables_as_underscores() -> None:
    console = Console(record=True, width=300, highlight=False)
    kinds, _ = parse_kinds("actions,warnings,goals")
    agent = Agent.from_string("""
        init module { beliefs { p(1). } goals { g(1). } }
        main module { program [order=linearall] {
            if true then adopt(g(1)).
            if bel(Y = f(_)) then print(Y).
            if bel(atom_length(Z, 3)) then print(Z).
        } }
    """, name="refuser", tracer=None, warn=lambda message: None)
    agent.listen(TracePrinter(kinds, console=console))
    agent.step()
    text = console.export_text()
    assert "refuser #1 " in text
    assert "refused adopt(g(1)) not enabled (already a goal) at <string>:4:26" in text
    assert "action print(f(_))" in text and "_G" not in text  # actions without rules
    assert "fired" not in text and "rule main" not in text
    assert "warning module main, rule at <string>:6:" in text
    assert EventKind.WARNING.value == "warning"


def readme_run_commands() -> list[list[str]]:
    """The ``goalagent run`` commands of the first block of docs/running.md (the README's
    "Running agents" before the site), as written."""
    page = (ROOT / "docs" / "running.md").read_text()
    block = page.split("# Running agents", 1)[1].split("```sh\n", 1)[1].split("```", 1)[0]
    lines = block.replace("\\\n", " ").splitlines()
    return [shlex.split(line, comments=True)[1:] for line in lines
            if shlex.split(line, comments=True)[1:2] == ["run"]]


def test_the_readme_trace_examples_show_their_lists() -> None:
    """The issue's complaints, on the README's own commands traced: ``T_M1=`` for the
    blocks builder's macro variable, ``canMake(grinder,)`` for coffee, ``_5988``."""
    commands = {Path(command[1]).name: command for command in readme_run_commands()}
    blocks = commands["blocks_builder.goal"]
    assert "--trace" in blocks  # the README shows this one traced
    traced = cli(*blocks, env=WIDE)
    assert traced.exit_code == 0, traced.stderr
    assert "[X=a, Y=b, T=[c]]" in traced.stdout and "T_M1" not in traced.stdout
    coffee = cli(*commands["coffee.mas2g"], "--trace", env=WIDE)
    assert coffee.exit_code == 0, coffee.stderr
    assert "maker.sendonce(:canMake(grinder,[grounds]))" in coffee.stdout
    assert "received grinder: :canMake(grinder,[grounds])" in coffee.stdout
    assert "received maker: ?canMake(_,_)" in coffee.stdout  # fresh variables as _
    assert not re.search(r"_G?\d", coffee.stdout + traced.stdout)

"""The ``goalagent`` command as a user runs it: output, exit codes, clear errors."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "agents" / "examples"


def goalagent(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "goalagent", *args],
        cwd=cwd, capture_output=True, text=True, timeout=300,
    )


def test_run_prints_only_the_agents_output_on_stdout(tmp_path: Path):
    program = tmp_path / "count.goal"
    program.write_text("""
        init module { beliefs { n(0). } goals { n(3). } }
        main module [exit=nogoals] { program {
            if bel(n(N), M is N + 1) then print(M) + delete(n(N)) + insert(n(M)).
        } }
    """)
    result = goalagent("run", str(program))
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["1", "2", "3"]
    assert "count: terminated after 3 cycles" in result.stderr


def test_malformed_file_gives_location_and_exit_code_2(tmp_path: Path):
    program = tmp_path / "broken.goal"
    program.write_text("main module {\n  program {\n    if bel(on(X,Y) then skip.\n  }\n}\n")
    result = goalagent("run", str(program))
    assert result.returncode == 2
    assert f"{program}:3:" in result.stderr
    assert "Traceback" not in result.stderr + result.stdout


def test_check_accepts_every_shipped_example():
    files = sorted(str(p) for p in EXAMPLES.glob("*.goal")) + sorted(
        str(p) for p in EXAMPLES.glob("*.mas2g"))
    result = goalagent("check", *files)
    assert result.returncode == 0, result.stderr


def test_check_reports_unknown_actions_with_position(tmp_path: Path):
    program = tmp_path / "unknown.goal"
    program.write_text("main module { program {\n    if true then fly(away).\n} }\n")
    result = goalagent("check", str(program))
    assert result.returncode == 2
    assert f"{program}:2:18: unknown action fly/1" in result.stderr


def test_a_place_at_line_100_is_not_read_as_an_emoji_code(tmp_path: Path):
    """Rich turns ``:100:`` into an emoji unless told not to: ``a.goal:100:5`` must stay."""
    program = tmp_path / "long.goal"
    program.write_text("\n" * 99 + "main module { program { if true then jump. } }\n")
    result = goalagent("check", str(program))
    assert result.returncode == 2
    assert f"{program}:100:38: unknown action jump/0" in result.stderr, result.stderr


def test_check_warns_about_singleton_variables_but_succeeds(tmp_path: Path):
    program = tmp_path / "single.goal"
    program.write_text("main module { program {\n    if bel(p(X)) then print(done).\n} }\n")
    result = goalagent("check", str(program))
    assert result.returncode == 0
    assert "singleton variable X" in result.stderr


def test_unknown_environment_is_a_clear_error(tmp_path: Path):
    program = tmp_path / "a.goal"
    program.write_text("main module { program { if true then print(x). } }\n")
    result = goalagent("run", str(program), "--env", "nowhere")
    assert result.returncode == 2
    assert "unknown environment 'nowhere'" in result.stderr
    assert "Traceback" not in result.stderr


def test_missing_file_is_a_clear_error():
    result = goalagent("run", "no/such/file.goal")
    assert result.returncode == 2
    assert "no/such/file.goal:1:1: no such file" in result.stderr


@pytest.mark.parametrize("state", ["[on(c,a), on(a,table), on(b,table)]",
                                   "[on(a,c), on(c,b), on(b,table)]"])
def test_blocks_builder_reaches_its_goal_on_the_blocks_world(state: str):
    result = goalagent("run", str(EXAMPLES / "blocks_builder.goal"), "--env", "blocksworld",
                       "--env-param", f"state={state}", "--max-cycles", "60")
    assert result.returncode == 0, result.stderr
    assert "blocks_builder: terminated" in result.stderr
    assert "0 goals left" in result.stderr

"""``goalagent check`` catches more before anything runs: non-ground goals (located),
unknown environments and init parameters in a .mas2g, calls of predicates defined nowhere
(warnings), "did you mean" for misspelt actions, modules and environments, and directories
(every agent under them)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def goalagent(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "goalagent", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=300)


def test_non_ground_goals_are_located_by_check_and_by_run(tmp_path: Path) -> None:
    program = tmp_path / "deal.goal"
    program.write_text("init module {\n  goals { deal(X). }\n}\n"
                       "main module { program { if true then print(x). } }\n")
    for command in ("check", "run"):
        result = goalagent(command, str(program))
        assert result.returncode == 2
        assert f"{program}:2:11: goal deal(X) is not ground (variable(s) X)" in result.stderr
        assert "_G" not in result.stderr and "Traceback" not in result.stderr


def test_unknown_environment_and_init_parameter_in_a_mas2g(tmp_path: Path) -> None:
    agent = tmp_path / "a.goal"
    agent.write_text("main module { program { if true then print(x). } }\n")
    system = tmp_path / "s.mas2g"
    system.write_text('environment {\n  env = "blockworld".\n}\n'
                      'agentfiles { "a.goal". }\nlaunchpolicy { launch a : a. }\n')
    result = goalagent("check", str(system))
    assert result.returncode == 2
    assert f"{system}:2:" in result.stderr and "unknown environment 'blockworld'" in result.stderr
    assert "did you mean blocksworld?" in result.stderr
    system.write_text('environment {\n  env = "blocksworld".\n  init = [stat = [], robots = 1].'
                      '\n}\nagentfiles { "a.goal". }\nlaunchpolicy { launch a : a. }\n')
    result = goalagent("check", str(system))
    assert result.returncode == 2
    assert f"{system}:3:" in result.stderr and "no init parameter 'stat'" in result.stderr
    assert "did you mean state?" in result.stderr


def test_a_goal_environment_jar_goalagent_lacks_is_a_warning(tmp_path: Path) -> None:
    """eishub Starcraft's SimpleAgentTerran.mas2g: use "../../connector.jar" as environment.
    The system is not wrong; it only cannot run here."""
    home = tmp_path / "agents" / "terran"
    home.mkdir(parents=True)
    (tmp_path / "connector.jar").write_bytes(b"PK")
    agent = home / "a.goal"
    agent.write_text("main module { program { if true then print(x). } }\n")
    system = home / "s.mas2g"
    system.write_text('environment {\n  env = "../../connector.jar".\n}\n'
                      'agentfiles { "a.goal". }\n'
                      'launchpolicy { when entity@env do launch a : a. }\n')
    result = goalagent("check", str(system))
    assert result.returncode == 0, result.stderr
    assert (f"{system}:2:9: warning: environment '../../connector.jar' is a GOAL environment "
            "goalagent does not ship") in result.stderr
    assert f"{system}: ok" in result.stderr
    result = goalagent("run", str(system))  # still an error for run
    assert result.returncode == 2
    assert f"{system}:2:9: unknown environment '../../connector.jar'" in result.stderr
    (tmp_path / "connector.jar").unlink()  # a jar built elsewhere: the text is still valid
    result = goalagent("check", str(system))
    assert result.returncode == 0
    assert (f"{system}:2:9: warning: environment '../../connector.jar' is a GOAL environment "
            "goalagent does not ship (and no such file is next to the system)") in result.stderr


def test_calls_of_predicates_defined_nowhere_are_warnings_with_suggestions(tmp_path: Path):
    program = tmp_path / "typo.goal"
    program.write_text("""init module {
    knowledge { clear(X) :- block(X), \\+ on(_, X). }
    beliefs { block(a). on(a, table). }
    actionspec { move(X, Y) { pre { clear(X), clearr(Y) } post { true } } }
}
main module { program {
    if bel(block(X), claer(X), member(X, [a]), findall(Y, blok(Y), _), seen(X)) then move(X, a).
    if true then insert(seen(a)).
} }
""")
    result = goalagent("check", str(program))
    assert result.returncode == 0, result.stderr
    lines = [line for line in result.stderr.splitlines() if "defined nowhere" in line]
    assert len(lines) == 3
    assert f"{program}:7:12: warning: claer/1" in lines[0] and "did you mean clear?" in lines[0]
    assert "blok/1" in lines[1] and "did you mean block?" in lines[1]
    assert f"{program}:4:37: warning: clearr/1" in lines[2]
    # built-ins, library predicates (member/2), inserted ones (seen/1) are not reported


def test_misspelt_actions_and_module_files_get_suggestions(tmp_path: Path) -> None:
    program = tmp_path / "act.goal"
    program.write_text("init module { actionspec { move(X) { pre { true } post { true } } } }\n"
                       "main module { program { if true then mvoe(a). } }\n")
    result = goalagent("check", str(program))
    assert result.returncode == 2 and "unknown action mvoe/1" in result.stderr
    assert "did you mean move?" in result.stderr
    (tmp_path / "mymain.mod2g").write_text("module mymain { if true then print(x). }\n")
    system = tmp_path / "s.mas2g"
    system.write_text("define a as agent {\n  use mymian as main module.\n}\n"
                      "launchpolicy { launch a. }\n")
    result = goalagent("check", str(system))
    assert result.returncode == 2
    assert f"{system}:2:" in result.stderr and "did you mean mymain?" in result.stderr


def test_a_directory_checks_every_agent_and_system_under_it(tmp_path: Path) -> None:
    (tmp_path / "sub").mkdir()
    (tmp_path / "good.goal").write_text("main module { program { if true then print(x). } }\n")
    (tmp_path / "sub" / "bad.goal").write_text("main module { program { if true then fly. } }\n")
    result = goalagent("check", str(tmp_path))
    assert result.returncode == 2
    assert f"{tmp_path / 'good.goal'}: ok" in result.stderr
    assert f"{tmp_path / 'sub' / 'bad.goal'}:1:" in result.stderr
    shipped = goalagent("check", "agents")
    assert shipped.returncode == 0, shipped.stderr
    assert "defined nowhere" not in shipped.stderr
    assert shipped.stderr.count(": ok") >= 20


def test_a_file_with_three_errors_gets_three_located_lines(tmp_path: Path) -> None:
    program = tmp_path / "three.goal"
    program.write_text("init module {\n"
                       "    beliefs { a(1). b(2 }\n"
                       "}\n"
                       "main module [exit=sometimes] {\n"
                       "    program {\n"
                       "        if bel(a(X)) then print(X).\n"
                       "        if true then frobnicate(3).\n"
                       "    }\n"
                       "}\n")
    result = goalagent("check", str(program))
    assert result.returncode == 2
    assert [line.split(": ")[0] for line in result.stderr.splitlines()] == [
        f"{program}:2:25", f"{program}:4:19", f"{program}:7:22"]


def test_more_than_twenty_errors_are_counted_not_printed(tmp_path: Path) -> None:
    program = tmp_path / "many.goal"
    rules = "".join(f"        if true then nothing{n}.\n" for n in range(25))
    program.write_text(f"main module {{\n    program {{\n{rules}    }}\n}}\n")
    result = goalagent("check", str(program))
    lines = result.stderr.splitlines()
    assert result.returncode == 2
    assert len(lines) == 21 and lines[-1] == f"{program}: and 5 more errors"
    assert lines[0].startswith(f"{program}:3:22: unknown action nothing0/0")


@pytest.mark.parametrize("env, key, suggestion", [
    ("hanoi", "disks", "discs"), ("elevator", "flors", "floors"), ("bw4t", "mapp", "map"),
    ("towerworld", "sed", "seed"), ("blocksworld", "robot", "robots"), ("printer", "x", None),
    ("navigation", "seeed", "seed"),  # a robot environment, through the extension seam
])
def test_every_shipped_environments_init_parameters_are_checked(
        tmp_path: Path, env: str, key: str, suggestion: str | None) -> None:
    (tmp_path / "a.goal").write_text("main module { program { if true then print(x). } }\n")
    system = tmp_path / "s.mas2g"
    system.write_text(f'environment {{ env = "{env}". init = [{key} = 1]. }}\n'
                      'agentfiles { "a.goal". }\n'
                      "launchpolicy { when entity@env do launch a. }\n")
    result = goalagent("check", str(system))
    assert result.returncode == 2
    line = result.stderr.strip()
    assert line.startswith(f"{system}:1:") and (
        f"environment '{env}' has no init parameter '{key}'") in line
    assert (f"(did you mean {suggestion}?)" in line) if suggestion else "did you mean" not in line


def test_env_options_get_did_you_mean_without_a_place_in_the_agent_file(tmp_path: Path):
    agent = tmp_path / "a.goal"
    agent.write_text("main module [exit=always] { program { if true then print(x). } }\n")
    result = goalagent("run", str(agent), "--env", "hanio")
    assert result.returncode == 2
    assert result.stderr.startswith("error: --env hanio: unknown environment 'hanio'")
    assert "(did you mean hanoi?)" in result.stderr and str(agent) not in result.stderr
    result = goalagent("run", str(agent), "--env", "hanoi", "--env-param", "disks=[0,0]")
    assert result.returncode == 2
    assert result.stderr.strip() == (
        "error: --env-param disks: environment 'hanoi' has no init parameter 'disks' (did you "
        "mean discs?); its parameters: discs, snapshots")

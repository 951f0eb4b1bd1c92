"""Runs that explain themselves: an idle agent with goals left is warned about once, a
warning repeated every cycle is not shown every cycle, ``--version``, ``--env module:Class``
from the current directory, the README's description of ``make demo``, and where the
afford/6 reliability plot goes without ``--plot`` (never the current directory), a Python
RecursionError in one agent, ``--max-cycles`` negatives and ``--save-beliefs`` permissions."""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from matplotlib import colormaps
from matplotlib.image import imread

from goalagent.agent import Agent, AgentError
from goalagent.agent.events import plain_variables
from tests.conftest import ROOT, cli, goalagent


def test_an_idle_agent_with_goals_left_is_warned_about_once() -> None:
    shown: list[str] = []
    agent = Agent.from_string("""
        init module { goals { done. } knowledge { :- dynamic ready/0. } }
        main module { program { if bel(ready) then insert(done). } }
    """, name="idler", warn=shown.append, idle_warning=5)
    agent.run(20)
    idle = [line for line in shown if "has done nothing" in line]
    assert idle == ["warning: agent idler: has done nothing for 5 cycles (no action, no new "
                    "percept or message) and has 1 goal(s) left, e.g. done: no rule applies to "
                    "them; it runs on until --max-cycles or Ctrl-C"]


def test_a_busy_or_goal_free_agent_is_not_warned_about() -> None:
    shown: list[str] = []
    busy = Agent.from_string("""
        init module { beliefs { n(0). } goals { n(1000). } }
        main module { program { if bel(n(N), M is N + 1) then delete(n(N)) + insert(n(M)). } }
    """, name="busy", warn=shown.append, idle_warning=5)
    busy.run(20)
    content = Agent.from_string("init module { knowledge { x :- fail. } } "
                                "main module { program { if bel(x) then print(x). } }",
                                name="content", warn=shown.append, idle_warning=5)
    content.run(20)
    assert not shown


def test_a_warning_repeated_every_cycle_is_shown_twice_at_most() -> None:
    shown: list[str] = []
    agent = Agent.from_string("main module { program { if bel(undefined_thing) then "
                              "print(x). } }", name="noisy", warn=shown.append)
    agent.run(30)
    assert len(agent.last_report.warnings) == 1  # every cycle keeps its own
    assert len(shown) == 2 and "again in cycle 2 (not shown again)" in shown[1]


def test_warnings_show_no_prolog_variable_numbers_so_repeats_read_the_same() -> None:
    shown: list[str] = []
    agent = Agent.from_string("""
        main module { program {
            if bel(X = f(_), atom_length(X, _)) then print(x).
            if true then adopt(handled(_)).
        } }
    """, name="fresh", warn=shown.append)
    agent.run(5)
    assert "found `f(_)' (a compound)" in shown[0]  # was f(_86), f(_1204), ... each cycle
    assert "adopt: handled(_) is not ground" in shown[1]
    assert len(shown) == 4 and all("again in cycle 2" in line for line in shown[2:])
    assert plain_variables("p(_12, _G3, _12) foo_12 '_7'") == "p(_G1, _, _G1) foo_12 '_7'"


def test_load_errors_show_no_prolog_variable_numbers() -> None:
    """``clear(X) : block(X)`` (a colon for ``:-``) is refused naming ``clear(_)``, the same
    text in every run (it named ``clear(_10642)`` or ``clear(_9808)``)."""
    with pytest.raises(AgentError, match=r"refused: clear\(_\) is qualified with a module"):
        Agent.from_string("init module { knowledge { clear(X) : block(X). } }\n"
                          "main module { program { if true then print(x). } }", name="colon")


def test_version() -> None:
    result = cli("--version")
    assert result.exit_code == 0 and re.fullmatch(r"goalagent \d+\.\d+\.\d+\n", result.stdout)


def test_env_module_class_is_found_in_the_current_directory(tmp_path: Path) -> None:
    (tmp_path / "counterenv.py").write_text('''
from goalagent.eis.pyenv import PythonEnvironment, action

class Counter(PythonEnvironment):
    name = "counter"
    entity_names = ("c",)

    def on_init(self, params):
        self.n = 0

    def percepts(self, entity):
        return [("n", self.n)]

    @action("inc")
    def inc(self, entity: str) -> None:
        self.n += 1
''')
    (tmp_path / "count.goal").write_text("""
        init module { goals { counted. } actionspec { inc { pre { true } post { true } } } }
        main module [exit=nogoals] { program {
            if bel(percept(n(N)), N < 3) then inc.
            if bel(percept(n(3))) then print(three) + insert(counted).
        } }
    """)
    result = goalagent("run", "count.goal", "--env", "counterenv:Counter", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout == "three\n"


def test_readme_says_what_make_demo_writes() -> None:
    makefile = (ROOT / "Makefile").read_text()
    recipe = makefile.split("\ndemo:", 1)[1].split("\n\n", 1)[0]
    written = re.findall(r"--(?:save-beliefs|plot) (\S+)", recipe)
    assert len(written) == 4
    readme = (ROOT / "README.md").read_text()
    demo = readme.split("`.ci/run` runs exactly `make test`.", 1)[1].split("\n\n", 1)[0]
    for path in written:
        assert f"`{path}`" in demo, path
    assert "afford-robot.png" not in demo


AFFORD_AGENT = """
init module { beliefs { afford(lid, push, opened, 2, 1, 0.5). } }
main module [exit=always] { program { if true then print(done). } }
"""


def test_the_reliability_plot_never_lands_in_the_current_directory(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    program = tmp_path / "learner.goal"
    program.write_text(AFFORD_AGENT)
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    plain = cli("run", str(program))
    assert plain.exit_code == 0, plain.stderr
    written = Path(re.search(r"reliability plot: (\S+)", plain.stderr).group(1))
    assert written.name == "afford-learner.png"
    plot = imread(written)
    assert plot.shape[:2] == (550, 990)  # 9 x 5 inches at 110 dpi
    first = colormaps["tab20"].colors[0]  # the one affordance's series
    assert np.all(np.abs(plot[..., :3] - first) < 0.02, axis=-1).sum() > 20
    assert written.parent != work and written.parent.name.startswith("goalagent-plots-")
    shutil.rmtree(written.parent)
    saved = tmp_path / "out" / "learned.pl"
    beside = cli("run", str(program), "--save-beliefs", str(saved))
    assert beside.exit_code == 0, beside.stderr
    assert f"reliability plot: {saved.parent / 'learned-afford-learner.png'}" in beside.stderr
    assert (saved.parent / "learned-afford-learner.png").is_file()
    assert list(work.iterdir()) == []
    other = cli("run", str(program), "--save-beliefs", str(saved.with_name("again.pl")))
    assert other.exit_code == 0, other.stderr  # a second run saving beside keeps its own plot
    assert {path.name for path in saved.parent.glob("*.png")} == {
        "learned-afford-learner.png", "again-afford-learner.png"}


DEEP = """
init module { knowledge { nest(0, a) :- !. nest(N, f(T)) :- M is N - 1, nest(M, T). } }
main module [exit=always] { program { if bel(nest(5000, T)) then insert(deep(T)). } }
"""
STEADY = "main module { program { if true then print(ok). } }\n"


def test_a_recursion_error_in_one_agent_is_reported_for_it_and_the_others_go_on(
        tmp_path: Path) -> None:
    """Tracing a belief 5000 terms deep: converting it to Python recurses too deep."""
    (tmp_path / "deep.goal").write_text(DEEP)
    (tmp_path / "steady.goal").write_text(STEADY)
    (tmp_path / "two.mas2g").write_text('agentfiles { "deep.goal". "steady.goal". }\n')
    result = cli("run", str(tmp_path / "two.mas2g"), "--max-cycles", "3", "--trace=beliefs")
    assert result.exit_code == 1
    assert ("error: agent deep failed: cannot pass a cyclic term, or one nested over ~1,000 "
            "levels, to Python\n") in result.stderr
    assert "deep: failed after 1 cycles" in result.stderr
    assert "steady: stopped at the cycle limit after 3 cycles" in result.stderr
    assert result.stdout.count("ok\n") == 3


def test_a_goal_too_deep_to_convert_still_gets_its_summary(tmp_path: Path) -> None:
    """The end-of-run summary counts goals in Prolog: a 5000-deep goal made it an
    "internal error" that lost every agent's summary."""
    (tmp_path / "deep.goal").write_text(DEEP.replace("insert(deep(T))", "adopt(deep(T))"))
    result = cli("run", str(tmp_path / "deep.goal"))
    assert result.exit_code == 0, result.stderr
    assert result.stderr == "deep: terminated after 1 cycles, 1 actions, 1 goals left\n"


def test_max_cycles_rejects_negatives() -> None:
    result = cli("run", str(ROOT / "agents/examples/hello_world.goal"), "--max-cycles",
                 "-1")
    assert result.exit_code == 2 and "Traceback" not in result.stderr
    assert "--max-cycles must be 0 or more" in result.stderr


def test_saved_beliefs_get_normal_permissions(tmp_path: Path) -> None:
    (tmp_path / "steady.goal").write_text(STEADY)
    target = tmp_path / "saved.pl"
    result = cli("run", str(tmp_path / "steady.goal"), "--max-cycles", "1",
                 "--save-beliefs", str(target), "--save-predicate", "p/1")
    assert result.exit_code == 0, result.stderr
    mask = os.umask(0)
    os.umask(mask)
    assert target.stat().st_mode & 0o777 == 0o666 & ~mask  # not mkstemp's 0600

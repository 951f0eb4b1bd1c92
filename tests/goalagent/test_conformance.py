"""Conformance: every shipped example agent runs on the real runtime (SWI-Prolog, the real
environments) and reaches its goal or prints what it should, through the Python API and
through the ``goalagent`` command line.
"""

from __future__ import annotations

import os
import random
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from goalagent.agent import Agent
from goalagent.eis.envs.blocksworld import random_towers
from goalagent.kb.terms import Atom, Struct, Term
from goalagent.mas import MultiAgentSystem
from goalagent.parser import GoalSyntaxError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "agents" / "examples"
CORPUS = Path(__file__).resolve().parents[1] / "agents"
BROKEN = CORPUS / "broken"

SUSSMAN = "[on(c,a), on(a,table), on(b,table)]"


def on(block: str, below: str) -> Struct:
    """The term on(block, below)."""
    return Struct("on", (Atom(block), Atom(below)))


SUSSMAN_TERMS = [on("c", "a"), on("a", "table"), on("b", "table")]
TOWER = {("a", "b"), ("b", "c"), ("c", "table")}


def load(name: str, **kwargs: object) -> Agent:
    """An example agent without an environment, loaded through the public API."""
    return Agent.from_file(EXAMPLES / name, **kwargs)


@pytest.fixture
def systems() -> Iterator[list[MultiAgentSystem]]:
    """Systems made by a test; their environments and Prolog modules are freed afterwards."""
    made: list[MultiAgentSystem] = []
    yield made
    for system in made:
        system.close()


@pytest.fixture
def on_env(systems: list[MultiAgentSystem]):
    """``on_env(name, env, params, seed)``: an example agent connected to an environment."""

    def connect(name: str, env: str, params: dict[str, Term] | None = None,
                seed: int = 0) -> Agent:
        system = MultiAgentSystem.for_agent_file(
            EXAMPLES / name, environment=env, env_params=params or {}, seed=seed
        )
        systems.append(system)
        return system.agents[0]

    return connect


def pairs(agent: Agent, query: str, x: str = "X", y: str = "Y") -> set[tuple[object, object]]:
    """The answers of ``bel(query)`` as (x, y) pairs."""
    return {(answer[x], answer[y]) for answer in agent.query("bel", query)}


def holds(agent: Agent, query: str) -> bool:
    """True when ``bel(query)`` has an answer."""
    return bool(agent.query("bel", query))


def line_of(name: str, fragment: str) -> int:
    """The line of ``fragment`` in an example file (to recognise which rule fired)."""
    for number, line in enumerate((EXAMPLES / name).read_text().splitlines(), start=1):
        if fragment in line:
            return number
    raise AssertionError(f"{fragment!r} not in {name}")


def goalagent(*args: str, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    """Run the ``goalagent`` command (the installed console script's module) in a subprocess."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "goalagent", *args],
        capture_output=True, text=True, timeout=timeout, cwd=ROOT, env=env,
    )


# ----------------------------------------------------------------------------- no environment


def test_hello_world_greets_three_times_then_stops(capsys: pytest.CaptureFixture[str]) -> None:
    agent = load("hello_world.goal")
    assert agent.name == "helloWorld"
    report = agent.step()
    assert [f.module for f in report.fired] == ["main"]
    assert {k: report.fired[0].bindings[k] for k in ("Count", "Next", "Target")} == {
        "Count": 0, "Next": 1, "Target": 3,
    }
    assert len(report.fired[0].actions) == 3  # print + delete + insert
    result = agent.run(max_cycles=20)
    assert result.terminated and result.goals_left == []
    assert result.cycles == 3
    assert agent.query("bel", "greeted(N)") == [{"N": 3}]
    assert capsys.readouterr().out.splitlines() == ["Hello, world!"] * 3


def test_stack_builder_solves_the_sussman_anomaly_through_postconditions() -> None:
    agent = load("stack_builder.goal")
    moved = []
    while not agent.terminated and agent.cycle < 20:
        report = agent.step()
        moved += [(f.bindings["X"], f.bindings.get("Y", "table")) for f in report.fired]
    assert moved == [("c", "table"), ("b", "c"), ("a", "b")]
    assert pairs(agent, "on(X, Y)") == TOWER
    assert agent.goals() == []


def test_nested_rules_carry_outer_bindings_inward(capsys: pytest.CaptureFixture[str]) -> None:
    agent = load("nested_rules.goal")
    outer = line_of("nested_rules.goal", "if bel(parcel(P, City, Kg)")
    first = agent.step()
    outer_fired = [f for f in first.fired if f.pos.line == outer]
    assert len(outer_fired) == 1
    assert {k: outer_fired[0].bindings[k] for k in ("P", "City", "Kg")} == {
        "P": "p1", "City": "Den Haag", "Kg": 3,
    }
    result = agent.run(max_cycles=20)
    assert result.terminated and result.goals_left == []
    assert pairs(agent, "loaded(X, Y)") == {("p1", "van"), ("p2", "t7")}
    assert agent.query("bel", "waiting(P)") == [{"P": "p3"}]
    assert capsys.readouterr().out.splitlines() == ["by van", "t7"]


def test_listall_and_macros_pack_one_sorted_box(capsys: pytest.CaptureFixture[str]) -> None:
    agent = load("listall_macros.goal")
    result = agent.run(max_cycles=10)
    assert result.terminated and result.goals_left == []
    assert result.cycles == 2
    assert agent.query("bel", "box(B)") == [{"B": ["apple", "kiwi", "plum"]}]
    assert {a["F"] for a in agent.query("bel", "kept(F)")} == {"pear", "fig"}
    assert capsys.readouterr().out.splitlines() == ["[apple,kiwi,plum]", "3", "shipped"]


def test_user_modules_with_focus_and_exit_module(capsys: pytest.CaptureFixture[str]) -> None:
    agent = load("user_modules.goal")
    result = agent.run(max_cycles=30)
    assert result.terminated and result.goals_left == []
    assert {a["T"] for a in agent.query("bel", "done(T)")} == {"dishes", "laundry"}
    assert agent.query("bel", "skipped(T)") == [{"T": "ironing"}]
    assert capsys.readouterr().out.splitlines() == ["dishes", "laundry"]


def test_old_single_module_layout_runs() -> None:
    """Sections at the top level of the wrapper (GOAL 3/4 layout) make a working agent; its
    main module has no exit option, so it keeps running after reaching its goal."""
    agent = Agent.from_file(CORPUS / "good" / "goal3_top_level.goal")
    result = agent.run(max_cycles=5)
    assert not result.terminated and result.goals_left == []
    assert pairs(agent, "on(X, Y)") == {("a", "b"), ("b", "table")}


# ----------------------------------------------------------------------------- environments


def test_script_printer_prints_the_script_on_the_printer(
    on_env, capsys: pytest.CaptureFixture[str]
) -> None:
    agent = on_env("script_printer.goal", "printer")
    result = agent.run(max_cycles=20)
    assert result.terminated and result.goals_left == []
    assert agent.query("bel", "printed(N)") == [{"N": 4}]
    assert capsys.readouterr().out.splitlines() == [
        "To be, or not to be, that is the question:",
        "Whether 'tis nobler in the mind to suffer",
        "The slings and arrows of outrageous fortune,",
        "Or to take arms against a sea of troubles",
    ]


def test_blocks_builder_builds_the_tower_in_the_blocks_world(on_env) -> None:
    agent = on_env("blocks_builder.goal", "blocksworld", {"state": SUSSMAN_TERMS})
    warnings: list[str] = []
    while not agent.terminated and agent.cycle < 30:
        warnings += agent.step().warnings
    assert agent.terminated and agent.goals() == []
    assert pairs(agent, "on(X, Y)") == TOWER
    assert warnings == []  # the environment accepted every move


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_blocks_builder_from_random_towers(on_env, seed: int) -> None:
    agent = on_env("blocks_builder.goal", "blocksworld", {"blocks": 3, "seed": seed}, seed)
    result = agent.run(max_cycles=30)
    assert result.terminated and result.goals_left == []
    assert pairs(agent, "on(X, Y)") == TOWER


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_table_agent_clears_any_world_in_random_order_skipping_internally(
    on_env, seed: int
) -> None:
    agent = on_env("table_agent.goal", "blocksworld", {"seed": seed}, seed)
    actions: list[str] = []
    warnings: list[str] = []
    while not agent.terminated and agent.cycle < 200:
        report = agent.step()
        actions += [a for f in report.fired for a in f.actions]
        warnings += report.warnings
    assert agent.terminated and agent.goals() == []
    blocks = {a["X"] for a in agent.query("bel", "block(X)")}
    assert len(blocks) == 5
    assert pairs(agent, "on(X, Y)") == {(b, "table") for b in blocks}
    assert any(a.startswith("skip") for a in actions)
    assert warnings == []  # skip@int never reached the environment, which would refuse it


def test_table_agent_is_reproducible_under_a_seed(on_env) -> None:
    def trace(seed: int) -> list[str]:
        agent = on_env("table_agent.goal", "blocksworld", {"seed": 1}, seed)
        seen: list[str] = []
        while not agent.terminated and agent.cycle < 200:
            seen += [a for f in agent.step().fired for a in f.actions]
        return seen

    assert trace(7) == trace(7)


def test_tower_builder_uses_the_gripper(on_env) -> None:
    agent = on_env("tower_builder.goal", "towerworld", {"state": SUSSMAN_TERMS})
    actions: list[str] = []
    while not agent.terminated and agent.cycle < 40:
        actions += [a for f in agent.step().fired if f.module == "main" for a in f.actions]
    assert agent.terminated and agent.goals() == []
    assert pairs(agent, "on(X, Y)") == TOWER
    assert not holds(agent, "holding(_)")
    assert [a.split("(")[0] for a in actions if a != "nil"] == [
        "pickup", "putdown", "pickup", "putdown", "pickup", "putdown",
    ]


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_tower_builder_from_random_towers(on_env, seed: int) -> None:
    agent = on_env("tower_builder.goal", "towerworld", {"blocks": 3, "seed": seed}, seed)
    result = agent.run(max_cycles=40)
    assert result.terminated and result.goals_left == []
    assert pairs(agent, "on(X, Y)") == TOWER


# ----------------------------------------------------------------------------- multi-agent


def test_coffee_pair_trades_questions_answers_and_requests(
    systems: list[MultiAgentSystem], capsys: pytest.CaptureFixture[str]
) -> None:
    system = MultiAgentSystem.from_mas_file(EXAMPLES / "coffee.mas2g")
    systems.append(system)
    summaries = system.run(max_cycles=40)
    assert [(s.name, s.status, s.goals_left) for s in summaries] == [
        ("maker", "terminated", 0), ("grinder", "terminated", 0),
    ]
    maker, grinder = system.agents
    assert holds(maker, "have(coffee)") and holds(grinder, "have(grounds)")
    # The moods left their marks: a question, an answer and a request went back and forth.
    assert holds(maker, "sent(grinder, int(canMake(_, _)))")
    assert holds(maker, "received(grinder, canMake(grinder, [grounds]))")
    assert holds(maker, "sent(grinder, imp(have(grounds)))")
    assert capsys.readouterr().out.splitlines() == ["made(coffee)"]


def test_blocks_team_shares_one_world(systems: list[MultiAgentSystem]) -> None:
    system = MultiAgentSystem.from_mas_file(EXAMPLES / "blocks_team.mas2g")
    systems.append(system)
    summaries = system.run(max_cycles=40)
    assert [(s.name, s.status) for s in summaries] == [
        ("builder", "terminated"), ("helper", "terminated"),
    ]
    builder, helper = system.agents
    assert {("a", "b"), ("b", "c"), ("c", "table"), ("d", "table")} == pairs(
        helper, "on(X, Y)"
    )
    assert holds(helper, "wanted(on(a, b))") and holds(helper, "released")
    assert holds(builder, "announced")


def test_goal5_style_coffee_machines_run_unmodified(systems: list[MultiAgentSystem]) -> None:
    """Real GOAL 5 forms at run time: #import, (Var).sendonce, event called as an action, a
    grinder whose main module never exits."""
    system = MultiAgentSystem.from_mas_file(CORPUS / "good" / "coffee5" / "coffee.mas2g")
    systems.append(system)
    summaries = system.run(max_cycles=15)
    assert [(s.name, s.status) for s in summaries][0] == ("maker", "terminated")
    assert summaries[1].cycles == 15 and summaries[1].goals_left == 0
    maker, grinder = system.agents
    assert holds(maker, "have(coffee)") and holds(grinder, "have(grounds)")
    assert holds(maker, "offers(grinder, [grounds])")  # learnt from its answer ...
    assert not holds(maker, "received(_, offers(_, _))")  # ... whose message was then deleted


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_blocks_team_from_random_towers_of_four(
    systems: list[MultiAgentSystem], seed: int
) -> None:
    start = random_towers(["a", "b", "c", "d"], random.Random(seed))
    state: list[Term] = [on(block, below) for block, below in sorted(start.items())]
    system = MultiAgentSystem.from_mas_file(
        EXAMPLES / "blocks_team.mas2g", env_params={"state": state}, seed=seed
    )
    systems.append(system)
    summaries = system.run(max_cycles=60)
    assert [s.status for s in summaries] == ["terminated", "terminated"]
    tower = pairs(system.agents[1], "on(X, Y)")
    assert TOWER <= tower and ("d", "table") in tower


# ----------------------------------------------------------------------------- errors


def test_unknown_action_is_reported_where_it_is_used() -> None:
    text = "main module {\n  program {\n    if true then jump(high).\n  }\n}\n"
    with pytest.raises(GoalSyntaxError) as caught:
        Agent.from_string(text, "jump.goal")
    assert (caught.value.file, caught.value.line, caught.value.col) == ("jump.goal", 3, 18)
    assert "jump" in caught.value.message


# ----------------------------------------------------------------------------- command line


def test_cli_runs_hello_world() -> None:
    done = goalagent("run", "agents/examples/hello_world.goal")
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["Hello, world!"] * 3
    assert "Traceback" not in done.stderr


def test_cli_runs_the_blocks_builder_with_env_params() -> None:
    done = goalagent("run", "agents/examples/blocks_builder.goal", "--env", "blocksworld",
                     "--env-param", f"state={SUSSMAN}", "--max-cycles", "30", "--seed", "3")
    assert done.returncode == 0, done.stderr
    assert done.stdout == ""  # the agent prints nothing; summaries go to stderr
    assert "Traceback" not in done.stderr


def test_cli_coffee_system_ends_with_coffee_made() -> None:
    done = goalagent("run", "agents/examples/coffee.mas2g", "--max-cycles", "40")
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["made(coffee)"]
    summary = done.stderr.splitlines()
    assert any("maker" in line for line in summary) and any("grinder" in line for line in summary)


def test_cli_blocks_team_cooperates_to_the_tower() -> None:
    done = goalagent("run", "agents/examples/blocks_team.mas2g", "--max-cycles", "40")
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["finished"]
    summary = done.stderr.splitlines()
    assert any("builder" in line for line in summary) and any("helper" in line for line in summary)


ENV_ARGS = {
    "script_printer.goal": ["--env", "printer"],
    "blocks_builder.goal": ["--env", "blocksworld", "--env-param", f"state={SUSSMAN}"],
    "table_agent.goal": ["--env", "blocksworld"],
    "tower_builder.goal": ["--env", "towerworld", "--env-param", f"state={SUSSMAN}"],
    "tower_agent.goal": ["--env", "towerworld", "--env-param",
                         "state=[on(a,b), on(b,c), on(c,d), on(d,e), on(e,f), on(f,table)]"],
    "bw4t_robot.goal": ["--env", "bw4t", "--env-param", "map=TwoRooms",
                        "--env-param", "ticks=20"],
    "elevator_car.goal": ["--env", "elevator", "--env-param",
                          "simulation='Three Person Elevator'", "--env-param", "floors=6",
                          "--env-param", "cars=1", "--env-param", "timefactor=5"],
    "hanoi_solver.goal": ["--env", "hanoi"],
}
RUNNABLE = sorted(p.name for p in EXAMPLES.glob("*.goal") if not p.name.startswith("team_")
                  and not p.name.startswith("coffee_")) + ["coffee.mas2g", "blocks_team.mas2g"]


@pytest.mark.parametrize("name", RUNNABLE)
def test_cli_traces_every_example_to_its_end(name: str) -> None:
    done = goalagent("run", f"agents/examples/{name}", *ENV_ARGS.get(name, []),
                     "--max-cycles", "60", "--trace")
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr and "warning" not in done.stderr
    assert "fired" in done.stdout  # the trace shows the rules that fired
    summaries = [line for line in done.stderr.splitlines() if " cycles" in line]
    assert summaries and all("terminated" in line for line in summaries), done.stderr


def test_cli_check_accepts_every_example() -> None:
    paths = sorted(str(p.relative_to(ROOT)) for p in EXAMPLES.iterdir()
                   if p.suffix in (".goal", ".mas2g"))
    done = goalagent("check", *paths)
    assert done.returncode == 0, done.stderr
    assert "warning" not in done.stderr


def test_cli_check_reports_every_broken_file_without_traceback() -> None:
    paths = sorted(BROKEN.glob("*.goal")) + sorted(BROKEN.glob("*.mas2g"))
    done = goalagent("check", *map(str, paths))
    assert done.returncode == 2
    assert "Traceback" not in done.stderr
    for path in paths:
        line, col = path.read_text().splitlines()[0].removeprefix("% expect-error: ").split(":")
        place = f"{path}:{line}:" + ("" if col == "*" else f"{col}: ")
        assert place in done.stderr, f"{path.name}: no {place!r} in\n{done.stderr}"


def test_cli_reports_a_broken_file_on_run_with_exit_code_2() -> None:
    path = BROKEN / "unterminated_comment.goal"
    done = goalagent("run", str(path))
    assert done.returncode == 2
    assert f"{path}:5:9: " in done.stderr
    assert "Traceback" not in done.stderr

"""GOAL 6+'s multi-file format read into the one program model: module files (.mod2g),
action specification files (.act2g), Prolog files used as knowledge, beliefs and goals,
agent definitions and launch policies of .mas2g files, and the newest dialect
(``use m for decisions``); every mistake located."""

from __future__ import annotations

import io
import textwrap
from pathlib import Path

import pytest

from goalagent.mas import MultiAgentSystem
from goalagent.parser import (
    GoalSyntaxError,
    load_agents,
    parse_action_file,
    parse_mas,
    parse_module_file,
)


def write(folder: Path, **files: str) -> None:
    """Files by name (``name_ext`` -> ``name.ext``) with dedented text."""
    for name, text in files.items():
        stem, _, ext = name.rpartition("_")
        (folder / f"{stem}.{ext}").write_text(textwrap.dedent(text))


def test_module_file_options_macros_and_rules(tmp_path: Path) -> None:
    write(tmp_path, stack_mod2g="""
        use blocks as knowledge.
        exit = nogoals.
        order = linearrandom.
        focus = select.
        define clearOne(X) as bel(clear(X)), not(bel(X = table)).
        module stack(N) {
            if clearOne(X) then print(X).
        }
    """)
    module_file = parse_module_file(tmp_path / "stack.mod2g")
    module = module_file.module
    assert (module.declared, module.exit, module.order, module.focus) == (
        "stack", "nogoals", "random", "select")
    assert [p.text for p in module.params] == ["N"]
    assert [u.case for u in module_file.uses] == ["knowledge"]
    (rule,) = module.rules
    assert [lit.query.text for lit in rule.condition if hasattr(lit, "query")] == ["clear(X)"]
    assert module_file.macros[0].name == "clearOne"


def test_action_file_with_internal_and_environment_actions(tmp_path: Path) -> None:
    write(tmp_path, acts_act2g="""
        use blocks as knowledge.
        define move(X, Y) with pre { clear(X) } post { on(X, Y) }
        define note(T) as internal with pre { true } post { noted(T) }
        define skip@int with pre { true } post { true }
        define drop(X)@env with pre { holding(X) } post { true }
    """)
    specs = parse_action_file(tmp_path / "acts.act2g").specs
    assert [(s.name, s.arity, s.internal, s.environment) for s in specs] == [
        ("move", 2, False, False), ("note", 1, True, False), ("skip", 0, True, False),
        ("drop", 1, False, True)]


def test_an_action_named_like_a_builtin_must_say_env(tmp_path: Path) -> None:
    write(tmp_path, acts_act2g="\ndefine insert(X) with pre { true } post { true }\n")
    with pytest.raises(GoalSyntaxError, match="insert is a built-in action") as err:
        parse_action_file(tmp_path / "acts.act2g")
    assert (err.value.line, err.value.col) == (2, 8)


def test_mas_with_environment_definitions_and_launch_instructions() -> None:
    mas = parse_mas(textwrap.dedent("""
        use "..\\envs\\ElevatorSim-1.3.2.jar" as environment with
            Floors = 10, Simulation = "Random Rider Insertion", start = [2, 0].
        define robot as agent {
            use robotInit as init module.
            use robotMain as main.
            use robotEvents as event module.
        }
        define helper as agent { use helper as main module. }
        launchpolicy {
            when * launch robot, helper.
            when type = car launch robot with max = 3.
            when name = boss launch helper with name = chief.
            launch helper with name = extra, number = 2.
        }
    """), "sys.mas2g")
    assert mas.environment == "../envs/ElevatorSim-1.3.2.jar"
    assert [(k, v.text) for k, v in mas.env_init] == [
        ("Floors", "10"), ("Simulation", '"Random Rider Insertion"'), ("start", "[2, 0]")]
    assert [(d.name, [(u.ref, u.case) for u in d.uses]) for d in mas.definitions] == [
        ("robot", [("robotInit", "init"), ("robotMain", "main"), ("robotEvents", "event")]),
        ("helper", [("helper", "main")])]
    rules = [(r.agent_name, r.agentfile, r.on_entity, r.entity_type, r.entity_name, r.max,
              r.number) for r in mas.launches]
    assert rules == [
        ("robot", "robot", True, None, None, None, 1),
        ("helper", "helper", True, None, None, None, 1),
        ("robot", "robot", True, "car", None, 3, 1),
        ("chief", "helper", True, None, "boss", None, 1),
        ("extra", "helper", False, None, None, None, 2)]
    groups = [r.group for r in mas.launches]
    assert groups[0] == groups[1] and len(set(groups)) == 4


def test_goal4_and_goal5_mas_forms() -> None:
    mas = parse_mas(textwrap.dedent("""
        environment {
            "environments\\blocksworld.jar".
            init[start = [0, 1]].
        }
        agentfiles {
            "agents\\IDM.goal" [name = IDM_Driver_Agent].
            "robot.goal".
        }
        launchpolicy {
            when [type = car, max = 2]@env do launch IDM_Driver_Agent.
            launch robot.
            when entity@env do launch * : robot.
        }
    """), "old.mas2g")
    assert mas.environment == "environments/blocksworld.jar"
    assert [(k, v.text) for k, v in mas.env_init] == [("start", "[0,1]")]
    assert [(a.path, a.name) for a in mas.agentfiles] == [
        ("agents/IDM.goal", "IDM_Driver_Agent"), ("robot.goal", "robot")]
    assert [(r.agent_name, r.agentfile, r.on_entity, r.max) for r in mas.launches] == [
        ("IDM_Driver_Agent", "IDM_Driver_Agent", True, 2), ("robot", "robot", False, None),
        ("*", "robot", True, None)]


@pytest.mark.parametrize("text, where, message", [
    ("define a as robot { use m as main. }", (1, 13), "expected 'as agent'"),
    ("define a as agent { use m as knowledge. }", (1, 21), "uses modules as init, main"),
    ("define a as agent { use m as main. }\nlaunchpolicy { launch a with size = 2. }",
     (2, 30), "unknown launch option 'size'"),
    ('use "x.jar" as knowledge.', (1, 16), "as environment only"),
])
def test_mas_mistakes_are_located(text: str, where: tuple[int, int], message: str) -> None:
    with pytest.raises(GoalSyntaxError, match=message) as err:
        parse_mas(text, "bad.mas2g")
    assert (err.value.line, err.value.col) == where


def test_a_launch_of_an_unknown_agent_is_a_located_warning_as_in_goal() -> None:
    mas = parse_mas("define a as agent { use m as main. }\nlaunchpolicy { launch b. }",
                    "bad.mas2g")
    assert mas.launches == ()
    assert mas.warnings[0].startswith("bad.mas2g:2:16: warning: launch refers to unknown "
                                      "agent 'b'")


def test_an_agent_definition_gathers_everything_its_modules_use(tmp_path: Path) -> None:
    (tmp_path / "sub").mkdir()
    write(tmp_path / "sub", facts_pl="colour(red).\ncolour(blue).\n")
    write(tmp_path, sys_mas2g="""
        define a as agent { use sub.main as main module. use init as init. }
        launchpolicy { launch a. }
    """, init_mod2g="""
        use known as knowledge.
        use start as beliefs.
        module init { if true then insert(started). }
    """, known_pl=":- dynamic started/0, seen/1.\n", start_pl="count(0), ready.\n",
          wanted_pl="seen(red), seen(blue).\nquiet.\n",
          act_act2g="""
        use known as knowledge.
        define look(C) as internal with pre { colour(C) } post { seen(C) }
    """)
    write(tmp_path / "sub", main_mod2g="""
        use facts as knowledge.
        use "../known" as knowledge.
        use "../wanted" as goals.
        use "../act" as actionspec.
        use helper.
        module main {
            if a-goal(seen(C)) then look(C).
            if bel(seen(red), seen(blue)) then helper.
        }
    """, helper_mod2g="""
        exit = always.
        module helper { if true then print(done). }
    """)
    programs = load_agents(parse_mas((tmp_path / "sys.mas2g").read_text(),
                                     str(tmp_path / "sys.mas2g")))
    program = programs["a"]
    assert [(m.name, m.kind, m.declared) for m in program.modules] == [
        ("main", "main", "main"), ("init", "init", "init"), ("helper", "user", "helper")]
    assert [k.text for k in program.knowledge] == [
        "colour(red)", "colour(blue)", ":- dynamic started/0, seen/1"]
    assert [b.text for b in program.beliefs] == ["count(0)", "ready"]
    assert [g.text for g in program.goals] == ["seen(red), seen(blue)", "quiet"]
    assert [s.name for s in program.actionspecs] == ["look"]


def test_a_missing_file_is_reported_where_it_is_used(tmp_path: Path) -> None:
    write(tmp_path, sys_mas2g="""
        define a as agent { use m as main module. }
        launchpolicy { launch a. }
    """, m_mod2g="""
        use nowhere as knowledge.
        module m { if true then print(x). }
    """)
    with pytest.raises(GoalSyntaxError,
                       match=r"use nowhere as knowledge: no such file .*nowhere\.pl") as err:
        MultiAgentSystem.from_mas_file(tmp_path / "sys.mas2g")
    assert err.value.file.endswith("m.mod2g") and (err.value.line, err.value.col) == (2, 1)


def test_two_main_modules_and_shutdown_modules_are_refused(tmp_path: Path) -> None:
    write(tmp_path, m_mod2g="module m { if true then print(x). }\n")
    for body, message in [("use m as main. use m as main module.", "two main modules"),
                          ("use m as main. use m as shutdown.", "shutdown modules are not")]:
        mas = parse_mas(f"define a as agent {{ {body} }}", str(tmp_path / "s.mas2g"))
        with pytest.raises(GoalSyntaxError, match=message):
            load_agents(mas)


def test_goal6_system_runs_with_module_calls_and_launch_numbers(tmp_path: Path) -> None:
    write(tmp_path, sys_mas2g="""
        define counter as agent {
            use count as main module.
            use setup as init module.
        }
        launchpolicy { launch counter with name = c, number = 2. }
    """, setup_mod2g="""
        module setup { if true then insert(n(0)). }
    """, count_mod2g="""
        use step as module.
        module count {
            if bel(n(N), N < 2) then step(N).
            if bel(n(2), me(Me)), not(bel(reported)) then print(Me) + insert(reported).
        }
    """, step_mod2g="""
        module step(N) {
            if bel(M is N + 1) then delete(n(N)) + insert(n(M)).
        }
    """)
    system = MultiAgentSystem.from_mas_file(tmp_path / "sys.mas2g", output=io.StringIO())
    try:
        assert [agent.name for agent in system.agents] == ["c1", "c2"]
        system.run(max_cycles=5)
        assert system.output.getvalue().split() == ["c1", "c2"]
        assert [agent.cycle for agent in system.agents] == [5, 5]
    finally:
        system.close()


def test_newest_dialect_bare_conditions_percept_rules_and_unspecified_actions(
        tmp_path: Path) -> None:
    write(tmp_path, sys_mas2g="""
        use blocksworld with state = [on(a, table), on(b, a)].
        define mover {
            use updates for updates.
            use decisions for decisions.
            replace on/2.
            add block/1.
        }
        launchpolicy { when * launch mover. }
    """, updates_mod2g="""
        module updates { if on(b, a) then insert(seen). }
    """, decisions_mod2g="""
        module decisions {
            if on(b, a), not(moved) then move(b, table) + insert(moved).
            if moved, on(b, table), not(reported) then print(done) + insert(reported).
        }
    """)
    system = MultiAgentSystem.from_mas_file(tmp_path / "sys.mas2g", output=io.StringIO())
    try:
        agent = system.agents[0]
        system.run(max_cycles=3)
        assert system.output.getvalue() == "done\n"
        assert agent.query("bel", "on(b, X)") == [{"X": "table"}]
        assert sorted(str(a["X"]) for a in agent.query("bel", "block(X)")) == ["a", "b"]
        assert agent.query("bel", "seen") == [{}]
        assert [s.name for s in agent.program.actionspecs] == ["move"]
    finally:
        system.close()


def test_goal5_module_file_is_still_checked_with_the_single_file_syntax(
        tmp_path: Path) -> None:
    from goalagent.checking import programs_to_check

    write(tmp_path, message_mod2g="""
        module message [exit=always] {
            program { if true then print(hi). }
        }
    """)
    (program,) = programs_to_check(tmp_path / "message.mod2g")
    assert [m.name for m in program.modules] == ["message"]


@pytest.mark.parametrize("text, where, message", [
    ("main module { program { if allother.bel(x(a)) then print(a). } }", (1, 28),
     r"the selector allother.bel\(..\) \(a quantified mental model\) is not supported"),
    ("main module { program { if true then starttimer(t, 10). } }", (1, 38),
     "starttimer takes 3 argument"),
    ("use facts as knowledge.\nmodule m { if true then print(a). }", (1, 1),
     "belong to GOAL 6's multi-file format"),
    ("main module { program { if done(x) then print(a). } }", (1, 28),
     r"done\(...\) is a test condition"),
])
def test_constructs_goalagent_lacks_are_named_where_they_are(
        text: str, where: tuple[int, int], message: str) -> None:
    from goalagent.agent import validate_program
    from goalagent.parser import parse_agent

    with pytest.raises(GoalSyntaxError, match=message) as err:
        validate_program(parse_agent(text, "x.goal"))
    assert (err.value.line, err.value.col) == where

"""Older GOAL text that real programs contain and GOAL itself reads: ``name (args)`` with a
blank (the SWI-Prolog of GOAL 4/5 read it as ``name(args)``), GOAL 3's mood prefix in
``send(Receiver, :content)``, a GOAL 4 environment ``env = "x.jar"`` holding a Windows path,
``define UTbot as agent``; and a GOAL 5 module file's error reported where it is. Each
snippet is taken from a public GOAL program (named in the test). Then what eishub/Starcraft's
GOAL 6 bots showed, each built from GOAL's grammar: backslashes in an environment
parameter's string, a string addressee, file names that differ in case only."""

from __future__ import annotations

import io
import textwrap
from pathlib import Path

import pytest

from goalagent.agent import Agent
from goalagent.checking import check_file
from goalagent.parser import GoalSyntaxError, parse_agent, parse_mas

from .shapes import one_rule


def run_printing(text: str) -> list[str]:
    """The lines an agent prints in its first cycle."""
    agent = Agent.from_string(textwrap.dedent(text), "old.goal", output=io.StringIO(),
                              warn=lambda message: None)
    try:
        agent.run(max_cycles=1)
        return agent.output.getvalue().splitlines()
    finally:
        agent.close()


def test_a_blank_between_a_name_and_its_arguments_is_read_as_goal_4_read_it() -> None:
    # OJAzzIC unaware_medic.goal: if bel(holding(_), in ('DropZone')) then putDown.
    assert run_printing("""
        main module [exit=always] {
            beliefs { holding(b1). in('DropZone'). }
            program { if bel(holding(_), in ('DropZone')) then print(drop). }
        }
    """) == ["drop"]


def test_a_prefix_operator_before_a_parenthesis_keeps_its_blank() -> None:
    # `dynamic (p/1)` is the prefix operator, not dynamic/1 glued: the program still reads
    # and the (unglued) text fails as before where gluing would not help.
    assert run_printing("""
        main module [exit=always] {
            knowledge { :- dynamic (seen/1). ok :- \\+ seen (x), X is 7 mod (2), X == 1. }
            program { if bel(ok) then print(ok). }
        }
    """) == ["ok"]
    with pytest.raises(GoalSyntaxError, match="Prolog syntax error") as err:
        parse_agent("main module { program { if bel(p (a) b) then print(x). } }", "x.goal")
    assert (err.value.line, err.value.col) == (1, 34)


def test_goal_3_mood_prefix_in_send_is_the_message_mood() -> None:
    # OJAzzIC aware_officer.goal: send(REA, :reached(Objective, Sc)); the mood is for
    # messages only.
    program = parse_agent(textwrap.dedent("""
        main module {
            program {
                if bel(fightLocated) then send(middleware, :reached(fightLocatedLmk)).
                if bel(x) then send(middleware, !rescue(b)).
            }
        }
    """), "old.goal")
    sends = [rule.actions[0] for rule in program.module("main").rules]
    assert [(s.receiver.text, s.mood, s.content.text) for s in sends] == [
        ("middleware", ":", "reached(fightLocatedLmk)"), ("middleware", "!", "rescue(b)")]
    with pytest.raises(GoalSyntaxError, match="Prolog syntax error"):
        parse_agent("main module { program { if true then insert(:p). } }", "x.goal")


def test_goal_4_env_string_with_windows_backslashes() -> None:
    # OJAzzIC crisisresponse.mas2g: GOAL reads no escapes in the jar's name.
    mas = parse_mas(textwrap.dedent("""
        environment{
            env= "environments\\BW4T2\\BW4TClient.jar" .
            init = [ clientip ="localhost", agentcount = "14"] .
        }
        agentfiles { "robot.goal". }
        launchpolicy { launch robot. }
    """), "crisisresponse.mas2g")
    assert mas.environment == "environments/BW4T2/BW4TClient.jar"
    assert [(key, value.text) for key, value in mas.env_init] == [
        ("clientip", '"localhost"'), ("agentcount", '"14"')]


def test_an_agent_definition_named_with_a_capital() -> None:
    # eishub UT3 deathmatch/UTbot.mas2g: define UTbot as agent { ... }
    mas = parse_mas(textwrap.dedent("""
        define UTbot as agent {
            use UTbotMain as main.
            use UTbotInit as init.
        }
        launchpolicy { when * launch UTbot. }
    """), "UTbot.mas2g")
    assert [d.name for d in mas.definitions] == ["UTbot"]
    assert [r.agent_name for r in mas.launches] == ["UTbot"]


def test_a_goal_5_module_files_error_is_reported_where_it_is(tmp_path: Path) -> None:
    """The GOAL 6 reading stops at the first line; the GOAL 5 one gets to the real mistake."""
    from goalagent.checking import programs_to_check

    path = tmp_path / "orgReasoning.mod2g"
    path.write_text(textwrap.dedent("""
        module orgReasoning(Agent) {
            program[order=linear] {
                if bel(x(Agent)) then print(a) print(b).
            }
        }
    """))
    with pytest.raises(GoalSyntaxError) as err:
        programs_to_check(path)
    assert (err.value.line, err.value.col) == (4, 40)


def test_a_goal_5_module_file_is_checked_in_the_agent_that_imports_it(tmp_path: Path) -> None:
    """OJAzzIC medic_capabilities.mod2g calls putDown, specified in unaware_medic.goal,
    which #imports it: the module is valid there; with no importer its error stands."""
    from goalagent.checking import programs_to_check

    module = tmp_path / "capabilities.mod2g"
    module.write_text(textwrap.dedent("""
        module locateInjured {
            program { if bel(holding(_)) then putDown. }
        }
    """))
    with pytest.raises(GoalSyntaxError, match="unknown action putDown/0") as err:
        programs_to_check(module)
    assert (err.value.line, err.value.col) == (3, 39)
    # an importer that lacks putDown too is passed over
    (tmp_path / "broken.goal").write_text('#import "capabilities.mod2g".\n'
                                          'main module { program { if true then putDown. } }\n')
    (tmp_path / "medic.goal").write_text(textwrap.dedent("""
        init module { actionspec { putDown { pre { true } post { true } } } }
        main module { program { if true then locateInjured. } }
        #import "capabilities.mod2g".
    """))
    (program,) = programs_to_check(module)
    assert program.file.endswith("medic.goal")
    assert [m.name for m in program.modules][-1] == "locateInjured"


def test_a_bare_comparison_is_a_belief_query_in_the_newest_dialect(tmp_path: Path) -> None:
    """hyunwooOpa/BW4T_single robotUpdate.mod2g (456d395): if block(B, C, 'DropZone'),
    block(B, C, P), P \\= 'DropZone' then delete(block(B, C, P))."""
    from goalagent.mas import MultiAgentSystem

    (tmp_path / "sys.mas2g").write_text(textwrap.dedent("""
        use blocksworld with state = [on(a, table), on(b, a)].
        define mover { use decisions for decisions. replace on/2. }
        launchpolicy { when * launch mover. }
    """))
    (tmp_path / "decisions.mod2g").write_text(textwrap.dedent("""
        module decisions {
            if on(X, Y), Y \\= table, not(seen(X)) then print(X) + insert(seen(X)).
            if on(X, _), X = [a], not(seen(list)) then print(list) + insert(seen(list)).
        }
    """))
    system = MultiAgentSystem.from_mas_file(tmp_path / "sys.mas2g", output=io.StringIO())
    try:
        system.run(max_cycles=2)
        assert system.output.getvalue() == "b\n"
    finally:
        system.close()
    with pytest.raises(GoalSyntaxError, match=r"outside bel\(..\): only the newest") as err:
        parse_agent("main module { program { if bel(p(X)), X > 1 then print(x). } }", "x.goal")
    assert (err.value.line, err.value.col) == (1, 39)


def test_goal_6_environment_parameter_strings_keep_their_backslashes() -> None:
    # GOAL's MAS2G grammar: StringLiteral is '"' ('\\"' | ~[\r\n"])* '"', so a backslash
    # before anything but a quote is itself (Windows paths, map names with '\(').
    mas = parse_mas(textwrap.dedent("""
        use "env.jar" as environment with
            map = "maps\\(4)Arena.scx", home = "C:\\Games", title = "say \\"hi\\"".
        define robot as agent { use robot as main. }
        launchpolicy { launch robot. }
    """), "robots.mas2g")
    assert [(key, value.text) for key, value in mas.env_init] == [
        ("map", '"maps\\\\(4)Arena.scx"'), ("home", '"C:\\\\Games"'),
        ("title", '"say \\"hi\\""')]


@pytest.mark.parametrize("receiver", ['("bob")', "('bob')", "(bob)", "bob"])
def test_a_quoted_name_in_parentheses_addresses_that_agent(receiver: str) -> None:
    # GOAL's selector is a parenthesised term list (PARLIST); a string in it names the agent.
    send = one_rule(f"if true then {receiver}.send(:hi).").actions[0]
    assert send.receiver.text.strip("'") == "bob"
    assert send.content.text == "hi"


def test_a_use_clause_finds_a_file_whose_name_differs_in_case_only(tmp_path: Path) -> None:
    # Windows and macOS file systems, where GOAL programs are written, ignore case.
    (tmp_path / "ZergHatchery.act2g").write_text("define morph with pre { true } post { true }\n")
    (tmp_path / "hatchery.mod2g").write_text(
        "use Zerghatchery as actionspec.\nmodule hatchery { if true then morph. }\n")
    (tmp_path / "Other.act2g").write_text("define a with pre { true } post { true }\n")
    (tmp_path / "OTHER.act2g").write_text("define b with pre { true } post { true }\n")
    lines: list[str] = []
    assert check_file(tmp_path / "hatchery.mod2g", False, lines.append), lines
    (tmp_path / "hatchery.mod2g").write_text(
        "use other as actionspec.\nmodule hatchery { if true then a. }\n")
    lines.clear()  # two files differ from the name in case only: neither is taken
    assert not check_file(tmp_path / "hatchery.mod2g", False, lines.append)
    assert "use other as actionspec: no such file" in "\n".join(lines)


def test_an_agent_file_whose_name_differs_in_case_only_is_found(tmp_path: Path) -> None:
    (tmp_path / "Starport.goal").write_text("main module { program { if true then print(x). } }\n")
    system = tmp_path / "base.mas2g"
    system.write_text('agentfiles { "StarPort.goal". }\nlaunchpolicy { launch port : StarPort. }\n')
    lines: list[str] = []
    assert check_file(system, False, lines.append), lines

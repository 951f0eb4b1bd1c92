"""GOAL's validator verdicts (issue 26): GOAL's grammar tests (``AgentValidatorErrorTest``,
``AgentValidatorWarningTest``, ``AgentSyntaxErrorTest`` and the ``MAS*`` ones of the GOAL
grammar tools, GPL-3, read in tygron-virtual-humans/port-grammar) state for each of their
``test_*.goal`` / ``test_*.mas2g`` files how many syntax errors, errors and warnings GOAL
reports. GOAL's files are not copied here: each case below is a program of our own that
makes the same mistake (or none), named after GOAL's test, with GOAL's verdict: refused
(an error at a place) or accepted (with the warnings GOAL gives, printed).

A file GOAL refuses must be refused by ``goalagent check`` with the error at its place; a
file GOAL accepts must be accepted, its warnings printed. The cases where goalagent's
verdict differs from GOAL's are marked as such (strict xfail) with the reason.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from goalagent.checking import check_file

TEMPLATE = "main module { program { if true then print(hello). } }\n"

# (GOAL's test, files, GOAL's verdict: ("error", "line:col") or ("ok", warnings expected))
AGENT_CASES = [
    ("ACTION_LABEL_ALREADY_DEFINED", """main module {
    program { if bel(c(X)) then act(X). }
    actionspec {
        act(X) { pre { c(X) } post { d(X) } }
        act(Y) { pre { c(Y) } post { e(Y) } }
    }
}
""", ("error", "5:9")),
    ("ACTION_USED_NEVER_DEFINED", """main module {
    knowledge { c(a). }
    program {
        if bel(c(X)) then step(X).
        if bel(c(X)) then walk(X).
    }
    actionspec { step(X) { pre { c(X) } post { true } } }
}
""", ("error", "5:27")),
    ("GOAL_UNINSTANTIATED_VARIABLE", """init module { goals { wanted(X). } }
main module { program { if true then print(hello). } }
""", ("error", "1:23")),
    ("GOALSECTION_NOT_A_QUERY", """init module { goals { happy :- rich. } }
main module { program { if true then print(hello). } }
""", ("error", "1:23")),
    ("IMPORT_MISSING_FILE", """#import "absent.mod2g".
main module { program { if true then print(hello). } }
""", ("error", "1:9")),
    ("KR_SAYS_PARAMETER_INVALID", """main module { program { if true then go(a). } }
module go(a) { program { if true then print(a). } }
""", ("error", "2:11")),
    ("MACRO_DUPLICATE_NAME", """main module {
    program {
        #define near(X, Y) bel(at(X, Y)).
        #define near(A, B) bel(close(A, B)).
        if bel(at(X, _)) then print(X).
    }
}
""", ("error", "4:17")),
    ("MACRO_PARAMETERS_NOT_IN_DEFINITION", """main module {
    beliefs { at(1). }
    program {
        #define here(X, Y) bel(at(X)).
        if here(X, _) then print(X).
    }
}
""", ("error", "4:17")),
    ("POSTCONDITION_UNBOUND_VARIABLE", """main module {
    knowledge { at(a, b). }
    program { if bel(at(A, B)) then move(A, B). }
    actionspec { move(X, Y) { pre { at(X, Z) } post { moved(X, Y, Z, W) } } }
}
""", ("error", "4:55")),
    ("MODULE_MISSING_PROGRAM_SECTION", "main module {\n}\n", ("error", "1:1")),
    ("PROGRAM_NO_MAIN_NOR_EVENT", "init module { program { if true then print(hi). } }\n",
     ("error", "1:1")),
    ("RULE_MISSING_BODY", """main module {
    beliefs { b. }
    program { if bel(b) then. }
}
""", ("error", "3:29")),
    ("RULE_MISSING_CONDITION", "main module { program { if then print(b). } }\n",
     ("error", "1:33")),
    ("RULE_VARIABLE_NOT_BOUND", """main module {
    knowledge { ready. }
    program { if bel(ready) then print(Who). }
}
""", ("error", "3:34")),
    ("SEND_INVALID_SELECTOR", """main module {
    beliefs { b. }
    program {
        if bel(b) then some.send(b).
        if bel(b) then this.send(b).
    }
}
""", ("error", "4:24")),
    ("PROLOG_ANONYMOUS_VARIABLE", """main module {
    program { listall _ <- bel(p(X)) do print(x). }
}
""", ("error", "2:15")),
    ("KR_EXPRESSION_QUERIED_NEVER_DEFINED", """main module {
    knowledge { p :- q. r. }
    program { if bel(p, s), goal(t) then print(x). }
}
""", ("error", "3:25")),
    ("PROLOG_MENTAL_LITERAL_ANONYMOUS_VARIABLE", """main module {
    knowledge { cannot(_). }
    program { if a-goal(cannot(_)) then print(x). }
}
""", ("error", "3:18")),
    ("SELECTOR_VAR_NOT_BOUND", """main module {
    knowledge { on(a, b). }
    program { if (Who).bel(on(a, b)) then print(x). }
}
""", ("error", "3:18")),
    # AgentValidatorWarningTest: accepted with warnings
    ("ACTIONSPEC_DUPLICATE_PARAMETER", """main module {
    program { if true then pair(a, b). }
    actionspec { pair(X, X) { pre { true } post { true } } }
}
""", ("error", "3:18")),
    ("ACTIONSPEC_MISSING_PRE", """main module {
    beliefs { ready. }
    program { if bel(ready) then go. }
    actionspec { go { pre { } post { } } }
}
""", ("ok", ["empty pre", "empty post"])),
    ("EXITMODULE_CANNOT_REACH", """main module {
    beliefs { b. }
    program { if bel(b) then delete(b) + exit-module + insert(b). }
}
""", ("ok", ["insert is never done"])),
    ("INVALID_MODULE_OPTIONS", """main module [focus=none, exit=sometimes] {
    program { if true then log(x). }
}
""", ("error", "1:31")),
    ("MODULE_EMPTY_PROGRAMSECTION", "main module {\n    program {\n    }\n}\n",
     ("ok", ["empty program section"])),
    # AgentSyntaxErrorTest
    ("IMPORT_NOT_A_MOD2G", """#import "other.goal".
main module { program { if true then print(hello). } }
""", ("error", "1:9")),
    ("MODULE_MISSING_NAME", TEMPLATE + "module { program { if true then print(x). } }\n",
     ("error", "2:8")),
    ("CORRECT", """main module {
    knowledge { above(a, b). on(a, b). clear(X) :- \\+ on(_, X). }
    program { if self.bel(above(B, Y) ; B = Y) then sub(a). }
    actionspec { move(X, Y) { pre { clear(X), clear(Y), on(X, Z) } post { true } } }
}
module sub(X) {
    program {
        if (X).bel(on(a, b)) then move(X, table).
        if true then allother.sendonce(?test).
    }
}
""", ("ok", [])),
]

MAS_CASES = [
    ("INIT_UNRECOGNIZED_KEY", """environment { env = "env.jar". init = [""=v]. }
agentfiles { "a.goal". }
launchpolicy { when entity@env do launch a. }
""", ("error", "1:39")),
    ("AGENTFILE_UNKNOWN_KEY", """agentfiles { "a.goal" [name = x, colour = red]. }
launchpolicy { launch x. }
""", ("error", "1:34")),
    ("CONSTRAINT_UNKNOWN_KEY", """environment { env = "env.jar". }
agentfiles { "a.goal" [name = x]. }
launchpolicy { when [type = bot, colour = red]@env do launch * : x. }
""", ("error", "3:34")),
    ("ENVIRONMENT_COULDNOT_FIND", """environment { env = "nowhere.jar". }
agentfiles { "a.goal". }
launchpolicy { when entity@env do launch a. }
""", ("error", "1:21")),
    ("INIT_UNRECOGNIZED_PARAMETER", """environment { env = "env.jar". init = [key=]. }
agentfiles { "a.goal". }
launchpolicy { when entity@env do launch a. }
""", ("error", "1:44")),
    ("AGENTFILE_OTHER_EXTENSION", """agentfiles { "empty.txt". }
launchpolicy { launch empty. }
""", ("error", "1:14")),
    ("AGENTFILE_COULDNOT_FIND", """agentfiles { "absent.goal". }
launchpolicy { launch absent. }
""", ("error", "1:14")),
    ("KRINTERFACE_NOT_SUPPORTED", """agentfiles { "a.goal" [name = x, language = pddl]. }
launchpolicy { launch x. }
""", ("error", "1:34")),
    ("template", "agentfiles {\n}\nlaunchpolicy {\n}\n", ("ok", ["names no agent file",
                                                             "launches no agent"])),
    ("ENVIRONMENT_NO_REFERENCE", """environment { init = [key = value]. }
agentfiles { "a.goal". }
launchpolicy { launch a. }
""", ("error", "1:1")),
    ("ENVIRONMENT_NO_REFERENCE_2", """environment { env = "". init = [key = value]. }
agentfiles { "a.goal". }
launchpolicy { launch a. }
""", ("ok", ['env = "" names no environment'])),
    ("INIT_DUPLICATE_KEY", """environment { env = "env.jar". init = [k = 1, k = 2]. }
agentfiles { "a.goal". }
launchpolicy { when entity@env do launch a. }
""", ("ok", ["init parameter k is given twice"])),
    ("AGENTFILES_DUPLICATE_NAME", """agentfiles { "a.goal". "a.goal". }
launchpolicy { launch a. }
""", ("ok", ["a second agent file called a"])),
    ("AGENTFILES_DUPLICATE_NAME_2", """agentfiles { "a.goal" [name = x]. "b.goal" [name = x]. }
launchpolicy { launch x. }
""", ("ok", ["a second agent file called x"])),
    ("SAME_AGENTFILE_ALIASED_TWICE", """agentfiles { "a.goal" [name = x]. "a.goal" [name = y]. }
launchpolicy { launch x. launch y. }
""", ("ok", [])),
    ("AGENTFILE_DUPLICATE_KEY", """agentfiles {
    "a.goal" [name = x, name = y, language = swiprolog].
}
launchpolicy { launch x. }
""", ("ok", ["option name is given twice"])),
    ("AGENTFILE_UNUSED", """agentfiles { "a.goal". "b.goal". }
launchpolicy { launch a. }
""", ("ok", ["is never launched"])),
    ("AGENTFILE_NONEXISTANT_REFERENCE", """agentfiles { "a.goal" [name = x]. }
launchpolicy { launch nobody. launch x. }
""", ("ok", ["unknown agent 'nobody'"])),
    ("AGENTFILE_NONEXISTANT_REFERENCE_2", """agentfiles { "a.goal" [name = x]. }
launchpolicy { launch a. launch x. }
""", ("ok", ["unknown agent 'a'"])),
    ("LAUNCH_INVALID_WILDCARD", """agentfiles { "a.goal" [name = x]. }
launchpolicy { launch * : x. launch x. }
""", ("ok", ["launch * takes the name of an entity"])),
    ("CONSTRAINT_DUPLICATE", """environment { env = "env.jar". }
agentfiles { "a.goal" [name = x]. }
launchpolicy { when [type = bot, max = 1, type = car]@env do launch * : x. }
""", ("ok", ["entity condition type is given twice"])),
    ("LAUNCH_NO_CONDITIONAL_RULES", """environment { env = "env.jar". }
agentfiles { "a.goal" [name = x]. }
launchpolicy { launch x. }
""", ("ok", ["no conditional launch rule"])),
]

# Where goalagent's verdict is not GOAL's, and why.
DIFFERENT = {
    "KR_EXPRESSION_QUERIED_NEVER_DEFINED": "a predicate defined nowhere is a warning here "
    "(programs insert percept-named facts GOAL's validator cannot see)",
    "PROLOG_MENTAL_LITERAL_ANONYMOUS_VARIABLE": "an anonymous variable in a goal literal is "
    "read as Prolog reads it (GOAL's later grammar dropped this check too: its test is off)",
    "SELECTOR_VAR_NOT_BOUND": "a selector variable is bound by the selector's own query",
    "ENVIRONMENT_COULDNOT_FIND": "an environment jar that is neither shipped nor there is a "
    "warning for check (the program text is valid; run refuses it), as issue 26 asks",
}


def _verdict(tmp_path: Path, name: str, text: str, suffix: str) -> tuple[bool, list[str]]:
    (tmp_path / "a.goal").write_text(TEMPLATE)
    (tmp_path / "b.goal").write_text(TEMPLATE)
    (tmp_path / "env.jar").write_bytes(b"PK")  # GOAL's dummy_environment.jar: present
    (tmp_path / "empty.txt").write_text("")
    path = tmp_path / f"test_{name}{suffix}"
    path.write_text(text)
    lines: list[str] = []
    return check_file(path, False, lines.append), lines


def _matches(tmp_path: Path, name: str, text: str, suffix: str, expected) -> bool:
    accepted, lines = _verdict(tmp_path, name, text, suffix)
    path = tmp_path / f"test_{name}{suffix}"
    kind, detail = expected
    if detail.count(":") == 2:  # the error is in another file of the case
        file, _, detail = detail.partition(":")
        path = tmp_path / file
    if kind == "error":
        return not accepted and any(line.startswith(f"{path}:{detail}: ")
                                    and ": warning: " not in line for line in lines)
    return accepted and all(any(w in line and ": warning: " in line for line in lines)
                            for w in detail)


CASES = [(name, text, ".goal", expected) for name, text, expected in AGENT_CASES] + [
    (name, text, ".mas2g", expected) for name, text, expected in MAS_CASES]


@pytest.mark.parametrize("name, text, suffix, expected", [
    pytest.param(*case, marks=pytest.mark.xfail(strict=True, reason=DIFFERENT[case[0]]))
    if case[0] in DIFFERENT else case for case in CASES], ids=[case[0] for case in CASES])
def test_goal_validator_verdict(tmp_path: Path, name: str, text: str, suffix: str,
                                expected) -> None:
    assert _matches(tmp_path, name, text, suffix, expected)


def test_at_least_nine_in_ten_of_goals_verdicts_are_matched(tmp_path: Path) -> None:
    matched = 0
    for index, (name, text, suffix, expected) in enumerate(CASES):
        case_dir = tmp_path / str(index)
        case_dir.mkdir()
        matched += _matches(case_dir, name, text, suffix, expected)
    assert matched == len(CASES) - len(DIFFERENT)
    assert matched / len(CASES) >= 0.9

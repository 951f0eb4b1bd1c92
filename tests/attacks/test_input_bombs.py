"""Small hostile inputs to the loaders: each is one located error line and exit code 2 (or is
accepted cleanly), never a traceback, a hang or a memory blow-up (issue 19, item 1). Every
command of the module runs in one child, one after the other, each measured alone
(``children``)."""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from pathlib import Path

import pytest

from goalagent.kb.engine import KBError, get_engine
from goalagent.kb.terms import Struct
from goalagent.parser import GoalSyntaxError, parse_agent, parse_mas
from goalagent.parser.conditions import MAX_CONDITION_LITERALS, MAX_MACRO_DEPTH
from goalagent.parser.source import MAX_NESTING, MAX_PROGRAM_BYTES
from tests.measured import Measured, goalagent_measured_each

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

PEAK_MB = 200  # what one of these inputs may cost the whole process


def _doubling_macros(levels: int) -> str:
    lines = ["#define m0 bel(p(X))."]
    lines += [f"#define m{i} m{i - 1}, m{i - 1}." for i in range(1, levels + 1)]
    return "\n".join(lines) + f"\nmain module {{ program {{ if m{levels} then print(x). }} }}\n"


def _growing_arguments(levels: int) -> str:
    lines = ["#define t0(X) bel(p(X, X))."]
    lines += [f"#define t{i}(X) t{i - 1}(f(X, X))." for i in range(1, levels + 1)]
    return "\n".join(lines) + f"\nmain module {{ program {{ if t{levels}(a) then print(x). }} }}\n"


def _macro_chain(levels: int) -> str:
    lines = ["#define c0 bel(p(X))."]
    lines += [f"#define c{i} c{i - 1}." for i in range(1, levels + 1)]
    return "\n".join(lines) + f"\nmain module {{ program {{ if c{levels} then print(x). }} }}\n"


def _many_expansions() -> str:
    wide = "#define w0 " + ", ".join(f"bel(p{i}(X))" for i in range(9)) + ".\n"
    wide += "#define w1 " + ", ".join(["w0"] * 100) + ".\n"
    return wide + "main module { program { " + "if w1 then print(x). " * 100 + "} }\n"


def _condition(query: str) -> str:
    return f"main module {{ program {{ if bel({query}) then print(x). }} }}\n"


BOMBS: dict[str, tuple[str, str, str]] = {
    # name: (file name, text, what the error says)
    "20 doubling macros": ("m.goal", _doubling_macros(20), "expands to more than"),
    "30 doubling macros": ("m.goal", _doubling_macros(30), "expands to more than"),
    "arguments doubling": ("t.goal", _growing_arguments(40), "expands to more than"),
    "a chain of 100 macros": ("c.goal", _macro_chain(100), "macros nested more than"),
    "many expansions": ("w.goal", _many_expansions(), "macros expand to more than"),
    "a 400-deep list": ("l.goal", _condition("X = " + "[" * 400 + "]" * 400), "nested more"),
    "a 5000-deep operator term": ("o.goal", _condition("X = 1" + "+1" * 5000), "nested more"),
    "a 3000-goal body": ("b.goal", "init module { knowledge { p :- " + ", ".join(["true"] * 3000)
                         + ". } }\n" + _condition("p"), "nested more"),
    # a backslash in an agent file is a Windows separator (GOAL 4/5 programs), never an escape
    "a backslash in agentfiles": ("e.mas2g", 'agentfiles { "a\\=b.goal". }\n', "a/=b.goal"),
    "a backslash in #import": ("i.goal", '#import "a\\=.pl".\n' + _condition("p"), "a/=.pl"),
    "an agent file that is /dev/zero": ("z.mas2g", 'agentfiles { "/dev/zero". }\n',
                                        "a device, not a regular file"),
    "an agent file that is a folder": ("d.mas2g", 'agentfiles { "/". }\n',
                                       "a directory, not a regular file"),
    "an unterminated macro call": ("u.goal", "#define m bel(p).\nmain module { program { if "
                                   "m(( then print(x). } }\n", ""),
}


def _bomb_commands(folder: Path) -> dict[str, tuple[Path, list[str]]]:
    """``goalagent check`` of each bomb (files written into ``folder``), by its name."""
    commands = {}
    for index, (name, (file, text, _)) in enumerate(BOMBS.items()):
        path = folder / str(index) / file
        path.parent.mkdir()
        path.write_text(text)
        commands[f"bomb {name}"] = (path, ["check", str(path)])
    return commands


@pytest.fixture(scope="module")
def children(tmp_path_factory: pytest.TempPathFactory) -> dict[str, tuple[Path, Measured]]:
    """Every ``goalagent`` command of this module, one after the other in one child, each
    measured alone (its streams, seconds, and peak: the child resets it before each), by
    name: the command's file and what it did. The one that grows the process for good
    (printing the deep term) comes last, after every peak the tests bound."""
    commands = {}  # each group in a folder of its own (two of them write a huge.goal)
    for make in (_bomb_commands, _unreadable_commands, _accepted_commands, _deep_commands):
        commands.update(make(tmp_path_factory.mktemp(make.__name__.strip("_"))))
    results = goalagent_measured_each(*(args for _, args in commands.values()))
    return {name: (path, result)
            for (name, (path, _)), result in zip(commands.items(), results, strict=True)}


@pytest.fixture(scope="module")
def checked(children: dict[str, tuple[Path, Measured]]) -> dict[str, tuple[Path, Measured]]:
    """``goalagent check`` of each bomb, by name: the bomb's path and what the check did."""
    return {name: children[f"bomb {name}"] for name in BOMBS}


@pytest.mark.parametrize("name", list(BOMBS))
def test_each_bomb_is_one_located_error_line_with_exit_2(
        name: str, checked: dict[str, tuple[Path, Measured]]):
    _, _, says = BOMBS[name]
    path, result = checked[name]
    assert result.returncode == 2, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert re.match(rf"{re.escape(str(path))}:\d+:\d+: \S", lines[0]), lines[0]
    assert says in lines[0]
    assert result.peak_mb < PEAK_MB, result.peak_mb


def _unreadable_commands(folder: Path) -> dict[str, tuple[Path, list[str]]]:
    """``goalagent check`` of a FIFO and of a huge sparse file."""
    fifo = folder / "agent.goal"
    os.mkfifo(fifo)  # nobody writes: reading it would wait for ever
    huge = folder / "huge.goal"
    with huge.open("wb") as stream:
        stream.truncate(MAX_PROGRAM_BYTES * 50)
    return {"fifo": (fifo, ["check", str(fifo)]), "huge": (huge, ["check", str(huge)])}


def test_a_fifo_or_a_huge_sparse_file_is_refused_before_reading(
        children: dict[str, tuple[Path, Measured]]):
    for (path, result), says in ((children["fifo"], "a FIFO, not a regular file"),
                                 (children["huge"], "larger than")):
        assert result.returncode == 2
        assert result.stderr.strip() == f"{path}:1:1: cannot read file: " + (
            says if says != "larger than" else
            f"{MAX_PROGRAM_BYTES * 50} bytes: larger than the {MAX_PROGRAM_BYTES} bytes "
            "accepted")
        assert result.peak_mb < PEAK_MB


ACCEPTED = {  # name: an agent file's bytes, which must run to its end
    "latin1": b"% caf\xe9 au lait\nmain module [exit=always] {\n"
              b"  program { if true then print('caf\xe9'). }\n}\n",
    "big": ("init module { beliefs { big(" + "7" * 5000 + "). } }\n"
            "main module [exit=always] { program {\n"
            "  if bel(big(B), X is B * 10^5000) then print(X). } }\n").encode(),
    "huge": b"main module [exit=always] { program {\n"
            b"  if bel(X is 10^200000) then print(X). } }\n",
}


def _accepted_commands(folder: Path) -> dict[str, tuple[Path, list[str]]]:
    """``goalagent run`` of each ACCEPTED program."""
    commands = {}
    for name, text in ACCEPTED.items():
        path = folder / f"{name}.goal"
        path.write_bytes(text)
        commands[f"accepted {name}"] = (path, ["run", str(path)])
    return commands


@pytest.fixture(scope="module")
def ran(children: dict[str, tuple[Path, Measured]]) -> dict[str, Measured]:
    """What ``goalagent run`` of each ACCEPTED program did, by name."""
    return {name: children[f"accepted {name}"][1] for name in ACCEPTED}


def test_text_that_is_not_utf8_is_read_as_latin1_as_goal_read_it(ran: dict[str, Measured]):
    result = ran["latin1"]
    assert result.returncode == 0
    assert result.stdout.strip() == "caf\u00e9"


def test_a_huge_integer_is_accepted_and_printed_whole(ran: dict[str, Measured]):
    result = ran["big"]
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "7" * 5000 + "0" * 5000


def test_an_integer_too_long_for_python_is_printed_by_prolog_whole(ran: dict[str, Measured]):
    result = ran["huge"]
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "1" + "0" * 200000
    assert result.cpu_seconds < 5 and result.peak_mb < 200


def test_an_integer_too_long_to_convert_to_python_is_refused_cleanly():
    with pytest.raises(KBError, match="an integer of more than 100,000 digits is too large"):
        get_engine().call("is", None, Struct("^", (10, 200000)), module="system")


@pytest.mark.parametrize("make, says", [
    (lambda: "(" * (MAX_NESTING + 1) + ")" * (MAX_NESTING + 1), "brackets nested more than"),
    (lambda: "f(" * (MAX_NESTING + 1) + "a" + ")" * (MAX_NESTING + 1), "nested more than"),
])
def test_nesting_is_bounded_in_queries_with_the_position(make: Callable[[], str], says: str):
    with pytest.raises(GoalSyntaxError, match=says) as caught:
        parse_agent(_condition("X = " + make()), "deep.goal")
    assert caught.value.line == 1 and caught.value.col > 30


def test_nesting_just_within_the_bounds_is_accepted():
    depth = 150
    program = parse_agent(_condition("X = " + "f(" * depth + "a" + ")" * depth), "ok.goal")
    assert program.modules[0].rules


def test_the_limits_leave_ordinary_macro_use_alone():
    chain = [f"#define c{i} c{i - 1}." for i in range(1, MAX_MACRO_DEPTH)]
    doubling = [f"#define m{i} m{i - 1}, m{i - 1}." for i in range(1, 9)]
    text = "\n".join(["#define c0 bel(q(X)).", *chain, "#define m0 bel(p(X)).", *doubling])
    text += (f"\nmain module {{ program {{ if m8 then print(x). "
             f"if c{MAX_MACRO_DEPTH - 1} then print(y). }} }}\n")
    program = parse_agent(text, "ok.goal")
    conditions = [rule.condition for module in program.modules for rule in module.rules]
    assert len(conditions[0]) == 2**8 <= MAX_CONDITION_LITERALS
    assert len(conditions[1]) == 1


def test_a_backslash_in_a_mas_agent_file_is_a_windows_separator_not_an_escape():
    mas = parse_mas('environment { env = "blocksworld". }\nagentfiles { "a\\=b.goal". }\n',
                    "x.mas2g")
    assert [agentfile.path for agentfile in mas.agentfiles] == ["a/=b.goal"]


def _deep_commands(folder: Path) -> dict[str, tuple[Path, list[str]]]:
    """A run loading a belief file nested too deep, then one printing a term too deep for
    SWI-Prolog's writer."""
    deep = folder / "deep.pl"
    deep.write_text("f(" + "[" * 100_000 + "]" * 100_000 + ").\n")
    program = folder / "a.goal"
    program.write_text(_condition("true"))
    printing = folder / "deep.goal"
    printing.write_text("init module { knowledge { nest(0, a) :- !.\n"
                        "    nest(N, f(T)) :- N1 is N - 1, nest(N1, T). } }\n"
                        "main module [exit=always] { program [order=linearall] {\n"
                        "    if bel(X = 1) then print(X).\n"
                        "    if bel(nest(1000000, T)) then print(T).\n"
                        "    if true then print(after). } }\n")
    return {"deep beliefs": (deep, ["run", str(program), "--load-beliefs", str(deep),
                                    "--max-cycles", "1"]),
            "deep print": (printing, ["run", str(printing)])}


def test_a_belief_file_nested_too_deep_is_refused_before_swi_reads_it(
        children: dict[str, tuple[Path, Measured]]):
    deep, result = children["deep beliefs"]
    assert result.returncode == 2, result.stderr  # it was a segmentation fault (-11)
    assert result.stderr == f"error: {deep}:1:202: brackets nested more than 200 deep\n"


def test_printing_a_term_too_deep_for_swis_writer_is_the_agents_problem(
        children: dict[str, tuple[Path, Measured]]):
    _, result = children["deep print"]
    assert result.returncode in (0, 1), result.stderr  # it was a segmentation fault (-11)
    assert result.stdout.splitlines()[0] == "1"
    assert "Traceback" not in result.stderr

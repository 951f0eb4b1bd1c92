"""What ``goalagent check`` does: for each file (or every program file under a directory) the
programs it holds or names are parsed and validated (``goalagent.agent.validate_program``),
the environment a ``.mas2g`` names and its init parameters are checked, and calls in
``bel``/precondition queries of predicates defined nowhere are warnings. The command line
(``goalagent.cli``) only prints what :func:`check_file` reports.
"""

from __future__ import annotations

import difflib
import io
import re
from collections.abc import Callable, Iterator
from pathlib import Path

from goalagent import ast
from goalagent.agent import Agent, AgentError, validate_program
from goalagent.agent.checks import program_errors
from goalagent.agent.validator import structure_warnings
from goalagent.eis.exceptions import EnvironmentInterfaceException
from goalagent.eis.interface import Environment
from goalagent.eis.registry import known_environments, load_environment
from goalagent.kb.engine import KBError, get_engine
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Atom, Struct, Term, Var, format_term
from goalagent.parser import (
    GoalSyntaxError,
    load_agents,
    load_module_as_agent,
    parse_action_file,
    parse_agent,
    parse_agent_file,
    parse_mas,
    parse_mas_file,
    parse_prolog_file,
    parse_test_file,
)
from goalagent.parser.recovery import later_errors
from goalagent.parser.source import read_program_file

SYSTEM_SUFFIXES = (".goal", ".mas2g", ".test2g")
# Control constructs whose arguments are goals (argument positions), and meta-calls.
_CONTROL = {(",", 2): (0, 1), (";", 2): (0, 1), ("->", 2): (0, 1), ("*->", 2): (0, 1),
            ("\\+", 1): (0,), ("not", 1): (0,), ("call", 1): (0,), ("once", 1): (0,),
            ("ignore", 1): (0,), ("forall", 2): (0, 1), ("findall", 3): (1,),
            ("findall", 4): (1,), ("bagof", 3): (1,), ("setof", 3): (1,),
            ("aggregate_all", 3): (1,), ("aggregate_all", 4): (2,), ("^", 2): (1,)}
# Predicates every belief base has (the mental state defines them).
_MENTAL_STATE = {("percept", 1), ("received", 2), ("sent", 2), ("me", 1), ("agent", 1)}


def did_you_mean(name: str, known: list[str]) -> str:
    """`` (did you mean X?)`` for the closest known name, or nothing."""
    close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
    return f" (did you mean {close[0]}?)" if close else ""


def files_to_check(path: Path) -> list[Path]:
    """``path`` itself, or every agent and system under a directory (sorted): ``.goal``,
    ``.mas2g`` and ``.test2g`` files (module, action and Prolog files are checked as the
    systems that use them)."""
    if not path.is_dir():
        return [path]
    return sorted(p for p in path.rglob("*") if p.suffix in SYSTEM_SUFFIXES and p.is_file())


def importers_of(module_file: Path) -> list[Path]:
    """The agent and module files next to a GOAL 5 module file that ``#import`` it (sorted):
    GOAL checks such a file in its importer, whose actions and knowledge it may use."""
    pattern = re.compile(r'#import\s+"' + re.escape(module_file.name) + '"')
    return sorted(p for p in module_file.parent.iterdir()
                  if p.suffix in (".goal", ".mod2g") and p != module_file and p.is_file()
                  and pattern.search(p.read_text(encoding="utf-8", errors="replace")))


def check_environment(mas: ast.MasProgram) -> list[str]:
    """The environment a ``.mas2g`` names exists and takes the init parameters it is given
    (``GoalSyntaxError`` at the environment or the parameter otherwise). A GOAL environment
    jar that goalagent has no counterpart for is a warning (returned): the program is not
    wrong, it only cannot run here."""
    if not mas.environment:
        return []
    pos = mas.env_pos or mas.pos
    try:
        environment = load_environment(mas.environment)
    except EnvironmentInterfaceException as err:
        if mas.environment.lower().endswith(".jar"):
            where = ("" if (Path(mas.file).parent / mas.environment).is_file() else
                     " (and no such file is next to the system)")
            return [f"{pos}: warning: environment '{mas.environment}' is a GOAL environment "
                    f"goalagent does not ship{where}: the system checks, but cannot run here"]
        hint = did_you_mean(mas.environment, known_environments())
        raise GoalSyntaxError.at(pos, f"{err}{hint}") from None
    for key, value in mas.env_init:
        problem = unknown_parameter(environment, mas.environment, key)
        if problem is not None:
            raise GoalSyntaxError.at(value.pos, problem)
    return []


def unknown_parameter(environment: type[Environment], name: str, key: str) -> str | None:
    """What is wrong with init parameter ``key`` of ``environment`` (registered as
    ``name``), with the closest known name; None when it takes it (or declares nothing)."""
    parameters = environment.init_parameters()
    if parameters is None or environment.init_key(key) in parameters:
        return None
    known = sorted(parameters)
    return (f"environment '{name}' has no init parameter {key!r}"
            f"{did_you_mean(environment.init_key(key), known)}; its parameters: "
            f"{', '.join(known) or 'none'}")


def undefined_calls(agent: Agent) -> list[str]:
    """Warnings for calls, in ``bel`` queries and preconditions, of predicates that are not
    built in (nor in a library) and that no knowledge, belief, dynamic declaration or update
    of the agent defines."""
    warnings: list[str] = []
    seen: set[tuple[str, int]] = set()
    known = sorted({str(answer["N"]) for answer in agent.query(
        "bel", "current_predicate(N/A), \\+ sub_atom(N, 0, _, _, '$'), functor(H, N, A), "
        "\\+ predicate_property(H, imported_from(_)), \\+ predicate_property(H, built_in)")})
    for query in _queries(agent.program):
        try:
            term = get_engine().parse_term(query.text)
        except KBError:
            continue  # unreadable texts are reported where they are compiled
        for name, arity in _calls(term):
            key = (name, arity)
            if key in _MENTAL_STATE or key in seen:
                continue
            seen.add(key)
            head = format_term(Struct(name, (Var("_"),) * arity) if arity else Atom(name))
            if agent.query("bel", f"predicate_property({head}, defined)"):
                continue
            warnings.append(f"{query.pos}: warning: {name}/{arity} is called but defined "
                            f"nowhere (not built in, not in knowledge or beliefs, never "
                            f"inserted){did_you_mean(name, known)}")
    return warnings


def _queries(program: ast.AgentProgram) -> Iterator[ast.PrologText]:
    """The Prolog queries run against the belief base: bel(...) and preconditions."""
    for module in program.modules:
        for rule in ast.iter_rules(module.rules):
            yield from _bel_queries(rule.condition)
    for spec in program.actionspecs:
        yield spec.pre


def _bel_queries(condition: ast.Condition) -> Iterator[ast.PrologText]:
    for literal in condition:
        if isinstance(literal, ast.NotLiteral):
            yield from _bel_queries(literal.condition)
        elif literal.op == "bel" and literal.query is not None:
            yield literal.query


def _calls(term: Term) -> Iterator[tuple[str, int]]:
    """The predicates a goal calls (through control constructs; not inside meta-calls whose
    goal is a variable)."""
    if isinstance(term, Var) or not isinstance(term, (Atom, Struct)):
        return
    name, args = (str(term), ()) if isinstance(term, Atom) else (term.name, term.args)
    if name == ":" and len(args) == 2:  # module-qualified: someone else's predicate
        return
    goals = _CONTROL.get((name, len(args)))
    if goals is None:
        yield name, len(args)
        return
    for index in goals:
        yield from _calls(args[index])


MAX_REPORTED = 20
"""Errors ``check`` prints per file; the rest are counted ("and N more")."""


def check_file(path: Path, sandbox: bool, report: Callable[[str], None]) -> bool:
    """Checks one program file, telling ``report`` every warning and every error line (up to
    ``MAX_REPORTED``, then how many more); True when it has no error. Each agent is loaded
    as ``run`` would (``sandbox``: as ``--sandbox`` would) but runs none of its code
    (``Limits.runs_code``): its directives are checked, not run, and its goals are not
    adopted."""
    errors: list[GoalSyntaxError] = []
    try:
        if path.suffix == ".mas2g":
            mas = parse_mas_file(path)
            for warning in mas.warnings:
                report(warning)
            try:
                for warning in check_environment(mas):
                    report(warning)
            except GoalSyntaxError as err:
                errors.append(err)
        for program in programs_to_check(path, report):
            errors += program_errors(program)
            for warning in (*program.warnings, *structure_warnings(program)):
                report(warning)
            if errors:
                continue
            if path.suffix == ".mod2g" and not sandbox:
                continue  # a module alone lacks its agent's knowledge: no calls to look up
            agent = Agent(program, output=io.StringIO(), warn=lambda message: None,
                          limits=Limits(sandbox=sandbox, runs_code=False))
            try:
                if path.suffix != ".mod2g":
                    for warning in undefined_calls(agent):
                        report(warning)
            finally:
                agent.close()
    except GoalSyntaxError as err:
        errors += [err, *_later_syntax_errors(path, err)]
    except AgentError as err:
        errors += [err]  # type: ignore[list-item]
    for error in errors[:MAX_REPORTED]:
        report(str(error))
    if len(errors) > MAX_REPORTED:
        report(f"{path}: and {len(errors) - MAX_REPORTED} more errors")
    return not errors


def _later_syntax_errors(path: Path, first: GoalSyntaxError) -> list[GoalSyntaxError]:
    """The syntax errors of a .goal or .mas2g file after its first (none for other files,
    or when the first is in a file it uses)."""
    def parse(text: str, file: str) -> object:
        if path.suffix == ".mas2g":
            return parse_mas(text, file)
        return program_errors(parse_agent(text, file))

    if path.suffix in (".mod2g", ".act2g", ".pl", ".test2g") or first.file != str(path):
        return []
    try:
        text = read_program_file(path)
    except GoalSyntaxError:
        return []
    return later_errors(text, str(path), first, parse)


def programs_to_check(path: Path, report: Callable[[str], None] = lambda line: None
                      ) -> list[ast.AgentProgram]:
    """The agent programs a file holds or names: a system's agents (any GOAL version), a
    module file as its own agent, a test's system; action and Prolog files are only read."""
    if path.suffix == ".mas2g":
        return list(load_agents(parse_mas_file(path)).values())
    if path.suffix == ".test2g":
        return list(load_agents(parse_mas_file(parse_test_file(path).mas)).values())
    if path.suffix == ".mod2g":
        try:
            return [load_module_as_agent(path)]
        except GoalSyntaxError as err:
            try:  # a GOAL 5 module file is written in the single-file syntax
                module = parse_agent_file(path)
            except GoalSyntaxError as goal5:
                # report the reading that got further into the file
                further = (goal5.file, goal5.line, goal5.col) > (err.file, err.line, err.col)
                raise (goal5 if further and goal5.file == err.file else err) from None
            return [_goal5_module_in_context(path, module, report)]
    if path.suffix == ".act2g":
        parse_action_file(path)
        return []
    if path.suffix == ".pl":
        parse_prolog_file(path)
        return []
    return [parse_agent_file(path)]


def _goal5_module_in_context(path: Path, module: ast.AgentProgram,
                             report: Callable[[str], None]) -> ast.AgentProgram:
    """A GOAL 5 module file valid on its own, else the first agent next to it that
    ``#import``s it and is valid with it (the module may use that agent's actions); the
    module's own error when there is none."""
    try:
        validate_program(module)
        return module
    except GoalSyntaxError as alone:
        for importer in importers_of(path):
            try:
                program = parse_agent_file(importer)
                validate_program(program)
            except GoalSyntaxError:
                continue
            report(f"{path}: checked as part of {importer.name}, which imports it")
            return program
        raise alone from None

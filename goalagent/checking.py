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
from goalagent.eis.exceptions import EnvironmentInterfaceException
from goalagent.eis.registry import known_environments, load_environment
from goalagent.kb.engine import KBError, get_engine
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Atom, Struct, Term, Var, format_term
from goalagent.parser import (
    GoalSyntaxError,
    load_agents,
    load_module_as_agent,
    parse_action_file,
    parse_agent_file,
    parse_mas_file,
    parse_prolog_file,
    parse_test_file,
)

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
            return [f"{pos}: warning: environment '{mas.environment}' is a GOAL environment "
                    "goalagent does not ship: the system checks, but cannot run here"]
        hint = did_you_mean(mas.environment, known_environments())
        raise GoalSyntaxError.at(pos, f"{err}{hint}") from None
    parameters = getattr(environment, "parameters", None)
    if parameters is None:
        return []
    for key, value in mas.env_init:
        if key not in parameters:
            known = sorted(parameters)
            raise GoalSyntaxError.at(
                value.pos, f"environment '{mas.environment}' has no init parameter {key!r}"
                f"{did_you_mean(key, known)}; its parameters: {', '.join(known) or 'none'}")
    return []


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


def check_file(path: Path, sandbox: bool, report: Callable[[str], None]) -> bool:
    """Checks one program file, telling ``report`` every warning and error line; True when
    it has no error. Each agent is loaded as ``run`` would (``sandbox``: as ``--sandbox``
    would) but runs none of its code (``Limits.runs_code``): its directives are checked,
    not run, and its goals are not adopted."""
    try:
        if path.suffix == ".mas2g":
            for warning in check_environment(parse_mas_file(path)):
                report(warning)
        for program in programs_to_check(path, report):
            validate_program(program)
            for warning in program.warnings:
                report(warning)
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
    except (GoalSyntaxError, AgentError) as err:
        report(str(err))
        return False
    return True


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

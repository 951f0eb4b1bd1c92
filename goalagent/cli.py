"""The ``goalagent`` command: run agents and multi-agent systems, check programs.

User mistakes (a malformed file, an unknown environment, a bad parameter) print one
``file:line:col: message`` line on stderr and exit with code 2, never a traceback.
Installed extensions (``goalagent.extensions``) add commands, ``run`` options and run hooks:
``main`` builds the command line from the language's commands and theirs.
"""

from __future__ import annotations

import contextlib
import inspect
import os
import sys
from collections.abc import Callable, Sequence
from importlib import metadata
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console

from goalagent.agent import AgentError
from goalagent.agent.problems import cause_traceback
from goalagent.beliefs import BeliefSaver, SaveInterval, load_beliefs
from goalagent.checking import check_file, did_you_mean, files_to_check, unknown_parameter
from goalagent.commandline import HELP_OPTIONS, RunCommand, readable_metavars
from goalagent.console import USER_ERROR, err_console, user_error
from goalagent.debugger import Debugger, DebuggerError, FrontEnd
from goalagent.eis.exceptions import EnvironmentInterfaceException
from goalagent.eis.registry import known_environments, load_environment
from goalagent.extensions import (
    Extension,
    RunContext,
    RunHook,
    SavedPredicate,
    installed_extensions,
)
from goalagent.extras import install_hint
from goalagent.kb.engine import KBError
from goalagent.kb.limits import Limits, default_module_depth
from goalagent.mas import MultiAgentSystem, ParameterText
from goalagent.parser import GoalSyntaxError, parse_mas_file
from goalagent.runner import Run
from goalagent.stepper import TerminalStepper
from goalagent.testing import run_test_file
from goalagent.trace import TraceKindError, TracePrinter, parse_kinds
from ondisk import check_target

HELP = "Run GOAL agent programs whose beliefs live in SWI-Prolog."
MAX_SAVED_ARITY = 255  # --save-predicate: larger arities are surely mistakes

# The limits and confinement options of run and test (goalagent.kb.limits).
MaxInferences = Annotated[int, typer.Option(
    help="Inferences one rule of an agent may make before it is not applicable.")]
MaxQuerySeconds = Annotated[float, typer.Option(
    help="Seconds Prolog may run for an agent without returning (then the rule is not "
         "applicable).")]
MaxBeliefs = Annotated[int, typer.Option(
    help="Beliefs and goals an agent may hold before it is stopped.")]
MaxMemory = Annotated[int, typer.Option(
    help="Megabytes an agent's clauses (with their atoms) may hold, and one of its calls take "
         "outside Prolog's stacks, before it is stopped.")]
Sandbox = Annotated[bool, typer.Option(
    help="Agents' Prolog may call only safe built-ins (no files, OS, flags, ...).")]
DEFAULT_MODULE_DEPTH = default_module_depth()  # (as the C stack allows: read once)
MaxModuleDepth = Annotated[int, typer.Option(
    help="How deep module calls may nest before the agent is stopped (default: as deep as "
         "the C stack safely allows).")]
MaxAgents = Annotated[int | None, typer.Option(
    min=1, help="How many agents the run may launch (default: as many as 3/4 of the memory "
                "available holds, 64 KiB each); a .mas2g launching more is refused.")]


def _env_params(pairs: list[str]) -> dict[str, ParameterText]:
    """``--env-param KEY=VALUE`` pairs, each value kept as typed until the environment says
    whether it is a path (``goalagent.mas.read_parameter``)."""
    params: dict[str, ParameterText] = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key.strip():
            raise user_error(f"--env-param {pair!r}: expected KEY=VALUE")
        params[key.strip()] = ParameterText(value.strip())
    return params


def _saved_predicates(indicators: list[str],
                      extensions: Sequence[Extension]) -> tuple[SavedPredicate, ...]:
    """The extensions' saved predicates, then those named by ``--save-predicate NAME/ARITY``
    (an extension's own comes first when both name it)."""
    chosen = {p.indicator: p for e in extensions for p in e.saved_predicates}
    for indicator in indicators:
        name, sep, arity = indicator.strip().rpartition("/")
        if not sep or not name or not arity.isdigit() or int(arity) > MAX_SAVED_ARITY:
            raise user_error(f"--save-predicate {indicator!r}: expected NAME/ARITY, "
                             "e.g. visited/2")
        chosen.setdefault(f"{name}/{int(arity)}", SavedPredicate(name, int(arity)))
    return tuple(chosen.values())


def _trace_printer(kinds: str | None, file: Path | None) -> TracePrinter | None:
    """The ``--trace[=KINDS]`` / ``--trace-file F`` listener (None: no trace)."""
    if kinds is None and file is None:
        return None
    try:
        chosen, idle = parse_kinds(kinds or "all")
        return TracePrinter(chosen, idle, file=file)
    except TraceKindError as err:
        raise user_error(str(err)) from None
    except OSError as err:
        raise user_error(f"--trace-file {file}: {err.strerror or err}") from None


def _close_trace(printer: TracePrinter) -> bool:
    """Put the trace file in place; False (said on stderr) when it could not be written."""
    try:
        printer.close()
        return True
    except OSError as err:
        err_console.print(f"error: --trace-file: {err}", markup=False)
        return False


def _language_run_options(
    path: Annotated[Path, typer.Argument(help="A .goal agent file or a .mas2g system file.")],
    env: Annotated[str | None, typer.Option(help="Environment name or module:Class.")] = None,
    env_param: Annotated[
        list[str] | None,
        typer.Option("--env-param", help="KEY=VALUE environment init parameter (a Prolog "
                                          "term; a file name for a path parameter)."),
    ] = None,
    max_cycles: Annotated[int | None, typer.Option(help="Stop after this many cycles.")] = None,
    seed: Annotated[int, typer.Option(help="Seed for rule order and Prolog's random.")] = 0,
    trace: Annotated[str | None, typer.Option(
        help="Show what the agents do, per agent and cycle: --trace for everything, "
             "--trace KINDS (or --trace=KINDS) to choose, comma-separated: percepts, rules, "
             "actions, beliefs, goals, messages, warnings, modules; idle adds rules tried "
             "with no instantiation.")] = None,
    trace_file: Annotated[Path | None, typer.Option(
        help="Write the trace to this file instead of stdout (JSON lines when it ends in "
             ".jsonl).")] = None,
    load_beliefs: Annotated[
        Path | None, typer.Option(help="Prolog facts (e.g. saved afford/6) to add to the "
                                       "agents' beliefs before they start.")] = None,
    save_beliefs: Annotated[
        Path | None, typer.Option(help="Write the final beliefs of the saved predicates here "
                                       "(those extensions declare, e.g. afford/6, and "
                                       "--save-predicate).")] = None,
    save_predicate: Annotated[
        list[str] | None, typer.Option("--save-predicate", help="NAME/ARITY of a predicate "
                                       "--save-beliefs also writes (repeatable).")] = None,
    save_every: Annotated[
        str, typer.Option(help="How often --save-beliefs saves during the run: cycles (100), "
                               "seconds (30s), minutes (5m), or 'end'.")] = "30s",
    step: Annotated[bool, typer.Option(
        help="Stop after each cycle with a prompt on the terminal (? lists its commands).")
    ] = False,
    breakpoint: Annotated[list[str] | None, typer.Option(
        "--break", help="Stop when the rule at FILE:LINE applies or when a condition such as "
                        "bel(done) becomes true, then prompt (repeatable).")] = None,
    inspect: Annotated[bool, typer.Option(
        help="Serve the mind inspector, a web page showing each agent live with pause, "
             "step, breakpoints and queries; the run starts paused.")] = False,
    port: Annotated[int, typer.Option(min=0, max=65535,
                                      help="The inspector's port (0: any free one).")] = 8765,
    host: Annotated[str, typer.Option(
        help="The address the inspector listens on (only this machine by default).")
    ] = "127.0.0.1",
    max_inferences: MaxInferences = Limits.max_inferences,
    max_query_seconds: MaxQuerySeconds = Limits.max_query_seconds,
    max_beliefs: MaxBeliefs = Limits.max_beliefs,
    max_memory: MaxMemory = Limits.max_memory,
    sandbox: Sandbox = False,
    max_module_depth: MaxModuleDepth = DEFAULT_MODULE_DEPTH,
    max_agents: MaxAgents = None,
) -> None:
    """The language's own ``run`` options (its signature is the start of ``run``'s)."""


def _run_command(extensions: Sequence[Extension]) -> Callable[..., None]:
    """``run`` with the language's options followed by those the extensions add."""
    parameters = list(inspect.signature(_language_run_options, eval_str=True).parameters.values())
    taken = {parameter.name for parameter in parameters}
    for extension in extensions:
        for option in extension.run_options:
            if option.name in taken:
                err_console.print(f"warning: goalagent extension {extension.name!r}: run option "
                                  f"--{option.name.replace('_', '-')} is already taken",
                                  markup=False)
                continue
            taken.add(option.name)
            annotation = Annotated[option.type | None, typer.Option(help=option.help)]
            parameters.append(inspect.Parameter(option.name, inspect.Parameter.KEYWORD_ONLY,
                                                default=option.default, annotation=annotation))

    def run(**values: Any) -> None:
        """Run an agent (or a multi-agent system) until it terminates or the cycle limit."""
        _run(values, extensions)

    run.__signature__ = inspect.Signature(parameters)  # type: ignore[attr-defined]
    return run


def _run(values: dict[str, Any], extensions: Sequence[Extension]) -> None:
    """What ``goalagent run`` does with its option ``values``."""
    path: Path = values["path"]
    env: str | None = values["env"]
    printer = _trace_printer(values["trace"], values["trace_file"])
    trace = printer is not None and values["trace_file"] is None  # on stdout
    params = _env_params(values["env_param"] or [])
    predicates = _saved_predicates(values["save_predicate"] or [], extensions)
    if values["save_beliefs"] is not None and not predicates:
        raise user_error("--save-beliefs: no predicate to save; name one with "
                         "--save-predicate NAME/ARITY")
    try:
        every = SaveInterval.parse(values["save_every"])
        if values["save_beliefs"] is not None:
            check_target(values["save_beliefs"])
    except ValueError as err:
        raise user_error(str(err)) from None
    except OSError as err:
        raise user_error(f"--save-beliefs {values['save_beliefs']}: "
                         f"{err.strerror or err}") from None
    if values["max_cycles"] is not None and values["max_cycles"] < 0:
        raise user_error("--max-cycles must be 0 or more")
    limits = _limits(values["max_inferences"], values["max_query_seconds"],
                     values["max_beliefs"], values["sandbox"], values["max_module_depth"],
                     values["max_memory"])
    options = dict(seed=values["seed"], listeners=[printer] if printer is not None else [],
                   warn=lambda message: err_console.print(message, markup=False), limits=limits,
                   max_agents=values["max_agents"])
    if path.suffix in (".mod2g", ".act2g", ".pl", ".test2g"):
        raise user_error(f"{path}: a {path.suffix} file does not run on its own: run the "
                         ".mas2g that uses it" + (", or goalagent test for a test file"
                                                  if path.suffix == ".test2g" else ""))
    system = _build_system(path, env, params, options)
    try:
        if values["load_beliefs"] is not None:
            load_beliefs(system.agents, values["load_beliefs"],
                         [p for e in extensions for p in e.saved_predicates])
    except (GoalSyntaxError, KBError) as err:
        system.close()
        raise user_error(str(err)) from None
    hooks: list[RunHook] = []
    if values["save_beliefs"] is not None:  # first: saved before any report runs
        hooks.append(_belief_saver(values, predicates, every, system, extensions))
    hooks += [make() for extension in extensions for make in extension.run_hooks]
    debugger = _debugger(values, system, extensions)
    if debugger is not None:
        hooks.append(debugger)
    run = Run(system, hooks, RunContext(system, values, err_console),
              lambda line: err_console.print(line, markup=False))
    # A live status line on an interactive stderr (never with --trace, a prompt or the
    # inspector, never in pipes).
    live = err_console.is_terminal and not trace and debugger is None
    status = err_console.status("starting") if live else contextlib.nullcontext()
    try:
        with status:
            code = run.execute(values["max_cycles"], status=(
                (lambda agent: status.update(f"{agent.name}: cycle {agent.cycle}, "  # type: ignore
                                             f"{agent.total_actions} actions")) if live else None))
    finally:
        traced = printer is None or _close_trace(printer)
    if code or not traced:
        raise typer.Exit(code=code or 1)


def _limits(max_inferences: int, max_query_seconds: float, max_beliefs: int,
            sandbox: bool, max_module_depth: int, max_memory: int) -> Limits:
    """The agents' limits from the options (exit 2 naming the option that is out of range)."""
    try:
        return Limits(max_inferences, max_query_seconds, max_beliefs, sandbox,
                      max_module_depth=max_module_depth, max_memory=max_memory)
    except ValueError as err:
        raise user_error(f"--{str(err).replace('_', '-')}") from None


def _check_env_options(path: Path, env: str | None,
                       params: dict[str, ParameterText]) -> None:
    """``--env`` names an environment and ``--env-param`` keys it takes, with the closest
    name when not (said of the option, not of a place in the agent file)."""
    name = env
    if name is None and path.suffix == ".mas2g" and params:
        try:
            name = parse_mas_file(path).environment
        except GoalSyntaxError:
            return  # said where it is when the system is built
    if name is None:
        return
    try:
        environment = load_environment(name)
    except EnvironmentInterfaceException as err:
        if env is None:
            return
        raise user_error(f"--env {env}: {err}{did_you_mean(env, known_environments())}"
                         ) from None
    for key in params:
        problem = unknown_parameter(environment, name, key)
        if problem is not None:
            raise user_error(f"--env-param {key}: {problem}")


def _belief_saver(values: dict[str, Any], predicates: Sequence[SavedPredicate],
                  every: SaveInterval, system: MultiAgentSystem,
                  extensions: Sequence[Extension]) -> BeliefSaver:
    """The ``--save-beliefs`` hook: the predicates named with ``--save-predicate`` and those
    of an extension whose environment the run uses always; another extension's only where
    an agent has them (a plain agent's file says nothing of the robot's afford/6)."""
    environment = system.environment
    used = "" if environment is None else (
        f"{type(environment).__module__}:{type(environment).__qualname__}")
    named = {indicator.strip() for indicator in values["save_predicate"] or []}
    always = {p.indicator for e in extensions if used in e.environments.values()
              for p in e.saved_predicates}
    offered = {p.indicator for e in extensions for p in e.saved_predicates} - always - {
        f"{name}/{int(arity)}" for name, _, arity in (n.rpartition("/") for n in named)}
    return BeliefSaver(values["save_beliefs"],
                       [p for p in predicates if p.indicator not in offered], every,
                       offered=[p for p in predicates if p.indicator in offered])


def _build_system(path: Path, env: str | None, params: dict[str, ParameterText],
                  options: dict[str, Any]) -> MultiAgentSystem:
    """The system of a .mas2g file, or of one .goal agent (on ``env``); user errors exit 2."""
    if path.suffix != ".mas2g" or env is None:
        _check_env_options(path, env, params)
    try:
        if path.suffix == ".mas2g":
            if env is not None:
                raise user_error("--env is for .goal files; a .mas2g names its own environment")
            return MultiAgentSystem.from_mas_file(path, env_params=params, **options)
        if params and env is None:
            raise user_error("--env-param sets an environment's init parameters: give --env too")
        return MultiAgentSystem.for_agent_file(path, environment=env, env_params=params,
                                               **options)
    except (GoalSyntaxError, AgentError, KBError, EnvironmentInterfaceException) as err:
        shown = cause_traceback(err)  # (GOALAGENT_DEBUG: the environment's own code that raised)
        if shown is not None:
            err_console.print(shown, markup=False)
        raise user_error(str(err)) from None


def _debugger(values: dict[str, Any], system: MultiAgentSystem,
              extensions: Sequence[Extension]) -> Debugger | None:
    """The hook of ``--step``, ``--break`` or ``--inspect`` (None without them)."""
    breaks = values["breakpoint"] or []
    if not (values["step"] or breaks or values["inspect"]):
        return None
    if values["step"] and values["inspect"]:
        system.close()
        raise user_error("--step and --inspect: choose one (the inspector steps too)")
    if values["inspect"]:
        from goalagent.inspector import Inspector

        front: FrontEnd = Inspector(values["host"], values["port"], extensions, err_console)
    else:
        front = TerminalStepper()
    debugger = Debugger(front, stepping=values["step"] or values["inspect"])
    debugger.system = system
    try:
        for text in breaks:
            debugger.add_breakpoint(text)
        if values["inspect"]:
            front.attach(debugger)  # type: ignore[attr-defined]
    except DebuggerError as err:
        system.close()
        raise user_error(f"--break {err}") from None
    except OSError as err:
        system.close()
        raise user_error(f"--inspect: {err}") from None
    return debugger


def check(
    paths: Annotated[list[Path], typer.Argument(help="Program files to check: .goal, "
                                                ".mas2g, .mod2g, .act2g, .pl, .test2g; a "
                                                "directory: every one under it.")],
    sandbox: Annotated[bool, typer.Option(
        help="Also load each agent as --sandbox would (nothing runs): report every call "
             "the sandbox refuses, and every reach into other modules.")] = False,
) -> None:
    """Parse and validate programs: syntax, undefined actions and modules, macros, ground
    goals, a system's environment and its init parameters, the files GOAL 6+ programs use;
    singleton variables and calls of predicates defined nowhere are reported as warnings."""
    failed = False
    for path in (file for given in paths for file in files_to_check(given)):
        if check_file(path, sandbox, lambda line: err_console.print(line, markup=False)):
            err_console.print(f"{path}: ok", markup=False)
        else:
            failed = True
    if failed:
        raise typer.Exit(code=USER_ERROR)


def test(
    paths: Annotated[list[Path], typer.Argument(help=".test2g test files to run.")],
    max_cycles: Annotated[int, typer.Option(help="Stop each test after this many rounds "
                                            "(besides the file's timeout).")] = 1000,
    seed: Annotated[int, typer.Option(help="Seed for rule order and Prolog's random.")] = 0,
    max_inferences: MaxInferences = Limits.max_inferences,
    max_query_seconds: MaxQuerySeconds = Limits.max_query_seconds,
    max_beliefs: MaxBeliefs = Limits.max_beliefs,
    max_memory: MaxMemory = Limits.max_memory,
    sandbox: Sandbox = False,
    max_module_depth: MaxModuleDepth = DEFAULT_MODULE_DEPTH,
) -> None:
    """Run GOAL agent tests (.test2g): the system each file names, its agents' steps and its
    conditions, under the limits and confinement of run (a condition that runs past a limit
    or is refused fails its item); a report per test on stdout (what the agents print goes
    to stderr), exit code 1 when one failed."""
    limits = _limits(max_inferences, max_query_seconds, max_beliefs, sandbox, max_module_depth,
                     max_memory)
    failed = False
    for path in paths:
        try:
            report = run_test_file(path, max_cycles=max_cycles, seed=seed, limits=limits,
                                   output=sys.stderr,
                                   warn=lambda message: err_console.print(message, markup=False))
        except (GoalSyntaxError, AgentError, KBError, EnvironmentInterfaceException) as err:
            raise user_error(str(err)) from None
        Console(highlight=False, soft_wrap=True, emoji=False).print(report.text(), markup=False)
        failed = failed or not report.passed
    if failed:
        raise typer.Exit(code=1)


def _show_version(shown: bool) -> None:
    if shown:
        print(f"goalagent {metadata.version('goalagent')}")
        raise typer.Exit()


def _version_option(
    version: Annotated[bool, typer.Option("--version", callback=_show_version, is_eager=True,
                                          help="Show the version and exit.")] = False,
) -> None:
    """Run GOAL agent programs whose beliefs live in SWI-Prolog."""


def create_app(extensions: Sequence[Extension] | None = None) -> typer.Typer:
    """The ``goalagent`` command line: ``run``, ``check`` and ``test``, then the extensions'
    commands."""
    extensions = installed_extensions() if extensions is None else extensions
    app = typer.Typer(no_args_is_help=True, help=HELP, context_settings=HELP_OPTIONS,
                      rich_markup_mode=None)
    app.callback()(_version_option)
    app.command(name="run", cls=RunCommand)(_run_command(extensions))
    app.command()(check)
    app.command(name="test")(test)
    for extension in extensions:
        if extension.add_commands is not None:
            extension.add_commands(app)
    return app


def command(extensions: Sequence[Extension] | None = None) -> Any:
    """The ``goalagent`` command as click runs it: :func:`create_app`'s, with shell
    completion (``--install-completion``) and readable metavars on every option."""
    built = typer.main.get_command(create_app(extensions))
    readable_metavars(built)
    return built


def main() -> None:
    """The ``goalagent`` console script. Whatever goes wrong ends in one ``error:`` line,
    never a traceback (``GOALAGENT_DEBUG=1`` shows it, for reporting a bug); a package of an
    extra that is not installed is named with the extra."""
    try:
        command()(prog_name="goalagent")
    except Exception as error:  # noqa: BLE001 - the last guard of the command line
        if os.environ.get("GOALAGENT_DEBUG"):
            raise
        hint = install_hint(error.name) if isinstance(error, ModuleNotFoundError) else None
        if hint is not None:  # an extra that is not installed
            err_console.print(f"error: this command {hint}", markup=False)
            sys.exit(USER_ERROR)
        err_console.print(f"error: internal error, please report it: {type(error).__name__}: "
                          f"{error}", markup=False)
        sys.exit(1)

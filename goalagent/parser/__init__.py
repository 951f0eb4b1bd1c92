"""Parse agent programs into immutable program objects (``goalagent.ast``).

The structure is read by lark with ``grammar.lark``; every Prolog fragment is then read by
SWI-Prolog itself (``goalagent.kb.engine``), so Prolog text means exactly what it means to
SWI-Prolog. Every error is a ``GoalSyntaxError`` carrying ``file:line:col``.

One module per kind of file: ``goal_file`` (GOAL's single-file `.goal` format),
``mas_file`` (`.mas2g` of every GOAL version), ``agents`` (the agents of a system, GOAL 6+'s
`.mod2g` / `.act2g` / `.pl` files of an agent definition assembled into the same program
model as a `.goal` file), ``test_file`` (`.test2g`), ``prolog_file`` (``#import``ed `.pl`);
the AST builder they share is ``ast_builder`` with its parts ``goal_sections``,
``conditions`` (mental state conditions and macros), ``module_sections`` (`.mod2g`,
`.act2g`), ``mas_sections`` and ``test_sections``; ``source`` blanks comments and maps
offsets; ``grammar`` runs lark and words its errors.
"""

from goalagent.ast import iter_rules
from goalagent.parser.agents import (
    load_agents,
    load_definition,
    load_module_as_agent,
    parse_action_file,
    parse_module_file,
)
from goalagent.parser.errors import GoalSyntaxError
from goalagent.parser.goal_file import parse_agent, parse_agent_file
from goalagent.parser.mas_file import parse_mas, parse_mas_file
from goalagent.parser.prolog_file import parse_prolog_file
from goalagent.parser.source import Source
from goalagent.parser.test_file import parse_test, parse_test_file
from goalagent.parser.variables import rename_variables, variable_occurrences

__all__ = [
    "GoalSyntaxError",
    "Source",
    "iter_rules",
    "load_agents",
    "load_definition",
    "load_module_as_agent",
    "parse_action_file",
    "parse_module_file",
    "parse_test",
    "parse_test_file",
    "parse_agent",
    "parse_agent_file",
    "parse_mas",
    "parse_mas_file",
    "parse_prolog_file",
    "rename_variables",
    "variable_occurrences",
]

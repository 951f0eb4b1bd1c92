"""goalagent: GOAL agents on SWI-Prolog, with environments reached through EIS.

The Python API in one place (``from goalagent import Agent, MultiAgentSystem``):

- :class:`Agent` -- one agent: ``step()``, ``run()``, ``query()``, ``listen()``; what a
  cycle did is a :class:`CycleReport` of :class:`FiredRule` entries, what a listener hears
  an :class:`Event` of an :class:`EventKind`.
- :class:`MultiAgentSystem` -- agents on an environment (a ``.mas2g`` file, or one agent
  file or text on a named environment).
- :func:`run_test_file` -- a ``.test2g`` file's :class:`TestReport`.
- Terms as Python values: :class:`Atom`, :class:`Struct`, :class:`Var`, :data:`Term`,
  :func:`format_term`; ``parse_parameter`` reads one from Prolog text.
- Environments: :class:`PythonEnvironment` with :func:`action`, ``register_environment``,
  ``ActionRefused`` (all in ``goalagent.eis``).

The names are imported when first used, so ``import goalagent`` alone does not start
SWI-Prolog (the ``goalagent`` command installs its signal handlers first).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # (for type checkers: "X as X" re-exports X)
    from goalagent.agent import Agent as Agent
    from goalagent.agent import AgentError as AgentError
    from goalagent.agent import CycleReport as CycleReport
    from goalagent.agent import Event as Event
    from goalagent.agent import EventKind as EventKind
    from goalagent.agent import FiredRule as FiredRule
    from goalagent.agent import RunResult as RunResult
    from goalagent.agent.events import Bindings as Bindings
    from goalagent.eis import ActionRefused as ActionRefused
    from goalagent.eis import PythonEnvironment as PythonEnvironment
    from goalagent.eis import action as action
    from goalagent.eis import register_environment as register_environment
    from goalagent.kb.limits import Limits as Limits
    from goalagent.kb.terms import Atom as Atom
    from goalagent.kb.terms import Struct as Struct
    from goalagent.kb.terms import Term as Term
    from goalagent.kb.terms import Var as Var
    from goalagent.kb.terms import format_term as format_term
    from goalagent.mas import MultiAgentSystem as MultiAgentSystem
    from goalagent.mas import parse_parameter as parse_parameter
    from goalagent.testing import TestReport as TestReport
    from goalagent.testing import run_test_file as run_test_file

_WHERE = {
    "Agent": "goalagent.agent",
    "AgentError": "goalagent.agent",
    "CycleReport": "goalagent.agent",
    "Event": "goalagent.agent",
    "EventKind": "goalagent.agent",
    "FiredRule": "goalagent.agent",
    "RunResult": "goalagent.agent",
    "Bindings": "goalagent.agent.events",
    "ActionRefused": "goalagent.eis",
    "PythonEnvironment": "goalagent.eis",
    "action": "goalagent.eis",
    "register_environment": "goalagent.eis",
    "Limits": "goalagent.kb.limits",
    "Atom": "goalagent.kb.terms",
    "Struct": "goalagent.kb.terms",
    "Term": "goalagent.kb.terms",
    "Var": "goalagent.kb.terms",
    "format_term": "goalagent.kb.terms",
    "MultiAgentSystem": "goalagent.mas",
    "parse_parameter": "goalagent.mas",
    "TestReport": "goalagent.testing",
    "run_test_file": "goalagent.testing",
}

__all__ = sorted(_WHERE)


def __getattr__(name: str) -> object:
    """The public name ``name``, imported from its module on first use."""
    module = _WHERE.get(name)
    if module is None:
        raise AttributeError(f"module 'goalagent' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value

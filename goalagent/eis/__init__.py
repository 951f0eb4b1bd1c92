"""Environment interface standard (EIS): environments, their entities, percepts and actions.

``Environment`` is the base (state machine, entities, agents, listeners); ``PythonEnvironment``
with ``@action`` writes one in plain Python; ``load_environment`` finds one by name or path;
``terms`` converts interface-level terms to and from Prolog.
"""

from goalagent.eis.exceptions import (
    ActException,
    ActExceptionKind,
    ActionRefused,
    AgentException,
    EntityException,
    EnvironmentInterfaceException,
    ManagementException,
    NoEnvironmentException,
    PerceiveException,
    RelationException,
    TranslationException,
)
from goalagent.eis.interface import (
    AgentListener,
    Environment,
    EnvironmentListener,
    EnvironmentState,
)
from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action
from goalagent.eis.registry import known_environments, load_environment, register_environment
from goalagent.eis.terms import (
    Action,
    Function,
    Identifier,
    Numeral,
    Parameter,
    ParameterList,
    Percept,
    TruthValue,
    action_from_term,
    action_to_term,
    from_term,
    percept_from_term,
    percept_to_term,
    to_parameter,
    to_python,
    to_term,
)

__all__ = [
    "ActException",
    "ActExceptionKind",
    "Action",
    "ActionRefused",
    "AgentException",
    "AgentListener",
    "EntityException",
    "Environment",
    "EnvironmentInterfaceException",
    "EnvironmentListener",
    "EnvironmentState",
    "Function",
    "Identifier",
    "ManagementException",
    "NoEnvironmentException",
    "Numeral",
    "Parameter",
    "ParameterList",
    "PerceiveException",
    "Percept",
    "PerceptLike",
    "PythonEnvironment",
    "RelationException",
    "TranslationException",
    "TruthValue",
    "action",
    "action_from_term",
    "action_to_term",
    "from_term",
    "known_environments",
    "load_environment",
    "percept_from_term",
    "percept_to_term",
    "register_environment",
    "to_parameter",
    "to_python",
    "to_term",
]

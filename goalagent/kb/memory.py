"""Memory bounded per agent in bytes (``--max-memory``, default 512 MB): what its clauses
hold -- knowledge, beliefs, goals, percepts, mail, with the text of the atoms in them -- and
what one of its calls takes outside Prolog's stacks. Over either, the agent is stopped with
a message naming it; the process and the other agents live on.

SWI-Prolog bounds only each thread's stacks; atoms, clauses and text being written are
malloc()ed without limit (doubling an atom 16 times, or one 2,000,000-element fact a cycle,
ended the whole process in ``Could not allocate memory``). Measuring every assert would cost
every cycle, so nothing is measured on the cycle's path: the watchdog thread reads the
process's resident memory each tick (goalagent/kb/watchdog.py) and raises an alarm when it
has grown; after an alarm each agent accounts for what it holds at its next interpreter
call (:func:`check_held`, memory.pl's account/4: SWI's own size of its predicates, its
atoms' text only when the process's atoms could put it over), and the running call is asked
at once. The alarm also collects the process's garbage atoms, which SWI collects by count
only (a few huge atoms never trigger it).
"""

from __future__ import annotations

from goalagent.kb.engine import Engine
from goalagent.kb.limits import Limits, limit_stop
from goalagent.kb.terms import Atom, Struct

__all__ = ["check_held"]


def check_held(engine: Engine, module: Atom, limits: Limits, generation: int) -> None:
    """Raises :class:`~goalagent.kb.errors.LimitError` when the agent of belief module
    ``module`` holds more than its ``--max-memory``; ``generation``: the watchdog's alarm
    it accounts after."""
    most = limits.max_memory_bytes
    result = engine.call("account", module, most, generation, None, module="ga_memory")
    assert result is not None
    outcome = result[3]
    if isinstance(outcome, Struct):  # over(Bytes)
        raise limit_stop(Struct("memory", (Struct("held", (outcome.args[0],)), most)))

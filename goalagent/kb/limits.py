"""How much Prolog work one agent may cause, and what it may call: the bounds the runtime
puts on an agent (``goalagent run --max-inferences/--max-query-seconds/--max-beliefs``,
``--max-module-depth``, ``--sandbox``, or per agent file in a .mas2g).

Defaults are generous: measured on every shipped agent and the benchmarks (see
docs in README "Limits"), the busiest rule makes a few hundred thousand inferences
and the slowest stretch of Prolog takes well under a second, so only runaway rules meet
them. What happens at each bound: a rule passing the inference or time limit is not
applicable, with a warning naming agent, module and rule (rules.pl, watchdog.py); an agent
holding more beliefs and goals than ``max_beliefs``, or more memory than ``max_memory``
(goalagent/kb/memory.py), is stopped with a message.
"""

from __future__ import annotations

import resource
from collections.abc import Sequence
from dataclasses import dataclass, field

from goalagent import ast
from goalagent.kb.errors import KBError, LimitError, PrologRuntimeError
from goalagent.kb.terms import Struct, Term, format_term

__all__ = ["Limits", "limit_stop", "limit_text", "refused_precondition", "stopping_error"]


BYTES_PER_MODULE_LEVEL = 8 * 1024
"""C stack one nested module call takes, with a margin: each level is a Prolog query inside
a Python callback inside a Prolog query (measured: an 8 MiB stack overflows between 1,500
and 2,000 levels, about 4.5 KiB a level)."""


def default_module_depth() -> int:
    """How deep module calls may nest by default: as deep as the process's C stack safely
    allows (``ulimit -s``; 1,024 levels for Linux's usual 8 MiB, at most 10,000)."""
    soft, _ = resource.getrlimit(resource.RLIMIT_STACK)
    if soft == resource.RLIM_INFINITY or soft <= 0:
        return 10_000
    return max(24, min(10_000, soft // BYTES_PER_MODULE_LEVEL))


@dataclass(frozen=True)
class Limits:
    """An agent's bounds. ``max_query_seconds``: the longest stretch the main thread may
    spend in Prolog for it without returning to Python (a rule's condition, its actions'
    Prolog part); ``sandbox``: its Prolog text may call only safe built-ins (confine.pl);
    ``runs_code`` False: loaded only to be checked (``goalagent check``), none of its code
    runs -- its directives are checked but not run (declarations, operators and library
    loads take effect) and its initial goals are declared, not adopted."""

    max_inferences: int = 10_000_000
    max_query_seconds: float = 20.0
    max_beliefs: int = 2_000_000
    sandbox: bool = False
    runs_code: bool = True
    max_module_depth: int = field(default_factory=default_module_depth)
    max_memory: int = 512  # megabytes (memory.py)

    @property
    def max_memory_bytes(self) -> int:
        return self.max_memory * 2**20

    def __post_init__(self) -> None:
        if not 0 < self.max_module_depth <= 100_000:
            raise ValueError("max_module_depth must be a whole number from 1 to 100000")
        if not 0 < self.max_inferences <= 2**62:
            raise ValueError("max_inferences must be a positive whole number")
        if not 0 < self.max_query_seconds <= 10**7:
            raise ValueError("max_query_seconds must be a positive number of seconds")
        if not 0 < self.max_beliefs <= 2**62:
            raise ValueError("max_beliefs must be a positive whole number")
        if not 0 < self.max_memory <= 2**62:
            raise ValueError("max_memory must be a positive whole number of megabytes")


def limit_text(limit: Term) -> str:
    """What a ``ga_limit(Limit)`` of guard.pl / rules.pl says was passed."""
    assert isinstance(limit, Struct)
    value = limit.args[0]
    if limit.name == "inferences":
        return f"more than {value:,} inferences (--max-inferences)"
    if limit.name == "time":
        return f"longer than {value:g} s (--max-query-seconds)"
    if limit.name == "beliefs":
        return f"{value:,} beliefs, more than {limit.args[1]:,} (--max-beliefs)"
    if limit.name == "memory" and isinstance(value, Struct):
        taken = -(-int(value.args[0]) // 2**20)  # type: ignore[arg-type]  # (rounded up)
        most = int(limit.args[1]) // 2**20  # type: ignore[arg-type]
        if value.name == "held":
            return (f"{taken:,} MB in its clauses, records and global variables, more than "
                    f"--max-memory {most:,} MB")
        return (f"{taken:,} MB outside Prolog's stacks in one call, more than --max-memory "
                f"{most:,} MB")
    return format_term(limit)


def stopping_error(error: PrologRuntimeError) -> KBError:
    """The error that stops an agent for ``ga_limit(Limit)`` escaping an interpreter call
    (rules.pl: its beliefs over --max-beliefs, its memory over --max-memory, or a limit met
    between rules); any other error as it is."""
    term = error.term
    if not (isinstance(term, Struct) and term.name == "ga_limit"):
        return error
    return limit_stop(term.args[0])


def limit_stop(limit: Term) -> LimitError:
    """The error that stops an agent for passing ``limit`` (a ga_limit/1 argument)."""
    if isinstance(limit, Struct) and limit.name == "beliefs":
        return LimitError(f"holds {limit_text(limit)}; stopped")
    if isinstance(limit, Struct) and limit.name == "memory":
        took = "holds" if limit.args[0].name == "held" else "took"  # type: ignore[union-attr]
        return LimitError(f"{took} {limit_text(limit)}; stopped")
    return LimitError(f"ran {limit_text(limit)} outside a rule; stopped")


def refused_precondition(error: PrologRuntimeError, specs: Sequence[ast.ActionSpec]) -> KBError:
    """The located error for a precondition confine.pl refused (``ga_refused_spec``)."""
    term = error.term
    if not (isinstance(term, Struct) and term.name == "ga_refused_spec"):
        return error
    spec = specs[int(term.args[0])]  # type: ignore[arg-type]
    return KBError(f"{spec.pre.pos}: precondition of {spec.name}: refused: {term.args[1]}",
                   spec.pre.pos)

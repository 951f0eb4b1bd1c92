"""How many agents one process can hold, so that a launch beyond it is refused before any
agent is built (one line naming the limit and how to raise it) instead of swapping the
machine to a halt.

An agent of the size of ``bench/reference_agent.goal`` (20 beliefs, a goal, seven rules)
takes 40 -- 52 KiB of resident memory (``bench/agents.py``, 10 to 100,000 agents: its two
Prolog modules with their clauses, its compiled conditions and its Python objects);
:data:`BYTES_PER_AGENT` counts 64 KiB to leave room for beliefs that grow. The process may
use :data:`MEMORY_SHARE` of the memory the kernel says is available when the system is
built (``MemAvailable``; a lower ``ulimit -v`` or ``ulimit -d`` counts instead), so 100,000
agents (about 6 GB) launch where 8 GB are free. ``--max-agents`` (``max_agents``) sets the
limit by hand.
"""

from __future__ import annotations

import resource
from collections.abc import Mapping

from goalagent import ast
from goalagent.parser import GoalSyntaxError

__all__ = ["BYTES_PER_AGENT", "MEMORY_SHARE", "agent_capacity", "available_memory",
           "capacity_message", "check_launches"]

BYTES_PER_AGENT = 64 * 1024
"""Resident memory counted for each agent (measured 40 -- 52 KiB, see the module's doc)."""

MEMORY_SHARE = 0.75
"""The share of the available memory the agents may take (the rest: the environment,
Prolog's stacks, the machine's other work)."""


def available_memory() -> int:
    """Bytes this process can still take: the kernel's ``MemAvailable``, or less when
    ``ulimit -v`` / ``ulimit -d`` leaves less room (their soft limits minus what the process
    has already mapped, or holds as data)."""
    available = _meminfo_available()
    for limit, used in ((resource.RLIMIT_AS, "VmSize"), (resource.RLIMIT_DATA, "VmData")):
        soft, _ = resource.getrlimit(limit)
        if soft != resource.RLIM_INFINITY and soft > 0:
            available = min(available, max(0, soft - _status_bytes(used)))
    return available


def agent_capacity() -> int:
    """How many agents fit in :data:`MEMORY_SHARE` of :func:`available_memory`."""
    return int(available_memory() * MEMORY_SHARE) // BYTES_PER_AGENT


def capacity_message(wanted: int, limit: int, *, by_hand: bool) -> str:
    """The one line refusing ``wanted`` agents over ``limit`` (set with --max-agents when
    ``by_hand``, else from the memory available)."""
    need = _size(wanted * BYTES_PER_AGENT)
    if by_hand:
        return (f"{wanted:,} agents are more than --max-agents {limit:,} allows "
                f"(about {need}); raise it with --max-agents N")
    room = _size(limit * BYTES_PER_AGENT)
    return (f"{wanted:,} agents need about {need}, more than the {room} this "
            f"process may use ({MEMORY_SHARE:.0%} of the memory available): the limit is "
            f"{limit:,} agents; free memory, or raise it with --max-agents N")


def check_launches(mas: ast.MasProgram, numbers: Mapping[str, int], limit: int,
                   by_hand: bool) -> None:
    """Refuses, before any agent is built, a file launching more than ``limit`` agents
    (``numbers``: each agent file's ``number``): a GoalSyntaxError at the launch rule, or
    agent file, that passes it."""
    counted = [(rule.number if rule.number != 1 else numbers.get(rule.agentfile, 1), rule.pos)
               for rule in mas.launches if not rule.on_entity]
    if not mas.launches:
        counted = [(agentfile.number, agentfile.pos) for agentfile in mas.agentfiles]
    total = 0
    for number, pos in counted:
        total += number
        if total > limit:
            raise GoalSyntaxError.at(pos, capacity_message(total, limit, by_hand=by_hand))


def _size(size: int) -> str:
    """A number of bytes for people: 6.6 GB, 66 MB, 393 kB."""
    if size >= 10**9:
        return f"{size / 1e9:,.1f} GB"
    if size >= 10**6:
        return f"{size / 1e6:,.0f} MB"
    return f"{size / 1e3:,.0f} kB"


def _meminfo_available() -> int:
    """``MemAvailable`` of /proc/meminfo in bytes (MemFree where the kernel lacks it)."""
    fields: dict[str, int] = {}
    with open("/proc/meminfo") as meminfo:
        for line in meminfo:
            name, _, value = line.partition(":")
            fields[name] = int(value.split()[0]) * 1024
    return fields.get("MemAvailable", fields.get("MemFree", 0))


def _status_bytes(field: str) -> int:
    """A memory figure of /proc/self/status (VmSize: mapped, VmData: data) in bytes."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(f"{field}:"):
                return int(line.split()[1]) * 1024
    return 0

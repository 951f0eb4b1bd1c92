"""The error of an agent: found loading it (unknown action, bad clause, ...) or stopping it
while it runs (module calls nested without end)."""

from __future__ import annotations


class AgentError(Exception):
    """A user error of one agent, with a readable message."""

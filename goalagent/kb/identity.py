"""Who an agent is and who else is there: ``me/1`` and ``agent/1``, a private list or one
shared by every member of a system (:class:`AgentDirectory`).
"""

from __future__ import annotations

import secrets
from collections.abc import Iterable

from goalagent.kb.engine import Engine, KBError, get_engine
from goalagent.kb.prolog_modules import PrologModules
from goalagent.kb.terms import Atom

__all__ = ["AgentDirectory", "Identity"]


class AgentDirectory:
    """The names of the agents of one system, kept once in a Prolog module that every
    member's ``agent/1`` reads (see :meth:`Identity.join`): adding an agent is one fact."""

    def __init__(self, engine: Engine | None = None) -> None:
        self._engine = engine or get_engine()
        self.module = Atom(f"ga_dir_{secrets.token_hex(8)}")
        self.closed = False
        self._engine.call("new_directory", self.module)

    def add(self, name: str) -> None:
        """Adds ``agent(name)`` for every member."""
        if self.closed:
            raise KBError("the agent directory is closed")
        self._engine.call("directory_add", self.module, Atom(name))

    def close(self) -> None:
        """Frees the module (close the members first: their ``agent/1`` reads it)."""
        if not self.closed:
            self._engine.call("destroy_directory", self.module)
            self._engine.forget_atom(self.module)
            self.closed = True


class Identity(PrologModules):
    """The agent's ``me/1`` and ``agent/1`` beliefs."""

    def set_identity(self, me: str, agents: Iterable[str]) -> None:
        """Believes ``me(Me)`` and ``agent(A)`` for every agent of the system (a private copy
        of the list; agents of one system share theirs through :meth:`join`)."""
        names = [name if isinstance(name, Atom) else Atom(name) for name in agents]
        self._call("set_identity", self._b, self._g, Atom(me), names)
        self._recheck = True

    def join(self, me: str, directory: AgentDirectory) -> None:
        """Believes ``me(Me)``, and ``agent(A)`` for every agent in ``directory``, also for
        agents added to it later (the list is shared, not copied)."""
        if directory.closed:
            raise KBError("the agent directory is closed")
        self._call("join_directory", self._b, Atom(me), directory.module)
        self._recheck = True

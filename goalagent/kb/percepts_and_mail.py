"""What reaches one agent from outside: the percept base its environment fills each cycle,
and the mailbox (``received/2`` and ``sent/2`` beliefs) of its messages.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from goalagent.kb.engine import KBError
from goalagent.kb.prolog_modules import PrologModules
from goalagent.kb.terms import Atom, Struct, Term

__all__ = ["PerceptsAndMail"]

_MOODS = {":": None, "!": "imp", "?": "int"}


class PerceptsAndMail(PrologModules):
    """The percept base and the mailbox in the agent's belief module; an empty one replaced
    by an empty one costs no Prolog call."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._has_percepts = self._has_mail = False  # the percept base, received/2 not empty
        super().__init__(*args, **kwargs)

    def set_percepts(self, percepts: Iterable[Term]) -> None:
        """Replaces the percept base (``percept(φ)`` and ``bel(percept(φ))`` see it); an
        empty base replaced by an empty one costs no Prolog call."""
        percepts = list(percepts)
        if not percepts and not self._has_percepts:
            return
        self._call("set_percepts", self._b, percepts)
        self._has_percepts = bool(percepts)
        self._recheck = True

    def percepts(self) -> list[Term]:
        """The current percepts."""
        percepts = self._call("percepts", self._b, None)[1]
        assert isinstance(percepts, list)
        return percepts

    def receive(self, messages: Sequence[tuple[str, str, Term]], replace: bool = False) -> None:
        """Believes received(S, φ), imp(φ) for '!', int(φ) for '?'; ``replace``: GOAL 6+'s mail."""
        facts = [Struct("received", tuple(_message(*message))) for message in messages]
        if facts or (replace and self._has_mail):  # no Prolog call for no change
            self._call("receive", self._b, facts, Atom("true" if replace else "false"))
            self._has_mail, self._recheck = bool(facts) or (self._has_mail and not replace), True

    def add_sent(self, receiver: str, mood: str, content: Term) -> bool:
        """Believes ``sent(Receiver, φ)`` (moods as for received); False if already there."""
        fact = Struct("sent", tuple(_message(receiver, mood, content)))
        self._recheck = True
        return self._call("add_once", self._b, fact, None)[2] == "true"


def _message(peer: str, mood: str, content: Term) -> list[Term]:
    """The (peer, content) arguments of received/2 or sent/2 for a message in ``mood``."""
    if mood not in _MOODS:
        raise KBError(f"unknown message mood {mood!r}: use ':', '!' or '?'")
    wrapper = _MOODS[mood]
    body = Struct(wrapper, (content,)) if wrapper else content
    return [peer if isinstance(peer, Atom) else Atom(peer), body]

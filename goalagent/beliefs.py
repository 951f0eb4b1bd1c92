"""Beliefs kept between runs: Prolog fact files loaded into agents and saved from them.

``goalagent run --load-beliefs FILE`` adds a file's facts to every agent's beliefs before it
starts; ``--save-beliefs FILE`` writes the final beliefs of the saved predicates (those the
installed extensions declare, e.g. the robot application's ``afford/6``, and those named with
``--save-predicate NAME/ARITY``). Files are written atomically (temp file + ``os.replace``).
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from goalagent.extensions import RunContext, RunHook, SavedPredicate
from goalagent.kb.terms import Atom, Struct, Term, format_term, quote_atom
from goalagent.parser import parse_prolog_file

if TYPE_CHECKING:
    from goalagent.agent import Agent


def write_atomically(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` so that a crash leaves either the old or the new file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as stream:
            stream.write(text)
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def load_beliefs(agent: Agent, path: Path) -> int:
    """Add the facts of a Prolog file to the agent's beliefs (before its first cycle);
    returns how many. A malformed file raises ``GoalSyntaxError`` at its file:line:col."""
    facts = parse_prolog_file(path)
    for fact in facts:
        agent.ms.insert(fact)
    return len(facts)


def beliefs_of(agent: Agent, predicate: SavedPredicate) -> list[Term]:
    """The agent's current beliefs of ``predicate`` as terms, in belief-base order."""
    if not agent.query("bel", f"current_predicate({quote_atom(predicate.name)}/"
                              f"{predicate.arity})"):
        return []
    if predicate.arity == 0:
        return [Atom(predicate.name) for _ in agent.query("bel", quote_atom(predicate.name))]
    names = [f"A{index}" for index in range(predicate.arity)]
    text = f"{quote_atom(predicate.name)}({', '.join(names)})"
    facts: list[Term] = []
    for answer in agent.query("bel", text):
        args = tuple(answer[name] for name in names)
        if predicate.canonical is not None:
            args = predicate.canonical(args)
        facts.append(Struct(predicate.name, args))
    return facts


def save_beliefs(agents: Iterable[Agent], predicates: Sequence[SavedPredicate],
                 path: Path) -> int:
    """Write every agent's beliefs of ``predicates`` as Prolog facts; returns how many."""
    lines = [f"% {predicate.heading} saved by goalagent" for predicate in predicates]
    count = 0
    for agent in agents:
        lines.append(f"% agent {agent.name}")
        for predicate in predicates:
            facts = beliefs_of(agent, predicate)
            lines.extend(format_term(fact) + "." for fact in facts)
            count += len(facts)
    write_atomically(path, "\n".join(lines) + "\n")
    return count


class BeliefSaver(RunHook):
    """The ``--save-beliefs`` hook: writes the saved predicates when the run ends."""

    def __init__(self, path: Path, predicates: Sequence[SavedPredicate]) -> None:
        self.path = path
        self.predicates = tuple(predicates)

    def finish(self, run: RunContext) -> None:
        """Save and say how many beliefs of which predicates went where."""
        count = save_beliefs(run.system.agents, self.predicates, self.path)
        which = ", ".join(predicate.indicator for predicate in self.predicates)
        run.console.print(f"saved {count} {which} beliefs to {self.path}", markup=False)

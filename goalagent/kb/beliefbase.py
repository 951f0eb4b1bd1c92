"""The belief base of one agent: the predicates its program updates, insert and delete (with
blind commitment in the same Prolog call), files of facts added and watched, the listing.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

from goalagent import ast
from goalagent.kb.engine import KBError
from goalagent.kb.facts import FactFile, FactFileError, FactWatch
from goalagent.kb.prolog_modules import (
    PrologModules,
    image_kept,
    image_number,
    instantiate,
    note_image,
    text_of,
)
from goalagent.kb.terms import Atom, Struct, Term

__all__ = ["BeliefBase"]


class BeliefBase(PrologModules):
    """The agent's beliefs (the facts of its belief module that are neither knowledge nor
    percepts). Updates remove the goals they achieve at once and keep them in
    ``_achieved`` until :meth:`~goalagent.kb.goalbases.GoalBases.blind_commitment` reports
    them."""

    def declare_updates(self, formulas: Iterable[ast.PrologText | str]) -> None:
        """Declares dynamic every predicate in these conjunctions (also under not/1), so that
        querying them before the first insert/adopt fails instead of raising an error; they
        are the agent's own even where SWI-Prolog has a predicate of that name. A KBError
        (at the formula) when one is an ISO built-in."""
        formulas = list(formulas)
        image = None if self._image is None else image_number(
            ("declare", self._image, tuple(formulas)))
        terms = [] if image_kept(image) else [self._engine.parsed(text_of(formula))
                                              for formula in formulas]
        if image is None:
            result = self._call("declare", self._b, self._g, terms, None)[3]
        else:  # after a load from an image: as the first agent's declaration of them did
            result = self._call("declare_imaged", image, self._b, self._g, terms, None)[4]
            note_image(image, result)
        if isinstance(result, Struct) and result.name == "error":
            index, message = result.args
            formula = formulas[int(index)]  # type: ignore[arg-type]
            pos = formula.pos if isinstance(formula, ast.PrologText) else None
            where = f"{pos}: " if pos else ""
            raise KBError(f"{where}`{text_of(formula)}`: {message}", pos)

    def insert(self, formula: ast.PrologText | str,
               bindings: Mapping[str, Term] | None = None) -> list[tuple[str, Term]]:
        """Adds the positive literals, deletes those under not(..); returns the changes.
        Goals the change achieves are removed at once (blind commitment: the agent calls
        ``blind_commitment`` after every action, which then reports them)."""
        return self._update("insert", instantiate(formula, bindings or {}, self._engine))

    def delete(self, formula: ast.PrologText | str,
               bindings: Mapping[str, Term] | None = None) -> list[tuple[str, Term]]:
        """Deletes the positive literals, adds those under not(..); returns the changes
        (achieved goals are removed at once, as for :meth:`insert`)."""
        return self._update("delete", instantiate(formula, bindings or {}, self._engine))

    def _update(self, mode: str, term: Term) -> list[tuple[str, Term]]:
        """Runs insert or delete (``mode``) of ``term`` in Prolog, with blind commitment in
        the same call when beliefs changed (its result waits for ``blind_commitment``)."""
        result = self._call("update", self._b, self._g, Atom(mode), term, None, None, None)
        deleted, added, achieved = result[4], result[5], result[6]
        self._achieved.extend(achieved)
        removals, additions = _split_update(term, mode)
        changes: list[tuple[str, Term]] = []
        for fact, outcome in zip(removals, deleted, strict=True):
            if isinstance(outcome, int):
                changes.extend([("-", fact)] * outcome)
            else:
                changes.extend(("-", instance) for instance in outcome)
        changes.extend(("+", fact) for fact, flag in zip(additions, added, strict=True) if flag)
        return changes

    def add_facts(self, facts: FactFile) -> int:
        """Adds a checked file of facts (:func:`goalagent.kb.facts.read_facts`) to the
        beliefs, as insert would, each fact once and in file order; returns how many were
        new. One Prolog call, however many facts."""
        if facts.closed:
            raise KBError(f"the facts of {facts.file} were freed")
        self._check_open()
        result = self._engine.call("load_facts", self._b, self._g, facts.key, None,
                                   module="ga_guard")
        assert result is not None
        outcome = result[3]
        if outcome.name == "error":
            offset, message = outcome.args
            raise FactFileError(facts.pos(int(offset)), str(message))
        self._recheck = True
        return int(outcome.args[0])

    def watch(self, name: str, arity: int) -> FactWatch:
        """Follows this agent's facts of ``name/arity`` (see :class:`FactWatch`)."""
        self._check_open()
        return FactWatch(self._engine, self._b, name, arity)

    def beliefs(self) -> list[Term]:
        """The belief facts (not knowledge, not percepts), in Prolog clause order."""
        facts = self._call("beliefs", self._b, None)[1]
        assert isinstance(facts, list)
        return facts


def _split_update(term: Term, mode: str) -> tuple[list[Term], list[Term]]:
    """The facts an insert/delete (``mode``) of ``term`` deletes and adds, in the order
    mentalstate.pl's update/7 handles them (conjunction order, `true` skipped)."""
    removals: list[Term] = []
    additions: list[Term] = []
    pending = [term]
    while pending:
        literal = pending.pop()
        if isinstance(literal, Struct) and literal.name == "," and len(literal.args) == 2:
            pending.extend(reversed(literal.args))
        elif type(literal) is Atom and literal == "true":
            continue
        elif isinstance(literal, Struct) and literal.name in ("not", "\\+") and literal.arity == 1:
            (additions if mode == "delete" else removals).append(literal.args[0])
        else:
            (additions if mode == "insert" else removals).append(literal)
    return removals, additions
